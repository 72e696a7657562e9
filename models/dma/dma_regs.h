#pragma once
// Registers of the standalone memory-to-memory DMA (the smoke scenario's test master): the
// contract between the model and the software. 32-bit registers, big-endian on the bus.
#include <cstdint>

#include "models/common/register_bank.h"

namespace surfvp::dma {

constexpr uint32_t CTRL = 0x00;        // write START to begin a copy; IRQ_EN enables the interrupt
constexpr uint32_t STATUS = 0x04;      // BUSY, DONE, ERROR; write 1 to DONE or ERROR to clear it
constexpr uint32_t SRC = 0x08;         // source address (bus address on the DMA's PLB)
constexpr uint32_t DST = 0x0C;         // destination address
constexpr uint32_t LEN = 0x10;         // bytes to copy
constexpr uint32_t ERROR_CODE = 0x14;  // why ERROR was set (read only)
constexpr uint32_t ERROR_ADDR = 0x18;  // the bus address that failed (read only)

constexpr uint32_t CTRL_START = 1u << 0;
constexpr uint32_t CTRL_IRQ_EN = 1u << 1;

constexpr uint32_t STATUS_BUSY = 1u << 0;
constexpr uint32_t STATUS_DONE = 1u << 1;
constexpr uint32_t STATUS_ERROR = 1u << 2;

enum ErrorCode : uint32_t {
    ERR_NONE = 0,
    ERR_READ = 1,         // a read burst got an error response
    ERR_WRITE = 2,        // a write burst got an error response
    ERR_START_BUSY = 3,   // START written while a copy was running (ignored)
    ERR_ZERO_LENGTH = 4,  // START with LEN = 0
};

// The same registers as a table: the model behaves by it, docs/registers.md is generated from it.
inline const RegisterTable& table() {
    static const RegisterTable t{
        "Test DMA",
        "A memory-to-memory copy over PLB2 (the smoke scenario's test master).",
        {{"CTRL",
          CTRL,
          Access::RW,
          0,
          "command and interrupt enable",
          {{"START", 0, 1, Access::command, "begin a copy (ERROR START_BUSY while busy, ZERO_LENGTH for LEN = 0)"},
           {"IRQ_EN", 1, 1, Access::RW, "raise the interrupt while DONE or ERROR"}}},
         {"STATUS",
          STATUS,
          Access::W1C,
          0,
          "the copy's state",
          {{"BUSY", 0, 1, Access::RO, "a copy is running"},
           {"DONE", 1, 1, Access::W1C, "the last copy ended well"},
           {"ERROR", 2, 1, Access::W1C, "a command was refused or the copy failed"}}},
         {"SRC", SRC, Access::RW, 0, "source address (bus address on PLB2)", {}},
         {"DST", DST, Access::RW, 0, "destination address", {}},
         {"LEN", LEN, Access::RW, 0, "bytes to copy", {}},
         {"ERROR_CODE",
          ERROR_CODE,
          Access::RO,
          ERR_NONE,
          "why ERROR was set: 1 read, 2 write, 3 START while busy, 4 zero length",
          {}},
         {"ERROR_ADDR", ERROR_ADDR, Access::RO, 0, "the bus address that failed", {}}}};
    return t;
}

}  // namespace surfvp::dma
