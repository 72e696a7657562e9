// Fuzz target: the RegisterBank rules (models/common/register_bank.h) on the chip's own
// register tables and on random ones, against the rules restated here:
//   - an offset holds a register exactly when the table lists one there;
//   - a read returns the register's on_read answer when it has one, else 0 for a write-only
//     register, else the stored value;
//   - a write to a read-only register changes nothing and calls nothing; otherwise an RW
//     register stores the bits of its RW fields (all 32 when it has no fields), a W1C register
//     clears the bits of its W1C fields (all 32 when none) that are written 1, and the
//     register's on_write is called with the value as written;
//   - reset() gives every register its reset value.
//
// Input: a table byte (0-3: the IIG's, FHG's, INTC's, DMA's tables; otherwise a random table
// follows: a count, then per register its offset byte, access, reset value and up to three
// fields of lsb, width and access), a byte saying which registers get an on_read answer, then
// operations: a byte (bits 0-1: read, write, reset), an offset byte, a 32-bit value.
//
// Expected answer: std::logic_error from the RegisterBank constructor for a table it refuses
// (an offset not word aligned or taken twice, a field outside the 32 bits); the chip's own
// tables must be taken. Any other exception, a crash, a sanitizer report or a difference
// from the rules is a bug.
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "fuzz_support.h"
#include "models/common/register_bank.h"
#include "models/dma/dma_regs.h"
#include "models/fhg/fhg_regs.h"
#include "models/iig/iig_regs.h"
#include "models/intc/intc_regs.h"

namespace {
using namespace surfvp;

Access access_of(uint8_t byte) { return Access(byte % 5); }

RegisterTable random_table(fuzz::Bytes& in) {
    RegisterTable t{"fuzz", "a random table", {}};
    const unsigned n = 1 + in.u8() % 8;
    for (unsigned k = 0; k < n; ++k) {
        Register r{"R" + std::to_string(k), in.u8(), access_of(in.u8()), in.u32(), "", {}};
        const unsigned fields = in.u8() % 4;
        for (unsigned f = 0; f < fields; ++f) {
            const unsigned lsb = in.u8() % 40, width = in.u8() % 40;
            r.fields.push_back({"F" + std::to_string(f), lsb, width, access_of(in.u8()), ""});
        }
        t.registers.push_back(std::move(r));
    }
    return t;
}

// The rules' own masks, in 64 bits so that no field can shift out of range here.
uint32_t mask_of(const Register& r, Access access) {
    if (r.fields.empty()) return ~0u;
    uint64_t mask = 0;
    for (const RegisterField& f : r.fields)
        if (f.access == access) mask |= ((uint64_t(1) << f.width) - 1) << f.lsb;
    return uint32_t(mask);
}

struct Expected {
    uint32_t value;
    bool answers;                   // has an on_read answer
    uint32_t writes = 0, last = 0;  // on_write calls, as seen by the bank's hook
};

uint32_t answer_of(uint32_t offset) { return 0x5A5A0000u ^ offset; }

void check(bool ok, const std::string& what) {
    if (!ok) fuzz::bug(what);
}

// `may_refuse`: the table is a random one, which the constructor may refuse.
void exercise(const RegisterTable& table, fuzz::Bytes& in, bool may_refuse) {
    std::unique_ptr<RegisterBank> made;
    try {
        made = std::make_unique<RegisterBank>(table);
    } catch (const std::logic_error& e) {
        if (!may_refuse) fuzz::unexpected(e);
        return;  // the bank's answer to a table it cannot give behaviour to
    }
    RegisterBank& bank = *made;
    const uint8_t answering = in.u8();
    std::map<uint32_t, Expected> model;
    std::map<uint32_t, Expected> seen;  // what the hooks saw
    for (size_t k = 0; k < table.registers.size(); ++k) {
        const Register& r = table.registers[k];
        const bool answers = (answering >> (k % 8)) & 1;
        model[r.offset] = {r.reset, answers};
        seen[r.offset] = {0, answers};
        if (answers) bank.on_read(r.offset, [o = r.offset] { return answer_of(o); });
        bank.on_write(r.offset, [&seen, o = r.offset](uint32_t v) {
            ++seen[o].writes;
            seen[o].last = v;
        });
    }
    while (!in.empty()) {
        const uint8_t op = in.u8() % 3;
        const uint32_t offset = in.u8();
        uint32_t value = in.u32();
        if (op == 2) {
            bank.reset();
            for (const Register& r : table.registers) model[r.offset].value = r.reset;
        } else {
            const Register* r = table.find(offset);
            const bool write = op == 1;
            const uint32_t written = value;
            check(bank.access(offset, value, write) == (r != nullptr),
                  "access() disagrees on whether a register is there");
            if (!r) continue;
            Expected& m = model[offset];
            if (!write) {
                const uint32_t expected = m.answers ? answer_of(offset) : r->access == Access::WO ? 0 : m.value;
                check(value == expected, table.block + "." + r->name + " reads " + std::to_string(value) +
                                             ", the rules say " + std::to_string(expected));
            } else if (r->access != Access::RO) {
                if (r->access == Access::RW) {
                    const uint32_t w = mask_of(*r, Access::RW);
                    m.value = (m.value & ~w) | (written & w);
                }
                if (r->access == Access::W1C) m.value &= ~(written & mask_of(*r, Access::W1C));
                ++m.writes;
                m.last = written;
            }
            check(seen[offset].writes == m.writes && seen[offset].last == m.last,
                  table.block + "." + r->name + ": on_write was not called as the rules say");
        }
        for (const Register& r : table.registers)
            check(bank.value(r.offset) == model[r.offset].value,
                  table.block + "." + r.name + " holds another value than the rules say");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fuzz::Bytes in(data, size);
    const uint8_t which = in.u8();
    const RegisterTable* chip_tables[] = {&iig::table(), &fhg_regs::table(), &intc::table(), &dma::table()};
    try {
        if (which < 4)
            exercise(*chip_tables[which], in, false);
        else
            exercise(random_table(in), in, true);
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
