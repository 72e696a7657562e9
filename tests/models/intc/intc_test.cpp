// XPS INTC register semantics: enable, acknowledge, masked lines, master enable, vector.
#include "harness.h"
#include "models/common/byte_order.h"
#include "models/intc/intc.h"
#include "models/intc/intc_regs.h"

namespace surfvp {
namespace {
using test::Initiator;
using test::ns;

struct IntcBench {
    Tracer tracer;
    Intc intc{"intc", Intc::Params{4, {}}, tracer};
    sc_core::sc_signal<bool> lines[4];
    sc_core::sc_signal<bool> out;
    std::unique_ptr<Initiator> cpu;

    explicit IntcBench(Initiator::Script script) {
        for (int i = 0; i < 4; ++i) intc.irq_in[i].bind(lines[i]);
        intc.irq.bind(out);
        cpu = std::make_unique<Initiator>("cpu", std::move(script));
        cpu->socket.bind(intc.regs);
    }
};

uint32_t intc_read(Initiator& m, uint32_t offset) {
    uint8_t b[4];
    EXPECT_EQ(m.transact(tlm::TLM_READ_COMMAND, offset, b, 4), tlm::TLM_OK_RESPONSE);
    return load_be32(b);
}
void intc_write(Initiator& m, uint32_t offset, uint32_t v) {
    uint8_t b[4];
    store_be32(b, v);
    EXPECT_EQ(m.transact(tlm::TLM_WRITE_COMMAND, offset, b, 4), tlm::TLM_OK_RESPONSE);
}
void settle() { sc_core::wait(ns(1)); }

TEST(Intc, EnabledLineRaisesTheOutputUntilAcknowledged) {
    IntcBench* b = nullptr;
    IntcBench bench([&](Initiator& m) {
        intc_write(m, intc::IER, 0b0100);
        intc_write(m, intc::MER, intc::MER_ME | intc::MER_HIE);
        b->lines[2].write(true);
        settle();
        EXPECT_EQ(intc_read(m, intc::ISR), 0b0100u);
        EXPECT_EQ(intc_read(m, intc::IPR), 0b0100u);
        EXPECT_EQ(intc_read(m, intc::IVR), 2u);
        EXPECT_TRUE(b->out.read());
        intc_write(m, intc::IAR, 0b0100);  // the line is still high: pending again at once
        EXPECT_EQ(intc_read(m, intc::ISR), 0b0100u);
        b->lines[2].write(false);
        settle();
        intc_write(m, intc::IAR, 0b0100);
        settle();
        EXPECT_EQ(intc_read(m, intc::ISR), 0u);
        EXPECT_EQ(intc_read(m, intc::IVR), intc::kNoVector);
        EXPECT_FALSE(b->out.read());
    });
    b = &bench;
    sc_core::sc_start();
    EXPECT_EQ(bench.intc.interrupts_raised(), 1u);
}

TEST(Intc, MaskedLineIsLatchedButNotPending) {
    IntcBench* b = nullptr;
    IntcBench bench([&](Initiator& m) {
        intc_write(m, intc::IER, 0b0001);
        intc_write(m, intc::MER, intc::MER_ME | intc::MER_HIE);
        b->lines[3].write(true);
        settle();
        EXPECT_EQ(intc_read(m, intc::ISR), 0b1000u);
        EXPECT_EQ(intc_read(m, intc::IPR), 0u);
        EXPECT_FALSE(b->out.read());
        intc_write(m, intc::SIE, 0b1000);  // enabling it makes it pending
        settle();
        EXPECT_EQ(intc_read(m, intc::IER), 0b1001u);
        EXPECT_TRUE(b->out.read());
        intc_write(m, intc::CIE, 0b1000);
        settle();
        EXPECT_EQ(intc_read(m, intc::IER), 0b0001u);
        EXPECT_FALSE(b->out.read());
    });
    b = &bench;
    sc_core::sc_start();
}

TEST(Intc, MasterEnableGatesTheOutputAndHieIsWriteOnce) {
    IntcBench* b = nullptr;
    IntcBench bench([&](Initiator& m) {
        intc_write(m, intc::IER, 0b0011);
        intc_write(m, intc::ISR, 0b0010);  // software interrupt: allowed while HIE = 0
        EXPECT_EQ(intc_read(m, intc::ISR), 0b0010u);
        settle();
        EXPECT_FALSE(b->out.read());  // ME = 0
        intc_write(m, intc::MER, intc::MER_ME);
        settle();
        EXPECT_TRUE(b->out.read());
        intc_write(m, intc::IAR, 0b0010);
        intc_write(m, intc::MER, intc::MER_ME | intc::MER_HIE);
        intc_write(m, intc::MER, 0);  // HIE cannot be cleared again
        EXPECT_EQ(intc_read(m, intc::MER), intc::MER_HIE);
        intc_write(m, intc::ISR, 0b0001);  // ignored once hardware interrupts are on
        EXPECT_EQ(intc_read(m, intc::ISR), 0u);
    });
    b = &bench;
    sc_core::sc_start();
}

TEST(Intc, VectorIsTheLowestPendingLine) {
    IntcBench* b = nullptr;
    IntcBench bench([&](Initiator& m) {
        intc_write(m, intc::IER, 0b1110);
        intc_write(m, intc::MER, intc::MER_ME | intc::MER_HIE);
        b->lines[3].write(true);
        b->lines[1].write(true);
        b->lines[0].write(true);  // not enabled
        settle();
        EXPECT_EQ(intc_read(m, intc::IVR), 1u);
    });
    b = &bench;
    sc_core::sc_start();
}

TEST(Intc, BadAccessesAreErrorResponses) {
    IntcBench bench([&](Initiator& m) {
        uint8_t b[4];
        EXPECT_EQ(m.transact(tlm::TLM_READ_COMMAND, 0x20, b, 4), tlm::TLM_ADDRESS_ERROR_RESPONSE);
        EXPECT_EQ(m.transact(tlm::TLM_READ_COMMAND, intc::IER, b, 2), tlm::TLM_BURST_ERROR_RESPONSE);
        EXPECT_EQ(m.transact(tlm::TLM_READ_COMMAND, intc::IER + 1, b, 4), tlm::TLM_BURST_ERROR_RESPONSE);
    });
    sc_core::sc_start();
}

}  // namespace
}  // namespace surfvp
