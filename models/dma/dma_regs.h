#pragma once
// Registers of the standalone memory-to-memory DMA (the smoke scenario's test master): the
// contract between the model and the software. 32-bit registers, big-endian on the bus.
#include <cstdint>

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
    ERR_READ = 1,           // a read burst got an error response
    ERR_WRITE = 2,          // a write burst got an error response
    ERR_START_BUSY = 3,     // START written while a copy was running (ignored)
    ERR_ZERO_LENGTH = 4,    // START with LEN = 0
};

}  // namespace surfvp::dma
