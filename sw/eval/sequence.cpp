#include "sw/eval/sequence.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <stdexcept>
#include <string_view>

#include <opencv2/imgproc.hpp>

#include "sw/eval/text_io.h"

namespace surfvp::eval {

namespace {

std::string lower_extension(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string trim(const std::string& s) {
    auto first = s.find_first_not_of(" \t\r\n\v\f");
    if (first == std::string::npos) return {};
    auto last = s.find_last_not_of(" \t\r\n\v\f");
    return s.substr(first, last - first + 1);
}

void limit(std::vector<std::filesystem::path>& images, std::size_t max_frames) {
    if (max_frames > 0 && images.size() > max_frames) images.resize(max_frames);
}

Sequence image_sequence(SequenceKind kind, const std::filesystem::path& source,
                        const std::vector<std::filesystem::path>& images) {
    Sequence s{kind, source, {}};
    for (std::size_t i = 0; i < images.size(); ++i) {
        s.frames.push_back({i, images[i].filename().string(), images[i]});
    }
    return s;
}

Sequence video_sequence(const std::filesystem::path& source, std::size_t max_frames) {
    media::Video video(source.string());
    if (!video.opened()) {
        throw std::runtime_error(source.string() +
                                 ": not a folder, an image list (.txt, .lst) or a video that "
                                 "OpenCV can open");
    }
    Sequence s{SequenceKind::video, source, {}};
    std::string stem = source.filename().string();
    while ((max_frames == 0 || s.frames.size() < max_frames) && video.grab()) {
        std::size_t i = s.frames.size();
        s.frames.push_back({i, stem + "#" + std::to_string(i), {}});
    }
    if (s.frames.empty()) throw std::runtime_error(source.string() + ": the video has no frame");
    return s;
}

}  // namespace

bool is_image_file(const std::filesystem::path& file) {
    static constexpr std::array<std::string_view, 11> kExtensions = {".pgm",  ".ppm", ".pnm", ".pbm",  ".png", ".jpg",
                                                                     ".jpeg", ".bmp", ".tif", ".tiff", ".webp"};
    std::string ext = lower_extension(file);
    return std::any_of(kExtensions.begin(), kExtensions.end(), [&](std::string_view e) { return ext == e; });
}

std::vector<std::filesystem::path> list_image_folder(const std::filesystem::path& folder) {
    if (!std::filesystem::is_directory(folder)) {
        throw std::runtime_error(folder.string() + ": no such folder");
    }
    std::vector<std::filesystem::path> images;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        if (entry.is_regular_file() && is_image_file(entry.path())) images.push_back(entry.path());
    }
    std::sort(images.begin(), images.end(),
              [](const auto& x, const auto& y) { return x.filename().string() < y.filename().string(); });
    return images;
}

std::vector<std::filesystem::path> read_image_list(const std::filesystem::path& list_file) {
    TextReader reader(list_file, /*comments=*/true);
    std::vector<std::string_view> tokens;
    std::vector<std::filesystem::path> images;
    while (reader.next(tokens)) {
        std::filesystem::path image = trim(reader.text());
        if (image.is_relative()) image = list_file.parent_path() / image;
        if (!std::filesystem::exists(image)) reader.fail("image '" + image.string() + "' does not exist");
        if (!std::filesystem::is_regular_file(image))
            reader.fail("image '" + image.string() + "' is not a regular file");
        images.push_back(image);
    }
    return images;
}

Sequence open_sequence(const std::filesystem::path& source, std::size_t max_frames) {
    if (std::filesystem::is_directory(source)) {
        auto images = list_image_folder(source);
        if (images.empty()) throw std::runtime_error(source.string() + ": no image files in the folder");
        limit(images, max_frames);
        return image_sequence(SequenceKind::image_folder, source, images);
    }
    if (!std::filesystem::exists(source)) {
        throw std::runtime_error(source.string() + ": no such file or folder");
    }
    // A FIFO or a device would be read until it ends, which may be never.
    if (!std::filesystem::is_regular_file(source)) {
        throw std::runtime_error(source.string() + ": not a regular file or a folder");
    }
    std::string ext = lower_extension(source);
    if (ext == ".txt" || ext == ".lst") {
        auto images = read_image_list(source);
        if (images.empty()) throw std::runtime_error(source.string() + ": the list names no image");
        limit(images, max_frames);
        return image_sequence(SequenceKind::image_list, source, images);
    }
    return video_sequence(source, max_frames);
}

SequenceReader::SequenceReader(Sequence sequence, int imread_flags)
    : sequence_(std::move(sequence)), flags_(imread_flags) {}

bool SequenceReader::next(cv::Mat& image) {
    if (next_ >= sequence_.frames.size()) return false;
    const SequenceFrame& frame = sequence_.frames[next_];
    if (sequence_.kind != SequenceKind::video) {
        std::error_code ec;
        if (std::filesystem::file_size(frame.image, ec) == 0 && !ec)
            throw std::runtime_error(frame.image.string() + ": the image file is empty (0 bytes)");
        image = media::read_image(frame.image.string(), flags_);
        if (image.empty()) throw std::runtime_error(frame.image.string() + ": cannot decode the image");
    } else {
        if (!video_) video_ = std::make_unique<media::Video>(sequence_.source.string());
        if (!video_->opened()) throw std::runtime_error(sequence_.source.string() + ": cannot reopen the video");
        cv::Mat decoded;
        if (!video_->read(decoded) || decoded.empty()) {
            throw std::runtime_error(sequence_.source.string() + ": cannot decode frame " + std::to_string(next_));
        }
        if (flags_ == cv::IMREAD_GRAYSCALE && decoded.channels() == 3) {
            cv::cvtColor(decoded, image, cv::COLOR_BGR2GRAY);
        } else {
            image = decoded;
        }
    }
    ++next_;
    return true;
}

}  // namespace surfvp::eval
