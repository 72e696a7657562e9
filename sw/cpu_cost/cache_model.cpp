#include "sw/cpu_cost/cache_model.h"

#include <algorithm>
#include <new>
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
    if (!power_of_two(params.line_bytes) || params.line_bytes < 2 || params.ways == 0 || params.ways > 0xFFFF ||
        set_bytes == 0 || params.size_bytes % set_bytes)
        throw std::invalid_argument(
            "cache: line_bytes must be a power of two of 2 B or more, the ways 1 to 65535 and size a "
            "multiple of line x ways (" +
            std::to_string(params.size_bytes) + " B, " + std::to_string(params.line_bytes) + " B lines, " +
            std::to_string(params.ways) + " ways)");
    sets_ = uint32_t(params.size_bytes / set_bytes);
    if (!power_of_two(sets_)) throw std::invalid_argument("cache: the number of sets must be a power of two");
    line_shift_ = log2_of(params.line_bytes);
    lines_.assign(size_t(sets_) * params.ways, kNoLine);
    filled_.assign(sets_, 0);
    where_.resize(size_t(((uint64_t(1) << (32 - line_shift_)) + kChunk - 1) >> kChunkShift));
    links_.assign(lines_.size(), Link{0, 0});
    ends_.assign(sets_, Ends{0, 0});
    victim_.assign(sets_, 0);
}

void CacheModel::invalidate() {
    for (uint32_t& line : lines_) {
        if (line != kNoLine) where(line) = 0;
        line = kNoLine;
    }
    std::fill(filled_.begin(), filled_.end(), 0);
    std::fill(victim_.begin(), victim_.end(), 0);
    last_line_ = kNoLine;
}

// The look-up's steps are forced inline into access_lines (below them): as calls they were a
// sixth of its time.
[[gnu::always_inline]] inline bool CacheModel::touch(uint32_t line) {
    if (line == last_line_) return true;
    last_line_ = line;
    const uint32_t set = line & (sets_ - 1);
    return params_.replacement == Replacement::lru ? touch_lru(set, line) : touch_round_robin(set, line);
}

[[gnu::always_inline]] inline uint16_t& CacheModel::where(uint32_t line) {
    Chunk& chunk = where_[line >> kChunkShift];
    if (!chunk) {
        // calloc: a chunk's zeroes are the allocator's fresh pages, not written; the software's
        // few reads spread over the determinant buffers then fault in a page of it, not 32.
        chunk.reset(static_cast<uint16_t*>(std::calloc(kChunk, sizeof(uint16_t))));
        if (!chunk) throw std::bad_alloc();
    }
    return chunk.get()[line & (kChunk - 1)];
}

// A hit moves its way to the front; a miss fills the next free way (the new front) or, in a
// full set, refills the least recently used one.
[[gnu::always_inline]] inline bool CacheModel::touch_lru(uint32_t set, uint32_t line) {
    const size_t base = size_t(set) * params_.ways;
    uint16_t& slot = where(line);
    if (slot) {
        make_newest(base, set, slot - 1u);
        return true;
    }
    uint32_t& filled = filled_[set];
    uint32_t way;
    Ends& ends = ends_[set];
    if (filled == params_.ways) {
        way = ends.oldest;
        where(lines_[base + way]) = 0;
        make_newest(base, set, way);
    } else {
        way = filled++;
        if (way) {
            links_[base + way].older = ends.newest;
            links_[base + ends.newest].newer = uint16_t(way);
        } else {
            ends.oldest = 0;
        }
        ends.newest = uint16_t(way);
    }
    lines_[base + way] = line;
    slot = uint16_t(way + 1);
    return false;
}

// Hits change nothing; a miss fills way victim_[set] and advances it (PPC440x5 §4.1.1).
bool CacheModel::touch_round_robin(uint32_t set, uint32_t line) {
    uint16_t& slot = where(line);
    if (slot) return true;
    uint32_t& victim = victim_[set];
    uint32_t& replaced = lines_[size_t(set) * params_.ways + victim];
    if (replaced != kNoLine) where(replaced) = 0;
    replaced = line;
    slot = uint16_t(victim + 1);
    victim = (victim + 1) % params_.ways;
    return false;
}

// Every line a read touches, when it is not within the line touched last (access()).
CacheModel::Result CacheModel::access_lines(uint32_t address, uint32_t bytes, std::vector<uint32_t>* missed) {
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

}  // namespace surfvp::sw
