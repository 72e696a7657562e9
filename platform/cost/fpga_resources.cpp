#include "platform/cost/fpga_resources.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "models/fhg/fhg.h"
#include "models/fhg/fhg_regs.h"
#include "models/fhg/hessian_core.h"
#include "models/fhg/rtl_parameters.h"
#include "models/fhg/sequence_cache.h"
#include "models/fhg/sequence_memory.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/run_settings.h"
#include "platform/workload/describer.h"

namespace surfvp {
namespace {

unsigned ceil_div(unsigned long a, unsigned long b) { return unsigned((a + b - 1) / b); }

// The FHG of one pair: its parts added up.
BlockResources fhg_block(const Config& c) {
    const FhgParts parts = fhg_parts(c);
    const unsigned macs = fhg_params(c).sequence.triple_macs;
    BlockResources b{"fhg", 0, 0, 0, 0, ""};
    for (const BlockResources* part :
         {&parts.line_fifo, &parts.sequence_memory, &parts.maxima_fifo, &parts.det_rows, &parts.line_routing,
          &parts.hessian_calc, &parts.local_max_finder, &parts.control}) {
        b.ramb36 += part->ramb36, b.dsp48e += part->dsp48e, b.luts += part->luts, b.ffs += part->ffs;
        if (part->ramb36 + part->dsp48e > 0) b.basis += (b.basis.empty() ? "" : ", ") + part->basis;
    }
    b.luts += macs * parts.triple_mac.luts;
    b.ffs += macs * parts.triple_mac.ffs;
    return b;
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

// Block RAM: each line-FIFO line holds max_width integral words, in the organisation
// fhg.line_fifo names (one RAMB36, 1K x 32 or 512 x 72, or two column banks); the maxima FIFO
// 32-bit words; the MasterController's sequence one word per cycle of its interval, as `surfvp
// export-sequence` writes it; each determinant row buffer a block row of records.
// Logic: per-bit constants fitted to yosys 0.23's synthesis of the Verilog reference for
// Virtex-5 (synth_xilinx -family xc5v, models/fhg/rtl) at three precisions (docs/resources.md):
// a TripleMAC 9 LUTs + 10 and 7 flip-flops + 6 per accumulator bit; HessianCalc 55 LUTs per
// accumulator bit (the 18-way read multiplexer of three sums and the normalisation after it)
// and 3 flip-flops per accumulator bit + 6.5 per response bit + 111 (its four pipeline
// stages). DSP48E: HessianCalc's products as the RTL forms them (three sums x K_L, rxx x ryy,
// rxy^2, W x rxy^2). LocMaxFinder and the control are not in the RTL: estimates.
namespace {

// The logic beside each line-FIFO BRAM (line_ram.v), as yosys 0.23 synthesizes it for
// Virtex-5: a true dual-port BRAM's port A takes the write address or a read's (one LUT an
// address bit); `sdp72` writes a half of the pair (2 LUTs of write enables); `tdp_x2` adds the
// hold registers of its four reads a cycle (4 x 32 + 2 flip-flops), and its address and
// phase multiplexers come to 86 or 87 LUTs at a 10-bit address (8.6 a bit).
struct BramLogic {
    double luts = 0, ffs = 0;
};
BramLogic bram_logic(const fhg::LineFifoShape& shape, unsigned address_bits) {
    if (shape.aligned_pairs) return {2, 0};
    if (shape.clock_multiple == 2) return {8.6 * address_bits, 4 * 32 + 2};
    return {double(address_bits), 0};
}

// The line FIFO's routing (line_fifo.v), fitted to yosys 0.23's synthesis of the whole FIFO at
// six crossbar machines (docs/rtl.md), within 14 % on each: every bus lane picks its value
// among the BRAMs it reaches (all, or its line group's) and gives its address to its port of
// the one it reads (23.4 LUTs a lane per BRAM), and with every lane reaching every BRAM each
// BRAM gathers its ports' addresses (18 LUTs a BRAM). Four groups' turn of the buses (180 LUTs
// a lane) is fitted on four scalar buses; two groups hold within 3 % unfitted (docs/rtl.md).
// Its flip-flops are exact: a bit a lane for `took`, one more with aligned pairs (the half),
// the BRAM index of each line a bus word spans, and the write side's column, row count, slot
// and frame bit.
BramLogic line_routing(const fhg::SequenceParams& s, const fhg::LineFifoShape& shape, unsigned brams) {
    auto clog2 = [](unsigned n) {  // Verilog's $clog2, as the RTL sizes its indices
        unsigned b = 0;
        while ((1u << b) < n) ++b;
        return b;
    };
    const auto& word = fhg::word_shape(s.bus_word);
    const unsigned lanes = s.read_buses * unsigned(word.size());
    const unsigned lines_a_word = word.size() == 4 ? 2 : 1;
    const unsigned lane_bits =
        lanes * (shape.aligned_pairs ? 2 : 1) + s.read_buses * lines_a_word * clog2(brams / s.line_groups);
    const unsigned reach = brams / s.line_groups;  // the BRAMs one lane multiplexes
    // Wired to one group, a port gathers no other group's addresses (the 18 a BRAM go); four
    // groups turn the buses (180 a lane); the turn's register is a bit a group bit.
    const double gather = s.line_groups == 1 ? 18.0 * brams : 0, turn = s.line_groups == 4 ? 180.0 * lanes : 0;
    return {std::round(lanes * 23.4 * reach + gather + turn),
            double(lane_bits + 16 + 16 + clog2(s.fifo_lines) + 1 + clog2(s.line_groups))};
}

}  // namespace

FhgParts fhg_parts(const Config& c) {
    const Fhg::Params p = fhg_params(c);
    const fhg::Sequence& seq = fhg::cached_sequence(p.sequence);
    const auto& s = p.sequence;
    const unsigned integral_bits = 32;  // an integral value travels and is kept as a 32-bit word
    const fhg::LineFifoShape shape = fhg::line_fifo_shape(s.line_fifo);
    const fhg::LineBram line_bram = fhg::line_bram(s.line_fifo, p.max_width);  // a line, or a bank of one
    const unsigned line = shape.banks * ramb36_for(line_bram.words, (shape.aligned_pairs ? 2 : 1) * integral_bits);
    const unsigned control_bits = unsigned(fhg::sequence_layout(s).width);  // the exported image's word
    const unsigned sequence = ramb36_for(unsigned(std::max(seq.interval, 1)), control_bits);
    const unsigned record_bits = fhg_regs::record_bytes(fhg_regs::det_bytes_for(p.precision.det_bits)) * 8;
    const unsigned row = ramb36_for(ceil_div(p.max_width, 2), record_bits);
    const unsigned maxima = ramb36_for(p.maxima_fifo_depth, 32);
    // The RTL's constants, as the signed operands it multiplies by.
    const fhg::ConstantWidths widths = fhg::constant_widths(fhg::HessianCore(p.precision));
    const unsigned acc = p.precision.accumulator_bits, r = p.precision.response_bits, k = widths.k_bits + 1,
                   w = widths.w_bits + 1;
    const unsigned dsp = 3 * dsp48e_for(acc, k) + 2 * dsp48e_for(r, r) + dsp48e_for(2 * r, w);
    const double det = p.precision.det_bits;
    FhgParts parts;
    const BramLogic bram = bram_logic(shape, line_bram.address_bits);
    const double brams = double(s.fifo_lines) * shape.banks;
    parts.line_fifo = {
        "line FIFO",
        double(s.fifo_lines * line),
        0,
        brams * bram.luts,
        brams * bram.ffs,
        fmt::format("line FIFO {} x {} RAMB36 ({}), each with {:g} LUTs and {:g} flip-flops of port logic",
                    s.fifo_lines, line, fhg::line_fifo_name(s.line_fifo), bram.luts, bram.ffs)};
    const BramLogic routing = line_routing(s, shape, unsigned(brams));
    parts.line_routing = {"line FIFO routing",
                          0,
                          0,
                          routing.luts,
                          routing.ffs,
                          fmt::format("the reads of {} bus lanes routed to and from {:g} BRAMs",
                                      s.read_buses * fhg::word_shape(s.bus_word).size(), brams)};
    parts.sequence_memory = {"sequence memory",
                             double(sequence),
                             0,
                             0,
                             0,
                             fmt::format("sequence {} ({} cycles x {} bit)", sequence, seq.interval, control_bits)};
    parts.maxima_fifo = {"maxima FIFO", double(maxima), 0, 0, 0, fmt::format("maxima FIFO {}", maxima)};
    parts.det_rows = {"determinant rows",
                      double(p.det_row_buffers * row),
                      0,
                      0,
                      0,
                      fmt::format("determinant rows {} x {}", p.det_row_buffers, row)};
    parts.triple_mac = {"TripleMAC", 0, 0, 9.0 * acc + 10, 7.0 * acc + 6, "three accumulators and output buffers"};
    parts.hessian_calc = {"HessianCalc",
                          0,
                          double(dsp),
                          55.0 * acc,
                          3.0 * acc + 6.5 * r + 111,
                          fmt::format("DSP48E for the sums x K_L, rxx x ryy, rxy^2 and W x rxy^2 at {} bit", r)};
    parts.local_max_finder = {"LocMaxFinder", 0, 0, 26 * det, 27 * det, "26 comparisons over a 3x3x3 window"};
    parts.control = {"control", 0, 0, 400, 400, "the MasterController's counters and the registers' decoding"};
    return parts;
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
    r.max_utilisation = device.max_utilisation;
    r.max_block_utilisation = device.max_block_utilisation;
    auto check = [&](const char* name, double need, double have, double share, const char* key) {
        if (need <= have * share) return;
        const std::string used = fmt::format("{}: {:.0f} of {:g} ({:.0f} %)", name, need, have, 100 * need / have);
        r.over.push_back(need > have
                             ? used + ", more than the device has"
                             : fmt::format("{}, above the {:g} % that places and routes ({})", used, 100 * share, key));
    };
    check("LUT", r.total.luts, r.lut_capacity, r.max_utilisation, "fpga.max_utilisation");
    check("FF", r.total.ffs, r.ff_capacity, r.max_utilisation, "fpga.max_utilisation");
    check("RAMB36", r.total.ramb36, r.ramb36_capacity, r.max_block_utilisation, "fpga.max_block_utilisation");
    check("DSP48E", r.total.dsp48e, r.dsp48e_capacity, r.max_block_utilisation, "fpga.max_block_utilisation");
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
            {"max_utilisation", {{"logic", r.max_utilisation}, {"blocks", r.max_block_utilisation}}},
            {"fits", r.fits()},
            {"over", r.over},
            {"blocks", blocks}};
}

}  // namespace surfvp
