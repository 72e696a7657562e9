#include "byte_order.h"

namespace surfvp {

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void store_be32_run(uint8_t* p,
                                                                                                  const uint32_t* words,
                                                                                                  size_t count) {
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the host's words are swapped into the PLB's byte order");
    constexpr size_t kChunk = 16;
    size_t k = 0;
    for (; k + kChunk <= count; k += kChunk) {
        uint32_t swapped[kChunk];
        for (size_t i = 0; i < kChunk; ++i) swapped[i] = __builtin_bswap32(words[k + i]);
        std::memcpy(p + 4 * k, swapped, sizeof swapped);
    }
    for (; k < count; ++k) {
        const uint32_t word = __builtin_bswap32(words[k]);
        std::memcpy(p + 4 * k, &word, 4);
    }
}

}  // namespace surfvp
