#pragma once
// A large zero-filled block for a modelled memory: untouched pages cost nothing (as with
// calloc), and the kernel is asked for 2 MB pages, so that a frame's buffers fault in a few
// hundred times instead of thousands (the page faults were ~5 % of a run's time).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace surfvp {

struct ZeroedMemoryRelease {
    size_t bytes = 0;
    void operator()(uint8_t* p) const;
};
using ZeroedMemory = std::unique_ptr<uint8_t[], ZeroedMemoryRelease>;

// Throws std::runtime_error naming `what` and the size when the block cannot be had.
ZeroedMemory zeroed_memory(size_t bytes, const std::string& what);

}  // namespace surfvp
