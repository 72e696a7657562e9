#pragma once
// SSA IIG registers: the contract between the model and libSSA2. 32-bit, big-endian.
#include <cstdint>

namespace surfvp::iig {

constexpr uint32_t CTRL = 0x00;          // START, IRQ_EN, STREAM, ABORT
constexpr uint32_t STATUS = 0x04;        // BUSY, DONE, ERROR; write 1 to DONE/ERROR to clear
constexpr uint32_t ERROR_CODE = 0x08;    // ErrorCode of the last ERROR (read only)
constexpr uint32_t SRC = 0x0C;           // 8-bit image in memory (bus address on PLB2)
constexpr uint32_t DST = 0x10;           // integral image in memory: 32-bit big-endian words
constexpr uint32_t WIDTH = 0x14;         // pixels
constexpr uint32_t HEIGHT = 0x18;        // rows
constexpr uint32_t SRC_STRIDE = 0x1C;    // bytes from one image row to the next
constexpr uint32_t DST_STRIDE = 0x20;    // bytes from one integral row to the next
constexpr uint32_t STALL_CYCLES = 0x24;  // IIG cycles the last frame waited on PixelBus back-pressure (read only)

constexpr uint32_t CTRL_START = 1u << 0;
constexpr uint32_t CTRL_IRQ_EN = 1u << 1;
constexpr uint32_t CTRL_STREAM = 1u << 2;  // also send each line over PixelBus to the FHG
constexpr uint32_t CTRL_ABORT = 1u << 3;   // stop the frame in progress (status ERROR, code ABORTED)

constexpr uint32_t STATUS_BUSY = 1u << 0;
constexpr uint32_t STATUS_DONE = 1u << 1;
constexpr uint32_t STATUS_ERROR = 1u << 2;

enum ErrorCode : uint32_t {
    ERR_NONE = 0,
    ERR_READ = 1,        // a DMA read got an error response
    ERR_WRITE = 2,       // a DMA write got an error response
    ERR_OVERFLOW = 3,    // a sum exceeded the integral word's significant bits
    ERR_SIZE = 4,        // WIDTH or HEIGHT zero or above the maximum
    ERR_START_BUSY = 5,  // START while a frame was running (ignored)
    ERR_ABORTED = 6,     // CTRL.ABORT
};

}  // namespace surfvp::iig
