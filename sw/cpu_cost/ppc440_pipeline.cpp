#include "sw/cpu_cost/ppc440_pipeline.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace surfvp::sw {
namespace {

constexpr const char* kClassNames[kInsnClasses] = {
    "integer", "multiply", "divide", "compare", "cr_logical", "spr_move", "load",  "store",  "branch",  "fadd",  "fmul",
    "fmadd",   "fdiv",     "fsqrt",  "fcmp",    "fmove",      "fconvert", "fload", "fstore", "fstatus", "system"};

bool starts(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }
bool one_of(const std::string& s, std::initializer_list<const char*> names) {
    for (const char* n : names)
        if (s == n) return true;
    return false;
}

// "r9" -> 9, "f1" -> 33, "cr7" -> 71, "-0x480(r8)" -> 8 (the base); -1 for anything else.
int reg_of(const std::string& t) {
    const size_t open = t.find('(');
    if (open != std::string::npos) return reg_of(t.substr(open + 1, t.size() - open - 2));
    auto number = [&](size_t from, int limit) {
        if (from >= t.size()) return -1;
        for (size_t i = from; i < t.size(); ++i)
            if (!std::isdigit(static_cast<unsigned char>(t[i]))) return -1;
        const int n = std::atoi(t.c_str() + from);
        return n < limit ? n : -1;
    };
    if (starts(t, "cr")) {
        const int n = number(2, 8);
        return n < 0 ? -1 : kCr + n;
    }
    if (t[0] == 'r') return number(1, 32);
    if (t[0] == 'f') {
        const int n = number(1, 32);
        return n < 0 ? -1 : kFpr + n;
    }
    return -1;
}

std::vector<std::string> split_operands(const std::string& ops) {
    std::vector<std::string> out;
    std::string cur;
    for (char ch : ops) {
        if (ch == ',') {
            out.push_back(cur);
            cur.clear();
        } else if (!std::isspace(static_cast<unsigned char>(ch))) {
            cur += ch;
        }
    }
    if (!cur.empty()) out.push_back(cur);
    return out;
}

void add_dst(Insn& in, int r) {
    if (r >= 0 && in.ndst < 3) in.dst[in.ndst++] = uint8_t(r);
}
void add_src(Insn& in, int r) {
    if (r >= 0 && in.nsrc < 4) in.src[in.nsrc++] = uint8_t(r);
}

// Branch mnemonics: b, bl, ba, blr, bctr(l), bdnz, bdz, beq, bne, blt+ ... with cr fields.
void decode_branch(Insn& in, std::string m, const std::vector<std::string>& ops) {
    in.cls = InsnClass::branch;
    while (!m.empty() && (m.back() == '+' || m.back() == '-')) m.pop_back();  // static hints
    if (m == "b" || m == "ba" || m == "bl" || m == "bla") {
        in.btac = true;
        if (m == "bl" || m == "bla") add_dst(in, kLr);
        return;
    }
    if (starts(m, "blr") || m == "blrl") {
        in.btac = true;
        add_src(in, kLr);
        if (m == "blrl") add_dst(in, kLr);
        return;
    }
    if (starts(m, "bctr")) {
        in.btac = true;
        add_src(in, kCtr);
        if (m == "bctrl") add_dst(in, kLr);
        return;
    }
    in.conditional = true;
    if (starts(m, "bd")) {  // bdnz, bdz, bdnzf ...: decrement CTR
        in.btac = m == "bdnz";
        add_src(in, kCtr);
        add_dst(in, kCtr);
    }
    int cr = -1;
    for (const std::string& t : ops) {
        const int r = reg_of(t);
        if (r >= kCr && r < kCr + 8) cr = r;
    }
    if (!starts(m, "bdnz") && !starts(m, "bdz")) add_src(in, cr >= 0 ? cr : kCr);
    if (m.find("lr") != std::string::npos) add_src(in, kLr);
    if (m.find("ctr") != std::string::npos) add_src(in, kCtr);
    if (m.back() == 'l') add_dst(in, kLr);  // beql, bnectrl ...: conditional calls
}

InsnClass fp_class(const std::string& m) {
    std::string b = m;
    if (b.size() > 1 && b.back() == 's' && !one_of(b, {"fabs"})) b.pop_back();  // single-precision forms
    if (one_of(b, {"fadd", "fsub"})) return InsnClass::fadd;
    if (b == "fmul") return InsnClass::fmul;
    if (one_of(b, {"fmadd", "fmsub", "fnmadd", "fnmsub"})) return InsnClass::fmadd;
    if (one_of(b, {"fdiv", "fre"})) return InsnClass::fdiv;
    if (one_of(b, {"fsqrt", "frsqrte"})) return InsnClass::fsqrt;
    if (one_of(b, {"fcmpu", "fcmpo"})) return InsnClass::fcmp;
    if (one_of(m, {"fmr", "fabs", "fneg", "fnabs", "fsel"})) return InsnClass::fmove;
    if (one_of(m, {"fctiw", "fctiwz", "frsp", "fcfid"})) return InsnClass::fconvert;
    return InsnClass::system;
}

}  // namespace

const char* insn_class_name(InsnClass c) { return kClassNames[static_cast<size_t>(c)]; }

bool is_fpu_arithmetic(InsnClass c) {
    return (c >= InsnClass::fadd && c <= InsnClass::fconvert) || c == InsnClass::fstatus;
}

Insn decode(const std::string& mnemonic, const std::string& operands) {
    Insn in;
    std::string m = mnemonic;
    const bool record = !m.empty() && m.back() == '.';
    if (record) m.pop_back();
    const std::vector<std::string> ops = split_operands(operands);
    std::vector<int> regs;
    for (const std::string& t : ops) regs.push_back(reg_of(t));
    auto all_src = [&](size_t from) {
        for (size_t i = from; i < regs.size(); ++i) add_src(in, regs[i]);
    };
    auto first_dst = [&] {
        if (!regs.empty()) add_dst(in, regs[0]);
        all_src(1);
    };

    if (m[0] == 'b') {  // the trace reader sets `backward`: it knows the pc
        decode_branch(in, m, ops);
        return in;
    }
    if (starts(m, "cmp")) {
        in.cls = InsnClass::compare;
        const bool has_cr = !regs.empty() && regs[0] >= kCr;
        add_dst(in, has_cr ? regs[0] : kCr);
        all_src(has_cr ? 1 : 0);
        return in;
    }
    if (one_of(m, {"fcmpu", "fcmpo"})) {
        in.cls = InsnClass::fcmp;
        add_dst(in, regs.empty() || regs[0] < kCr ? kCr : regs[0]);
        all_src(1);
        return in;
    }
    if (starts(m, "cr") || m == "mcrf") {
        in.cls = InsnClass::cr_logical;
        return in;
    }
    if (one_of(m, {"mflr", "mfctr", "mfxer", "mfcr", "mfspr", "mftb", "mfmsr"})) {
        in.cls = InsnClass::spr_move;
        add_dst(in, regs.empty() ? -1 : regs[0]);
        add_src(in, m == "mflr" ? kLr : m == "mfctr" ? kCtr : m == "mfxer" ? kXer : -1);
        return in;
    }
    if (one_of(m, {"mtlr", "mtctr", "mtxer", "mtcrf", "mtcr", "mtspr", "mtmsr"})) {
        in.cls = InsnClass::spr_move;
        add_dst(in, m == "mtlr" ? kLr : m == "mtctr" ? kCtr : m == "mtxer" ? kXer : -1);
        for (int r : regs)
            if (r >= 0 && r < 32) add_src(in, r);
        return in;
    }
    if (one_of(m, {"mffs", "mtfsf", "mtfsfi", "mtfsb0", "mtfsb1"})) {
        in.cls = InsnClass::fstatus;
        add_dst(in, m == "mffs" ? (regs.empty() ? -1 : regs[0]) : kFpscr);
        add_src(in, m == "mffs" ? kFpscr : -1);
        for (int r : regs)
            if (m != "mffs" && r >= kFpr && r < kCr) add_src(in, r);
        return in;
    }
    if (m[0] == 'f') {
        in.cls = fp_class(m);
        in.round_to_single = m == "frsp";
        if (in.cls == InsnClass::system) return in;
        first_dst();
        if (record) add_dst(in, kCr + 1);
        return in;
    }
    const bool update = (starts(m, "l") || starts(m, "st")) && m.find('u') != std::string::npos && !starts(m, "lhbr");
    if (starts(m, "lf")) {
        in.cls = InsnClass::fload;
        first_dst();
        if (update && regs.size() > 1) add_dst(in, regs[1]);
        return in;
    }
    if (starts(m, "stf")) {
        in.cls = InsnClass::fstore;
        all_src(0);
        if (update && regs.size() > 1) add_dst(in, regs[1]);
        return in;
    }
    if (starts(m, "st") || starts(m, "dcb") || starts(m, "icb")) {
        in.cls = InsnClass::store;
        all_src(0);
        if (update && regs.size() > 1) add_dst(in, regs[1]);
        if (m == "stmw" && !regs.empty() && regs[0] >= 0) in.repeat = uint8_t(32 - regs[0]);
        return in;
    }
    if (m[0] == 'l' && !one_of(m, {"li", "lis"})) {
        in.cls = InsnClass::load;
        first_dst();
        if (update && regs.size() > 1) add_dst(in, regs[1]);
        if (m == "lmw" && !regs.empty() && regs[0] >= 0) in.repeat = uint8_t(32 - regs[0]);
        return in;
    }
    if (starts(m, "mul")) {
        in.cls = InsnClass::multiply;
    } else if (starts(m, "div")) {
        in.cls = InsnClass::divide;
    } else if (one_of(m, {"sc", "sync", "isync", "eieio", "msync", "mbar", "tw", "twi", "trap", "rfi", "wrteei"})) {
        in.cls = InsnClass::system;
        return in;
    } else {
        in.cls = InsnClass::integer;
    }
    first_dst();
    if (record) add_dst(in, kCr);
    if (starts(m, "addic") || starts(m, "subfic") || starts(m, "subfc") || starts(m, "addc") || m == "srawi" ||
        m == "sraw")
        add_dst(in, kXer);
    if (starts(m, "adde") || starts(m, "addze") || starts(m, "subfe") || starts(m, "subfze") || starts(m, "addme"))
        add_src(in, kXer), add_dst(in, kXer);
    if (m == "isel") add_src(in, kCr);
    return in;
}

const std::vector<PipelineKnob>& pipeline_knobs() {
    using P = PipelineParams;
    static const std::vector<PipelineKnob> knobs = {
        {"ppc.issue_width", &P::issue_width, 1, 2, false, "count", "Instructions the PPC440 issues per cycle",
         "[S] PowerPC 440 core datasheet: dual-issue superscalar", "probe: single issue"},
        {"ppc.load_latency", &P::load_latency, 2, 4, false, "cycles", "CPU cycles from an integer load to its use",
         "[S] GCC's PPC440 pipeline description (rs6000/440.md): load 3", "probe: one cycle either way"},
        {"ppc.multiply_latency", &P::multiply_latency, 2, 4, false, "cycles", "CPU cycles of an integer multiply",
         "[S] 440.md: imul 3", "probe: one cycle either way"},
        {"ppc.divide_latency", &P::divide_latency, 33, 35, false, "cycles",
         "CPU cycles of an integer divide (the complex pipe is busy meanwhile)", "[S] 440.md: idiv 34",
         "probe: one cycle either way"},
        {"ppc.compare_latency", &P::compare_latency, 1, 3, false, "cycles", "CPU cycles from a compare to its branch",
         "[S] 440.md: compare 2", "probe: one cycle either way"},
        {"ppc.spr_latency", &P::spr_latency, 3, 5, false, "cycles", "CPU cycles of a move to LR or CTR",
         "[S] 440.md: mtjmpr 4", "probe: one cycle either way"},
        {"ppc.mfspr_latency", &P::mfspr_latency, 1, 3, false, "cycles", "CPU cycles of a move from LR or CTR",
         "[S] 440.md: mfjmpr 2", "probe: one cycle either way"},
        {"ppc.taken_bubble", &P::taken_bubble, 0, 2, false, "cycles",
         "CPU cycles lost by a taken branch the BTAC does not hold",
         "[S] PowerPC 440 datasheet: the BTAC \"avoids a one cycle penalty\"", "probe: one cycle either way"},
        {"ppc.mispredict", &P::mispredict_cycles, 2, 7, true, "cycles", "CPU cycles lost by a mispredicted branch",
         "[A] not retrieved: the 7-stage pipeline resolves branches late", "an early or a late branch resolution"},
        {"cpu.fpu_ratio", &P::fpu_ratio, 2, 3, true, "count", "CPU cycles per FPU cycle",
         "[S] DS693: optimised for 2:1 and 3:1", "the other ratio DS693 supports"},
        {"fpu.precision", &P::double_precision, 0, 1, true, "precision",
         "The APU FPU's precision: the latency column the stream is timed with (and frsp, which only the double FPU "
         "has)",
         "[A] single: the FPU Xilinx offers for float code (DS693: 2620 LUT-FF pairs and 3 DSP48E against 4950 and "
         "13); "
         "the firmware is built for the double FPU, the only one Debian's GCC targets (sw/cpu_cost/README.md)",
         "the paper says only \"FPU\": DS693 offers both"},
        {"apu.issue", &P::apu_issue, 1, 4, true, "cycles",
         "CPU cycles an FP add, multiply or multiply-add holds the APU's issue",
         "[S/proxy] GCC xfpu.md (Xilinx APU FPU): Xfpu_issue*2",
         "the Virtex-4 APU FPU sheet's one instruction every 4 CPU cycles; 1 if the Virtex-5 APU issues faster"},
        {"apu.load_issue", &P::apu_load_issue, 2, 14, true, "cycles", "CPU cycles an FP load holds the APU's issue",
         "[S/proxy] xfpu.md: Xfpu_issue*10 (issue 2 + 4 FPU cycles x 2); the Virtex-4 sheet: issue 4 + at least 3 FPU "
         "cycles, one load at a time",
         "2: a Virtex-5 APU that frees the issue after 2 cycles (DS693's autonomous issue); 14: a double load (2 + 6 x "
         "2)"},
        {"apu.store_issue", &P::apu_store_issue, 2, 8, true, "cycles", "CPU cycles an FP store holds the APU's issue",
         "[S/proxy] xfpu.md: Xfpu_issue*4", "2: the issue alone; 8: the Virtex-4 sheet's 4 FPU cycles a store"},
        {"apu.move_issue", &P::apu_move_issue, 1, 4, true, "cycles",
         "CPU cycles an FP move, abs, negate or FPSCR access holds the APU's issue",
         "[S/proxy] xfpu.md: fp-default, Xfpu_issue*2", "as apu.issue"},
        {"apu.compare_issue", &P::apu_compare_issue, 1, 4, true, "cycles",
         "CPU cycles an FP compare holds the APU's issue", "[S/proxy] xfpu.md: fp-compare, Xfpu_issue*2",
         "as apu.issue"},
        {"apu.convert_issue", &P::apu_convert_issue, 1, 4, true, "cycles",
         "CPU cycles an FP conversion (fctiwz, frsp) holds the APU's issue",
         "[S/proxy] xfpu.md: fp-default, Xfpu_issue*2", "as apu.issue"},
        {"apu.divide_issue", &P::apu_divide_issue, 1, 4, true, "cycles",
         "CPU cycles an FP divide or square root holds the APU's issue (the unpipelined divider stays busy for its "
         "whole "
         "latency: the next divide waits)",
         "[S/proxy] xfpu.md: Xfpu_issue*2 then Xfpu_div (unpipelined); the Virtex-4 sheet: divide and square root not "
         "pipelined",
         "as apu.issue"},
        {"apu.outstanding_loads", &P::apu_outstanding_loads, 1, 2, true, "count",
         "FP loads in flight at once: a load waits while this many have not delivered their data",
         "[S/proxy] Virtex-4 APU FPU sheet: the APU controller cannot process more than one outstanding load",
         "2: a Virtex-5 APU controller that takes a second (DS693 says nothing)"},
        {"apu.overhead", &P::apu_overhead, 1, 4, true, "cycles",
         "CPU cycles of the APU's register file access and write back", "[A] proxy: xfpu.md: 2",
         "the Virtex-5 APU may be faster or slower than the PPC405's (DS693's table not retrieved)"},
        {"fpu.fadd", &P::fadd, 5, 7, true, "fpu_cycles", "FPU cycles of an add or subtract",
         "[A] proxy: xfpu.md, the precision's column: single 5, double 7; the Virtex-4 sheet: 6",
         "the columns and the sheet"},
        {"fpu.fmul", &P::fmul, 4, 11, true, "fpu_cycles", "FPU cycles of a multiply",
         "[A] proxy: xfpu.md: single 4, double 11; the Virtex-4 sheet: 5", "the columns and the sheet"},
        {"fpu.fmadd", &P::fmadd, 10, 19, true, "fpu_cycles", "FPU cycles of a fused multiply-add",
         "[A] proxy: xfpu.md: single 10, double 19; the Virtex-4 sheet: 10", "the columns and the sheet"},
        {"fpu.fdiv", &P::fdiv, 17, 56, true, "fpu_cycles", "FPU cycles of a divide (the divider is unpipelined)",
         "[A] proxy: xfpu.md: single 27, double 56; the Virtex-4 sheet: 17", "the columns and the sheet"},
        {"fpu.fsqrt", &P::fsqrt, 17, 56, true, "fpu_cycles", "FPU cycles of a square root (the divider is unpipelined)",
         "[A] proxy: xfpu.md: single 27, double 56; the Virtex-4 sheet: 17", "the columns and the sheet"},
        {"fpu.fcmp", &P::fcmp, 1, 3, true, "fpu_cycles", "FPU cycles of a compare",
         "[A] proxy: xfpu.md: single 1, double 2; the Virtex-4 sheet: 3", "the columns and the sheet"},
        {"fpu.fmove", &P::fmove, 1, 2, true, "fpu_cycles", "FPU cycles of a move, abs or negate",
         "[A] proxy: xfpu.md: 1 in both; the Virtex-4 sheet: 2", "the sheet"},
        {"fpu.fconvert", &P::fconvert, 4, 6, true, "fpu_cycles", "FPU cycles of a conversion (fctiwz, frsp)",
         "[A] proxy: xfpu.md: single 4, double 6; the Virtex-4 sheet: 6", "the columns"},
        {"fpu.fload", &P::fload, 3, 6, true, "fpu_cycles", "FPU cycles of a load into the FPU (L1 hit)",
         "[A] proxy: xfpu.md: single 4, double 6; the Virtex-4 sheet: at least 3", "the columns and the sheet"},
        {"fpu.fstore", &P::fstore, 1, 4, true, "fpu_cycles", "FPU cycles of a store from the FPU",
         "[A] proxy: xfpu.md: single 1, double 2 (from the data's availability); the Virtex-4 sheet: 4",
         "the columns and the sheet"},
        {"apu.overlap", &P::fpu_overlap, 0, 1, true, "switch",
         "Whether integer work issues while the FPU computes (on), or the CPU waits for each FPU result (off)",
         "[S] DS693: the FPU is autonomous, the PowerPC pipeline goes on with integer instructions meanwhile",
         "a CPU that waits for every FPU result"},
    };
    return knobs;
}

Ppc440Pipeline::Ppc440Pipeline(const PipelineParams& params) : p_(params) {
    if (!(p_.issue_width >= 1)) throw std::invalid_argument("ppc440 pipeline: issue_width must be >= 1");
    if (!(p_.apu_outstanding_loads >= 1))
        throw std::invalid_argument("ppc440 pipeline: apu.outstanding_loads must be >= 1");
    for (const PipelineKnob& k : pipeline_knobs())
        if (!std::isfinite(p_.*k.field) || p_.*k.field < 0)
            throw std::invalid_argument(std::string("ppc440 pipeline: ") + k.key + " must be >= 0");
}

FpuColumn fpu_column(bool double_precision) {
    // xfpu.md's latency table (FCB cycles): SP and DP columns.
    return double_precision ? FpuColumn{7, 11, 19, 56, 56, 2, 1, 6, 6, 2} : FpuColumn{5, 4, 10, 27, 27, 1, 1, 4, 4, 1};
}

PipelineParams PipelineParams::for_precision(bool double_precision) {
    PipelineParams p;
    p.double_precision = double_precision ? 1 : 0;
    const FpuColumn c = fpu_column(double_precision);
    p.fadd = c.fadd, p.fmul = c.fmul, p.fmadd = c.fmadd, p.fdiv = c.fdiv, p.fsqrt = c.fsqrt;
    p.fcmp = c.fcmp, p.fmove = c.fmove, p.fconvert = c.fconvert, p.fload = c.fload, p.fstore = c.fstore;
    return p;
}

const char* knob_choice(const PipelineKnob& k, double value) {
    const std::string unit = k.unit;
    if (unit == "switch") return value > 0.5 ? "on" : "off";
    if (unit == "precision") return value > 0.5 ? "double" : "single";
    return nullptr;
}

double Ppc440Pipeline::occupancy(InsnClass c) const {
    switch (c) {
        case InsnClass::fload:
            return p_.apu_load_issue;
        case InsnClass::fstore:
            return p_.apu_store_issue;
        case InsnClass::fmove:
        case InsnClass::fstatus:
            return p_.apu_move_issue;
        case InsnClass::fcmp:
            return p_.apu_compare_issue;
        case InsnClass::fconvert:
            return p_.apu_convert_issue;
        case InsnClass::fdiv:
        case InsnClass::fsqrt:
            return p_.apu_divide_issue;
        default:
            return p_.apu_issue;
    }
}

double Ppc440Pipeline::result_latency(InsnClass c) const {
    const double apu = p_.apu_issue + p_.apu_overhead;
    switch (c) {
        case InsnClass::multiply:
            return p_.multiply_latency;
        case InsnClass::divide:
            return p_.divide_latency;
        case InsnClass::compare:
            return p_.compare_latency;
        case InsnClass::load:
            return p_.load_latency;
        case InsnClass::fadd:
            return apu + p_.fadd * p_.fpu_ratio;
        case InsnClass::fmul:
            return apu + p_.fmul * p_.fpu_ratio;
        case InsnClass::fmadd:
            return apu + p_.fmadd * p_.fpu_ratio;
        case InsnClass::fdiv:
            return apu + p_.fdiv * p_.fpu_ratio;
        case InsnClass::fsqrt:
            return apu + p_.fsqrt * p_.fpu_ratio;
        case InsnClass::fcmp:
            return apu + p_.fcmp * p_.fpu_ratio;
        case InsnClass::fmove:
        case InsnClass::fstatus:
            return apu + p_.fmove * p_.fpu_ratio;
        case InsnClass::fconvert:
            return apu + p_.fconvert * p_.fpu_ratio;
        // APU loads and stores: issue plus the FPU's access (xfpu.md: a load 10 = 2 + 4 x 2).
        case InsnClass::fload:
            return p_.apu_issue + p_.fload * p_.fpu_ratio;
        case InsnClass::fstore:
            return p_.apu_issue + p_.fstore * p_.fpu_ratio;
        default:
            return 1;
    }
}

Ppc440Pipeline::Pipe Ppc440Pipeline::pick_pipe(InsnClass c, uint64_t at) const {
    switch (c) {
        case InsnClass::integer:
            return used(kPipeJ, at) ? kPipeI : kPipeJ;
        case InsnClass::load:
        case InsnClass::store:
        case InsnClass::fload:
        case InsnClass::fstore:
            return kPipeL;
        default:
            return is_fpu_arithmetic(c) ? kPipeF : kPipeI;
    }
}

uint64_t Ppc440Pipeline::issue(const Insn& in, uint32_t pc, bool taken) {
    const auto ceil = [](double v) { return uint64_t(std::ceil(v - 1e-9)); };
    const bool fpu = is_fpu_arithmetic(in.cls) || in.cls == InsnClass::fload || in.cls == InsnClass::fstore;
    if (in.round_to_single && p_.double_precision < 0.5) {
        // Code for the single-precision FPU has nothing to round (DS693: that FPU has no frsp).
        if (in.ndst && in.nsrc) ready_[in.dst[0]] = ready_[in.src[0]];
        return cycle_;
    }
    uint64_t t = std::max(cycle_, next_);
    if (t == cycle_ && issued_now_ >= unsigned(p_.issue_width)) ++t;
    for (uint8_t i = 0; i < in.nsrc; ++i) t = std::max(t, ready_[in.src[i]]);
    if (fpu) t = std::max(t, fpu_free_);
    const bool divider = in.cls == InsnClass::fdiv || in.cls == InsnClass::fsqrt;
    if (divider) t = std::max(t, divider_free_);
    if (in.cls == InsnClass::fload) {  // in-order issue: the oldest outstanding load delivers first
        while (!loads_.empty() && loads_.front() <= t) loads_.erase(loads_.begin());
        while (double(loads_.size()) >= p_.apu_outstanding_loads) {
            t = std::max(t, loads_.front());
            loads_.erase(loads_.begin());
        }
    }
    if (in.cls != InsnClass::integer && pick_pipe(in.cls, t) == kPipeI) t = std::max(t, i_pipe_free_);
    const Pipe pipe0 = pick_pipe(in.cls, t);
    if (used(pipe0, t) || (pipe0 == kPipeI && in.cls == InsnClass::integer && t < i_pipe_free_)) ++t;
    if (t > cycle_) {
        cycle_ = t;
        issued_now_ = 0;
    }
    const Pipe pipe = pick_pipe(in.cls, t);
    pipe_used_[pipe] = t + 1;
    ++issued_now_;
    // lmw/stmw: one access per cycle after the first.
    const uint64_t extra = in.repeat > 1 ? in.repeat - 1u : 0u;
    if (extra) {
        cycle_ += extra;
        issued_now_ = 1;
        pipe_used_[pipe] = cycle_ + 1;
    }

    double latency = result_latency(in.cls);
    if (in.cls == InsnClass::spr_move) latency = in.ndst && in.dst[0] >= kLr ? p_.spr_latency : p_.mfspr_latency;
    const uint64_t done = cycle_ + ceil(latency);
    for (uint8_t i = 0; i < in.ndst; ++i)
        ready_[in.dst[i]] =
            in.dst[i] >= kCr && in.dst[i] < kCr + 8 && in.cls != InsnClass::compare && in.cls != InsnClass::fcmp
                ? cycle_ + ceil(p_.compare_latency)  // a record form's CR0
                : done;
    last_ = std::max(last_, done);
    if (fpu) {
        fpu_free_ = cycle_ + ceil(occupancy(in.cls));
        if (divider) divider_free_ = done;
        if (in.cls == InsnClass::fload) loads_.push_back(done);
        if (p_.fpu_overlap < 0.5) next_ = std::max(next_, done);
    }
    if (in.cls == InsnClass::divide) i_pipe_free_ = cycle_ + ceil(p_.divide_latency) - 1;

    if (in.cls == InsnClass::branch) {
        bool mispredicted = false;
        if (in.conditional) {
            // A new branch starts from the static prediction: weakly taken backward, weakly not taken forward.
            uint8_t& counter = bht_.try_emplace(pc, uint8_t(in.backward ? 2 : 1)).first->second;
            mispredicted = (counter >= 2) != taken;
            counter = uint8_t(taken ? std::min(3, counter + 1) : std::max(0, counter - 1));
        }
        if (mispredicted)
            next_ = std::max(next_, cycle_ + 1 + ceil(p_.mispredict_cycles));
        else if (taken)
            next_ = std::max(next_, cycle_ + 1 + (in.btac ? 0 : ceil(p_.taken_bubble)));
    }
    return cycle_;
}

uint64_t Ppc440Pipeline::cycles() const { return std::max(cycle_ + 1, last_); }

void Ppc440Pipeline::reset() {
    cycle_ = 0;
    issued_now_ = 0;
    std::fill(std::begin(pipe_used_), std::end(pipe_used_), 0);
    std::fill(std::begin(ready_), std::end(ready_), 0);
    fpu_free_ = divider_free_ = i_pipe_free_ = next_ = last_ = 0;
    loads_.clear();
    bht_.clear();
}

}  // namespace surfvp::sw
