// The bit-exact cores' own cost per 1024x768 frame (graf1 resized, as the budget scenario):
// the IIG's integral image and the FHG's block rows (determinants of both octaves, stored
// big-endian, maxima marked at the budget run's threshold). They are the functional work every
// simulated frame does, in the VP on the FHG's worker and in direct mode; issue 14's profile
// and before/after figures for them come from here, free of the whole run's noise.
#include <benchmark/benchmark.h>
#include <vector>

#include "bench_frame.h"

#include "models/fhg/block_row.h"
#include "models/fhg/fhg_regs.h"
#include "models/iig/integral_core.h"

namespace {

constexpr int kWidth = surfvp::bench::kFrameWidth, kHeight = surfvp::bench::kFrameHeight;
constexpr unsigned kSumBits = 32;
constexpr double kThreshold = 497.7;  // the budget run's: the 100th strongest response of frame 0

using surfvp::bench::frame;

std::vector<uint32_t> integral_image() {
    const cv::Mat& f = frame();
    return *surfvp::IntegralCore(kSumBits).image(f.data, f.cols, f.rows, f.step);
}

void BM_IntegralImage(benchmark::State& state) {
    const cv::Mat& f = frame();
    const surfvp::IntegralCore core(kSumBits);
    std::vector<uint32_t> out(size_t(kWidth) * kHeight);
    for (auto _ : state) {
        for (int y = 0; y < kHeight; ++y)
            core.row(f.data + size_t(y) * f.step, y ? &out[size_t(y - 1) * kWidth] : nullptr, &out[size_t(y) * kWidth],
                     kWidth);
        benchmark::DoNotOptimize(out.data());
    }
}

// Every block row of a frame, as the FHG (or direct mode) produces it.
void BM_FhgFrame(benchmark::State& state) {
    const std::vector<uint32_t> integral = integral_image();
    const surfvp::IntegralView view{integral.data(), kWidth, kHeight, kWidth};
    const surfvp::fhg::HessianCore core(surfvp::fhg::Precision{});
    const int32_t threshold = core.from_float(kThreshold);
    const uint32_t det_bytes = 4;
    const int blocks_y = (kHeight + 1) / 2;
    const size_t row_bytes = surfvp::fhg_regs::row_bytes(kWidth, det_bytes);
    std::vector<uint8_t> dets(row_bytes * blocks_y);
    size_t candidates = 0;
    for (auto _ : state) {
        candidates = 0;
        for (int by = 0; by < blocks_y; ++by)
            candidates +=
                surfvp::fhg::block_row(core, view, by, threshold, det_bytes, dets.data() + by * row_bytes).size();
        benchmark::DoNotOptimize(dets.data());
    }
    state.counters["candidates"] = double(candidates);
}

}  // namespace

BENCHMARK(BM_IntegralImage)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_FhgFrame)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

BENCHMARK_MAIN();
