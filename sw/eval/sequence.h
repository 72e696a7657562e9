#pragma once
// Image sequences for the evaluation: a folder of images, a text file listing image paths, or a
// video file, each with an optional frame limit. open_sequence lists the frames; SequenceReader
// decodes them in order (a video is read once, front to back).
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <memory>

#include <opencv2/core/mat.hpp>
#include <opencv2/imgcodecs.hpp>  // cv::IMREAD_*

#include "sw/eval/format_error.h"
#include "sw/media/media.h"

namespace surfvp::eval {

enum class SequenceKind { image_folder, image_list, video };

struct SequenceFrame {
    std::size_t index = 0;
    std::string name;             // the image's file name, or "<video file name>#<index>"
    std::filesystem::path image;  // empty for video frames
};

struct Sequence {
    SequenceKind kind = SequenceKind::image_folder;
    std::filesystem::path source;
    std::vector<SequenceFrame> frames;
};

// Whether a file's extension is one of the image extensions below (any case).
bool is_image_file(const std::filesystem::path& file);

// The image files of a folder (extensions .pgm .ppm .pnm .pbm .png .jpg .jpeg .bmp .tif .tiff
// .webp, any case), sorted by file name (byte order). Throws std::runtime_error naming the
// folder when it does not exist.
std::vector<std::filesystem::path> list_image_folder(const std::filesystem::path& folder);

// One image path per line; relative paths are relative to the list file's folder; blank lines
// and '#' comments are ignored; leading and trailing blanks are trimmed. Throws FormatError
// naming the list file and line of a path that does not exist.
std::vector<std::filesystem::path> read_image_list(const std::filesystem::path& list_file);

// A folder, a list file (extension .txt or .lst) or any other file that cv::VideoCapture opens
// (media::Video).
// `max_frames` 0 takes every frame. Video frames are counted by decoding them. Throws
// std::runtime_error naming the source when it is none of these or holds no frame.
Sequence open_sequence(const std::filesystem::path& source, std::size_t max_frames = 0);

class SequenceReader {
public:
    // `imread_flags` as for cv::imread; video frames are converted to grey for
    // cv::IMREAD_GRAYSCALE and left as decoded (BGR) otherwise.
    explicit SequenceReader(Sequence sequence, int imread_flags = cv::IMREAD_GRAYSCALE);

    // The next frame into `image`; false after the last. Throws std::runtime_error naming the
    // frame that cannot be decoded.
    bool next(cv::Mat& image);

    std::size_t position() const { return next_; }  // index of the frame next() reads
    const Sequence& sequence() const { return sequence_; }

private:
    Sequence sequence_;
    int flags_;
    std::size_t next_ = 0;
    std::unique_ptr<media::Video> video_;  // opened on the first video frame
};

}  // namespace surfvp::eval
