#include "fault_plan.h"

#include <algorithm>
#include <fmt/format.h>

namespace surfvp {
namespace {

struct KindName {
    FaultKind kind;
    const char* name;
};
constexpr KindName kNames[] = {
    {FaultKind::dma_outside_memory, "dma_outside_memory"},
    {FaultKind::bus_error, "bus_error"},
    {FaultKind::lost_interrupt, "lost_interrupt"},
    {FaultKind::stuck_interrupt, "stuck_interrupt"},
    {FaultKind::fifo_overflow, "fifo_overflow"},
    {FaultKind::never_finishes, "never_finishes"},
    {FaultKind::corrupt_determinant, "corrupt_determinant"},
};

}  // namespace

const char* fault_kind_name(FaultKind kind) {
    for (const KindName& k : kNames)
        if (k.kind == kind) return k.name;
    return "?";
}

std::optional<FaultKind> parse_fault_kind(std::string_view name) {
    for (const KindName& k : kNames)
        if (name == k.name) return k.kind;
    return std::nullopt;
}

const std::vector<FaultKind>& fault_kinds() {
    static const std::vector<FaultKind> all = [] {
        std::vector<FaultKind> v;
        for (const KindName& k : kNames) v.push_back(k.kind);
        return v;
    }();
    return all;
}

bool strikes_a_frame(FaultKind kind) { return kind != FaultKind::bus_error; }

std::string Fault::describe() const {
    if (kind == FaultKind::bus_error) return fmt::format("bus_error on {}'s burst {}", block, burst);
    return fmt::format("{} on {}, frame {}", fault_kind_name(kind), block, frame);
}

std::optional<unsigned> pair_of(std::string_view name) {
    for (std::string_view kind : {"iig", "fhg"}) {
        if (name.substr(0, kind.size()) != kind) continue;
        const std::string_view digits = name.substr(kind.size());
        if (digits.empty()) return 0u;
        if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
            return std::nullopt;
        return unsigned(std::stoul(std::string(digits)));
    }
    return std::nullopt;
}

void FaultPlan::frame_started(unsigned pair, uint32_t src) {
    if (current_.size() <= pair) current_.resize(pair + 1, -1);
    const auto it = images_.find(src);
    current_[pair] = it == images_.end() ? -1 : it->second;
}

void FaultPlan::fire(Fault& fault, int64_t frame, uint64_t now_ps) {
    fault.fired = true;
    fault.fired_ps = now_ps;
    fault.struck_frame = frame;
}

bool FaultPlan::strike(FaultKind kind, std::string_view block, unsigned pair, uint64_t now_ps) {
    const int64_t frame = frame_of(pair);
    if (frame < 0) return false;
    for (Fault& f : faults_)
        if (!f.fired && f.kind == kind && f.block == block && int64_t(f.frame) == frame) {
            fire(f, frame, now_ps);
            return true;
        }
    return false;
}

void FaultPlan::strike_in_software(size_t index, uint64_t now_ps) {
    Fault& f = faults_.at(index);
    fire(f, int64_t(f.frame), now_ps);
}

bool FaultPlan::bus_error(std::string_view master, uint64_t burst, uint64_t now_ps) {
    for (Fault& f : faults_)
        if (!f.fired && f.kind == FaultKind::bus_error && f.block == master && f.burst == burst) {
            const auto pair = pair_of(master);
            fire(f, pair ? frame_of(*pair) : -1, now_ps);
            return true;
        }
    return false;
}

}  // namespace surfvp
