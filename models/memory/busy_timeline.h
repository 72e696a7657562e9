#pragma once
// The busy intervals of one shared resource (the DRAM behind the memory controller), in
// picoseconds. reserve() places a piece of work at the earliest start, at or after its
// request, where it fits between the intervals already reserved. Requests normally arrive in
// time order (the buses synchronise), and then this is first-come first-served; a master
// that hands over work ahead of time (the CPU's batch of line fills) takes the gaps the
// others have left, and whoever asks later for a time it has taken waits behind it. Plain
// C++.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace surfvp {

class BusyTimeline {
public:
    // Reserves `length` ps at the earliest start >= `request`; returns the start.
    uint64_t reserve(uint64_t request, uint64_t length);
    // Forgets intervals that end at or before `time` (no request can come before it).
    void forget_before(uint64_t time);
    size_t intervals() const { return busy_.size() - first_; }

private:
    struct Interval {
        uint64_t start, end;
    };
    static constexpr size_t kSpare = 64;  // dead slots compaction leaves before the live ones
    void insert(std::vector<Interval>::iterator before, const Interval& interval);
    // Sorted by start; disjoint, never touching. A sorted vector, not a map: nearly every
    // reservation lands at the end, forgetting takes from the front (slots before first_
    // are dead and compacted now and then), and no node is allocated per transaction. An
    // insertion in the middle moves the shorter side (insert()).
    std::vector<Interval> busy_;
    size_t first_ = 0;
};

}  // namespace surfvp
