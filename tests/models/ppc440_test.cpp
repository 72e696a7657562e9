// The CPU stub: byte order through the HAL, MMIO and memory timing, interrupts, errors.
#include "harness.h"
#include "models/common/dmi_rate.h"
#include "models/memory/ddr_memory.h"
#include "models/plb/plb_bus.h"
#include "models/ppc440/ppc440.h"

namespace surfvp {
namespace {
using test::ns;
using test::ZeroTarget;

constexpr uint32_t kRegs = 0x8000'0000;

// CPU -> PLB1 -> {DDR at 0, a register-like target at kRegs}.
struct Bench {
    Tracer tracer;
    DdrMemory memory{"memory", DdrMemory::Params{}};
    PlbBus bus{"bus", PlbBus::Params{}, tracer};
    ZeroTarget regs{"regs", 0x100};
    sc_core::sc_signal<bool> irq;
    Ppc440 cpu;

    explicit Bench(Ppc440::Software software) : cpu("cpu", Ppc440::Params{}, std::move(software), tracer) {
        bus.connect_master(cpu.bus, "cpu");
        bus.slaves.bind(memory.ports);
        bus.slaves.bind(regs.socket);
        bus.map(0, 256u << 20, 0, "ddr");
        bus.map(kRegs, 0x100, 1, "regs");
        cpu.irq.bind(irq);
    }
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
    Bench bench([&](sw::Hal& hal) {
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
    Bench bench([&](sw::Hal& hal) {
        hal.write32(kRegs + 8, 0x11223344);
        back = hal.read32(kRegs + 8);
    });
    sc_core::sc_start();
    EXPECT_EQ(std::vector<uint8_t>(bench.regs.data.begin() + 8, bench.regs.data.begin() + 12),
              (std::vector<uint8_t>{0x11, 0x22, 0x33, 0x44}));
    EXPECT_EQ(back, 0x11223344u);
}

TEST(Ppc440, TimeIsMmioPlusMemoryPlusConsumedCycles) {
    Bench* b = nullptr;
    Bench bench([&](sw::Hal& hal) {
        hal.write32(kRegs, 1);  // one beat: (3 + 1 + 1) x 10 ns
        hal.consume(400);       // 400 cycles at 400 MHz: 1 us
        std::vector<uint8_t> data(1000);
        hal.write(0x1000, data.data(), data.size());  // DMI: bus + DDR latency, slower rate
        (void)b;
    });
    b = &bench;
    sc_core::sc_start();
    const sc_core::sc_time dmi = ns(40) + bench.memory.latency() +
                                 transfer_time(1000, std::min(bench.memory.bytes_per_second(), 16 * 100e6));
    EXPECT_EQ(bench.cpu.finish_time(), ns(50) + ns(1000) + dmi);
    EXPECT_EQ(bench.cpu.stats().cycles_consumed, 400u);
    EXPECT_EQ(bench.cpu.stats().mmio_writes, 1u);
    EXPECT_EQ(bench.cpu.stats().bytes_written, 1000u);
}

TEST(Ppc440, WaitForIrqSleepsUntilTheLineRises) {
    sc_core::sc_time woke;
    Bench* b = nullptr;
    Bench bench([&](sw::Hal& hal) {
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
    Bench bench([&](sw::Hal& hal) {
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
