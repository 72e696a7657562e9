#include "zeroed_memory.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <sys/mman.h>
#include <unistd.h>

namespace surfvp {

void ZeroedMemoryRelease::operator()(uint8_t* p) const {
    if (p) munmap(p, bytes);
}

// In the kernel's 4 KB pages. A 2 MB page (MADV_HUGEPAGE) faults in 512 times fewer, but on
// the virtual machine measured the host takes freed 2 MB blocks back (free page reporting), so
// a run's fresh 2 MB pages were mostly faulted in on the host too: 64 MB took 75-150 ms in
// 2 MB pages and 22-26 ms in 4 KB ones (3 ms in 2 MB pages only when a run just before had
// freed them). docs/architecture.md gives the runs' figures.
namespace {
bool huge_pages = false;
}  // namespace

void use_huge_pages() { huge_pages = true; }

uint8_t* map_zeroed(size_t bytes) {
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (p == MAP_FAILED) return nullptr;
    if (huge_pages) madvise(p, bytes, MADV_HUGEPAGE);  // a hint: without it, 4 KB pages as usual
    return static_cast<uint8_t*>(p);
}

ZeroedMemory zeroed_memory(size_t bytes, const std::string& what) {
    uint8_t* p = map_zeroed(bytes);
    if (!p) throw OutOfMemory(what + ": cannot have " + std::to_string(bytes >> 20) + " MiB");
    return ZeroedMemory(p, ZeroedMemoryRelease{bytes});
}

void release_in_background(ZeroedMemory block) {
    const size_t bytes = block.get_deleter().bytes;
    uint8_t* p = block.release();
    if (!p) return;
    try {
        std::thread([p, bytes] { ZeroedMemoryRelease{bytes}(p); }).detach();
    } catch (const std::system_error&) {
        ZeroedMemoryRelease{bytes}(p);
    }
}

void populate_until(const std::atomic<bool>& stop, uint8_t* begin, uint8_t* end) {
#ifdef MADV_POPULATE_WRITE
    constexpr size_t kStretch = size_t(64) << 10;  // ~16 faults: the flag is looked at every ~25 us
    const uintptr_t page = uintptr_t(sysconf(_SC_PAGESIZE));
    // NOLINTNEXTLINE(performance-no-int-to-ptr): madvise wants the page the range begins in
    uint8_t* at = reinterpret_cast<uint8_t*>(reinterpret_cast<uintptr_t>(begin) & ~(page - 1));
    for (; at < end && !stop.load(std::memory_order_acquire); at += kStretch)
        madvise(at, std::min<size_t>(kStretch, size_t(end - at)),
                MADV_POPULATE_WRITE);  // a hint: failure is a fault later
#else
    (void)stop, (void)begin, (void)end;
#endif
}

PopulateAhead::PopulateAhead(uint8_t* block, size_t bytes)
    : block_(block),
      bytes_(bytes),
      first_offset_(reinterpret_cast<uintptr_t>(block) & ((uint64_t(1) << kPageShift) - 1)),
      asked_(page_of(bytes ? bytes - 1 : 0) + 1, false),
      worker_(std::chrono::microseconds(0)) {}  // asked for a few dozen times a run: no spinning

void PopulateAhead::ask(size_t page) {
    asked_[page] = true;
#ifdef MADV_POPULATE_WRITE
    const uint64_t begin = page ? (uint64_t(page) << kPageShift) - first_offset_ : 0;
    const uint64_t end = std::min<uint64_t>((uint64_t(page + 1) << kPageShift) - first_offset_, bytes_);
    uint8_t* start = block_ + begin;
    const size_t length = size_t(end - begin);
    worker_.submit(
        [start, length] { madvise(start, length, MADV_POPULATE_WRITE); });  // a hint: failure is a fault later
#endif
}

}  // namespace surfvp
