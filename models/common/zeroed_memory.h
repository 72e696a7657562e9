#pragma once
// A large zero-filled block for a modelled memory: untouched pages cost nothing (as with
// calloc), and the kernel is asked for 2 MB pages, so that a frame's buffers fault in a few
// hundred times instead of thousands (the page faults were ~5 % of a run's time).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "models/common/worker.h"

namespace surfvp {

struct ZeroedMemoryRelease {
    size_t bytes = 0;
    void operator()(uint8_t* p) const;
};
using ZeroedMemory = std::unique_ptr<uint8_t[], ZeroedMemoryRelease>;

// Throws std::runtime_error naming `what` and the size when the block cannot be had. The
// block starts on a 2 MB boundary, so its pages can all be 2 MB ones.
ZeroedMemory zeroed_memory(size_t bytes, const std::string& what);

// The allocator of a model's large buffers that are refilled every frame (integral lines,
// determinant rows): zeroed_memory's 2 MB pages, so a run's first frames fault them in a few
// times instead of a thousand (a page fault cost ~30 us on the virtual machine measured, and
// a 1024x768 frame's buffers are ~12 MB). Throws std::bad_alloc.
uint8_t* map_zeroed(size_t bytes);  // nullptr when it cannot be had
template <class T>
struct HugePageAllocator {
    using value_type = T;
    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) {}
    T* allocate(size_t n) {
        if (uint8_t* p = map_zeroed(n * sizeof(T))) return reinterpret_cast<T*>(p);
        throw std::bad_alloc();
    }
    void deallocate(T* p, size_t n) { ZeroedMemoryRelease{n * sizeof(T)}(reinterpret_cast<uint8_t*>(p)); }
    bool operator==(const HugePageAllocator&) const { return true; }
    bool operator!=(const HugePageAllocator&) const { return false; }
};
template <class T>
using FrameBuffer = std::vector<T, HugePageAllocator<T>>;

// Faults a block's pages in on a background thread just ahead of the writes that would
// fault them on the caller's (the kernel's) thread: a write reaching into a 2 MB page asks
// for the page after it. The kernel clears a page when it is first written, and those
// clears were ~5 % of the simulator's main thread (the FHG writer's buffers, the first frames
// of a run). Only the pages' residency changes, never their bytes (MADV_POPULATE_WRITE);
// without that call (kernels before 5.14) the writes fault as before.
class PopulateAhead {
public:
    PopulateAhead(uint8_t* block, size_t bytes);  // destroyed, it waits for the pages asked for
    PopulateAhead(const PopulateAhead&) = delete;
    PopulateAhead& operator=(const PopulateAhead&) = delete;

    void writing(uint64_t address, uint64_t bytes) {
        const size_t next = page_of(address + bytes - 1) + 1;
        if (bytes && next < asked_.size() && !asked_[next]) ask(next);
    }

private:
    static constexpr unsigned kPageShift = 21;  // 2 MB: a transparent huge page
    size_t page_of(uint64_t address) const { return size_t((first_offset_ + address) >> kPageShift); }
    void ask(size_t page);

    uint8_t* block_;
    size_t bytes_;
    uint64_t first_offset_;     // the block's start within its first 2 MB page
    std::vector<bool> asked_;   // per page of the block
    Worker worker_;             // last: finishes its jobs and stops before the rest goes
};

}  // namespace surfvp
