#include "zeroed_memory.h"

#include <stdexcept>
#include <sys/mman.h>

namespace surfvp {

void ZeroedMemoryRelease::operator()(uint8_t* p) const {
    if (p) munmap(p, bytes);
}

ZeroedMemory zeroed_memory(size_t bytes, const std::string& what) {
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (p == MAP_FAILED) throw std::runtime_error(what + ": cannot allocate " + std::to_string(bytes) + " bytes");
    madvise(p, bytes, MADV_HUGEPAGE);  // a hint: without transparent huge pages it changes nothing
    return ZeroedMemory(static_cast<uint8_t*>(p), ZeroedMemoryRelease{bytes});
}

}  // namespace surfvp
