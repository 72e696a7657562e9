// The CPU stub: byte order through the HAL, MMIO and memory timing, interrupts, errors.
#include "harness.h"
#include <cmath>

#include "models/common/clock.h"
#include "models/mci/mci_link.h"
#include "models/memory/ddr_memory.h"
#include "models/plb/plb_bus.h"
#include "models/ppc440/ppc440.h"

namespace surfvp {
namespace {
using test::ns;
using test::ZeroTarget;

constexpr uint32_t kRegs = 0x8000'0000;

// CPU -> PLB1 -> a register-like target at kRegs; CPU memory -> MCI link -> DDR.
struct CpuBench {
    Tracer tracer;
    DdrMemory memory{"memory", DdrMemory::Params{}};
    PlbBus bus{"bus", PlbBus::Params{}, tracer};
    MciLink mci{"mci", MciLink::Params{}};
    ZeroTarget regs{"regs", 0x100};
    sc_core::sc_signal<bool> irq;
    Ppc440 cpu;

    explicit CpuBench(Ppc440::Software software, const Ppc440::Params& params = {})
        : cpu("cpu", params, std::move(software), tracer) {
        bus.connect_master(cpu.bus, "cpu");
        bus.slaves.bind(regs.socket);
        bus.map(kRegs, 0x100, 0, "regs");
        cpu.mem.bind(mci.cpu);
        mci.memory.bind(memory.ports);
        cpu.irq.bind(irq);
    }
    // One line over the MCI link whose DDR time is `ddr`.
    sc_core::sc_time line(uint64_t bytes, const sc_core::sc_time& ddr) const {
        return MciLink::access_time(mci.params(), bytes, ddr);
    }
    sc_core::sc_time transfer(uint64_t bytes) const { return transfer_time(bytes, memory.bytes_per_second()); }
    void poke(uint32_t address, const std::vector<uint8_t>& bytes) {
        std::copy(bytes.begin(), bytes.end(), memory.backdoor(address, bytes.size()));
    }
    std::vector<uint8_t> peek(uint32_t address, size_t n) {
        const uint8_t* p = memory.backdoor(address, n);
        return {p, p + n};
    }
};

TEST(ByteOrder, SoftwareAndBusMastersSeeOneBigEndianMemory) {
    uint32_t word = 0, half = 0, byte = 0;
    CpuBench bench([&](sw::Hal& hal) {
        sw::store32(hal, 0x100, 0x12345678);
        word = sw::load32(hal, 0x200);
        uint8_t b[2];
        hal.read(0x202, b, 2);
        half = load_be16(b);
        hal.read(0x201, b, 1);
        byte = b[0];
    });
    bench.poke(0x200, {0xCA, 0xFE, 0xBA, 0xBE});
    sc_core::sc_start();
    EXPECT_EQ(bench.peek(0x100, 4), (std::vector<uint8_t>{0x12, 0x34, 0x56, 0x78}));
    EXPECT_EQ(word, 0xCAFEBABEu);
    EXPECT_EQ(half, 0xBABEu);
    EXPECT_EQ(byte, 0xFEu);
}

TEST(ByteOrder, RegisterWordsTravelMostSignificantByteFirst) {
    uint32_t back = 0;
    CpuBench bench([&](sw::Hal& hal) {
        hal.write32(kRegs + 8, 0x11223344);
        back = hal.read32(kRegs + 8);
    });
    sc_core::sc_start();
    EXPECT_EQ(std::vector<uint8_t>(bench.regs.data.begin() + 8, bench.regs.data.begin() + 12),
              (std::vector<uint8_t>{0x11, 0x22, 0x33, 0x44}));
    EXPECT_EQ(back, 0x11223344u);
}

TEST(Ppc440, TimeIsMmioPlusMemoryPlusConsumedCycles) {
    CpuBench bench([&](sw::Hal& hal) {
        hal.write32(kRegs, 1);  // one beat: (3 + 1 + 1) x 10 ns
        hal.consume(400);       // 400 cycles at 400 MHz: 1 us
        std::vector<uint8_t> data(1000);
        hal.write(0x1000, data.data(), data.size());  // 31 whole lines and one of 8 B, one after the other
    });
    sc_core::sc_start();
    // A posted write line: the link's overhead and beats, or the DRAM's transfer if longer.
    const sc_core::sc_time copy = 31 * bench.line(32, bench.transfer(32)) + bench.line(8, bench.transfer(8));
    EXPECT_EQ(bench.cpu.finish_time(), ns(50) + ns(1000) + copy);
    EXPECT_EQ(bench.cpu.stats().cycles_consumed, 400u);
    EXPECT_EQ(bench.cpu.stats().mmio_writes, 1u);
    EXPECT_EQ(bench.cpu.stats().bytes_written, 1000u);
    EXPECT_EQ(bench.mci.stats().writes, 32u);
}

// A step of work with its L1 traffic: every fill stalls the CPU for the line's way to DDR
// and back (two asked at one cycle overlap, the second 30 ns behind on the link); a
// write-back does not.
TEST(Ppc440, ComputeStallsForEachFillAndPostsWriteBacks) {
    uint64_t spent = 0;
    CpuBench bench([&](sw::Hal& hal) {
        spent = hal.compute(1000,
                            {{0x2000, 100, false}, {0x2020, 100, false}, {0x3000, 900, true}, {0x2040, 950, false}}, 0);
    });
    sc_core::sc_start();
    const sc_core::sc_time fill = bench.line(32, bench.memory.access_time(32));  // 20 ns + 125 ns + 12.5 ns
    EXPECT_EQ(fill, ns(157.5));
    EXPECT_EQ(bench.cpu.finish_time(), ns(2500) + 2 * fill + ns(30));  // 1000 cycles at 400 MHz and the stalls
    EXPECT_EQ(spent, 1000u + 138);                                     // 345 ns = 138 cycles
    EXPECT_EQ(bench.cpu.stats().fills, 3u);
    EXPECT_EQ(bench.cpu.stats().write_backs, 1u);
    EXPECT_EQ(bench.cpu.stats().fill_stall, 2 * fill + ns(30));
    EXPECT_EQ(bench.cpu.stats().bytes_read, 96u);
    EXPECT_EQ(bench.cpu.stats().bytes_written, 32u);
}

// Fills asked at one cycle (a burst) overlap up to cpu.outstanding_fills: the MCI link
// pipelines them (its address phase and beats only, 30 ns each), the DRAM's latency overlaps;
// a fourth waits for the oldest; the CPU goes on when the last critical word is in.
// Returns the stall and the fills that waited for a slot.
std::pair<sc_core::sc_time, uint64_t> burst_of_four(unsigned outstanding, double lead_ns) {
    Ppc440::Params p;
    p.outstanding_fills = outstanding;
    p.critical_word_lead = Duration{uint64_t(lead_ns * 1000)};
    CpuBench bench(
        [](sw::Hal& hal) {
            hal.compute(1000, {{0x2000, 100, false}, {0x2100, 100, false}, {0x2200, 100, false}, {0x2300, 100, false}},
                        0);
        },
        p);
    sc_core::sc_start();
    return {bench.cpu.stats().fill_stall, bench.cpu.stats().fill_slot_waits};
}

// Asked at 250 ns: lines end at 407.5, 437.5, 467.5 (30 ns apart on the link); the fourth asks
// when the first is in (407.5) and ends 157.5 later, at 565: 315 ns of stall.
TEST(Ppc440, ABurstOfFillsOverlapsUpToThree) { EXPECT_EQ(burst_of_four(3, 0), std::pair(ns(315), uint64_t{1})); }

// Critical word first: the CPU has the fourth line's word 7.5 ns before its end.
TEST(Ppc440, ABurstEndsAtItsLastCriticalWord) { EXPECT_EQ(burst_of_four(3, 7.5).first, ns(307.5)); }

// A blocking cache: one line after the other, 4 x 157.5 ns.
TEST(Ppc440, OneOutstandingFillIsABlockingCache) { EXPECT_EQ(burst_of_four(1, 0), std::pair(ns(630), uint64_t{3})); }

// The DDR serves the CPU's fill and a DMA burst in the order they were asked, whenever the
// CPU handed its fill over: the CPU computes from 0 and needs a line at 1 us (it reaches the
// DRAM at 1020 ns, after the link's address phase); a DMA asks 128 bytes at 1015 ns and gets
// the DRAM at once (50 ns), the fill waits behind it.
TEST(Ppc440, DdrGrantsTheCpusFillsAndTheDmaInRequestOrder) {
    CpuBench bench([](sw::Hal& hal) { hal.compute(2000, {{0x2000, 400, false}}, 0); });
    uint8_t data[128];
    test::Initiator dma("dma", [&](test::Initiator& i) {
        sc_core::wait(ns(1015));
        i.transact(tlm::TLM_READ_COMMAND, 0x8000, data, sizeof data);
    });
    dma.socket.bind(bench.memory.ports);
    bench.memory.name_port("cpu");
    bench.memory.name_port("dma");
    sc_core::sc_start();
    ASSERT_EQ(bench.memory.port_stats().size(), 2u);
    EXPECT_EQ(bench.memory.port_stats()[1].wait, sc_core::SC_ZERO_TIME);  // the DMA asked first
    EXPECT_EQ(bench.memory.port_stats()[0].wait, ns(45));                 // 1020 -> 1065
    EXPECT_EQ(bench.cpu.stats().fill_stall, ns(157.5 + 45));
}

// Over PLB1 (a bus that synchronises) the CPU waits for each line's grant: write-backs
// queued behind each other push the step's end later, never before the kernel's time.
TEST(Ppc440, WriteBacksOverASynchronisingBusKeepTimeForward) {
    Tracer tracer;
    DdrMemory memory{"memory", DdrMemory::Params{}};
    PlbBus bus{"plb", PlbBus::Params{}, tracer};
    sc_core::sc_signal<bool> irq;
    uint64_t spent = 0;
    Ppc440 cpu(
        "cpu", Ppc440::Params{},
        [&](sw::Hal& hal) {
            std::vector<sw::LineTransfer> lines;
            for (uint32_t i = 0; i < 10; ++i)
                lines.push_back({0x4000 + 32 * i, 100, true});  // one record's lines at once
            spent = hal.compute(200, lines, 0);
        },
        tracer);
    bus.connect_master(cpu.bus, "cpu");
    bus.connect_master(cpu.mem, "cpu memory");
    bus.slaves.bind(memory.ports);
    bus.map(0, 256u << 20, 0, "ddr");
    cpu.irq.bind(irq);
    sc_core::sc_start();
    // Ten posted writes of 2 beats each over PLB1: 40 + 20 ns a burst, one after the other from
    // cycle 100 (250 ns), then the remaining 100 cycles.
    const sc_core::sc_time burst = PlbBus::burst_time(PlbBus::Params{}, 32, sc_core::sc_time(12.5, sc_core::SC_NS));
    EXPECT_EQ(burst, ns(60));
    EXPECT_EQ(cpu.finish_time(), ns(250) + 9 * burst + ns(250));
    EXPECT_EQ(spent, uint64_t(std::llround((cpu.finish_time().to_seconds()) * 400e6)));
    EXPECT_EQ(cpu.stats().write_backs, 10u);
}

// The VP times every fill at its cycle: software must list its fills, a bare count is refused.
TEST(Ppc440, TimesEveryFillAndRefusesACount) {
    bool timed = false;
    std::string refused;
    CpuBench bench([&](sw::Hal& hal) {
        timed = hal.times_fills();
        try {
            hal.compute(100, {}, 1);
        } catch (const std::logic_error& e) {
            refused = e.what();
        }
    });
    sc_core::sc_start();
    EXPECT_TRUE(timed);
    EXPECT_NE(refused.find("timed"), std::string::npos) << refused;
    EXPECT_EQ(bench.cpu.stats().fills, 0u);
}

TEST(Ppc440, WaitForIrqSleepsUntilTheLineRises) {
    sc_core::sc_time woke;
    CpuBench* b = nullptr;
    CpuBench bench([&](sw::Hal& hal) {
        hal.wait_for_irq();
        woke = sc_core::sc_time_stamp();
    });
    b = &bench;
    sc_core::sc_spawn([b] {
        sc_core::wait(ns(5000));
        b->irq.write(true);
    });
    sc_core::sc_start();
    EXPECT_EQ(woke, ns(5000));
    EXPECT_EQ(bench.cpu.stats().irq_wait_time, ns(5000));
}

TEST(Ppc440, BusErrorStopsTheSoftwareWithTheAddress) {
    bool after = false;
    CpuBench bench([&](sw::Hal& hal) {
        hal.read32(0x9000'0000);
        after = true;
    });
    sc_core::sc_start();
    EXPECT_TRUE(bench.cpu.finished());
    EXPECT_FALSE(after);
    EXPECT_NE(bench.cpu.error().find("0x90000000"), std::string::npos) << bench.cpu.error();
}

}  // namespace
}  // namespace surfvp
