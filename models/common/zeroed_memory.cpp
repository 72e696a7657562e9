#include "zeroed_memory.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <sys/mman.h>
#include <unistd.h>

namespace surfvp {

void ZeroedMemoryRelease::operator()(uint8_t* p) const {
    if (p) munmap(p, bytes);
}

// Maps 2 MB more than asked and gives back what lies before the first 2 MB boundary and after
// the block: the kernel backs a 2 MB page only where the mapping covers it whole.
uint8_t* map_zeroed(size_t bytes) {
    constexpr uintptr_t kHuge = uintptr_t(1) << 21;
    const size_t mapped = bytes + kHuge;
    void* p = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (p == MAP_FAILED) return nullptr;
    const uintptr_t begin = reinterpret_cast<uintptr_t>(p), start = (begin + kHuge - 1) & ~(kHuge - 1);
    const uintptr_t page = uintptr_t(sysconf(_SC_PAGESIZE)), end = (start + bytes + page - 1) & ~(page - 1);
    if (start > begin) munmap(p, start - begin);
    if (begin + mapped > end) munmap(reinterpret_cast<void*>(end), begin + mapped - end);
    madvise(reinterpret_cast<void*>(start), bytes, MADV_HUGEPAGE);  // a hint: without transparent huge pages it changes nothing
    return reinterpret_cast<uint8_t*>(start);
}

ZeroedMemory zeroed_memory(size_t bytes, const std::string& what) {
    uint8_t* p = map_zeroed(bytes);
    if (!p) throw std::runtime_error(what + ": cannot allocate " + std::to_string(bytes) + " bytes");
    return ZeroedMemory(p, ZeroedMemoryRelease{bytes});
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
    worker_.submit([start, length] { madvise(start, length, MADV_POPULATE_WRITE); });  // a hint: failure is a fault later
#endif
}

}  // namespace surfvp
