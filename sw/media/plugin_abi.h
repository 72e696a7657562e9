#pragma once
// The functions libsurfvp_media.so exports (media_plugin.cpp) and the loader looks up by name
// (media.cpp). Both sides are built by the same compiler in the same build, so C++ types pass
// through the C linkage by pointer.
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

extern "C" {
void surfvp_media_read_image(const std::string* path, int flags, cv::Mat* out);
bool surfvp_media_encode_image(const std::string* extension, const cv::Mat* image, std::vector<unsigned char>* bytes);
void* surfvp_media_video_open(const std::string* path);
bool surfvp_media_video_grab(void* video);
bool surfvp_media_video_read(void* video, cv::Mat* frame);
void surfvp_media_video_close(void* video);
}
