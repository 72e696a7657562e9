#include "hessian_core.h"

#include <algorithm>
#include <cmath>
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

[[gnu::always_inline]] inline int64_t clamp_to(int64_t v, int64_t max) { return v > max ? max : (v < -max - 1 ? -max - 1 : v); }

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void finish_run(const uint32_t* xx, const uint32_t* yy, const uint32_t* xy, int n, const FinishConstants& c,
                int32_t* out) {
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
    return {64 - p.accumulator_bits, k, weight, p.recip_shift, p.weight_frac_bits,
            2 * p.response_frac_bits - p.det_frac_bits, (int64_t(1) << (p.response_bits - 1)) - 1,
            (int64_t(1) << (p.det_bits - 1)) - 1};
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

// The same steps in double precision: every intermediate is an integer below 2^53 (the
// constructor checks the bounds), so each product, sum and power-of-two scaling is exact and
// floor() gives the arithmetic shift; the loop vectorises where int64 multiplies do not.
struct FinishConstantsF {
    double k, weight;
    double recip_half, recip_inverse, weight_half, weight_inverse, det_half, det_inverse;
    double response_max, det_max;
};

[[gnu::always_inline]] inline double shift_f(double v, double half, double inverse) { return std::floor((v + half) * inverse); }

[[gnu::always_inline]] inline double clamp_f(double v, double max) { return std::min(std::max(v, -max - 1), max); }

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void finish_run_exact_double(const int32_t* xx, const int32_t* yy, const int32_t* xy, int n, const FinishConstantsF& c,
                             int32_t* out) {
    for (int i = 0; i < n; ++i) {
        const double rxx = clamp_f(shift_f(double(xx[i]) * c.k, c.recip_half, c.recip_inverse), c.response_max);
        const double ryy = clamp_f(shift_f(double(yy[i]) * c.k, c.recip_half, c.recip_inverse), c.response_max);
        const double rxy = clamp_f(shift_f(double(xy[i]) * c.k, c.recip_half, c.recip_inverse), c.response_max);
        const double det = rxx * ryy - shift_f(c.weight * rxy * rxy, c.weight_half, c.weight_inverse);
        out[i] = int32_t(clamp_f(shift_f(det, c.det_half, c.det_inverse), c.det_max));
    }
}

// Sums narrowed to the accumulator's width, sign-extended: what the TripleMAC holds.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void narrow(const uint32_t* in, int32_t* out, int n, unsigned drop) {
    for (int i = 0; i < n; ++i) out[i] = int32_t(in[i] << drop) >> drop;
}

// The TripleMAC sums of one box of a filter along a row: its four corner reads (one integral
// row each, so each read is a column offset) added into the box's response at once, so the
// sums go through memory once per box, not once per read. 32-bit unsigned sums wrap, which is
// exact modulo 2^32 in any order and so for any accumulator width up to 32 bits.
struct BoxReads {
    const uint32_t* src[4];
    uint32_t coefficient[4];
};

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void accumulate_box(uint32_t* a, const BoxReads& box, int k, int n, int step) {
    const uint32_t *s0 = box.src[0], *s1 = box.src[1], *s2 = box.src[2], *s3 = box.src[3];
    const uint32_t c0 = box.coefficient[0], c1 = box.coefficient[1], c2 = box.coefficient[2], c3 = box.coefficient[3];
    if (step == 1)
        for (; k < n; ++k) a[k] += c0 * s0[k] + c1 * s1[k] + c2 * s2[k] + c3 * s3[k];
    else
        for (; k < n; ++k) a[k] += c0 * s0[k * step] + c1 * s1[k * step] + c2 * s2[k * step] + c3 * s3[k * step];
}

}  // namespace

// The fast path: for one filter and one image row, every read is a column offset into one
// integral row, so the sums are loops over x.
void HessianCore::row(const IntegralView& ii, int y, int size, int x0, int step, int count, int32_t* out,
                      int out_stride) const {
    const int b = (size - 1) / 2;
    // Only x in [b, width - 1 - b] and y in [b, height - 1 - b] have determinants.
    int first = 0, last = count;  // k range inside
    while (first < count && x0 + first * step < b) ++first;
    while (last > first && x0 + (last - 1) * step > ii.width - 1 - b) --last;
    if (y < b || y > ii.height - 1 - b) first = last = count;
    for (int k = 0; k < first; ++k) out[k * out_stride] = 0;
    for (int k = last; k < count; ++k) out[k * out_stride] = 0;
    if (first >= last) return;

    const int n = last - first;
    thread_local std::vector<uint32_t> acc;
    thread_local std::vector<int32_t> dets;
    acc.assign(size_t(3) * n, 0);
    dets.resize(size_t(n));
    int32_t* finished = out_stride == 1 ? out + first : dets.data();  // contiguous output takes them directly
    const std::vector<Read>& reads = reads_[size];
    const int x_first = x0 + first * step;
    for (size_t i = 0; i < reads.size(); i += 4) {  // filter_reads gives each box's 4 corners together
        BoxReads box{};
        const uint32_t* any_row = nullptr;
        uint32_t first_sample = 0;  // the box at k = 0, where a corner may fall on column -1
        for (int c = 0; c < 4; ++c) {
            const Read& r = reads[i + size_t(c)];
            if (y + r.dy < 0) continue;  // row -1 of the integral image is zero: coefficient 0
            box.src[c] = any_row = ii.row(y + r.dy) + x_first + r.dx;
            box.coefficient[c] = uint32_t(r.coefficient);
            if (x_first + r.dx >= 0) first_sample += box.coefficient[c] * box.src[c][0];  // column -1 is zero too
        }
        if (!any_row) continue;
        for (auto& src : box.src)
            if (!src) src = any_row;  // read, times 0
        uint32_t* a = acc.data() + size_t(int(reads[i].response)) * n;
        a[0] += first_sample;
        accumulate_box(a, box, 1, n, step);
    }
    const Precision& p = precision_;
    if (double_exact_) {
        thread_local std::vector<int32_t> sums;
        sums.resize(size_t(3) * n);
        narrow(acc.data(), sums.data(), 3 * n, 32 - p.accumulator_bits);
        auto half = [](unsigned s) { return s ? std::ldexp(1.0, int(s) - 1) : 0.0; };
        const unsigned det_shift = 2 * p.response_frac_bits - p.det_frac_bits;
        const FinishConstantsF c{double(reciprocal_[size]), double(weight_), half(p.recip_shift),
                                 std::ldexp(1.0, -int(p.recip_shift)), half(p.weight_frac_bits),
                                 std::ldexp(1.0, -int(p.weight_frac_bits)), half(det_shift), std::ldexp(1.0, -int(det_shift)),
                                 std::ldexp(1.0, int(p.response_bits) - 1) - 1, std::ldexp(1.0, int(p.det_bits) - 1) - 1};
        finish_run_exact_double(sums.data(), sums.data() + n, sums.data() + 2 * n, n, c, finished);
    } else {
        finish_run(acc.data(), acc.data() + n, acc.data() + 2 * n, n, finish_constants(p, reciprocal_[size], weight_),
                   finished);
    }
    if (out_stride != 1)
        for (int k = 0; k < n; ++k) out[(first + k) * out_stride] = dets[size_t(k)];
}

void HessianCore::block_row(const IntegralView& ii, int by, int32_t* out) const {
    const int blocks = (ii.width + 1) / 2;
    thread_local std::vector<int32_t> line;
    line.assign(size_t(blocks) * 2, 0);  // one image row at one size (padded to even width: the pad stays 0)
    for (int py = 0; py < 2; ++py) {
        const int y = 2 * by + py;
        for (int i = 0; i < 4; ++i) {
            if (y < ii.height) row(ii, y, kSizes[i], 0, 1, ii.width, line.data(), 1);
            else std::fill(line.begin(), line.end(), 0);
            int32_t* o = out + 4 * i + 2 * py;  // a pair of neighbours per block
            for (int j = 0; j < blocks; ++j, o += kDeterminantsPerBlock) {
                o[0] = line[size_t(2 * j)];
                o[1] = line[size_t(2 * j + 1)];
            }
        }
    }
    for (int j = 0; j < 2; ++j) row(ii, 2 * by, kSizes[4 + j], 0, 2, blocks, out + 16 + j, kDeterminantsPerBlock);
}

int32_t HessianCore::from_float(double det) const {
    const double scaled = std::round(det * double(int64_t(1) << precision_.det_frac_bits));
    return int32_t(clamp_to(int64_t(std::clamp(scaled, -9.2e18, 9.2e18)), (int64_t(1) << (precision_.det_bits - 1)) - 1));
}

}  // namespace surfvp::fhg
