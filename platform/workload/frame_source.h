#pragma once
// The frames surf.source names (one image, a folder, a list or a video), as the chip takes
// them: grey, resized to surf.width x surf.height when both are set.
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sw/eval/sequence.h"

namespace surfvp {

class Config;

// Every frame is decoded and checked once before anything is
// built, and none is kept but frame 0 (the threshold's calibration, the report's picture): a
// run decodes each again as it arrives (FrameStream), so host memory does not grow with the
// frames either.
struct SourceFrames {
    size_t count = 0;
    bool repeated = false;                     // one image, every frame
    cv::Mat first;                             // frame 0 as the chip takes it
    std::vector<std::filesystem::path> files;  // each frame's file; empty for a video or one repeated image
    cv::Size original;                         // frame 0 before resizing
    std::vector<cv::Size> sizes;  // each frame's size as the chip takes it (images of a folder or list may differ)
    cv::Size largest() const {
        cv::Size most;
        for (const cv::Size& s : sizes) most = cv::Size(std::max(most.width, s.width), std::max(most.height, s.height));
        return most;
    }
};

// The frames of `c`'s source, read and checked once per process and source (the verdict's
// re-simulations are forked from one process and inherit them). Throws ConfigError naming
// surf.source (or surf.width) for a source that is missing, unreadable, too short, or has
// frames the filters or the chip cannot take.
const SourceFrames& load_source(const Config& c);

// The source and the size its frames are taken at: the key of what is computed from frame 0
// once per process.
std::string source_key(const Config& c);

// The frames of a run as they arrive, in order; one decoded at a time.
class FrameStream {
public:
    FrameStream(const Config& c, const SourceFrames& source) : config_(c), source_(source) {}

    // Frame i as the chip takes it: the next after the one before (a frame before it starts
    // the sequence again).
    const cv::Mat& frame(size_t i);

private:
    const Config& config_;
    const SourceFrames& source_;
    std::optional<eval::SequenceReader> reader_;
    cv::Mat current_;
};

}  // namespace surfvp
