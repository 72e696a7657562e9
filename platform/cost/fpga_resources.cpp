#include "platform/cost/fpga_resources.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "models/fhg/fhg.h"
#include "models/fhg/fhg_regs.h"
#include "models/fhg/sequence_cache.h"
#include "models/fhg/sequence_memory.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/run_settings.h"
#include "platform/workload/describer.h"

namespace surfvp {
namespace {

unsigned ceil_div(unsigned long a, unsigned long b) { return unsigned((a + b - 1) / b); }

// The FHG of one pair. Block RAM: each line-FIFO line holds max_width integral words, in the
// organisation fhg.line_fifo names (one RAMB36, 1K x 32 or 512 x 72, or two column banks); the maxima FIFO 32-bit words; the MasterController's sequence one control
// word per cycle of its interval, as `surfvp export-sequence` writes it (per bus: valid, line,
// column; per TripleMAC: take, bus, lane, coefficient, response); each determinant row buffer a block row of records. DSP48E:
// HessianCalc's three products per determinant (Dxx Dyy, w Dxy, (w Dxy)^2), pipelined at one
// determinant a cycle; the TripleMACs only add (the paper: x3 is three additions).
BlockResources fhg_block(const Config& c) {
    const Fhg::Params p = fhg_params(c);
    const fhg::Sequence& seq = fhg::cached_sequence(p.sequence);
    const auto& s = p.sequence;
    const unsigned integral_bits =
        32;  // an integral value travels and is kept as a 32-bit word (iig.sum_bits of it used)
    const fhg::LineFifoShape shape = fhg::line_fifo_shape(s.line_fifo);
    const unsigned line =
        shape.banks * (shape.aligned_pairs ? ramb36_for(ceil_div(p.max_width, 2), 2 * integral_bits)
                                           : ramb36_for(ceil_div(p.max_width, shape.banks), integral_bits));
    const unsigned fifo = s.fifo_lines * line;
    const unsigned maxima = ramb36_for(p.maxima_fifo_depth, 32);
    const unsigned control_bits = unsigned(fhg::sequence_layout(s).width);  // the exported image's word
    const unsigned sequence = ramb36_for(unsigned(std::max(seq.interval, 1)), control_bits);
    const unsigned record_bits = fhg_regs::record_bytes(fhg_regs::det_bytes_for(p.precision.det_bits)) * 8;
    const unsigned rows = p.det_row_buffers * ramb36_for(ceil_div(p.max_width, 2), record_bits);
    const unsigned r = p.precision.response_bits, w = p.precision.weight_frac_bits + 1;
    const unsigned dsp = dsp48e_for(r, r) + dsp48e_for(w, r) + dsp48e_for(r, r);
    // TripleMAC: three accumulators with their output buffers and a coefficient adder each;
    // HessianCalc, LocMaxFinder (26 comparisons of det_bits over a 3x3x3 window) and control.
    const double acc = p.precision.accumulator_bits, det = p.precision.det_bits;
    const double luts = s.triple_macs * 4 * acc + 6 * r + 26 * det + 400;
    const double ffs = s.triple_macs * 6 * acc + 8 * r + 27 * det + 400;
    return {"fhg",
            double(fifo + maxima + sequence + rows),
            double(dsp),
            luts,
            ffs,
            fmt::format("line FIFO {} x {} RAMB36 ({}), maxima FIFO {}, sequence {} ({} cycles x {} bit), determinant "
                        "rows {} x {}; "
                        "DSP48E for Dxx*Dyy, w*Dxy and (w*Dxy)^2 at {} bit",
                        s.fifo_lines, line, fhg::line_fifo_name(s.line_fifo), maxima, sequence, seq.interval,
                        control_bits, p.det_row_buffers, ramb36_for(ceil_div(p.max_width, 2), record_bits), r)};
}

// The IIG of one pair: its line buffers of integral words, a row-sum adder and a column adder.
BlockResources iig_block(const Config& c) {
    const Iig::Params iig = iig_params(c);
    const unsigned width = iig.max_width, sum = iig.sum_bits;
    const unsigned ram = iig.line_buffers * ramb36_for(width, 32);
    return {
        "iig",           double(ram),     0,
        4.0 * sum + 200, 6.0 * sum + 200, fmt::format("{} line buffers of {} integral words", iig.line_buffers, width)};
}

}  // namespace

unsigned ramb36_for(unsigned long words, unsigned bits) {
    if (words == 0 || bits == 0) return 0;
    // (width, depth) of a RAMB36's modes, widest last (Virtex-5 UG190).
    constexpr unsigned modes[][2] = {{1, 32768}, {2, 16384}, {4, 8192}, {9, 4096}, {18, 2048}, {36, 1024}, {72, 512}};
    for (const auto& [width, depth] : modes)
        if (bits <= width) return ceil_div(words, depth);
    return ceil_div(bits, 72) * ceil_div(words, 512);
}

unsigned dsp48e_for(unsigned a, unsigned b) {
    if (a < b) std::swap(a, b);
    // 25 x 18 signed per slice; a wider product tiles 24 x 17-bit unsigned pieces around it.
    auto pieces = [](unsigned bits, unsigned port) { return bits <= port ? 1u : 1u + ceil_div(bits - port, port - 1); };
    return std::min(pieces(a, 25) * pieces(b, 18), pieces(a, 18) * pieces(b, 25));
}

FpgaResources fpga_resources(const Config& c) {
    FpgaResources r;
    const FpgaDevice device = fpga_device(c);
    r.device = device.device;
    r.ramb36_capacity = double(device.ramb36);
    r.dsp48e_capacity = double(device.dsp48e);
    r.lut_capacity = 4.0 * double(device.slices);  // a Virtex-5 slice: 4 LUT6, 4 flip-flops
    r.ff_capacity = r.lut_capacity;
    const double pairs = run_settings(c).accelerators;
    const double ip_luts = double(device.ip_interface_luts), ip_ffs = double(device.ip_interface_ffs);
    for (BlockResources b : {iig_block(c), fhg_block(c)}) {
        b.luts += ip_luts;  // its PLB slave (registers) and master (DMA) interface
        b.ffs += ip_ffs;
        b.ramb36 *= pairs, b.dsp48e *= pairs, b.luts *= pairs, b.ffs *= pairs;
        b.block = pairs > 1 ? fmt::format("{} (x{})", b.block, pairs) : b.block;
        r.blocks.push_back(b);
    }
    const bool dp = pipeline_params(c).double_precision != 0;
    r.blocks.push_back({"apu fpu", 0, dp ? 13.0 : 3.0, dp ? 4950.0 : 2620.0, dp ? 4950.0 : 2620.0,
                        fmt::format("DS693, {} precision (LUT-FF pairs)", dp ? "double" : "single")});
    r.blocks.push_back({"infrastructure", double(device.infrastructure_ramb36), 0, double(device.infrastructure_luts),
                        double(device.infrastructure_ffs),
                        "MPMC, two PLBs, INTC and the rest of an EDK system (fpga.infrastructure_*)"});
    r.total.block = "total";
    for (const BlockResources& b : r.blocks) {
        r.total.ramb36 += b.ramb36, r.total.dsp48e += b.dsp48e, r.total.luts += b.luts, r.total.ffs += b.ffs;
    }
    auto check = [&](const char* name, double need, double have) {
        if (need > have) r.over.push_back(fmt::format("{}: {:g} of {:g}", name, need, have));
    };
    check("RAMB36", r.total.ramb36, r.ramb36_capacity);
    check("DSP48E", r.total.dsp48e, r.dsp48e_capacity);
    check("LUT", r.total.luts, r.lut_capacity);
    check("FF", r.total.ffs, r.ff_capacity);
    return r;
}

nlohmann::ordered_json resources_json(const FpgaResources& r) {
    using Json = nlohmann::ordered_json;
    auto figures = [](const BlockResources& b) {
        return Json{
            {"ramb36", b.ramb36}, {"dsp48e", b.dsp48e}, {"luts", std::round(b.luts)}, {"ffs", std::round(b.ffs)}};
    };
    Json blocks = Json::object();
    for (const BlockResources& b : r.blocks) {
        Json j = figures(b);
        j["basis"] = b.basis;
        blocks[b.block] = j;
    }
    Json share = {{"ramb36", r.total.ramb36 / r.ramb36_capacity},
                  {"dsp48e", r.total.dsp48e / r.dsp48e_capacity},
                  {"luts", r.total.luts / r.lut_capacity},
                  {"ffs", r.total.ffs / r.ff_capacity}};
    return {{"device", r.device},
            {"capacity",
             {{"ramb36", r.ramb36_capacity},
              {"dsp48e", r.dsp48e_capacity},
              {"luts", r.lut_capacity},
              {"ffs", r.ff_capacity}}},
            {"total", figures(r.total)},
            {"share", share},
            {"fits", r.fits()},
            {"over", r.over},
            {"blocks", blocks}};
}

}  // namespace surfvp
