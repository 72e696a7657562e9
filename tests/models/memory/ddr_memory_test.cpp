// DDR timing formula, contention between ports, and DMI giving the same data and time.
#include <cstring>

#include "harness.h"
#include "models/memory/ddr_memory.h"

namespace surfvp {
namespace {
using test::Initiator;
using test::ns;

// Defaults: 64 bit x 200 MHz x 2 transfers x 0.8 = 2.56 GB/s; latency 25 cycles = 125 ns.
TEST(DdrMemory, AccessTimeIsLatencyPlusBytesOverBandwidth) {
    DdrMemory memory("memory", DdrMemory::Params{});
    EXPECT_DOUBLE_EQ(memory.bytes_per_second(), 2.56e9);
    EXPECT_EQ(memory.access_time(256), ns(125 + 100));
    EXPECT_EQ(memory.access_time(4), ns(125) + sc_core::sc_time(1562.5, sc_core::SC_PS));
}

TEST(DdrMemory, SecondPortWaitsForTheDramBehindTheFirst) {
    DdrMemory memory("memory", DdrMemory::Params{});
    sc_core::sc_time end[2];
    std::vector<std::unique_ptr<Initiator>> ports;
    for (int i = 0; i < 2; ++i) {
        ports.push_back(std::make_unique<Initiator>(("port" + std::to_string(i)).c_str(), [&end, i](Initiator& m) {
            static uint8_t data[2][256];
            m.transact(tlm::TLM_READ_COMMAND, 0x1000 * i, data[i], 256);
            end[i] = m.end_time();
        }));
        ports.back()->socket.bind(memory.ports);
    }
    sc_core::sc_start();
    // Both at t = 0: one streams at once (225 ns), the other starts when the DRAM is free (100 ns later).
    EXPECT_EQ(std::min(end[0], end[1]), ns(225));
    EXPECT_EQ(std::max(end[0], end[1]), ns(325));
    EXPECT_EQ(memory.busy(), ns(200));
}

TEST(DdrMemory, DmiPointsAtTheSameBytes) {
    DdrMemory memory("memory", DdrMemory::Params{});
    Initiator m("m", [&](Initiator& self) {
        uint8_t written[1000];
        for (int i = 0; i < 1000; ++i) written[i] = uint8_t(i * 7);
        self.transact(tlm::TLM_WRITE_COMMAND, 0x4000, written, 1000);
        tlm::tlm_generic_payload tx;
        tlm::tlm_dmi dmi;
        tx.set_address(0x4000);
        ASSERT_TRUE(self.socket->get_direct_mem_ptr(tx, dmi));
        EXPECT_TRUE(dmi.is_read_write_allowed());
        EXPECT_EQ(0, std::memcmp(dmi.get_dmi_ptr() + 0x4000, written, 1000));
    });
    m.socket.bind(memory.ports);
    sc_core::sc_start();
}

// A write is posted (write_latency 0): its master sees the DRAM's transfer only; a read waits
// out the latency too.
TEST(DdrMemory, WritesArePostedReadsSeeTheLatency) {
    DdrMemory memory("memory", DdrMemory::Params{});
    sc_core::sc_time write_time, read_time;
    Initiator m("m", [&](Initiator& self) {
        uint8_t data[256];
        self.transact(tlm::TLM_WRITE_COMMAND, 0x4000, data, 256);
        write_time = self.local;
        self.local = ns(1000);
        self.transact(tlm::TLM_READ_COMMAND, 0x4000, data, 256);
        read_time = self.local - ns(1000);
    });
    m.socket.bind(memory.ports);
    sc_core::sc_start();
    EXPECT_EQ(write_time, ns(100));
    EXPECT_EQ(read_time, ns(225));
}

// A master that hands over an access ahead of time (annotated far into the future) does not
// block one asked for later but due earlier: it takes the gap before it, or waits behind it
// only where they overlap.
TEST(DdrMemory, AnAccessAheadOfTimeLeavesTheGapBeforeIt) {
    DdrMemory memory("memory", DdrMemory::Params{});
    sc_core::sc_time early, overlapping;
    Initiator ahead("ahead", [&](Initiator& self) {
        uint8_t data[256];
        self.local = ns(1000);
        self.transact(tlm::TLM_READ_COMMAND, 0, data, 256);  // the DRAM: [1000, 1100) ns
    });
    Initiator later("later", [&](Initiator& self) {
        uint8_t data[256];
        sc_core::wait(ns(1));  // asks after `ahead` has reserved
        self.local = ns(0);
        self.transact(tlm::TLM_READ_COMMAND, 0x1000, data, 256);  // fits in [1, 101)
        early = self.local;
        self.local = ns(949);
        self.transact(tlm::TLM_READ_COMMAND, 0x1000, data, 256);  // [950, 1050) overlaps: starts at 1100
        overlapping = self.local - ns(949);
    });
    ahead.socket.bind(memory.ports);
    later.socket.bind(memory.ports);
    sc_core::sc_start();
    EXPECT_EQ(early, ns(225));
    EXPECT_EQ(overlapping, ns(150 + 225));
    EXPECT_EQ(memory.port_stats()[1].wait, ns(150));
}

TEST(DdrMemory, OutsideTheInstalledSizeIsAnAddressError) {
    DdrMemory::Params p;
    p.size = Bytes{1 << 20};
    DdrMemory memory("memory", p);
    tlm::tlm_response_status inside{}, outside{};
    Initiator m("m", [&](Initiator& self) {
        uint8_t data[8];
        inside = self.transact(tlm::TLM_READ_COMMAND, (1 << 20) - 8, data, 8);
        outside = self.transact(tlm::TLM_READ_COMMAND, (1 << 20) - 4, data, 8);
    });
    m.socket.bind(memory.ports);
    sc_core::sc_start();
    EXPECT_EQ(inside, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(outside, tlm::TLM_ADDRESS_ERROR_RESPONSE);
}

}  // namespace
}  // namespace surfvp
