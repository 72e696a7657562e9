#pragma once
// The one byte order of surfvp (docs/architecture.md#principles, 9). The PPC440 and the PLB are big-endian:
// memory holds bytes in address order, and a 32-bit word at address A has its most
// significant byte at A. Every TLM payload's data array is in that same address order
// (byte i of the array is the byte at address + i), so a memory-to-memory copy is a plain
// byte copy and needs no swapping. Only code that turns bytes into numbers (register
// slaves, the CPU stub's MMIO and word accesses) converts, through these helpers.
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace surfvp {

inline uint32_t load_be32(const uint8_t* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

inline void store_be32(uint8_t* p, uint32_t v) {
    p[0] = uint8_t(v >> 24);
    p[1] = uint8_t(v >> 16);
    p[2] = uint8_t(v >> 8);
    p[3] = uint8_t(v);
}

// `count` words stored from `p` on (byte_order.cpp): byte swaps of 16 words at a time into a
// word array, which the compiler vectorises (a loop of memcpy'd single words it does not).
void store_be32_run(uint8_t* p, const uint32_t* words, size_t count);

inline uint16_t load_be16(const uint8_t* p) { return uint16_t(p[0] << 8 | p[1]); }

inline void store_be16(uint8_t* p, uint16_t v) {
    p[0] = uint8_t(v >> 8);
    p[1] = uint8_t(v);
}

}  // namespace surfvp
