#include "hessian_core.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <vector>

namespace surfvp::fhg {
namespace {

void check(bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("fhg precision: " + what);
}

// The fixed-point steps 2 and 3 for a run of TripleMAC sums, as plain loops over arrays so
// that the compiler vectorises them (with clones for AVX2 and AVX-512 picked at run time).
// HessianCore::finish is this on a run of one.
struct FinishConstants {
    unsigned drop;  // 64 - accumulator_bits
    int64_t k, weight;
    unsigned recip_shift, weight_shift, det_shift;
    int64_t response_max, det_max;
};

[[gnu::always_inline]] inline int64_t step_shift(int64_t v, unsigned shift) {
    return shift ? (v + (int64_t(1) << (shift - 1))) >> shift : v;
}

[[gnu::always_inline]] inline int64_t clamp_to(int64_t v, int64_t max) {
    return v > max ? max : (v < -max - 1 ? -max - 1 : v);
}

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void finish_run(
    const uint32_t* xx, const uint32_t* yy, const uint32_t* xy, int n, const FinishConstants& c, int32_t* out) {
    for (int i = 0; i < n; ++i) {
        const int64_t sxx = int64_t(uint64_t(int64_t(int32_t(xx[i]))) << c.drop) >> c.drop;
        const int64_t syy = int64_t(uint64_t(int64_t(int32_t(yy[i]))) << c.drop) >> c.drop;
        const int64_t sxy = int64_t(uint64_t(int64_t(int32_t(xy[i]))) << c.drop) >> c.drop;
        const int64_t rxx = clamp_to(step_shift(sxx * c.k, c.recip_shift), c.response_max);
        const int64_t ryy = clamp_to(step_shift(syy * c.k, c.recip_shift), c.response_max);
        const int64_t rxy = clamp_to(step_shift(sxy * c.k, c.recip_shift), c.response_max);
        const int64_t det = rxx * ryy - step_shift(c.weight * rxy * rxy, c.weight_shift);
        out[i] = int32_t(clamp_to(step_shift(det, c.det_shift), c.det_max));
    }
}

FinishConstants finish_constants(const Precision& p, int64_t k, int64_t weight) {
    return {64 - p.accumulator_bits,
            k,
            weight,
            p.recip_shift,
            p.weight_frac_bits,
            2 * p.response_frac_bits - p.det_frac_bits,
            (int64_t(1) << (p.response_bits - 1)) - 1,
            (int64_t(1) << (p.det_bits - 1)) - 1};
}

// `count` terms of these weights as pairs of equal and opposite ones, those of magnitude 1
// first (no multiply); a term without a partner pairs with a zero row, a zero weight is left out.
HessianCore::Factors::Pairing pairing(int count, const std::array<int, 4>& weight) {
    HessianCore::Factors::Pairing unit, other;
    bool taken[4] = {};
    for (int i = 0; i < count; ++i) {
        if (taken[i] || weight[size_t(i)] == 0) continue;
        const int w = weight[size_t(i)];
        int j = i + 1;
        while (j < count && (taken[j] || weight[size_t(j)] != -w)) ++j;
        const int partner = j < count ? (taken[j] = true, j) : -1;
        auto& to = std::abs(w) == 1 ? unit : other;
        to.plus[size_t(to.count)] = w > 0 ? i : partner;
        to.minus[size_t(to.count)] = w > 0 ? partner : i;
        to.magnitude[size_t(to.count++)] = uint32_t(std::abs(w));
    }
    unit.units = unit.count;
    for (int j = 0; j < other.count; ++j) {
        unit.plus[size_t(unit.count)] = other.plus[size_t(j)], unit.minus[size_t(unit.count)] = other.minus[size_t(j)];
        unit.magnitude[size_t(unit.count++)] = other.magnitude[size_t(j)];
    }
    return unit;
}

// Reads grouped by column offset: each group combines the same rows with the same weights up
// to a factor (the box filters' corners share their rows), which gives the response as taps
// of one combined row.
HessianCore::Factors factor(const std::vector<Read>& reads, Response response, int size) {
    std::vector<Read> own;
    for (const Read& r : reads)
        if (r.response == response) own.push_back(r);
    HessianCore::Factors f;
    for (const Read& r : own)
        if (r.dx == own[0].dx) f.dy[size_t(f.rows)] = r.dy, f.weight[size_t(f.rows++)] = r.coefficient;
    auto weight_of = [&](int dy) {
        for (int i = 0; i < f.rows; ++i)
            if (f.dy[size_t(i)] == dy) return f.weight[size_t(i)];
        return 0;
    };
    for (const Read& r : own) {
        if (std::find(f.dx.begin(), f.dx.begin() + f.taps, r.dx) != f.dx.begin() + f.taps) continue;
        if (weight_of(r.dy) == 0) throw std::logic_error("filter " + std::to_string(size) + " does not factor");
        const int tap = r.coefficient / weight_of(r.dy);
        int group = 0;
        for (const Read& g : own)
            if (g.dx == r.dx) {
                ++group;
                if (g.coefficient != tap * weight_of(g.dy))
                    throw std::logic_error("filter " + std::to_string(size) + " does not factor");
            }
        if (group != f.rows || f.taps == 4)
            throw std::logic_error("filter " + std::to_string(size) + " does not factor");
        f.dx[size_t(f.taps)] = r.dx, f.tap[size_t(f.taps++)] = tap;
    }
    f.row_pairs = pairing(f.rows, f.weight);
    f.tap_pairs = pairing(f.taps, f.tap);
    return f;
}

}  // namespace

HessianCore::HessianCore(const Precision& p) : precision_(p) {
    check(p.accumulator_bits >= 16 && p.accumulator_bits <= 32, "accumulator_bits must be 16..32");
    check(p.response_bits >= 8 && p.response_bits <= 32, "response_bits must be 8..32");
    check(p.response_frac_bits < p.response_bits, "response_frac_bits must be below response_bits");
    check(p.recip_shift <= 24, "recip_shift must be 0..24");
    check(p.weight_frac_bits >= 1 && p.weight_frac_bits <= 20, "weight_frac_bits must be 1..20");
    check(p.det_bits >= 8 && p.det_bits <= 32, "det_bits must be 8..32");
    check(p.det_frac_bits <= 2 * p.response_frac_bits, "det_frac_bits must not exceed 2 x response_frac_bits");
    weight_ = std::llround(0.81 * double(int64_t(1) << p.weight_frac_bits));
    for (int size : kSizes) {
        reciprocal_[size] = std::llround(std::ldexp(1.0, int(p.response_frac_bits + p.recip_shift)) / (size * size));
        reads_[size] = filter_reads(size);
        for (Response r : {Response::xx, Response::yy, Response::xy})
            factors_[size_t(size)][size_t(r)] = factor(reads_[size], r, size);
    }
    // Largest magnitudes (as powers of two) of the finishing steps: sum x K, the squared
    // responses times W, the determinant. Below 2^52 every step is exact in double.
    const double k_bits = std::log2(double(*std::max_element(reciprocal_.begin(), reciprocal_.end())) + 1);
    const double bound = std::max({double(p.accumulator_bits) + k_bits, 2.0 * (p.response_bits - 1) + 1,
                                   2.0 * (p.response_bits - 1) + double(p.weight_frac_bits) + 1});
    double_exact_ = bound < 52;
}

int64_t HessianCore::wrap(int64_t sum) const {
    const unsigned drop = 64 - precision_.accumulator_bits;
    return int64_t(uint64_t(sum) << drop) >> drop;
}

int32_t HessianCore::finish(int64_t xx, int64_t yy, int64_t xy, int size) const {
    // The low 32 bits of each sum carry everything an accumulator of up to 32 bits keeps.
    const uint32_t sxx = uint32_t(xx), syy = uint32_t(yy), sxy = uint32_t(xy);
    int32_t det = 0;
    finish_run(&sxx, &syy, &sxy, 1, finish_constants(precision_, reciprocal_[size], weight_), &det);
    return det;
}

HessianCore::Sums HessianCore::sums(const IntegralView& ii, int x, int y, int size) const {
    int64_t acc[3] = {0, 0, 0};
    for (const Read& r : reads_[size]) {
        const int rx = x + r.dx, ry = y + r.dy;
        const int64_t value = (rx < 0 || ry < 0) ? 0 : ii.at(rx, ry);
        acc[int(r.response)] += r.coefficient * value;
    }
    return {wrap(acc[0]), wrap(acc[1]), wrap(acc[2])};
}

int32_t HessianCore::determinant(const IntegralView& ii, int x, int y, int size) const {
    if (!inside(ii.width, ii.height, x, y, size)) return 0;
    const Sums s = sums(ii, x, y, size);
    return finish(s.xx, s.yy, s.xy, size);
}

std::array<int32_t, kDeterminantsPerBlock> HessianCore::block(const IntegralView& ii, int bx, int by) const {
    std::array<int32_t, kDeterminantsPerBlock> out{};
    for (int k = 0; k < kDeterminantsPerBlock; ++k) {
        const BlockDeterminant d = block_determinant(k);
        out[k] = determinant(ii, 2 * bx + d.px, 2 * by + d.py, d.size);
    }
    return out;
}

namespace {

// The same steps in double precision: every intermediate is an integer below 2^52 (the
// constructor checks the bounds), so each product, sum and power-of-two scaling is exact and
// floor() gives the arithmetic shift; the loop vectorises where int64 multiplies do not. A
// rounding shift, (v + 2^(s-1)) >> s, is floor(v x 2^-s + 1/2): a product by a constant
// pre-scaled by 2^-s, plus a half, each exact (the result needs at most 52 significant bits),
// so the constants K and W come scaled. The sums come as the low 32 bits of the TripleMAC's;
// `drop` narrows them to its width.
struct FinishConstantsF {
    unsigned drop;
    double k_scaled, recip_half;  // K x 2^-recip_shift; 1/2, or 0 without a shift
    double weight_scaled, weight_half;
    double det_scale, det_half;  // 2^-det_shift
    double response_max, det_max;
};

// 2^-s, and the half a rounding shift by s adds (none for s = 0).
double scale_of(unsigned s) { return 1.0 / double(uint64_t(1) << s); }
double half_of(unsigned s) { return s ? 0.5 : 0.0; }

FinishConstantsF finish_constants_f(const Precision& p, int64_t k, int64_t weight) {
    const unsigned det_shift = 2 * p.response_frac_bits - p.det_frac_bits;
    return {32 - p.accumulator_bits,
            double(k) * scale_of(p.recip_shift),
            half_of(p.recip_shift),
            double(weight) * scale_of(p.weight_frac_bits),
            half_of(p.weight_frac_bits),
            scale_of(det_shift),
            half_of(det_shift),
            double((int64_t(1) << (p.response_bits - 1)) - 1),
            double((int64_t(1) << (p.det_bits - 1)) - 1)};
}

[[gnu::always_inline]] inline double clamp_f(double v, double max) { return std::min(std::max(v, -max - 1), max); }

[[gnu::always_inline]] inline double narrow_f(uint32_t sum, unsigned drop) {
    return double(int32_t(sum << drop) >> drop);
}

[[gnu::always_inline]] inline int32_t finish_exact_double(uint32_t xx, uint32_t yy, uint32_t xy,
                                                          const FinishConstantsF& c) {
    const double rxx = clamp_f(std::floor(narrow_f(xx, c.drop) * c.k_scaled + c.recip_half), c.response_max);
    const double ryy = clamp_f(std::floor(narrow_f(yy, c.drop) * c.k_scaled + c.recip_half), c.response_max);
    const double rxy = clamp_f(std::floor(narrow_f(xy, c.drop) * c.k_scaled + c.recip_half), c.response_max);
    const double det = rxx * ryy - std::floor(rxy * rxy * c.weight_scaled + c.weight_half);
    return int32_t(clamp_f(std::floor(det * c.det_scale + c.det_half), c.det_max));
}

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void finish_run_exact_double(
    const uint32_t* xx, const uint32_t* yy, const uint32_t* xy, int n, const FinishConstantsF& c, int32_t* out) {
    for (int i = 0; i < n; ++i) out[i] = finish_exact_double(xx[i], yy[i], xy[i], c);
}

// P(x) = sum of weight_i x row_i(x): one response's integral rows combined. The box filters'
// corners come in equal and opposite weights, so the terms go as pairs,
// P(x) = sum of m_j x (plus_j(x) - minus_j(x)), those of magnitude 1 first (no multiply); a
// term without a partner pairs with a zero row. 32-bit unsigned sums wrap, which is exact
// modulo 2^32 in any order and so for any accumulator width up to 32 bits.
struct Pairs {
    int count = 0, units = 0;
    const uint32_t* plus[4] = {};
    const uint32_t* minus[4] = {};
    uint32_t magnitude[4] = {};
};

// The loop for a known number of pairs and stride, so that it vectorises (a stride of 2, the
// second octave's, with permuting loads).
template <int P, int U, int Step>
[[gnu::always_inline]] inline void weigh_n(uint32_t* out, const Pairs& t, int n, int step) {
    const uint32_t *plus[P], *minus[P];
    uint32_t magnitude[P];
    for (int j = 0; j < P; ++j) plus[j] = t.plus[j], minus[j] = t.minus[j], magnitude[j] = t.magnitude[j];
    const int stride = Step ? Step : step;
    for (int k = 0; k < n; ++k) {
        uint32_t sum = 0;
        for (int j = 0; j < P; ++j) {
            const uint32_t d = plus[j][k * stride] - minus[j][k * stride];
            sum += j < U ? d : magnitude[j] * d;
        }
        out[k] = sum;
    }
}

template <int P, int U>
[[gnu::always_inline]] inline void weigh_stride(uint32_t* out, const Pairs& t, int n, int step) {
    if (step == 1)
        weigh_n<P, U, 1>(out, t, n, step);
    else if (step == 2)
        weigh_n<P, U, 2>(out, t, n, step);
    else
        weigh_n<P, U, 0>(out, t, n, step);
}

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void weigh(uint32_t* out, const Pairs& t,
                                                                                         int n, int step) {
    switch (t.count * 8 + std::min(t.units, 2)) {
        case 0:
            std::fill(out, out + n, 0u);
            break;
        case 8:
            weigh_stride<1, 0>(out, t, n, step);
            break;
        case 9:
            weigh_stride<1, 1>(out, t, n, step);
            break;
        case 16:
            weigh_stride<2, 0>(out, t, n, step);
            break;
        case 17:
            weigh_stride<2, 1>(out, t, n, step);
            break;
        case 18:
            weigh_stride<2, 2>(out, t, n, step);
            break;
        case 24:
        case 25:
        case 26:
            weigh_stride<3, 0>(out, t, n, step);
            break;
        default:
            weigh_stride<4, 0>(out, t, n, step);
            break;
    }
}

// A plan's pairs with their sources: `source(i)` is term i's row (nullptr: a zero row);
// `zeros` is a zero row as long as the sources.
template <class Source>
Pairs pairs(const HessianCore::Factors::Pairing& plan, Source source, const uint32_t* zeros) {
    const auto row = [&](int term) {
        const uint32_t* s = term < 0 ? nullptr : source(term);
        return s ? s : zeros;
    };
    Pairs t;
    t.count = plan.count, t.units = plan.units;
    for (int j = 0; j < plan.count; ++j)
        t.plus[j] = row(plan.plus[size_t(j)]), t.minus[j] = row(plan.minus[size_t(j)]),
        t.magnitude[j] = plan.magnitude[size_t(j)];
    return t;
}

// Step 1's taps and steps 2 and 3 in one loop, so that a determinant's three sums stay in
// registers instead of going through memory: for the taps every box filter has (xx: a unit
// pair and one of magnitude 3, yy: one unit pair, xy: two unit pairs). The same sums and the
// same finish as weigh() then finish_run_exact_double().
bool box_filter_taps(const Pairs (&taps)[3]) {
    return taps[0].count == 2 && taps[0].units == 1 && taps[1].count == 1 && taps[1].units == 1 && taps[2].count == 2 &&
           taps[2].units == 2;
}

template <int Step>
[[gnu::always_inline]] inline void taps_and_finish_n(const Pairs (&taps)[3], int n, int step, const FinishConstantsF& c,
                                                     int32_t* __restrict out) {
    // The output is a row of its own (restrict: without it, ten inputs are too many alias checks to vectorise).
    const uint32_t *xx_p0 = taps[0].plus[0], *xx_m0 = taps[0].minus[0], *xx_p1 = taps[0].plus[1],
                   *xx_m1 = taps[0].minus[1];
    const uint32_t *yy_p = taps[1].plus[0], *yy_m = taps[1].minus[0];
    const uint32_t *xy_p0 = taps[2].plus[0], *xy_m0 = taps[2].minus[0], *xy_p1 = taps[2].plus[1],
                   *xy_m1 = taps[2].minus[1];
    const uint32_t xx_m = taps[0].magnitude[1];
    const int stride = Step ? Step : step;
    for (int k = 0; k < n; ++k) {
        const int i = k * stride;
        const uint32_t sxx = (xx_p0[i] - xx_m0[i]) + xx_m * (xx_p1[i] - xx_m1[i]);
        const uint32_t syy = yy_p[i] - yy_m[i];
        const uint32_t sxy = (xy_p0[i] - xy_m0[i]) + (xy_p1[i] - xy_m1[i]);
        out[k] = finish_exact_double(sxx, syy, sxy, c);
    }
}

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void taps_and_finish(
    const Pairs (&taps)[3], int n, int step, const FinishConstantsF& c, int32_t* __restrict out) {
    if (step == 1)
        taps_and_finish_n<1>(taps, n, step, c, out);
    else if (step == 2)
        taps_and_finish_n<2>(taps, n, step, c, out);
    else
        taps_and_finish_n<0>(taps, n, step, c, out);
}

}  // namespace

// The fast path: for one filter and one image row, each response is a few taps of one
// combined integral row, so the sums are loops over x.
void HessianCore::row(const IntegralView& ii, int y, int size, int x0, int step, int count, int32_t* out) const {
    const int b = (size - 1) / 2;
    // Only x in [b, width - 1 - b] and y in [b, height - 1 - b] have determinants.
    int first = 0, last = count;  // k range inside
    while (first < count && x0 + first * step < b) ++first;
    while (last > first && x0 + (last - 1) * step > ii.width - 1 - b) --last;
    if (y < b || y > ii.height - 1 - b) first = last = count;
    std::fill(out, out + first, 0);
    std::fill(out + last, out + count, 0);
    if (first >= last) return;

    const int n = last - first;
    const size_t combined_size = size_t(ii.width) + 1;
    thread_local std::vector<uint32_t> combined, sums, zeros;
    combined.resize(3 * combined_size);
    zeros.resize(size_t(ii.width));  // never written: the row above the image
    const int x_first = x0 + first * step;
    Pairs taps[3];
    for (int r = 0; r < 3; ++r) {
        const Factors& f = factors_[size_t(size)][size_t(r)];
        uint32_t* p = combined.data() + size_t(r) * combined_size + 1;  // p[-1] = 0: column -1 of the integral image
        p[-1] = 0;
        // Inside the image every row read is in [-1, height - 1]; row -1 is zero.
        weigh(p,
              pairs(
                  f.row_pairs, [&](int i) { return y + f.dy[size_t(i)] < 0 ? nullptr : ii.row(y + f.dy[size_t(i)]); },
                  zeros.data()),
              ii.width, 1);
        taps[r] = pairs(
            f.tap_pairs, [&](int i) { return p + x_first + f.dx[size_t(i)]; }, zeros.data());
    }
    const Precision& pr = precision_;
    if (double_exact_ && box_filter_taps(taps))
        return taps_and_finish(taps, n, step, finish_constants_f(pr, reciprocal_[size], weight_), out + first);
    sums.resize(size_t(3) * n);
    for (int r = 0; r < 3; ++r) weigh(sums.data() + size_t(r) * n, taps[r], n, step);
    if (double_exact_)
        finish_run_exact_double(sums.data(), sums.data() + n, sums.data() + 2 * n, n,
                                finish_constants_f(pr, reciprocal_[size], weight_), out + first);
    else
        finish_run(sums.data(), sums.data() + n, sums.data() + 2 * n, n,
                   finish_constants(pr, reciprocal_[size], weight_), out + first);
}

namespace {

// Each block's peak raised to its largest value in `values` (per_block a block) at the
// positions k, k + 1 LocalMaxFinder tests. With clones for AVX2 and AVX-512: the max
// vectorises there, not in the baseline's SSE2.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void raise_peaks(const int32_t* values,
                                                                                               int per_block, int k,
                                                                                               int blocks,
                                                                                               int32_t* peaks) {
    const bool first = tested_by_finder(k), second = per_block == 2 && tested_by_finder(k + 1);
    if (first && second)
        for (int j = 0; j < blocks; ++j) peaks[j] = std::max(peaks[j], std::max(values[2 * j], values[2 * j + 1]));
    else if (first)
        for (int j = 0; j < blocks; ++j) peaks[j] = std::max(peaks[j], values[j * per_block]);
}

}  // namespace

HessianCore::Lines HessianCore::block_row_lines(const IntegralView& ii, int by, int32_t* peaks) const {
    Lines lines;
    lines.blocks = (ii.width + 1) / 2;
    const size_t pixels = size_t(lines.blocks) * 2;  // padded to even width: the pad stays 0
    thread_local std::vector<int32_t> storage;
    storage.resize(8 * pixels + 2 * size_t(lines.blocks));
    if (peaks) std::fill(peaks, peaks + lines.blocks, std::numeric_limits<int32_t>::min());
    for (int py = 0; py < 2; ++py) {
        const int y = 2 * by + py;
        for (int i = 0; i < 4; ++i) {
            int32_t* line = &storage[(2 * size_t(i) + size_t(py)) * pixels];
            lines.octave1[i][py] = line;
            line[pixels - 1] = 0;
            if (y < ii.height)
                row(ii, y, kSizes[i], 0, 1, ii.width, line);
            else
                std::fill(line, line + pixels, 0);
            if (peaks) raise_peaks(line, 2, 4 * i + 2 * py, lines.blocks, peaks);
        }
    }
    for (int j = 0; j < 2; ++j) {
        int32_t* line = &storage[8 * pixels + size_t(j) * size_t(lines.blocks)];
        lines.octave2[j] = line;
        row(ii, 2 * by, kSizes[4 + j], 0, 2, lines.blocks, line);
        if (peaks) raise_peaks(line, 1, 16 + j, lines.blocks, peaks);
    }
    return lines;
}

void HessianCore::block_row(const IntegralView& ii, int by, int32_t* out) const {
    const Lines lines = block_row_lines(ii, by);
    for (int bx = 0; bx < lines.blocks; ++bx) lines.record(bx, out + size_t(bx) * kDeterminantsPerBlock);
}

int32_t HessianCore::from_float(double det) const {
    const double scaled = std::round(det * double(int64_t(1) << precision_.det_frac_bits));
    return int32_t(
        clamp_to(int64_t(std::clamp(scaled, -9.2e18, 9.2e18)), (int64_t(1) << (precision_.det_bits - 1)) - 1));
}

}  // namespace surfvp::fhg
