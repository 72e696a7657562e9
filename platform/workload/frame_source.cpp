#include "platform/workload/frame_source.h"

#include <array>
#include <algorithm>
#include <fmt/format.h>
#include <map>
#include <opencv2/imgcodecs.hpp>  // cv::IMREAD_GRAYSCALE
#include <opencv2/imgproc.hpp>

#include "platform/scenario/block_params.h"
#include "platform/scenario/config.h"
#include "platform/workload/surf_settings.h"
#include "platform/workload/workload.h"
#include "sw/media/media.h"
#include "sw/surf/image_io.h"
#include "sw/surf/surf.h"

namespace surfvp {
namespace fs = std::filesystem;
namespace {

// A frame's size as the chip takes it: surf.width x surf.height when both are set.
cv::Size chip_size(const Config& c, cv::Size frame) {
    const SurfWorkloadSettings s = surf_settings(c);
    return s.width && s.height ? cv::Size(int(s.width), int(s.height)) : frame;
}

cv::Mat as_the_chip_takes(const Config& c, const cv::Mat& frame) {
    const cv::Size size = chip_size(c, frame.size());
    if (frame.size() == size) return frame;
    cv::Mat resized;
    cv::resize(frame, resized, size, 0, 0, cv::INTER_AREA);
    return resized;
}

// The largest frame the IIG and the FHG take, by key, beside a frame's size.
struct ChipLimit {
    const char* key;
    unsigned limit, pixels;
};
std::array<ChipLimit, 4> chip_limits(const Config& c, cv::Size size) {
    const Iig::Params iig = iig_params(c);
    const Fhg::Params fhg = fhg_params(c);
    const auto w = unsigned(size.width), h = unsigned(size.height);
    return {{{"iig.max_width", iig.max_width, w},
             {"iig.max_height", iig.max_height, h},
             {"fhg.max_width", fhg.max_width, w},
             {"fhg.max_height", fhg.max_height, h}}};
}

// Frames the chip can take: at least the filters' minimum (the float reference that
// calibrates the threshold runs on frame 0), at most what the IIG and FHG accept.
void check_frame_size(const Config& c, const SourceFrames& f) {
    const int side = surf::minimum_image_side(chip_surf_params(c));
    const bool resized = f.first.size() != f.original;
    const bool alike = std::all_of(f.sizes.begin(), f.sizes.end(), [&](const cv::Size& s) { return s == f.sizes[0]; });
    const std::string where = resized ? c.where("surf.width") : c.where("surf.source");
    for (size_t i = 0; i < f.sizes.size(); ++i) {
        const cv::Size size = f.sizes[i];
        if (i > 0 && size == f.sizes[i - 1]) continue;
        const std::string what =
            resized ? fmt::format("frames resized to {}x{} (surf.width x surf.height) are", size.width, size.height)
            : alike ? fmt::format("frames of {}x{} are", size.width, size.height)
                    : fmt::format("frame {} ({}) of {}x{} is", i, f.files[i].string(), size.width, size.height);
        if (size.width < side || size.height < side)
            throw ConfigError(fmt::format("{}: {} too small: the first octave's largest filter needs at least {}x{}",
                                          where, what, side, side));
        for (const auto& [key, limit, pixels] : chip_limits(c, size))
            if (pixels > limit)
                throw ConfigError(fmt::format("{}: {} larger than the chip takes: {} is {} (from {})", where, what, key,
                                              limit, c.source_of(key)));
    }
}

// A sequence's frames (a folder, a list or a video), decoded in order.
eval::SequenceReader open_frames(const Config& c) {
    const SurfWorkloadSettings s = surf_settings(c);
    return eval::SequenceReader(eval::open_sequence(s.source, s.frames));
}

// Every frame of a sequence decoded once: its file, and its size against frame 0's.
void read_sequence(const Config& c, SourceFrames& out) {
    const std::string source = surf_settings(c).source;
    auto too_few = [&](size_t has) {
        return ConfigError(fmt::format("{}: surf.frames is {} (from {}), but {} has only {}", c.where("surf.source"),
                                       out.count, c.source_of("surf.frames"), source, has));
    };
    eval::SequenceReader reader = open_frames(c);
    if (reader.sequence().frames.size() < out.count) throw too_few(reader.sequence().frames.size());  // before decoding
    size_t n = 0;
    for (cv::Mat frame; n < out.count && reader.next(frame); ++n) {
        const fs::path& file = reader.sequence().frames[n].image;
        if (!file.empty()) out.files.push_back(file);
        if (n == 0) {
            out.first = frame.clone();
            out.original = frame.size();
        }
        out.sizes.push_back(chip_size(c, frame.size()));
    }
    if (n < out.count) throw too_few(n);
}

SourceFrames read_frames(const Config& c) {
    const std::string source = surf_settings(c).source;
    const std::string where = c.where("surf.source");
    std::error_code ec;
    const fs::file_status status = fs::status(source, ec);
    if (!fs::exists(status)) throw ConfigError(fmt::format("{}: {}: no such file or folder", where, source));
    // A FIFO or a device would be read until it ends, which may be never.
    if (!fs::is_regular_file(status) && !fs::is_directory(status))
        throw ConfigError(fmt::format("{}: {}: not a regular file or a folder", where, source));
    SourceFrames out;
    out.count = surf_settings(c).frames;
    try {
        surf::QuietDecoding quiet;
        if (fs::is_regular_file(status) &&
            (eval::is_image_file(source) || !media::read_image(source, cv::IMREAD_GRAYSCALE).empty())) {
            out.repeated = true;
            out.first = surf::load_gray(source, chip_surf_params(c));
            out.original = out.first.size();
            out.sizes.assign(out.count, chip_size(c, out.first.size()));
        } else {
            read_sequence(c, out);
        }
    } catch (const ConfigError&) {
        throw;
    } catch (const OutOfMemory&) {  // the machine's, not the source's fault
        throw;
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(fmt::format("reading the frames of {}", where));
    } catch (const cv::Exception& e) {
        if (e.code == cv::Error::StsNoMem) throw OutOfMemory(fmt::format("reading the frames of {}: {}", where, e.err));
        throw ConfigError(fmt::format("{}: {}", where, e.what()));
    } catch (const std::exception& e) {
        throw ConfigError(fmt::format("{}: {}", where, e.what()));
    }
    out.first = as_the_chip_takes(c, out.first);
    check_frame_size(c, out);
    return out;
}

}  // namespace

const cv::Mat& FrameStream::frame(size_t i) {
    if (source_.repeated || i == 0) return source_.first;
    if (!reader_ || i < reader_->position()) reader_.emplace(open_frames(config_));
    surf::QuietDecoding quiet;
    cv::Mat decoded;
    while (reader_->position() <= i)
        if (!reader_->next(decoded))
            throw std::runtime_error(
                fmt::format("{}: frame {} can no longer be read", surf_settings(config_).source, i));
    current_ = as_the_chip_takes(config_, decoded);
    return current_;
}

std::string source_key(const Config& c) {
    const SurfWorkloadSettings s = surf_settings(c);
    return fmt::format("{}|{}x{}", s.source, s.width, s.height);
}

const SourceFrames& load_source(const Config& c) {
    static std::map<std::string, SourceFrames> cache;
    const std::string key = fmt::format("{}|{}", source_key(c), surf_settings(c).frames);
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, read_frames(c)).first;
    return it->second;
}

void for_each_chip_frame(const Config& config, const std::function<void(size_t, const cv::Mat&)>& take) {
    const SourceFrames& source = load_source(config);
    FrameStream stream(config, source);
    for (size_t i = 0; i < source.count; ++i) take(i, stream.frame(i));
}

}  // namespace surfvp
