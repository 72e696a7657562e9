#pragma once
// The files between `surfvp calibrate` and the PPC440 build of the software stage
// (firmware/stage_firmware.cpp). Each field is stored as the PPC440 holds it in memory:
// big-endian, so the firmware reads its structs directly and the host converts
// (calibrate.cpp). An input is a series of frames: a FrameHeader, the integral image as the IIG
// left it in DDR, the FHG's determinant records, then the maxima-FIFO words in the order the
// driver read them. The output has one Result per word.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "models/common/byte_order.h"
#include "sw/stage/software_stage.h"
#include "sw/surf/keypoint.h"

namespace surfvp::sw::calibration_dump {

constexpr uint32_t kMagic = 0x53565046;  // "SVPF"

struct FrameHeader {
    uint32_t magic;
    uint32_t width, height;
    uint32_t det_frac_bits, det_bytes;
    uint32_t rounded_haar, upright, msurf;
    float threshold, max_offset;
    uint32_t integral_address, determinants_address;
    uint32_t integral_bytes, determinant_bytes, words;
};

struct Result {
    uint32_t keypoint;  // 1 when the word became a keypoint
    float x, y, scale, response, orientation;
    int32_t laplacian;
    float descriptor[64];
};

// What the stage was given for this frame, back from its header (host order).
inline StageParams stage_params(const FrameHeader& h) {
    StageParams p;
    p.upright = h.upright != 0;
    p.haar = h.rounded_haar ? surf::HaarMode::rounded : surf::HaarMode::exact;
    p.threshold = h.threshold;
    p.max_offset = h.max_offset;
    p.descriptor = h.msurf ? surf::DescriptorKind::msurf : surf::DescriptorKind::surf;
    return p;
}
inline FrameBuffers frame_buffers(const FrameHeader& h, const uint8_t* integral, const uint8_t* determinants) {
    return {integral,     h.integral_address, size_t(h.width) * 4, determinants, h.determinants_address,
            int(h.width), int(h.height),      h.det_frac_bits,     h.det_bytes};
}

// Every field above is a 32-bit word: a struct goes between host and PPC440 order word by
// word (the same call both ways).
template <class T>
void swap_words_to_big_endian(T& value) {
    static_assert(sizeof(T) % 4 == 0, "32-bit fields only");
    auto* bytes = reinterpret_cast<uint8_t*>(&value);
    for (size_t i = 0; i < sizeof(T); i += 4) {
        uint32_t w;
        std::memcpy(&w, bytes + i, 4);
        store_be32(bytes + i, w);
    }
}

inline void fill(Result& r, const surf::Keypoint& kp) {
    r.keypoint = 1;
    r.x = kp.x;
    r.y = kp.y;
    r.scale = kp.scale;
    r.response = kp.response;
    r.orientation = kp.orientation;
    r.laplacian = kp.laplacian;
    for (int i = 0; i < 64; ++i) r.descriptor[i] = kp.descriptor[size_t(i)];
}

}  // namespace surfvp::sw::calibration_dump
