// The modelled memories' block: zero-filled, its pages faulted in ahead of the writes on a
// second thread without a byte of them changing; the models' frame buffers come from the same
// blocks.
#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <thread>
#include <cstdint>
#include <sys/mman.h>
#include <unistd.h>

#include "models/common/zeroed_memory.h"

namespace surfvp {
namespace {

constexpr size_t kHuge = size_t(1) << 21;

bool resident(const uint8_t* p) {
    const size_t page = size_t(sysconf(_SC_PAGESIZE));
    unsigned char state = 0;
    const auto start = reinterpret_cast<uintptr_t>(p) & ~(page - 1);
    EXPECT_EQ(mincore(reinterpret_cast<void*>(start), page, &state), 0);  // NOLINT(performance-no-int-to-ptr)
    return state & 1;
}

TEST(PopulateAhead, AWriteFaultsInTheNextTwoMegabytesAndNoFurtherWithTheirBytesUnchanged) {
    const size_t bytes = 8 * kHuge;
    ZeroedMemory block = zeroed_memory(bytes, "test block");
    uint8_t* p = block.get();
    // The first 2 MB boundary inside the block: the written stretch ends there, the next begins.
    const size_t boundary = kHuge - (reinterpret_cast<uintptr_t>(p) & (kHuge - 1));
    ASSERT_FALSE(resident(p + boundary + 4096));
    {
        PopulateAhead ahead(p, bytes);
        p[0] = 7;
        ahead.writing(0, 1);
    }  // waits for the page asked for
#ifdef MADV_POPULATE_WRITE
    EXPECT_TRUE(resident(p + boundary + 4096));
#endif
    EXPECT_FALSE(resident(p + boundary + kHuge + 4096));  // one page ahead, not more
    EXPECT_EQ(p[0], 7);
    for (size_t i = boundary; i < boundary + kHuge && i < bytes; i += 4096) ASSERT_EQ(p[i], 0) << i;
}

TEST(PopulateUntil, FaultsInTheRangeWhileNotStoppedAndNothingOnceStopped) {
    const size_t bytes = 4 * kHuge;
    ZeroedMemory block = zeroed_memory(bytes, "test block");
    uint8_t* p = block.get();
    std::atomic<bool> stop{true};
    populate_until(stop, p, p + bytes / 2);
    for (size_t i = 0; i < bytes; i += 4096) ASSERT_FALSE(resident(p + i)) << i;
    stop = false;
    p[5] = 9;
    populate_until(stop, p + 1, p + bytes / 2 + 1);  // from the page holding its start, to the one holding its end
#ifdef MADV_POPULATE_WRITE
    for (size_t i = 0; i <= bytes / 2; i += 4096) ASSERT_TRUE(resident(p + i)) << i;
#endif
    EXPECT_FALSE(resident(p + bytes / 2 + 4096));  // the page after the one holding the end
    EXPECT_EQ(p[5], 9);
    for (size_t i = 0; i < bytes; i += 4093) ASSERT_EQ(p[i], i == 5 ? 9 : 0) << i;
}

TEST(ReleaseInBackground, TheBlockIsUnmappedWithoutTheCallerWaiting) {
    const size_t bytes = 4 * kHuge;
    ZeroedMemory block = zeroed_memory(bytes, "test block");
    uint8_t* p = block.get();
    for (size_t i = 0; i < bytes; i += 4096) p[i] = 1;
    release_in_background(std::move(block));
    EXPECT_EQ(block.get(), nullptr);
    unsigned char state = 0;
    bool unmapped = false;  // mincore fails with ENOMEM on an address that is not mapped
    for (int tries = 0; tries < 1000 && !unmapped; ++tries) {
        unmapped = mincore(p, 4096, &state) != 0 && errno == ENOMEM;
        if (!unmapped) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_TRUE(unmapped);
    release_in_background(ZeroedMemory());  // nothing to give back
}

TEST(ZeroedMemory, BlocksAndFrameBuffersReadZero) {
    for (const size_t bytes : {size_t(1), size_t(4096), 3 * kHuge / 2, 5 * kHuge + 12345}) {
        ZeroedMemory block = zeroed_memory(bytes, "test block");
        for (size_t i = 0; i < bytes; i += 4093) ASSERT_EQ(block[i], 0) << i;
        block[bytes - 1] = 1;  // the whole block is mapped
    }
    FrameBuffer<uint32_t> lines(1024 * 768);
    for (size_t i = 0; i < lines.size(); i += 1021) ASSERT_EQ(lines[i], 0u) << i;
    lines.assign(lines.size(), 7u);
    lines.resize(2 * lines.size());  // a new block, the old one given back
    EXPECT_EQ(lines[1024 * 768 - 1], 7u);
    EXPECT_EQ(lines.back(), 0u);
}

}  // namespace
}  // namespace surfvp
