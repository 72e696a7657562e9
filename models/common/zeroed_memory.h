#pragma once
// A large zero-filled block for a modelled memory: untouched pages cost nothing (as with
// calloc); a page is cleared by the kernel when it is first written.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "models/host/worker.h"

namespace surfvp {

struct ZeroedMemoryRelease {
    size_t bytes = 0;
    void operator()(uint8_t* p) const;
};
using ZeroedMemory = std::unique_ptr<uint8_t[], ZeroedMemoryRelease>;

// The machine has no memory for what a run needs: neither the user's input (exit 2) nor a bug
// (exit 3), but an outcome of its own (exit 5). The message names the allocation and its size.
struct OutOfMemory : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Throws OutOfMemory naming `what` and the size when the block cannot be had.
ZeroedMemory zeroed_memory(size_t bytes, const std::string& what);

// From now on this process's blocks ask for 2 MB pages (MADV_HUGEPAGE). For a re-simulation's
// child, one of many short processes that each fault in the same ~40 MB of a modelled DDR and
// its buffers: on the virtual machines measured, a fresh 4 KB page costs ~10 us to fault in
// (36 MB in ~105 ms), while 2 MB pages that the children before it have just freed come back
// in ~3 ms. A single long run is better off in 4 KB pages (see map_zeroed).
void use_huge_pages();

// Gives a block back on a thread of its own, which the caller does not wait for: freeing a
// run's written pages (~0.3 us a page here, ~3.5 ms for direct mode's ~40 MB) then overlaps
// what the process does next (publishing its outputs, exiting); a process that exits first
// leaves the rest to the kernel's exit. Inline when no thread can be had.
void release_in_background(ZeroedMemory block);

// The allocator of a model's large buffers that are refilled every frame (integral lines,
// determinant rows): zeroed_memory's blocks, given back to the kernel when freed. An element
// made without a value is left as the memory holds it (zero in a new block), so resize() does
// not write a block's pages: they are faulted in by whoever first writes them (the FHG's
// worker, for the rows it computes ahead). assign() fills. Throws std::bad_alloc.
uint8_t* map_zeroed(size_t bytes);  // nullptr when it cannot be had
template <class T>
struct ZeroedAllocator {
    using value_type = T;
    ZeroedAllocator() = default;
    template <class U>
    ZeroedAllocator(const ZeroedAllocator<U>&) {}
    T* allocate(size_t n) {
        if (uint8_t* p = map_zeroed(n * sizeof(T))) return reinterpret_cast<T*>(p);
        throw std::bad_alloc();
    }
    void deallocate(T* p, size_t n) { ZeroedMemoryRelease{n * sizeof(T)}(reinterpret_cast<uint8_t*>(p)); }
    template <class U>
    void construct(U* p) {
        ::new (static_cast<void*>(p)) U;  // default-initialised: no store
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    bool operator==(const ZeroedAllocator&) const { return true; }
    bool operator!=(const ZeroedAllocator&) const { return false; }
};
template <class T>
using FrameBuffer = std::vector<T, ZeroedAllocator<T>>;

// Faults [begin, end) in, a stretch at a time, until `stop` is set: what a thread that waits
// for `stop` before writing there can do meanwhile (its writes then find the pages in). Only
// the pages' residency changes, never their bytes (MADV_POPULATE_WRITE; nothing without it).
void populate_until(const std::atomic<bool>& stop, uint8_t* begin, uint8_t* end);

// Faults a block's pages in on a background thread just ahead of the writes that would
// fault them on the caller's (the kernel's) thread: a write reaching into a 2 MB stretch of
// the block (aligned as addresses are) asks for the stretch after it. The kernel clears a
// page when it is first written, and those clears were ~5 % of the simulator's main thread
// (the FHG writer's buffers, the first frames of a run). Only the pages' residency changes, never their bytes (MADV_POPULATE_WRITE);
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
    static constexpr unsigned kPageShift = 21;  // 2 MB stretches, asked for one at a time
    size_t page_of(uint64_t address) const { return size_t((first_offset_ + address) >> kPageShift); }
    void ask(size_t page);

    uint8_t* block_;
    size_t bytes_;
    uint64_t first_offset_;    // the block's start within its first 2 MB stretch
    std::vector<bool> asked_;  // per stretch of the block
    Worker worker_;            // last: finishes its jobs and stops before the rest goes
};

}  // namespace surfvp
