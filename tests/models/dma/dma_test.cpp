// The test DMA: a copy arrives intact in bursts, errors are reported with code and address.
#include <cstring>

#include "harness.h"
#include "models/common/byte_order.h"
#include "models/dma/dma.h"
#include "models/dma/dma_regs.h"
#include "models/memory/ddr_memory.h"
#include "models/plb/plb_bus.h"

namespace surfvp {
namespace {
using test::Initiator;

struct DmaBench {
    Tracer tracer;
    DdrMemory memory;
    PlbBus bus{"bus", PlbBus::Params{}, tracer};
    Dma dma{"dma", Dma::Params{}, tracer};
    sc_core::sc_signal<bool> irq;
    Initiator cpu;

    explicit DmaBench(Initiator::Script script) : memory("memory", small()), cpu("cpu", std::move(script)) {
        bus.connect_master(dma.mplb, "dma");
        bus.slaves.bind(memory.ports);
        bus.map(0, 1 << 20, 0, "ddr");
        cpu.socket.bind(dma.regs);
        dma.irq.bind(irq);
    }
    static DdrMemory::Params small() {
        DdrMemory::Params p;
        p.size = Bytes{1 << 20};
        return p;
    }
};

uint32_t dma_read(Initiator& m, uint32_t offset) {
    uint8_t b[4];
    m.transact(tlm::TLM_READ_COMMAND, offset, b, 4);
    return load_be32(b);
}
void dma_write(Initiator& m, uint32_t offset, uint32_t v) {
    uint8_t b[4];
    store_be32(b, v);
    m.transact(tlm::TLM_WRITE_COMMAND, offset, b, 4);
}

TEST(Dma, CopiesInBurstsAndRaisesItsInterrupt) {
    DmaBench* b = nullptr;
    DmaBench bench([&](Initiator& m) {
        dma_write(m, dma::SRC, 0x1000);
        dma_write(m, dma::DST, 0x8000);
        dma_write(m, dma::LEN, 1000);  // 3 full 256-byte bursts and one of 232
        dma_write(m, dma::CTRL, dma::CTRL_START | dma::CTRL_IRQ_EN);
        EXPECT_EQ(dma_read(m, dma::STATUS), dma::STATUS_BUSY);
        sc_core::wait(b->irq.posedge_event());
        EXPECT_EQ(dma_read(m, dma::STATUS), dma::STATUS_DONE);
        dma_write(m, dma::STATUS, dma::STATUS_DONE);
        sc_core::wait(sc_core::sc_time(1, sc_core::SC_NS));
        EXPECT_FALSE(b->irq.read());
    });
    b = &bench;
    uint8_t* ddr = bench.memory.backdoor(0, 1 << 20);
    for (int i = 0; i < 1000; ++i) ddr[0x1000 + i] = uint8_t(i ^ 0x5A);
    sc_core::sc_start();
    EXPECT_EQ(0, std::memcmp(ddr + 0x1000, ddr + 0x8000, 1000));
    EXPECT_EQ(bench.bus.master_stats()[0].bursts, 8u);
    EXPECT_EQ(bench.dma.bytes_copied(), 1000u);
}

TEST(Dma, BusErrorSetsErrorWithCodeAndAddress) {
    DmaBench* b = nullptr;
    DmaBench bench([&](Initiator& m) {
        dma_write(m, dma::SRC, 0x1000);
        dma_write(m, dma::DST, (1 << 20) - 256);  // the second burst falls off the end of memory
        dma_write(m, dma::LEN, 512);
        dma_write(m, dma::CTRL, dma::CTRL_START | dma::CTRL_IRQ_EN);
        sc_core::wait(b->irq.posedge_event());
        EXPECT_EQ(dma_read(m, dma::STATUS), dma::STATUS_ERROR);
        EXPECT_EQ(dma_read(m, dma::ERROR_CODE), uint32_t(dma::ERR_WRITE));
        EXPECT_EQ(dma_read(m, dma::ERROR_ADDR), uint32_t(1 << 20));
    });
    b = &bench;
    sc_core::sc_start();
    EXPECT_EQ(bench.dma.bytes_copied(), 256u);
}

TEST(Dma, ProgrammingErrorsAreFlagged) {
    DmaBench bench([&](Initiator& m) {
        dma_write(m, dma::LEN, 0);
        dma_write(m, dma::CTRL, dma::CTRL_START);
        EXPECT_EQ(dma_read(m, dma::STATUS), dma::STATUS_ERROR);
        EXPECT_EQ(dma_read(m, dma::ERROR_CODE), uint32_t(dma::ERR_ZERO_LENGTH));
        dma_write(m, dma::STATUS, dma::STATUS_ERROR);
        dma_write(m, dma::LEN, 4096);
        dma_write(m, dma::CTRL, dma::CTRL_START);
        dma_write(m, dma::CTRL, dma::CTRL_START);  // while busy
        EXPECT_EQ(dma_read(m, dma::STATUS), dma::STATUS_BUSY | dma::STATUS_ERROR);
        EXPECT_EQ(dma_read(m, dma::ERROR_CODE), uint32_t(dma::ERR_START_BUSY));
    });
    sc_core::sc_start();
}

}  // namespace
}  // namespace surfvp
