// The register table's access rules, as both the models and direct mode answer them.
#include <gtest/gtest.h>

#include "models/common/register_bank.h"
#include "models/fhg/fhg_registers.h"

namespace surfvp {
namespace {

const RegisterTable& sample() {
    static const RegisterTable t{
        "sample",
        "A block with one register of each kind.",
        {{"CTRL", 0x0, Access::RW, 0, "", {{"GO", 0, 1, Access::command, ""}, {"EN", 1, 2, Access::RW, ""}}},
         {"STATUS", 0x4, Access::W1C, 0x1, "", {{"BUSY", 0, 1, Access::RO, ""}, {"DONE", 1, 1, Access::W1C, ""}}},
         {"DATA", 0x8, Access::RW, 0xABCD, "", {}},
         {"ID", 0xC, Access::RO, 0x1234, "", {}},
         {"KICK", 0x10, Access::WO, 0, "", {}}}};
    return t;
}

uint32_t read(RegisterBank& bank, uint32_t offset) {
    uint32_t v = 0;
    EXPECT_TRUE(bank.access(offset, v, false));
    return v;
}

void write(RegisterBank& bank, uint32_t offset, uint32_t v) { EXPECT_TRUE(bank.access(offset, v, true)); }

TEST(RegisterBank, ResetValuesAndTheRulesOfEachAccess) {
    RegisterBank bank(sample());
    uint32_t kicked = 0, commands = 0;
    bank.on_write(0x10, [&](uint32_t v) { kicked = v; });
    bank.on_write(0x0, [&](uint32_t v) { commands += v & 1; });
    EXPECT_EQ(read(bank, 0x8), 0xABCDu);
    EXPECT_EQ(read(bank, 0xC), 0x1234u);
    write(bank, 0xC, 7);  // read only: ignored
    EXPECT_EQ(read(bank, 0xC), 0x1234u);
    write(bank, 0x0, 0xFFFFFFFF);  // only EN (bits 2:1) is stored; GO acts and reads 0
    EXPECT_EQ(read(bank, 0x0), 0x6u);
    EXPECT_EQ(commands, 1u);
    bank.value(0x4) = 0x3;  // the block sets DONE
    write(bank, 0x4, 0x3);  // W1C clears DONE; BUSY is read only
    EXPECT_EQ(read(bank, 0x4), 0x1u);
    write(bank, 0x10, 42);
    EXPECT_EQ(kicked, 42u);
    EXPECT_EQ(read(bank, 0x10), 0u);  // write only
    uint32_t v = 0;
    EXPECT_FALSE(bank.access(0x14, v, false));  // no register: the bus answers an address error
    EXPECT_FALSE(bank.access(0x2, v, true));
    bank.reset();
    EXPECT_EQ(read(bank, 0x0), 0u);
    EXPECT_EQ(read(bank, 0x4), 0x1u);
}

TEST(RegisterBank, ATableWithTwoRegistersAtOneOffsetIsRefused) {
    static const RegisterTable twice{
        "twice", "", {{"A", 0x0, Access::RW, 0, "", {}}, {"B", 0x0, Access::RW, 0, "", {}}}};
    EXPECT_THROW(RegisterBank{twice}, std::logic_error);
}

// Found by tests/fuzz (register_bank): a field past bit 31 made RegisterField::mask() shift
// by more than the word (undefined behaviour) instead of being refused like a bad offset.
TEST(RegisterBank, AFieldOutsideTheWordIsRefused) {
    const RegisterTable beyond{"beyond", "", {{"CTRL", 0x0, Access::RW, 0, "", {{"HIGH", 30, 4, Access::RW, ""}}}}};
    EXPECT_THROW(RegisterBank{beyond}, std::logic_error);
    const RegisterTable past{"past", "", {{"CTRL", 0x0, Access::RW, 0, "", {{"HIGH", 39, 1, Access::RW, ""}}}}};
    EXPECT_THROW(RegisterBank{past}, std::logic_error);
    const RegisterTable top{"top", "", {{"CTRL", 0x0, Access::RW, 0, "", {{"TOP", 31, 1, Access::RW, ""}}}}};
    EXPECT_NO_THROW(RegisterBank{top});
}

TEST(RegisterBank, DocumentationListsRegistersAndFields) {
    const std::string md = registers_markdown({{&sample(), "Its window is nowhere"}});
    EXPECT_NE(md.find("## sample\n\nA block with one register of each kind. Its window is nowhere."), std::string::npos)
        << md;
    EXPECT_NE(md.find("| 0x0c | ID | RO | 0x1234 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| 2:1 | EN | RW |"), std::string::npos) << md;
}

// The maxima FIFO both the model and direct mode use: depth, drop count, overflow flag,
// threshold interrupt, pop order.
TEST(FhgRegisters, FifoKeepsTheFirstCandidatesAndCountsTheRest) {
    namespace r = fhg_regs;
    int started = 0;
    FhgRegisters regs({64, 64, 3, 8, 4}, {[&](const FhgRegisters::Frame& f) { started += int(f.width); }, {}, {}, {}});
    uint32_t v = 0;
    auto set = [&](uint32_t offset, uint32_t value) { ASSERT_TRUE(regs.access(offset, value, true)); };
    auto get = [&](uint32_t offset) {
        EXPECT_TRUE(regs.access(offset, v, false));
        return v;
    };
    EXPECT_EQ(get(r::DET_FRAC_BITS), 8u);
    set(r::WIDTH, 100);
    set(r::HEIGHT, 10);
    set(r::CTRL, r::CTRL_START);
    EXPECT_EQ(get(r::STATUS), r::STATUS_ERROR);  // 100 > 64 pixels
    EXPECT_EQ(get(r::ERROR_CODE), uint32_t(r::ERR_SIZE));
    set(r::WIDTH, 16);
    set(r::FIFO_THRESHOLD, 2);
    set(r::CTRL, r::CTRL_START | r::CTRL_IRQ_EN_FIFO);
    EXPECT_EQ(started, 16);
    std::vector<fhg::Candidate> found;
    for (int i = 0; i < 5; ++i) found.push_back({i, 2 * i, 1 + i % 4});
    EXPECT_FALSE(regs.irq());
    EXPECT_EQ(regs.push(found), 2u);
    EXPECT_TRUE(regs.irq());
    EXPECT_EQ(get(r::FIFO_LEVEL), 3u);
    EXPECT_EQ(get(r::OVERFLOW_COUNT), 2u);
    EXPECT_EQ(get(r::CANDIDATES), 5u);
    EXPECT_EQ(get(r::STATUS) & (r::STATUS_FIFO_OVERFLOW | r::STATUS_FIFO_IRQ),
              r::STATUS_FIFO_OVERFLOW | r::STATUS_FIFO_IRQ);
    EXPECT_EQ(get(r::FIFO_DATA), fhg::pack_candidate(found[0]));
    EXPECT_EQ(get(r::FIFO_DATA), fhg::pack_candidate(found[1]));
    EXPECT_FALSE(regs.irq());  // one left, below the threshold
    set(r::STATUS, r::STATUS_FIFO_OVERFLOW);
    EXPECT_EQ(get(r::STATUS) & r::STATUS_FIFO_OVERFLOW, 0u);
    EXPECT_EQ(get(r::FIFO_DATA), fhg::pack_candidate(found[2]));
    EXPECT_EQ(get(r::FIFO_DATA) >> 31, 0u);  // empty
}

}  // namespace
}  // namespace surfvp
