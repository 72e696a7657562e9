#pragma once
// SSA FHG registers and the determinant buffer's layout: the contract between the model
// and libSSA2. 32-bit registers, big-endian on the bus (models/common/byte_order.h).
#include <cstdint>

#include "models/common/byte_order.h"
#include "models/common/register_bank.h"

namespace surfvp::fhg_regs {

constexpr uint32_t CTRL = 0x00;  // START, IRQ_EN_DONE, IRQ_EN_FIFO, ABORT, RESET
constexpr uint32_t STATUS =
    0x04;  // BUSY, DONE, ERROR, FIFO_OVERFLOW, FIFO_IRQ; write 1 to clear DONE/ERROR/FIFO_OVERFLOW
constexpr uint32_t ERROR_CODE = 0x08;      // ErrorCode of the last ERROR (read only)
constexpr uint32_t DET_ADDR = 0x0C;        // determinant buffer (bus address on PLB2)
constexpr uint32_t WIDTH = 0x10;           // pixels
constexpr uint32_t HEIGHT = 0x14;          // rows
constexpr uint32_t THRESHOLD = 0x18;       // signed, in determinant units (fixed point, det_frac_bits)
constexpr uint32_t FIFO_DATA = 0x1C;       // reading pops one candidate word (bit 31 clear: FIFO was empty)
constexpr uint32_t FIFO_LEVEL = 0x20;      // candidates waiting (read only)
constexpr uint32_t FIFO_THRESHOLD = 0x24;  // FIFO_IRQ while FIFO_LEVEL >= this (0: never)
constexpr uint32_t OVERFLOW_COUNT = 0x28;  // candidates dropped on a full FIFO this frame (read only)
constexpr uint32_t CANDIDATES = 0x2C;      // candidates marked this frame (read only)
constexpr uint32_t DET_FRAC_BITS = 0x30;   // fraction bits of determinants and THRESHOLD (read only)
constexpr uint32_t DET_BYTES = 0x34;       // bytes of one determinant in the buffer: 1, 2 or 4 (read only)

constexpr uint32_t CTRL_START = 1u << 0;
constexpr uint32_t CTRL_IRQ_EN_DONE = 1u << 1;
constexpr uint32_t CTRL_IRQ_EN_FIFO = 1u << 2;
constexpr uint32_t CTRL_ABORT = 1u << 3;
constexpr uint32_t CTRL_RESET = 1u << 4;  // back to idle (see the table)

constexpr uint32_t STATUS_BUSY = 1u << 0;
constexpr uint32_t STATUS_DONE = 1u << 1;
constexpr uint32_t STATUS_ERROR = 1u << 2;
constexpr uint32_t STATUS_FIFO_OVERFLOW = 1u << 3;
constexpr uint32_t STATUS_FIFO_IRQ = 1u << 4;  // FIFO_LEVEL >= FIFO_THRESHOLD (read only)

enum ErrorCode : uint32_t {
    ERR_NONE = 0,
    ERR_WRITE = 1,       // a determinant DMA write got an error response
    ERR_SIZE = 2,        // WIDTH or HEIGHT zero or above the maximum
    ERR_START_BUSY = 3,  // START while a frame was running (ignored)
    ERR_ABORTED = 4,     // CTRL.ABORT
    ERR_PIXELBUS = 5,    // a PixelBus line of another width than WIDTH
};

// The same registers as a table: the model and direct mode behave by it (FhgRegisters),
// docs/registers.md is generated from it.
inline const RegisterTable& table() {
    static const RegisterTable t{
        "SSA FHG",
        "One frame: integral lines in over PixelBus, determinant records out to memory, local maxima into the maxima "
        "FIFO.",
        {{"CTRL",
          CTRL,
          Access::RW,
          0,
          "commands and interrupt enables",
          {{"START", 0, 1, Access::command,
            "listen for a frame with the registers as they are (ERROR START_BUSY while busy)"},
           {"IRQ_EN_DONE", 1, 1, Access::RW, "raise the interrupt while DONE or ERROR"},
           {"IRQ_EN_FIFO", 2, 1, Access::RW, "raise the interrupt while FIFO_IRQ"},
           {"ABORT", 3, 1, Access::command, "stop the frame in progress (ERROR ABORTED)"},
           {"RESET", 4, 1, Access::command,
            "back to idle: a frame in progress is aborted (as ABORT), one that never ended is dropped; once idle, "
            "STATUS "
            "and ERROR_CODE are cleared and the maxima FIFO emptied"}}},
         {"STATUS",
          STATUS,
          Access::W1C,
          0,
          "the frame's state and the maxima FIFO's",
          {{"BUSY", 0, 1, Access::RO, "a frame is running"},
           {"DONE", 1, 1, Access::W1C, "the last frame ended well"},
           {"ERROR", 2, 1, Access::W1C, "a command was refused or the frame failed (ERROR_CODE says why)"},
           {"FIFO_OVERFLOW", 3, 1, Access::W1C, "a candidate was dropped on a full maxima FIFO"},
           {"FIFO_IRQ", 4, 1, Access::RO, "FIFO_LEVEL >= FIFO_THRESHOLD (FIFO_THRESHOLD > 0)"}}},
         {"ERROR_CODE",
          ERROR_CODE,
          Access::RO,
          ERR_NONE,
          "why ERROR was set: 1 write, 2 size, 3 START while busy, 4 aborted, 5 PixelBus line of another width",
          {}},
         {"DET_ADDR",
          DET_ADDR,
          Access::RW,
          0,
          "determinant buffer (bus address on PLB2; layout below the table in fhg_regs.h)",
          {}},
         {"WIDTH", WIDTH, Access::RW, 0, "pixels (1 to fhg.max_width)", {}},
         {"HEIGHT", HEIGHT, Access::RW, 0, "rows (1 to fhg.max_height)", {}},
         {"THRESHOLD", THRESHOLD, Access::RW, 0, "signed, in determinant units (fixed point, DET_FRAC_BITS)", {}},
         {"FIFO_DATA",
          FIFO_DATA,
          Access::RO,
          0,
          "reading pops one candidate: [31] valid, [27] octave 2, [26:24] size index into 9, 15, 21, 27, 39, 51, "
          "[23:12] y, [11:0] x (bit 31 clear: the FIFO was empty)",
          {}},
         {"FIFO_LEVEL", FIFO_LEVEL, Access::RO, 0, "candidates waiting (at most fhg.maxima_fifo_depth)", {}},
         {"FIFO_THRESHOLD", FIFO_THRESHOLD, Access::RW, 0, "FIFO_IRQ while FIFO_LEVEL >= this (0: never)", {}},
         {"OVERFLOW_COUNT", OVERFLOW_COUNT, Access::RO, 0, "candidates dropped on a full FIFO this frame", {}},
         {"CANDIDATES", CANDIDATES, Access::RO, 0, "candidates marked this frame (kept and dropped)", {}},
         {"DET_FRAC_BITS",
          DET_FRAC_BITS,
          Access::RO,
          0,
          "fraction bits of determinants and THRESHOLD (fhg.det_frac_bits)",
          {}},
         {"DET_BYTES",
          DET_BYTES,
          Access::RO,
          0,
          "bytes of one determinant in the buffer: 1, 2 or 4 (from fhg.det_bits)",
          {}}}};
    return t;
}

// The determinant buffer: one record of 18 determinants per 2x2 block, blocks in raster order
// (record of block (bx, by) at DET_ADDR + (by x ceil(WIDTH/2) + bx) x record_bytes). Each
// determinant is a signed big-endian word of DET_BYTES bytes: the smallest of 1, 2 or 4 that
// holds the FHG's det_bits. Index k within a record:
//   k = 4 i + 2 py + px  octave 1, size 9, 15, 21, 27 (i = 0..3) at pixel (2 bx + px, 2 by + py)
//   k = 16, 17           octave 2, size 39, 51 at pixel (2 bx, 2 by)
// (octave 2's sizes 15 and 27 are k = 4 and k = 12). A determinant whose filter does not
// fit inside the image is 0.
constexpr uint32_t kDeterminantsPerRecord = 18;
constexpr uint32_t det_bytes_for(unsigned det_bits) { return det_bits <= 8 ? 1 : det_bits <= 16 ? 2 : 4; }
constexpr uint32_t record_bytes(uint32_t det_bytes) { return kDeterminantsPerRecord * det_bytes; }
// One block row of records (a frame `width` pixels wide), and a whole frame's buffer.
constexpr uint32_t row_bytes(uint32_t width, uint32_t det_bytes) { return (width + 1) / 2 * record_bytes(det_bytes); }
constexpr uint64_t buffer_bytes(uint32_t width, uint32_t height, uint32_t det_bytes) {
    return uint64_t(row_bytes(width, det_bytes)) * ((height + 1) / 2);
}

inline void store_det(uint8_t* p, int32_t value, uint32_t det_bytes) {
    if (det_bytes == 4)
        store_be32(p, uint32_t(value));
    else if (det_bytes == 2)
        store_be16(p, uint16_t(value));
    else
        p[0] = uint8_t(value);
}

// A run of determinants as the writer stores them.
inline void store_dets(uint8_t* p, const int32_t* values, size_t count, uint32_t det_bytes) {
    if (det_bytes == 4)
        return store_be32_run(p, reinterpret_cast<const uint32_t*>(values), count);  // signed/unsigned may alias
    for (size_t k = 0; k < count; ++k) store_det(p + det_bytes * k, values[k], det_bytes);
}

inline int32_t load_det(const uint8_t* p, uint32_t det_bytes) {
    if (det_bytes == 4) return int32_t(load_be32(p));
    if (det_bytes == 2) return int16_t(load_be16(p));
    return int8_t(p[0]);
}

// Maxima FIFO word: [31] valid, [27] octave 2, [26:24] size index into 9, 15, 21, 27, 39, 51,
// [23:12] y, [11:0] x (pixel of the candidate).

}  // namespace surfvp::fhg_regs
