#include "sw/cpu_cost/cache_model.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace surfvp::sw {
namespace {

bool power_of_two(uint64_t v) { return v && !(v & (v - 1)); }

unsigned log2_of(uint64_t v) {
    unsigned s = 0;
    while ((uint64_t(1) << s) < v) ++s;
    return s;
}

// The way holding `line` among `ways` distinct tags, or -1. Without an early exit, so that it
// vectorises: at most one way matches, so the sum of (way + 1) over matches is that way + 1.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
int find_way(const uint32_t* tags, uint32_t ways, uint32_t line) {
    uint32_t match = 0;
    for (uint32_t w = 0; w < ways; ++w) match += tags[w] == line ? w + 1 : 0;
    return int(match) - 1;
}

// The way with the smallest stamp among `ways` distinct ones (the least recently used).
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
uint32_t oldest_way(const uint64_t* stamps, uint32_t ways) {
    uint64_t least = ~uint64_t(0);
    for (uint32_t w = 0; w < ways; ++w) least = std::min(least, stamps[w]);
    uint32_t way = 0;
    for (uint32_t w = 0; w < ways; ++w) way += stamps[w] == least ? w : 0;
    return way;
}

}  // namespace

CacheModel::CacheModel(const CacheParams& params) : params_(params) {
    const uint64_t set_bytes = uint64_t(params.line_bytes) * params.ways;
    if (!power_of_two(params.line_bytes) || params.ways == 0 || set_bytes == 0 || params.size_bytes % set_bytes)
        throw std::invalid_argument("cache: line_bytes must be a power of two and size a multiple of line x ways (" +
                                    std::to_string(params.size_bytes) + " B, " + std::to_string(params.line_bytes) +
                                    " B lines, " + std::to_string(params.ways) + " ways)");
    sets_ = uint32_t(params.size_bytes / set_bytes);
    if (!power_of_two(sets_)) throw std::invalid_argument("cache: the number of sets must be a power of two");
    line_shift_ = log2_of(params.line_bytes);
    lines_.assign(size_t(sets_) * params.ways, kNoLine);
    use_.assign(lines_.size(), 0);
    hint_.assign(kHints, 0);
    filled_.assign(sets_, 0);
    victim_.assign(sets_, 0);
}

void CacheModel::invalidate() {
    std::fill(lines_.begin(), lines_.end(), kNoLine);
    std::fill(filled_.begin(), filled_.end(), 0);
    std::fill(victim_.begin(), victim_.end(), 0);
    last_valid_ = false;
}

CacheModel::Result CacheModel::access(uint32_t address, uint32_t bytes, std::vector<uint32_t>* missed) {
    Result r;
    if (bytes == 0) return r;
    const uint32_t first = address >> line_shift_;
    const uint32_t last = uint32_t((uint64_t(address) + bytes - 1) >> line_shift_);
    for (uint32_t line = first;; ++line) {
        if (touch(line)) {
            ++r.hits;
        } else {
            ++r.misses;
            if (missed) missed->push_back(line << line_shift_);
        }
        if (line == last) break;
    }
    hits_ += r.hits;
    misses_ += r.misses;
    return r;
}

bool CacheModel::touch(uint32_t line) {
    if (last_valid_ && line == last_line_) return true;
    last_line_ = line;
    last_valid_ = true;
    const uint32_t set = line & (sets_ - 1);
    return params_.replacement == Replacement::lru ? touch_lru(set, line) : touch_round_robin(set, line);
}

// A hit stamps its way; a miss fills the next free way or, in a full set, replaces the least
// recently used one.
bool CacheModel::touch_lru(uint32_t set, uint32_t line) {
    const size_t first = size_t(set) * params_.ways;
    uint32_t* tags = lines_.data() + first;
    uint64_t* stamps = use_.data() + first;
    uint32_t& hint = hint_[line & (kHints - 1)];
    const int found = tags[hint] == line ? int(hint) : find_way(tags, params_.ways, line);
    ++clock_;
    if (found >= 0) {
        stamps[found] = clock_;
        hint = uint32_t(found);
        return true;
    }
    uint32_t& filled = filled_[set];
    const uint32_t victim = filled < params_.ways ? filled++ : oldest_way(stamps, params_.ways);
    hint = victim;
    tags[victim] = line;
    stamps[victim] = clock_;
    return false;
}

// Hits change nothing; a miss fills way victim_[set] and advances it (PPC440x5 §4.1.1).
bool CacheModel::touch_round_robin(uint32_t set, uint32_t line) {
    uint32_t* slot = lines_.data() + size_t(set) * params_.ways;
    uint32_t& filled = filled_[set];
    if (std::find(slot, slot + filled, line) != slot + filled) return true;
    uint32_t& victim = victim_[set];
    slot[victim] = line;
    victim = (victim + 1) % params_.ways;
    if (filled < params_.ways) ++filled;
    return false;
}

}  // namespace surfvp::sw
