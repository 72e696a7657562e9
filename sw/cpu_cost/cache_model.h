#pragma once
// The PPC440's L1 data cache as the software stage's reads see it: set-associative, reads
// only (the stage writes nothing the hardware reads back), deterministic. Plain C++.
//
// PPC440 (IBM PPC440x5 CPU Core User's Manual, §4.1 and Table 4-2): 32 KB data cache, 32-byte
// lines, 64 ways (so 16 sets); the set index is the address bits just above the line offset.
// Its replacement is round-robin per set (a victim index incremented on every line fill,
// §4.1.1); LRU is offered too and is the default the scenario table asks for. The two differ
// only once a set is full and a line that was filled early is reused (tests/stage).
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <vector>

namespace surfvp::sw {

enum class Replacement { lru, round_robin };

struct CacheParams {
    uint32_t size_bytes = 32 * 1024;             // [S] ML507 DTS (docs/sources.md#cpu)
    uint32_t line_bytes = 32;                    // [S] ML507 DTS; PPC440x5 manual §4.1
    uint32_t ways = 64;                          // [S] PPC440x5 manual Table 4-2 (32 KB -> 64 ways)
    Replacement replacement = Replacement::lru;  // [A] as asked; the PPC440 is round-robin [S]
};

class CacheModel {
public:
    // Throws std::invalid_argument unless line_bytes (2 B or more) and the number of sets
    // (size / (line x ways)) are powers of two, size is a whole number of sets and there are
    // at most 65535 ways.
    explicit CacheModel(const CacheParams& params);

    struct Result {
        uint32_t hits = 0, misses = 0;  // lines touched
    };
    // A read of `bytes` bytes at `address`: every line it touches is one hit or one miss
    // (a miss fills the line). bytes == 0 touches nothing. The bus address of each line
    // that missed is appended to `missed` when given.
    Result access(uint32_t address, uint32_t bytes, std::vector<uint32_t>* missed = nullptr) {
        // The common cases inline (a call was a tenth of the software stage's time): a read
        // within one line, in the line read last (a hit that changes nothing) or, with LRU,
        // in another line the cache holds. Misses and reads across lines go the general way.
        const uint32_t line = address >> line_shift_;
        if (bytes && uint32_t((uint64_t(address) + bytes - 1) >> line_shift_) == line &&
            (line == last_line_ || (params_.replacement == Replacement::lru && lru_hit(line)))) {
            ++hits_;
            return {1, 0};
        }
        return access_lines(address, bytes, missed);
    }

    // Drops every line (e.g. after DMA rewrote the buffers: the PPC440 L1 is not coherent
    // with DMA, so the driver invalidates before reading). Counters are kept.
    void invalidate();
    void reset_counters() { hits_ = misses_ = 0; }

    uint64_t hits() const { return hits_; }
    uint64_t misses() const { return misses_; }
    uint64_t accesses() const { return hits_ + misses_; }  // line touches
    double hit_rate() const { return accesses() ? double(hits_) / double(accesses()) : 0.0; }
    uint32_t sets() const { return sets_; }
    const CacheParams& params() const { return params_; }

private:
    Result access_lines(uint32_t address, uint32_t bytes, std::vector<uint32_t>* missed);
    bool touch(uint32_t line);  // true on a hit
    bool touch_lru(uint32_t set, uint32_t line);
    // LRU: when the cache holds `line` (not the last one touched), moves it to its set's front
    // and makes it the last line touched; false (and nothing changed) when it does not.
    bool lru_hit(uint32_t line) {
        const uint16_t* chunk = where_[line >> kChunkShift].get();
        const uint16_t slot = chunk ? chunk[line & (kChunk - 1)] : 0;
        if (!slot) return false;
        last_line_ = line;
        const uint32_t set = line & (sets_ - 1);
        make_newest(size_t(set) * params_.ways, set, slot - 1u);
        return true;
    }
    bool touch_round_robin(uint32_t set, uint32_t line);
    uint16_t& where(uint32_t line);  // its entry in where_, made on first use
    // LRU: a filled way to its set's list's front.
    void make_newest(size_t base, uint32_t set, uint32_t way) {
        Ends& ends = ends_[set];
        if (way == ends.newest) return;
        Link* links = links_.data() + base;
        const Link moved = links[way];  // `moved.newer` exists: `way` is not the front
        if (way == ends.oldest)
            ends.oldest = moved.newer;
        else
            links[moved.older].newer = moved.newer;
        links[moved.newer].older = moved.older;
        links[way].older = ends.newest;
        links[ends.newest].newer = uint16_t(way);
        ends.newest = uint16_t(way);
    }

    CacheParams params_;
    uint32_t sets_ = 0;
    unsigned line_shift_ = 0;
    // Per set, `ways` line numbers (kNoLine in a way never filled since the last invalidate)
    // and (LRU) the ways filled so far.
    static constexpr uint32_t kNoLine = ~uint32_t(0);  // no 32-bit address's line number with lines of 2 B or more
    std::vector<uint32_t> lines_;
    std::vector<uint32_t> filled_;
    // Which way holds a line: per line number, its way + 1, or 0 when it is not in the cache;
    // in chunks of kChunk line numbers, each made when a line in it is first touched. A
    // look-up is two loads, a miss needs no search (the sets have 64 ways).
    static constexpr unsigned kChunkShift = 16;
    static constexpr uint32_t kChunk = uint32_t(1) << kChunkShift;
    struct Free {
        void operator()(uint16_t* p) const { std::free(p); }
    };
    using Chunk = std::unique_ptr<uint16_t, Free>;
    std::vector<Chunk> where_;
    // LRU: per set, its filled ways as a list from the most to the least recently used: a
    // Link per way (its neighbours' way numbers within the set), the list's Ends per set. A
    // hit moves one way to the front, a miss in a full set refills the last one.
    struct Link {
        uint16_t newer, older;
    };
    struct Ends {
        uint16_t newest, oldest;
    };
    std::vector<Link> links_;  // per set x way
    std::vector<Ends> ends_;   // per set
    // Round-robin: victim_[set] is the next way to fill.
    std::vector<uint32_t> victim_;
    uint32_t last_line_ = kNoLine;  // fast path: the line touched last is a hit without any change
    uint64_t hits_ = 0, misses_ = 0;
};

}  // namespace surfvp::sw
