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
    lines_.assign(size_t(sets_) * params.ways, 0);
    filled_.assign(sets_, 0);
    victim_.assign(sets_, 0);
}

void CacheModel::invalidate() {
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

// Slots [0, filled) in recency order; a hit moves the line to the front, a miss inserts it
// at the front and, in a full set, drops the last (least recently used) one.
bool CacheModel::touch_lru(uint32_t set, uint32_t line) {
    uint32_t* slot = lines_.data() + size_t(set) * params_.ways;
    uint32_t& filled = filled_[set];
    uint32_t* end = slot + filled;
    uint32_t* found = std::find(slot, end, line);
    const bool hit = found != end;
    if (!hit) {
        if (filled < params_.ways) ++filled;
        found = slot + filled - 1;  // the victim: the free slot, or the least recent
    }
    std::copy_backward(slot, found, found + 1);
    slot[0] = line;
    return hit;
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
