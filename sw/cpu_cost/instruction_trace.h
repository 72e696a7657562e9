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
    std::map<uint32_t, int> markers;                  // entry address -> step (0..4), or -1 for idle
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

// A few whole candidates of the stream, kept so that the native model can re-time them under
// any parameter set (calibration.h: unit_prices): the blocks they ran (qemu's disassembly,
// "mnemonic|operands" per instruction) and the order they ran in.
struct StreamSample {
    struct Block {
        uint32_t pc = 0;
        int marker = -2;  // the step it begins (-1: idle), -2: none
        bool libm = false;
        std::vector<std::string> code;
    };
    std::vector<Block> blocks;
    std::vector<uint32_t> sequence;  // indices into blocks
    bool empty() const { return sequence.empty(); }
};

class TraceReplay {
public:
    TraceReplay(const FirmwareLayout& layout, const std::vector<PipelineParams>& parameter_sets);

    // Consumes qemu's log. Throws std::runtime_error on a line it cannot read.
    void read(std::istream& log);
    // Times a kept sample as if qemu had run it (its candidates are appended to candidates()).
    void replay(const StreamSample& sample);

    // Keeps `keypoints` runs of candidates, one starting at every `stride`-th candidate and
    // ending when a keypoint of it has been described (spread over the stream: its first
    // keypoints alone are not typical).
    void keep_sample(size_t keypoints, size_t stride) {
        sample_keypoints_ = keypoints;
        sample_stride_ = stride;
    }
    const StreamSample& sample() const { return sample_; }

    const std::vector<CandidateStream>& candidates() const { return candidates_; }
    uint64_t instructions() const { return instructions_; }  // all of them, the harness's too
    const std::map<std::string, uint64_t>& unknown_mnemonics() const { return unknown_; }

private:
    struct Block {
        uint32_t pc = 0;
        std::vector<Insn> insns;
        std::vector<std::string> code;  // "mnemonic|operands", for a sample
        int marker = -2;                // -2: none
        bool libm = false;
    };
    void parse_instruction(const std::string& line, Block& block);
    void add_instruction(uint32_t pc, const std::string& mnemonic, const std::string& operands, Block& block);
    void execute(const Block& block, uint32_t next_pc);
    void sample(const Block& block);

    FirmwareLayout layout_;
    std::vector<Ppc440Pipeline> pipelines_;
    std::vector<uint64_t> last_issue_;
    std::unordered_map<uint32_t, Block> blocks_;
    std::vector<CandidateStream> candidates_;
    std::map<std::string, uint64_t> unknown_;
    int step_ = -1;  // current step, -1 outside a candidate
    bool was_libm_ = false;
    uint64_t instructions_ = 0;
    size_t sample_keypoints_ = 0, sampled_keypoints_ = 0, sample_stride_ = 1, sample_candidates_ = 0;
    bool sampling_ = false, described_in_run_ = false;
    StreamSample sample_;
    std::unordered_map<uint32_t, uint32_t> sample_index_;  // block pc -> index in sample_.blocks
};

}  // namespace surfvp::sw
