// libsurfvp_media.so: the OpenCV codec calls behind media.h, with C linkage so that the loader
// finds them by name. Built as a module of its own; only it links imgcodecs and videoio.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "sw/media/plugin_abi.h"

extern "C" {

void surfvp_media_read_image(const std::string* path, int flags, cv::Mat* out) { *out = cv::imread(*path, flags); }

bool surfvp_media_encode_image(const std::string* extension, const cv::Mat* image, std::vector<unsigned char>* bytes) {
    try {
        return cv::imencode(*extension, *image, *bytes);
    } catch (const cv::Exception&) {  // no encoder for the extension
        return false;
    }
}

void* surfvp_media_video_open(const std::string* path) {
    auto* video = new cv::VideoCapture(*path);
    if (video->isOpened()) return video;
    delete video;
    return nullptr;
}

bool surfvp_media_video_grab(void* video) { return static_cast<cv::VideoCapture*>(video)->grab(); }

bool surfvp_media_video_read(void* video, cv::Mat* frame) {
    return static_cast<cv::VideoCapture*>(video)->read(*frame);
}

void surfvp_media_video_close(void* video) { delete static_cast<cv::VideoCapture*>(video); }

}  // extern "C"
