#pragma once
// The software stage's instruction stream as qemu-ppc executed it, cut into candidates and
// steps, timed by the PPC440 pipeline model. `surfvp calibrate` pipes qemu's log
// (`-d in_asm,exec,nochain`: the disassembly of every translated block, then one line per
// executed block) into a TraceReplay, which times each instruction under one or more
// parameter sets at once, so the log is read once and never stored. Plain C++.
#include <array>
#include <cstdint>
#include <istream>
#include <map>
#include <unordered_map>
#include <string>
#include <vector>

#include "sw/cpu_cost/ppc440_pipeline.h"
#include "sw/cpu_cost/work_units.h"

namespace surfvp::sw {

// What the firmware's link map tells: where its step markers and libm's code are.
struct FirmwareLayout {
    std::map<uint32_t, int> markers;  // entry address -> step (0..4), or -1 for idle
    std::vector<std::pair<uint32_t, uint32_t>> libm;  // [begin, end) of every libm text section
    bool in_libm(uint32_t pc) const;
};
// Reads a GNU ld map (-Wl,-Map). Throws std::runtime_error naming what it could not find.
FirmwareLayout read_link_map(std::istream& map);

// One step of one candidate, as the stream ran it.
struct StepStream {
    uint64_t instructions = 0;
    std::array<uint64_t, kInsnClasses> mix{};
    uint64_t libm_calls = 0, libm_instructions = 0;
    std::vector<double> cycles;  // per parameter set
};
using CandidateStream = std::array<StepStream, kSteps>;

class TraceReplay {
public:
    TraceReplay(const FirmwareLayout& layout, const std::vector<PipelineParams>& parameter_sets);

    // Consumes qemu's log. Throws std::runtime_error on a line it cannot read.
    void read(std::istream& log);

    const std::vector<CandidateStream>& candidates() const { return candidates_; }
    uint64_t instructions() const { return instructions_; }  // all of them, the harness's too
    const std::map<std::string, uint64_t>& unknown_mnemonics() const { return unknown_; }

private:
    struct Block {
        uint32_t pc = 0;
        std::vector<Insn> insns;
        int marker = -2;  // -2: none
        bool libm = false;
    };
    void parse_instruction(const std::string& line, Block& block);
    void execute(const Block& block, uint32_t next_pc);

    FirmwareLayout layout_;
    std::vector<Ppc440Pipeline> pipelines_;
    std::vector<uint64_t> last_issue_;
    std::unordered_map<uint32_t, Block> blocks_;
    std::vector<CandidateStream> candidates_;
    std::map<std::string, uint64_t> unknown_;
    int step_ = -1;  // current step, -1 outside a candidate
    bool was_libm_ = false;
    uint64_t instructions_ = 0;
};

}  // namespace surfvp::sw
