#include "busy_timeline.h"

#include <algorithm>
#include <iterator>

namespace surfvp {

uint64_t BusyTimeline::reserve(uint64_t request, uint64_t length) {
    uint64_t start = request;
    auto next = busy_.upper_bound(start);
    if (next != busy_.begin() && std::prev(next)->second > start) start = std::prev(next)->second;
    while (next != busy_.end() && next->first < start + length) {
        start = std::max(start, next->second);
        ++next;
    }
    if (length == 0) return start;
    // Insert [start, end), merged with the intervals it touches.
    uint64_t begin = start, end = start + length;
    auto after = busy_.lower_bound(start);
    if (after != busy_.begin() && std::prev(after)->second == begin) {
        --after;
        begin = after->first;
        after = busy_.erase(after);
    }
    if (after != busy_.end() && after->first == end) {
        end = after->second;
        busy_.erase(after);
    }
    busy_[begin] = end;
    return start;
}

void BusyTimeline::forget_before(uint64_t time) {
    while (!busy_.empty() && busy_.begin()->second <= time) busy_.erase(busy_.begin());
}

}  // namespace surfvp
