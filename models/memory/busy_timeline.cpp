#include "busy_timeline.h"

#include <algorithm>

namespace surfvp {

uint64_t BusyTimeline::reserve(uint64_t request, uint64_t length) {
    const auto live = busy_.begin() + std::ptrdiff_t(first_);
    auto starts_after = [](uint64_t t, const Interval& i) { return t < i.start; };
    // The first interval starting after the request; the one before it may cover the request.
    auto next = std::upper_bound(live, busy_.end(), request, starts_after);
    uint64_t start = request;
    if (next != live && std::prev(next)->end > start) start = std::prev(next)->end;
    while (next != busy_.end() && next->start < start + length) {
        start = std::max(start, next->end);
        ++next;
    }
    if (length == 0) return start;
    // Insert [start, end) before `next`, merged with the intervals it touches (the one
    // before can only touch its start, `next` only its end).
    const uint64_t end = start + length;
    const bool joins_before = next != live && std::prev(next)->end == start;
    const bool joins_after = next != busy_.end() && next->start == end;
    if (joins_before && joins_after) {
        std::prev(next)->end = next->end;
        busy_.erase(next);
    } else if (joins_before) {
        std::prev(next)->end = end;
    } else if (joins_after) {
        next->start = start;
    } else {
        insert(next, Interval{start, end});
    }
    return start;
}

// Moves whichever side of the insertion point is shorter: the intervals before it into a dead
// slot, or those after it. Requests at the kernel's time land near the front of the live
// intervals while the CPU's fills reserved ahead of time fill the back (hundreds of them), so
// the front side is usually the short one.
void BusyTimeline::insert(std::vector<Interval>::iterator before, const Interval& interval) {
    const size_t at = size_t(before - busy_.begin());
    if (first_ > 0 && at - first_ < busy_.size() - at) {
        std::move(busy_.begin() + std::ptrdiff_t(first_), before, busy_.begin() + std::ptrdiff_t(first_ - 1));
        --first_;
        busy_[at - 1] = interval;
    } else {
        busy_.insert(before, interval);
    }
}

void BusyTimeline::forget_before(uint64_t time) {
    while (first_ < busy_.size() && busy_[first_].end <= time) ++first_;
    if (first_ > 2 * kSpare && first_ * 2 > busy_.size()) {  // compacted, keeping kSpare dead slots for insert()
        busy_.erase(busy_.begin(), busy_.begin() + std::ptrdiff_t(first_ - kSpare));
        first_ = kSpare;
    }
}

}  // namespace surfvp
