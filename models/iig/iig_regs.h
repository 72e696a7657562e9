#pragma once
// SSA IIG registers: the contract between the model and libSSA2. 32-bit, big-endian.
#include <cstdint>

#include "models/common/register_bank.h"

namespace surfvp::iig {

constexpr uint32_t CTRL = 0x00;          // START, IRQ_EN, STREAM, ABORT, RESET
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
constexpr uint32_t CTRL_RESET = 1u << 4;   // back to idle (see the table)

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

// The same registers as a table: the model and direct mode behave by it (IigRegisters),
// docs/registers.md is generated from it.
inline const RegisterTable& table() {
    static const RegisterTable t{
        "SSA IIG",
        "One frame: an 8-bit image in memory in, its integral image out to memory and (STREAM) over PixelBus.",
        {{"CTRL",
          CTRL,
          Access::RW,
          0,
          "commands and interrupt enable",
          {{"START", 0, 1, Access::command,
            "begin a frame with the registers as they are (ERROR START_BUSY while busy)"},
           {"IRQ_EN", 1, 1, Access::RW, "raise the interrupt while DONE or ERROR"},
           {"STREAM", 2, 1, Access::RW, "also send each integral line over PixelBus to the FHG"},
           {"ABORT", 3, 1, Access::command, "stop the frame in progress (ERROR ABORTED)"},
           {"RESET", 4, 1, Access::command,
            "back to idle: a frame in progress is aborted (as ABORT), one that never ended is dropped; once idle, "
            "STATUS "
            "and ERROR_CODE are cleared"}}},
         {"STATUS",
          STATUS,
          Access::W1C,
          0,
          "the frame's state",
          {{"BUSY", 0, 1, Access::RO, "a frame is running"},
           {"DONE", 1, 1, Access::W1C, "the last frame ended well"},
           {"ERROR", 2, 1, Access::W1C, "a command was refused or the frame failed (ERROR_CODE says why)"}}},
         {"ERROR_CODE",
          ERROR_CODE,
          Access::RO,
          ERR_NONE,
          "why ERROR was set: 1 read, 2 write, 3 sum overflow, 4 size, 5 START while busy, 6 aborted",
          {}},
         {"SRC", SRC, Access::RW, 0, "8-bit image in memory (bus address on PLB2)", {}},
         {"DST", DST, Access::RW, 0, "integral image in memory: 32-bit big-endian words", {}},
         {"WIDTH", WIDTH, Access::RW, 0, "pixels (1 to iig.max_width)", {}},
         {"HEIGHT", HEIGHT, Access::RW, 0, "rows (1 to iig.max_height)", {}},
         {"SRC_STRIDE", SRC_STRIDE, Access::RW, 0, "bytes from one image row to the next (0: WIDTH)", {}},
         {"DST_STRIDE", DST_STRIDE, Access::RW, 0, "bytes from one integral row to the next (0: 4 x WIDTH)", {}},
         {"STALL_CYCLES",
          STALL_CYCLES,
          Access::RO,
          0,
          "IIG cycles the last frame waited on PixelBus back-pressure (0 in direct mode, which has no time)",
          {}}}};
    return t;
}

}  // namespace surfvp::iig
