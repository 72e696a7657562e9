#pragma once
// A block's registers, declared once as a table (name, offset, access, reset value, fields)
// in its `*_regs.h`, and a RegisterBank that gives the table its behaviour: the values, the
// access rules, and the block's callbacks on a read or a write. The SystemC model and direct
// mode both answer the driver through the same bank, so they cannot disagree on a register.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace surfvp {

// How software may touch a register, or a field of one.
enum class Access {
    RO,       // read only: writes are ignored, as on the chip
    RW,       // read and write
    W1C,      // read; writing 1 clears the bit (a STATUS flag)
    WO,       // write only: reads return 0
    command,  // a field that acts when written 1 and reads 0 (CTRL.START)
};
const char* access_name(Access access);

struct RegisterField {
    std::string name;
    unsigned lsb, width;
    Access access;
    std::string meaning;
    uint32_t mask() const { return (width >= 32 ? ~0u : (1u << width) - 1) << lsb; }
};

struct Register {
    std::string name;
    uint32_t offset;
    Access access;
    uint32_t reset;
    std::string meaning;
    std::vector<RegisterField> fields;  // none: the whole word is one value
};

// One block's register file as the documentation shows it.
struct RegisterTable {
    std::string block;    // "SSA FHG"
    std::string summary;  // one line: what the registers are for
    std::vector<Register> registers;
    const Register* find(uint32_t offset) const;
};

// The values and the rules of one block's registers. A read returns the register's value,
// its `on_read` answer when it has one, 0 when it is write only. A write stores the bits
// software may set (RW fields, or the whole word when the register has no fields), clears
// the W1C bits written 1, ignores a read-only register, then calls `on_write` with the
// value as written (commands and side effects live there).
class RegisterBank {
public:
    explicit RegisterBank(const RegisterTable& table);

    void on_read(uint32_t offset, std::function<uint32_t()> answer);
    void on_write(uint32_t offset, std::function<void(uint32_t written)> act);

    // False for an offset that holds no register (the bus answers with an address error).
    bool access(uint32_t offset, uint32_t& value, bool write);

    uint32_t& value(uint32_t offset);  // the stored value, for the block's own use
    uint32_t value(uint32_t offset) const;
    void reset();
    const RegisterTable& table() const { return table_; }

private:
    struct Slot {
        const Register* reg;
        uint32_t value;
        uint32_t writable, clearable;
        std::function<uint32_t()> read;
        std::function<void(uint32_t)> write;
    };
    Slot* slot(uint32_t offset);
    const Slot* slot(uint32_t offset) const;

    const RegisterTable& table_;
    std::vector<Slot> slots_;
};

// docs/registers.md: every table as Markdown, in the order given, each with where it is
// on the chip ("PLB1 at 0xC1000000, pair k at + k x 0x100000").
struct MappedRegisters {
    const RegisterTable* table;
    std::string where;
};
std::string registers_markdown(const std::vector<MappedRegisters>& blocks);

}  // namespace surfvp
