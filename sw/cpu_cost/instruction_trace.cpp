#include "sw/cpu_cost/instruction_trace.h"

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <stdexcept>

namespace surfvp::sw {
namespace {

constexpr const char* kMarkerNames[] = {"surfvp_mark_check", "surfvp_mark_interpolation", "surfvp_mark_laplacian",
                                        "surfvp_mark_orientation", "surfvp_mark_descriptor"};
constexpr int kIdle = -1, kNoMarker = -2;

uint32_t hex(const std::string& s) { return uint32_t(std::strtoul(s.c_str(), nullptr, 16)); }

}  // namespace

bool FirmwareLayout::in_libm(uint32_t pc) const {
    for (const auto& [begin, end] : libm)
        if (pc >= begin && pc < end) return true;
    return false;
}

FirmwareLayout read_link_map(std::istream& map) {
    FirmwareLayout layout;
    const std::regex symbol(R"(^\s+0x([0-9a-f]+)\s+(surfvp_mark_\w+)\s*$)");
    const std::regex libm_text(R"(^ \.text\S*\s+0x([0-9a-f]+)\s+0x([0-9a-f]+)\s+\S*libm\.a\()");
    std::string line;
    std::smatch m;
    while (std::getline(map, line)) {
        if (std::regex_search(line, m, symbol)) {
            const std::string name = m[2];
            int step = name == "surfvp_mark_idle" ? kIdle : kNoMarker;
            for (int s = 0; s < int(kSteps); ++s)
                if (name == kMarkerNames[s]) step = s;
            if (step != kNoMarker) layout.markers[hex(m[1])] = step;
        } else if (line.find("libm.a(") != std::string::npos && std::regex_search(line, m, libm_text)) {
            const uint32_t begin = hex(m[1]), size = hex(m[2]);
            if (size) layout.libm.emplace_back(begin, begin + size);
        }
    }
    if (layout.markers.size() != kSteps + 1)
        throw std::runtime_error("link map: the firmware's six step markers (surfvp_mark_*) are not all there");
    if (layout.libm.empty()) throw std::runtime_error("link map: no libm code found (is the firmware static?)");
    return layout;
}

TraceReplay::TraceReplay(const FirmwareLayout& layout, const std::vector<PipelineParams>& parameter_sets)
    : layout_(layout), last_issue_(parameter_sets.size(), 0) {
    for (const PipelineParams& p : parameter_sets) pipelines_.emplace_back(p);
}

// "0x10000480:  7da802a6  mflr     r13"
void TraceReplay::parse_instruction(const std::string& line, Block& block) {
    const size_t colon = line.find(':');
    size_t i = line.find_first_not_of(' ', colon + 1);
    i = line.find(' ', i);  // skip the encoding
    i = line.find_first_not_of(' ', i);
    const size_t end = line.find(' ', i);
    const std::string mnemonic = line.substr(i, end == std::string::npos ? std::string::npos : end - i);
    const std::string operands = end == std::string::npos ? "" : line.substr(end);
    add_instruction(hex(line.substr(2, colon - 2)), mnemonic, operands, block);
}

void TraceReplay::add_instruction(uint32_t pc, const std::string& mnemonic, const std::string& operands, Block& block) {
    Insn in = decode(mnemonic, operands);
    if (in.cls == InsnClass::system && mnemonic != "sc" && mnemonic != "sync" && mnemonic != "isync")
        ++unknown_[mnemonic];
    if (in.conditional) {
        const size_t comma = operands.rfind(',');
        const std::string target = operands.substr(comma == std::string::npos ? 0 : comma + 1);
        const size_t x = target.find("0x");
        in.backward = x != std::string::npos && hex(target.substr(x + 2)) <= pc;
    }
    if (block.insns.empty()) block.pc = pc;
    block.insns.push_back(in);
    block.code.push_back(mnemonic + "|" + operands);
}

// A run of the sample starts at every sample_stride_-th candidate and ends at the first
// candidate after a keypoint's descriptor, until sample_keypoints_ runs are kept.
void TraceReplay::sample(const Block& b) {
    if (b.marker == int(Step::check)) {
        if (sampling_ && described_in_run_) sampling_ = false;
        if (!sampling_ && sampled_keypoints_ < sample_keypoints_ && sample_candidates_ % sample_stride_ == 0)
            sampling_ = true, described_in_run_ = false;
        ++sample_candidates_;
    }
    if (!sampling_) return;
    if (b.marker == int(Step::descriptor) && !described_in_run_) ++sampled_keypoints_, described_in_run_ = true;
    auto [it, added] = sample_index_.try_emplace(b.pc, uint32_t(sample_.blocks.size()));
    if (added) sample_.blocks.push_back({b.pc, b.marker, b.libm, b.code});
    sample_.sequence.push_back(it->second);
}

void TraceReplay::replay(const StreamSample& s) {
    std::vector<Block> blocks;
    for (const StreamSample::Block& in : s.blocks) {
        Block b;
        for (const std::string& text : in.code) {
            const size_t bar = text.find('|');
            add_instruction(in.pc + 4 * uint32_t(b.insns.size()), text.substr(0, bar),
                            bar == std::string::npos ? "" : text.substr(bar + 1), b);
        }
        b.pc = in.pc, b.marker = in.marker, b.libm = in.libm;
        blocks.push_back(std::move(b));
    }
    for (size_t i = 0; i < s.sequence.size(); ++i)
        execute(blocks.at(s.sequence[i]), i + 1 < s.sequence.size() ? blocks.at(s.sequence[i + 1]).pc : 0);
}

void TraceReplay::execute(const Block& b, uint32_t next_pc) {
    if (sample_keypoints_) sample(b);
    if (b.marker != kNoMarker) {
        step_ = b.marker;
        if (b.marker == int(Step::check)) {
            candidates_.emplace_back();
            for (StepStream& s : candidates_.back()) s.cycles.assign(pipelines_.size(), 0.0);
        }
    }
    StepStream* s = step_ >= 0 && !candidates_.empty() ? &candidates_.back()[size_t(step_)] : nullptr;
    instructions_ += b.insns.size();
    if (s) {
        s->instructions += b.insns.size();
        for (const Insn& in : b.insns) ++s->mix[size_t(in.cls)];
        if (b.libm) {
            s->libm_instructions += b.insns.size();
            if (!was_libm_) ++s->libm_calls;
        }
    }
    was_libm_ = b.libm;
    const uint32_t fallthrough = b.pc + 4 * uint32_t(b.insns.size());
    for (size_t k = 0; k < pipelines_.size(); ++k) {
        Ppc440Pipeline& pipe = pipelines_[k];
        for (size_t i = 0; i < b.insns.size(); ++i) {
            const bool last = i + 1 == b.insns.size();
            pipe.issue(b.insns[i], b.pc + 4 * uint32_t(i), last && next_pc != fallthrough);
        }
        const uint64_t now = pipe.issue_cycle();
        if (s) s->cycles[k] += double(now - last_issue_[k]);
        last_issue_[k] = now;
    }
}

void TraceReplay::read(std::istream& log) {
    std::string line;
    Block building;
    bool in_block = false;
    const Block* pending = nullptr;  // executed, waiting for the next block's address (was its branch taken?)
    while (std::getline(log, line)) {
        if (in_block) {
            if (line.rfind("0x", 0) == 0) {
                parse_instruction(line, building);
                continue;
            }
            in_block = false;
            if (!building.insns.empty()) {
                const auto marker = layout_.markers.find(building.pc);
                building.marker = marker == layout_.markers.end() ? kNoMarker : marker->second;
                building.libm = layout_.in_libm(building.pc);
                blocks_[building.pc] = building;
            }
        }
        if (line.rfind("IN:", 0) == 0) {
            in_block = true;
            building = Block{};
        } else if (line.rfind("Trace ", 0) == 0) {
            const size_t open = line.find('[');
            const size_t slash = line.find('/', open);
            if (open == std::string::npos || slash == std::string::npos)
                throw std::runtime_error("qemu log: cannot read \"" + line + "\"");
            const uint32_t pc = hex(line.substr(slash + 1, 8));
            const auto it = blocks_.find(pc);
            if (it == blocks_.end())
                throw std::runtime_error("qemu log: a block executed before its disassembly: " + line);
            if (pending) execute(*pending, pc);
            pending = &it->second;
        }
    }
    if (pending) execute(*pending, 0);
}

}  // namespace surfvp::sw
