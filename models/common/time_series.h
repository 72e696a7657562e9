#pragma once
// A figure over the run in fixed time bins, for report.html's charts: how busy a resource was
// in each bin (busy time over the bin's width) or the highest level a queue reached in it
// (carried forward through bins without a change). Plain C++ on picoseconds.
//
// A long run does not grow it without bound: when a time falls past kMaxBins bins, neighbouring
// bins are merged by twos and the width doubles (bin_ps() says the width in effect), so a
// 1000-frame run holds a few thousand bins, as a chart can show.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace surfvp {

class TimeSeries {
public:
    static constexpr size_t kMaxBins = 4096;

    explicit TimeSeries(uint64_t bin_ps = 1'000'000'000) : bin_(std::max<uint64_t>(bin_ps, 1)) {}

    uint64_t bin_ps() const { return bin_; }

    // Busy from `from` to `to` (the part in each bin adds to that bin).
    void busy(uint64_t from, uint64_t to) {
        for (uint64_t t = from; t < to;) {
            fit(t);
            const uint64_t b = t / bin_, end = std::min(to, (b + 1) * bin_);
            if (bins_.size() <= b) bins_.resize(b + 1, 0.0);
            bins_[b] += double(end - t);
            t = end;
        }
    }
    // The level became `value` at `at`.
    void level(uint64_t at, double value) {
        levels_ = true;
        fit(at);
        const uint64_t b = at / bin_;
        while (bins_.size() <= b) bins_.push_back(last_);
        bins_[b] = std::max(bins_[b], value);
        last_ = value;
    }
    // Per bin: the busy share (0..1) or the highest level, to four decimals.
    std::vector<double> values() const {
        std::vector<double> out;
        for (double v : bins_) out.push_back(std::round((levels_ ? v : v / double(bin_)) * 1e4) / 1e4);
        return out;
    }

private:
    // Widens the bins until time `t` falls in one of the first kMaxBins: busy time adds up,
    // levels keep the higher.
    void fit(uint64_t t) {
        while (t / bin_ >= kMaxBins) {
            std::vector<double> merged((bins_.size() + 1) / 2, 0.0);
            for (size_t i = 0; i < bins_.size(); ++i)
                merged[i / 2] = levels_ ? std::max(merged[i / 2], bins_[i]) : merged[i / 2] + bins_[i];
            bins_ = std::move(merged);
            bin_ *= 2;
        }
    }

    uint64_t bin_;
    std::vector<double> bins_;
    double last_ = 0;
    bool levels_ = false;
};

}  // namespace surfvp
