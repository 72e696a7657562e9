#include "platform/scenario/parameters.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "models/common/units.h"
#include "sw/cpu_cost/ppc440_pipeline.h"

namespace surfvp {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double MHz = 1e6;
constexpr double us = 1e6;  // in ps
constexpr double s = 1e12;  // in ps
constexpr double MiB = 1048576.0;

// PLB1 and PLB2 share their structure; only the width's default and its reason differ.
void add_plb(std::vector<ParamSpec>& t, const std::string& bus, const std::string& width, const std::string& width_source,
             const std::string& role) {
    t.push_back({bus + ".clock", ParamKind::frequency, "100 MHz", 1 * MHz, 1000 * MHz, {},
                 role + " bus clock", "[S] ML507 design: PLB at 100 MHz (mch-plb-clk-period-ps = 10000)"});
    t.push_back({bus + ".width", ParamKind::bits, width, 32, 128, {}, role + " data width: 32, 64 or 128 bit",
                 width_source});
    t.push_back({bus + ".max_burst", ParamKind::beats, "16 beats", 2, 16, {},
                 "Longest fixed-length burst; longer transactions are split", "[S] Xilinx DS711/DS561: fixed bursts of 2-16 beats"});
    t.push_back({bus + ".arbitration", ParamKind::choice, "round_robin", 0, 0, {"round_robin", "fixed_priority"},
                 "Arbitration among masters (fixed priority: the first master connected wins)",
                 "[A] PLB v4.6 supports both; round robin treats the masters alike"});
    t.push_back({bus + ".arbitration_latency", ParamKind::cycles, "3 cycles", 0, 64, {},
                 "Request-to-grant cycles paid by every burst",
                 "[A] PLATFORM_FACTS: ~3-4 cycles of arbitration overhead per burst (not retrieved)"});
    t.push_back({bus + ".address_latency", ParamKind::cycles, "1 cycle", 0, 64, {},
                 "Address-phase cycles paid by every burst (no address pipelining modelled)",
                 "[A] one address cycle; with arbitration, 4 cycles of overhead per burst"});
}

// A register slave's answer time on PLB1 (each block's own parameter).
void add_register_latency(std::vector<ParamSpec>& t, const std::string& block, const std::string& what) {
    t.push_back({block + ".register_latency", ParamKind::cycles, "2 cycles", 0, 64, {},
                 what + ": PLB1 cycles from the address phase to the register's data",
                 "[A] an XPS PLBv46 slave (IPIF) decodes the address and registers its data: a few cycles (DS561 "
                 "timing not retrieved)"});
}

// The software stage's cost model (sw/cpu_cost/README.md has the reasoning of each).
void add_cpu_cost(std::vector<ParamSpec>& t) {
    t.push_back({"cpu.dcache_size", ParamKind::bytes, "32 KiB", 1024, 1 << 20, {}, "L1 data cache",
                 "[S] ML507 DTS; PPC440 32 KB D-cache"});
    t.push_back({"cpu.dcache_ways", ParamKind::count, "64", 1, 1024, {}, "L1 data cache associativity",
                 "[S] PPC440x5 manual Table 4-2: 32 KB, 64 ways"});
    t.push_back({"cpu.dcache_replacement", ParamKind::choice, "lru", 0, 0, {"lru", "round_robin"},
                 "L1 data cache replacement", "[A] LRU; the PPC440's round robin differs by 0.25 % in cycles"});
    // The PPC440 pipeline the calibration priced the stage's instruction stream with
    // (sw/cpu_cost/ppc440_pipeline.h); its probes are the band where it has one.
    for (const sw::PipelineKnob& k : sw::pipeline_knobs()) {
        const std::string unit = k.unit;
        auto text = [&](double v) {
            if (unit == "switch") return std::string(v > 0.5 ? "on" : "off");
            if (unit == "count") return fmt::format("{}", v);
            return fmt::format("{} {}", v, v == 1 ? "cycle" : "cycles");
        };
        ParamSpec spec{k.key, ParamKind::cycles, text(sw::PipelineParams{}.*k.field), 0, 1000, {}, k.help, k.source};
        if (unit == "switch") spec.kind = ParamKind::choice, spec.choices = {"on", "off"};
        if (unit == "count") spec.kind = ParamKind::count, spec.min = 1, spec.max = 8;
        if (k.band) spec.band = {text(k.low), text(k.high), k.why};
        t.push_back(spec);
    }
}

void add_iig(std::vector<ParamSpec>& t) {
    t.push_back({"iig.clock", ParamKind::frequency, "100 MHz", 1 * MHz, 500 * MHz, {}, "SSA IIG clock",
                 "[A] the PLB clock of the ML507 design; Fig. 3's clocks are lost"});
    t.push_back({"iig.pixels_per_clock", ParamKind::count, "1", 1, 16, {}, "Pixels the integral core adds per clock",
                 "[A] one adder chain: 7.9 ms for 1024x768 at 100 MHz (PLATFORM_FACTS)"});
    t.push_back({"iig.sum_bits", ParamKind::bits, "28 bit", 16, 32, {},
                 "Significant bits of an integral value (in a 32-bit word); a larger sum is an error",
                 "[D] 255 x 1024 x 1024 < 2^28: enough for the 1024x1024 limit"});
    t.push_back({"iig.burst", ParamKind::beats, "16 beats", 1, 16, {}, "IIG DMA burst length on PLB2", "[A] the longest PLB burst"});
    t.push_back({"iig.line_buffers", ParamKind::count, "2", 1, 64, {},
                 "Lines queued between the IIG's fetch, compute, write and send units",
                 "[A] double buffering: one line in work, one waiting"});
    add_register_latency(t, "iig", "SSA IIG registers");
    t.push_back({"iig.max_width", ParamKind::count, "1024", 1, 4096, {}, "Widest image the IIG accepts",
                 "[S] paper §III: image size limit 1024 x 1024"});
    t.push_back({"iig.max_height", ParamKind::count, "1024", 1, 4096, {}, "Tallest image the IIG accepts",
                 "[S] paper §III: image size limit 1024 x 1024"});
}

void add_fhg(std::vector<ParamSpec>& t) {
    t.push_back({"fhg.clock", ParamKind::frequency, "100 MHz", 1 * MHz, 1000 * MHz, {}, "SSA FHG clock",
                 "[A] PLATFORM_FACTS §5.4: the quad schedule needs ~105 MHz for 10 FPS; the standard EDK clock"});
    t.push_back({"fhg.read_buses", ParamKind::count, "4", 1, 64, {}, "MasterController read buses from the line FIFO",
                 "[S] paper §III-C: 4 independent buses"});
    t.push_back({"fhg.bus_word", ParamKind::choice, "quad", 0, 0, {"quad", "pair", "scalar"},
                 "What one read bus delivers per cycle: a 2x2 quad of integral values (128 bit), two neighbours on "
                 "one line (64 bit) or one value (32 bit)",
                 "[A] PLATFORM_FACTS §5.3(c): only quads reach ~10 FPS at 100 MHz"});
    t.push_back({"fhg.reuse", ParamKind::choice, "on", 0, 0, {"on", "off"},
                 "Whether one delivered value may serve several TripleMACs in the same cycle",
                 "[A] the TripleMACs snoop all buses (paper §III-C)"});
    t.push_back({"fhg.triple_macs", ParamKind::count, "18", 18, 64, {}, "TripleMAC units (one per determinant of a block)",
                 "[S] paper §III-C: 18 TripleMACs"});
    t.push_back({"fhg.x3_cycles", ParamKind::cycles, "3 cycles", 1, 8, {}, "Cycles a TripleMAC spends on a x3 coefficient",
                 "[S] paper §III-C: three additions instead of a multiplication"});
    t.push_back({"fhg.fifo_lines", ParamKind::count, "56", 52, 1024, {}, "Integral lines the MasterController FIFO holds",
                 "[S] paper §III-C: 56 lines (52 for the largest filter + refill)"});
    t.push_back({"fhg.line_ports", ParamKind::count, "2", 1, 8, {},
                 "Reads one block RAM of a line-FIFO line serves per cycle (a quad word takes 2 of each of its 2 lines)",
                 "[A] a RAMB36 in true dual-port mode has 2 ports (Virtex-5 UG190, recalled; PLATFORM_FACTS)"});
    t.push_back({"fhg.line_banks", ParamKind::count, "1", 1, 2, {},
                 "Block RAMs each line-FIFO line is interleaved over, by column (each with fhg.line_ports ports)",
                 "[D] 56 lines x 1024 x 32 bit = one RAMB36 per line (PLATFORM_FACTS §5.6); 2 banks double the BRAMs"});
    t.push_back({"fhg.scheduler", ParamKind::choice, "basic", 0, 0, {"basic", "improved"},
                 "The MasterController sequence the chip runs: the paper's basic script (one greedy pass) or an "
                 "improved one (what-if: a better script)",
                 "[S] paper §III-C: \"only very basic algorithm has been written\" (~11 % above optimal)"});
    t.push_back({"fhg.sequence_attempts", ParamKind::count, "16", 1, 10000, {},
                 "Greedy passes (different tie-breaks) per schedule: the basic script is their median, the improved "
                 "one their best",
                 "[-] tool setting: more passes, a better improved script and a steadier basic one, slower start-up"});
    t.push_back({"fhg.cycles_per_block", ParamKind::cycles, "0 cycles", 0, 100000, {},
                 "What-if: FHG cycles per 2x2 block instead of the generated sequence's (0: the sequence's)",
                 "[-] what-if (the verdict's break-even search sets it)"});
    t.push_back({"fhg.hessian_cycles_per_triple_mac", ParamKind::cycles, "1 cycle", 1, 16, {},
                 "HessianCalc cycles to read one TripleMAC's three responses over the three-state bus",
                 "[A] one 3-response word per cycle: 18 cycles per block, below the sequence"});
    t.push_back({"fhg.pipeline_latency", ParamKind::cycles, "8 cycles", 0, 1000, {},
                 "HessianCalc and LocMaxFinder latency after the last block's sequence",
                 "[A] multiply, subtract, round, compare: a few pipeline stages"});
    t.push_back({"fhg.maxima_fifo_depth", ParamKind::count, "1024", 1, 1 << 20, {}, "Candidates the maxima FIFO holds",
                 "[A] one RAMB36 of 32-bit words (PLATFORM_FACTS table)"});
    t.push_back({"fhg.det_row_buffers", ParamKind::count, "2", 1, 64, {}, "Block rows of determinants waiting for the DMA writer",
                 "[A] double buffering"});
    t.push_back({"fhg.burst", ParamKind::beats, "16 beats", 1, 16, {}, "FHG DMA burst length on PLB2", "[A] the longest PLB burst"});
    add_register_latency(t, "fhg", "SSA FHG registers");
    t.push_back({"fhg.max_width", ParamKind::count, "1024", 1, 4096, {}, "Widest image the FHG accepts",
                 "[S] paper §III: 1024 x 1024, BRAM sized by the width (MVA 2014)"});
    t.push_back({"fhg.max_height", ParamKind::count, "1024", 1, 4096, {}, "Tallest image the FHG accepts",
                 "[S] paper §III: image size limit 1024 x 1024"});
    t.push_back({"fhg.accumulator_bits", ParamKind::bits, "24 bit", 16, 32, {}, "TripleMAC accumulator width (wrapping)",
                 "[D] |Dxx| < 2^19 for L = 51 (51 x 33 x 255 x 2): 21 bits with sign; 24 leaves margin"});
    t.push_back({"fhg.recip_shift", ParamKind::bits, "16 bit", 0, 24, {},
                 "Extra fraction bits of the 1/L^2 constants that normalise the responses", "[A] 1/L^2 to ~1e-5"});
    t.push_back({"fhg.response_frac_bits", ParamKind::bits, "9 bit", 0, 24, {}, "Fraction bits of the normalised responses",
                 "[A] |Dxx/L^2| < 95 needs 8 integer bits: 9 fraction bits fill an 18-bit DSP48E port"});
    t.push_back({"fhg.response_bits", ParamKind::bits, "18 bit", 8, 32, {}, "Width of the normalised responses (saturating)",
                 "[A] the DSP48E's 18-bit multiplier input"});
    t.push_back({"fhg.weight_frac_bits", ParamKind::bits, "12 bit", 1, 20, {}, "Fraction bits of the 0.81 weight",
                 "[A] 3318/4096 = 0.81006"});
    t.push_back({"fhg.det_frac_bits", ParamKind::bits, "16 bit", 0, 48, {},
                 "Fraction bits of the determinant word (and of THRESHOLD)",
                 "[A] determinants < 2^14 in threshold units: 16 fraction bits fit a signed 32-bit word"});
    t.push_back({"fhg.det_bits", ParamKind::bits, "32 bit", 8, 32, {}, "Determinant word written to memory (saturating)",
                 "[A] PLATFORM_FACTS: 32-bit fixed point"});
}

void add_surf(std::vector<ParamSpec>& t) {
    t.push_back({"surf.source", ParamKind::text, "/usr/share/doc/opencv-doc/examples/data/graf1.png", 0, 0, {},
                 "Frames: an image (repeated), a folder of images, a list file or a video",
                 "[-] Debian opencv-doc's graf1"});
    t.push_back({"surf.frames", ParamKind::count, "20", 1, 100000, {}, "Frames to process", "[-] scenario size"});
    t.push_back({"surf.width", ParamKind::count, "1024", 0, 4096, {}, "Frames are resized to this width (0: as they are)",
                 "[S] paper: 1024 x 768 frames"});
    t.push_back({"surf.height", ParamKind::count, "768", 0, 4096, {}, "Frames are resized to this height (0: as they are)",
                 "[S] paper: 1024 x 768 frames"});
    t.push_back({"surf.target_keypoints", ParamKind::count, "100", 0, 100000, {},
                 "Calibrate the threshold on the first frame (float reference) to give about this many keypoints; 0: use surf.threshold",
                 "[S] paper: ~100 descriptors per image"});
    t.push_back({"surf.threshold", ParamKind::real, "500", 0, 1e9, {}, "Determinant threshold (units of sw/surf/README.md) when not calibrated",
                 "[A] a middle value for 1024x768 scenes"});
    t.push_back({"surf.upright", ParamKind::choice, "off", 0, 0, {"on", "off"}, "Skip the orientation (U-SURF)",
                 "[S] paper §II: orientation is optional"});
    t.push_back({"surf.haar", ParamKind::choice, "rounded", 0, 0, {"rounded", "exact"},
                 "The CPU's Haar wavelets: at whole pixels with integer sizes (6 reads each), or exact at sub-pixel "
                 "positions like the float reference",
                 "[A] embedded SURF of the time (OpenSURF) samples at whole pixels; exact costs 2.4 ms a keypoint "
                 "on this PPC440 model against 0.76 ms rounded (sw/cpu_cost/README.md)"});
    t.push_back({"surf.tasks_in_flight", ParamKind::count, "2", 1, 16, {},
                 "Tasks between hardware start and descriptors done (buffer sets in memory)",
                 "[S] paper §III-D: tasks overlap; two let the CPU describe one while the hardware does the next"});
    t.push_back({"surf.fifo_irq_level", ParamKind::count, "256", 1, 1 << 20, {},
                 "Maxima FIFO level that interrupts the CPU to drain it", "[A] a quarter of the default FIFO"});
    t.push_back({"budget.fps", ParamKind::real, "10", 0, 1e6, {}, "Frames per second the scenario must sustain (0: no budget)",
                 "[S] paper: ~10 FPS at 1024 x 768"});
    t.push_back({"verdict.break_even", ParamKind::choice, "off", 0, 0, {"on", "off"},
                 "Find the limiting block's clock (and the FHG's cycles per block) that just meets budget.fps, by "
                 "re-simulation, and check it with one more run of the whole scenario",
                 "[-] analysis (DESIGN principle 7)"});
    t.push_back({"verdict.band", ParamKind::choice, "off", 0, 0, {"on", "off"},
                 "Re-simulate with every banded parameter at its low and at its high, one at a time: the frames/s range, "
                 "the assumptions that flip the verdict, tornado.svg",
                 "[-] analysis (DESIGN principle 7)"});
    t.push_back({"verdict.software", ParamKind::choice, "off", 0, 0, {"on", "off"},
                 "Re-simulate with the software settings that move the CPU's time (surf.haar, surf.upright, "
                 "surf.target_keypoints): the frames/s and CPU time under each",
                 "[-] analysis: what the verdict rests on"});
    t.push_back({"verdict.frames", ParamKind::count, "2", 2, 1000, {},
                 "Frames each of the verdict's re-simulations runs (at least soc.accelerators + 1, at most surf.frames)",
                 "[-] the pipeline is in steady state once each pair has done its first frame (every frame alike in the "
                 "budget scenario: the 2-frame rate equals the 20-frame rate to 0.01 %)"});
    t.push_back({"verdict.jobs", ParamKind::count, "0", 0, 256, {},
                 "Re-simulations run at once (0: one per core); no figure depends on it",
                 "[-] simulation setting"});
    t.push_back({"fault.frame", ParamKind::count, "0", 0, 100000, {},
                 "Fault injection: frame number (from 1) whose determinant buffer is placed outside memory; 0: none",
                 "[-] test hook: a DMA bus error in one task"});
    t.push_back({"eval.homography", ParamKind::text, "", 0, 0, {},
                 "Homography from frame 0 to frame 1 (Oxford or OpenCV file): report repeatability and precision", "[-] evaluation"});
    t.push_back({"eval.poses", ParamKind::text, "", 0, 0, {},
                 "Folder of Camera_NNN.txt poses (ViSP castle): report distinguishability with the true F too", "[-] evaluation"});
}

// The assumption band: for each assumed value the plausible low and high and why (the verdict
// re-simulates with each, one at a time). A low or high equal to the default means no
// plausible value on that side.
struct BandEntry {
    const char* key;
    const char* low;
    const char* high;
    const char* why;
};
constexpr BandEntry kBands[] = {
    {"cpu.clock", "300 MHz", "550 MHz", "the seed's CPU clock is not given: the ML507 design runs 400, FX designs run 250-400, the device allows 550"},
    {"cpu.memory_path", "plb1", "mci", "if the DDR were on PLB1 rather than the PPC440's MCI"},
    {"mci.clock", "100 MHz", "266 MHz", "the MCI at the PLB clock, or with a DDR2-533 MPMC"},
    {"mci.width", "64 bit", "128 bit", "a narrower memory interface than the crossbar's"},
    {"mci.latency", "2 cycles", "8 cycles", "crossbar and clock-crossing cycles are not retrieved"},
    {"cpu.dcache_replacement", "round_robin", "lru", "the PPC440 itself is round robin per set"},
    {"plb1.arbitration", "fixed_priority", "round_robin", "the other PLB v4.6 arbitration mode"},
    {"plb1.arbitration_latency", "1 cycle", "4 cycles", "PLATFORM_FACTS: ~3-4 cycles, not retrieved; overlapped arbitration would hide most"},
    {"plb1.address_latency", "0 cycles", "2 cycles", "address pipelining would hide it; a slow slave decode would add one"},
    {"plb2.width", "64 bit", "128 bit", "\"increased capacity\" could be 64 bit (PLATFORM_FACTS §5.5: enough)"},
    {"plb2.arbitration", "fixed_priority", "round_robin", "the other PLB v4.6 arbitration mode"},
    {"plb2.arbitration_latency", "1 cycle", "4 cycles", "as plb1.arbitration_latency"},
    {"plb2.address_latency", "0 cycles", "2 cycles", "as plb1.address_latency"},
    {"memory.clock", "133 MHz", "266 MHz", "DDR2-266 to DDR2-533 on the ML507 class of boards"},
    {"memory.width", "32 bit", "64 bit", "a 32-bit DDR2 component instead of the 64-bit DIMM"},
    {"memory.efficiency", "0.6", "0.9", "row misses and refresh: 60-90 % of the peak"},
    {"memory.latency", "20 cycles", "30 cycles", "PLATFORM_FACTS: ~20-30 MPMC cycles"},
    {"memory.write_latency", "0 cycles", "25 cycles", "posted into a write FIFO, or as slow as a read"},
    {"intc.register_latency", "1 cycle", "4 cycles", "a registered or a pipelined IPIF answer"},
    {"dma.burst", "8 beats", "16 beats", "the test DMA's own bursts"},
    {"dma.register_latency", "1 cycle", "4 cycles", "as intc.register_latency"},
    {"iig.clock", "50 MHz", "125 MHz", "Fig. 3's clocks are lost: half the PLB clock to the FHG's upper guess"},
    {"iig.pixels_per_clock", "1", "2", "one adder chain, or two"},
    {"iig.burst", "8 beats", "16 beats", "a DMA with shorter bursts"},
    {"iig.line_buffers", "1", "4", "single buffering, or deeper queues"},
    {"iig.register_latency", "1 cycle", "4 cycles", "as intc.register_latency"},
    {"pixelbus.width", "32 bit", "64 bit", "one value a cycle is the least that keeps up; two would be wider"},
    {"fhg.clock", "90 MHz", "125 MHz", "PLATFORM_FACTS: 100-125 MHz; a complex design may close timing a little lower"},
    {"fhg.bus_word", "pair", "quad", "64-bit read buses (two values of one line) instead of 2x2 quads"},
    {"fhg.reuse", "off", "on", "whether the TripleMACs may take a value delivered for another (the basic script does not use it)"},
    {"fhg.line_ports", "2", "2", "a RAMB36 has exactly two ports; more reads per line need more BRAMs (fhg.line_banks)"},
    {"fhg.line_banks", "1", "2", "one RAMB36 per line (56 in all), or two (112 of the FX70T's 148)"},
    {"fhg.hessian_cycles_per_triple_mac", "1 cycle", "3 cycles", "HessianCalc may read one response, not three, per cycle"},
    {"fhg.pipeline_latency", "4 cycles", "32 cycles", "a short or a deep HessianCalc/LocMaxFinder pipeline"},
    {"fhg.maxima_fifo_depth", "512", "2048", "half or two RAMB36 of 32-bit words"},
    {"fhg.det_row_buffers", "1", "4", "single buffering, or deeper"},
    {"fhg.burst", "8 beats", "16 beats", "a DMA with shorter bursts"},
    {"fhg.register_latency", "1 cycle", "4 cycles", "as intc.register_latency"},
    {"fhg.recip_shift", "12 bit", "20 bit", "coarser or finer 1/L^2 constants"},
    {"fhg.response_frac_bits", "8 bit", "10 bit", "one fraction bit less or more in the responses"},
    {"fhg.response_bits", "18 bit", "24 bit", "the DSP48E's 18-bit input, or 25 bits of its other port"},
    {"fhg.weight_frac_bits", "8 bit", "16 bit", "a coarser or finer 0.81"},
    {"fhg.det_frac_bits", "14 bit", "16 bit", "two fraction bits less still hold the threshold's resolution"},
    {"fhg.det_bits", "32 bit", "32 bit", "narrower words need det_frac_bits lowered with them (a two-parameter what-if); alone they saturate"},
    {"surf.target_keypoints", "80", "140", "~100 descriptors per image (TePRA 2009), ~140 (MVA 2014)"},
    {"surf.threshold", "400", "600", "used only when surf.target_keypoints is 0"},
    {"surf.haar", "exact", "rounded", "exact sub-pixel wavelets like the float reference"},
    {"surf.fifo_irq_level", "64", "512", "the driver drains the maxima FIFO earlier or later"},
};

std::vector<ParamSpec> make_table() {
    std::vector<ParamSpec> t;
    t.push_back({"run.workload", ParamKind::choice, "smoke", 0, 0, {"smoke", "surf"},
                 "What the CPU runs: the bus smoke test, or libSSA2 and SURF on frames", "[-] scenario choice"});
    t.push_back({"run.max_time", ParamKind::duration, "600 s", 1, 36000 * s, {},
                 "Simulated time after which a run that has not finished is stopped as stalled",
                 "[-] tool setting: a guard against a livelocked run, far above any shipped scenario (castle, exact Haar: 11 s)"});

    t.push_back({"run.dma_granularity", ParamKind::choice, "line", 0, 0, {"line", "burst"},
                 "IP blocks' DMA: one TLM transaction per line or per burst; the bus arbitrates every burst either "
                 "way, so the figures are the same",
                 "[-] simulation setting (no figure depends on it)"});
    t.push_back({"cpu.clock", ParamKind::frequency, "400 MHz", 1 * MHz, 550 * MHz, {}, "PowerPC 440 core clock",
                 "[S] ML507 reference design (Linux virtex440-ml507.dts, QEMU virtex_ml507): 400 MHz; 550 MHz is the device maximum"});
    t.push_back({"cpu.quantum", ParamKind::duration, "1 us", 1, 1000 * us, {},
                 "Temporal-decoupling quantum: how far the CPU runs ahead of the kernel between synchronisations",
                 "[-] simulation setting (no figure depends on it): 100 PLB cycles, coarse enough to be fast"});
    t.push_back({"cpu.cache_line", ParamKind::bytes, "32 B", 4, 256, {}, "L1 cache line: the CPU's memory traffic goes in lines",
                 "[S] ML507 DTS: 32-byte L1 lines"});
    t.push_back({"cpu.memory_path", ParamKind::choice, "mci", 0, 0, {"mci", "plb1"},
                 "How the CPU's line fills, write-backs and copies reach DDR: its crossbar and memory controller "
                 "interface (the MPMC's PPC440MC port), or PLB1",
                 "[A] the PPC440 block has a PPC440MC interface (PLATFORM_FACTS §2); EDK designs for the ML507 wire "
                 "the MPMC to it (recalled, not retrieved)"});
    t.push_back({"mci.clock", ParamKind::frequency, "200 MHz", 1 * MHz, 1000 * MHz, {},
                 "Clock of the PPC440's memory controller interface (CPMMCCLK)",
                 "[A] the MPMC's clock, which the PPC440MC port runs at (memory.clock)"});
    t.push_back({"mci.width", ParamKind::bits, "128 bit", 32, 128, {}, "Data width of the memory controller interface",
                 "[A] the PPC440 crossbar's 128-bit interfaces (PLATFORM_FACTS §2)"});
    t.push_back({"mci.latency", ParamKind::cycles, "4 cycles", 0, 1000, {},
                 "Cycles of mci.clock the crossbar and the MCI add to an access before the DDR sees it",
                 "[A] a request through the crossbar and the interface's address phase, like a PLB burst's overhead"});

    add_cpu_cost(t);

    add_plb(t, "plb1", "128 bit", "[S] ML507 DTS: mplb-dwidth = 0x80", "PLB1 (CPU and register slaves)");
    add_plb(t, "plb2", "128 bit", "[A] the paper: PLB2 \"has accordingly increased capacity\" (Fig. 3 lost); 64 bit would do",
            "PLB2 (IP DMA traffic)");

    t.push_back({"memory.size", ParamKind::bytes, "256 MiB", 1 * MiB, 256 * MiB, {}, "Installed DDR", "[S] ML507: 256 MB DDR2"});
    t.push_back({"memory.clock", ParamKind::frequency, "200 MHz", 50 * MHz, 800 * MHz, {}, "DDR clock",
                 "[A] DDR2 at ~200 MHz on the ML507 class of boards"});
    t.push_back({"memory.width", ParamKind::bits, "64 bit", 8, 256, {}, "DDR data width", "[A] 64-bit DDR2 DIMM"});
    t.push_back({"memory.transfers_per_clock", ParamKind::count, "2", 1, 2, {}, "Data transfers per clock (2 for DDR)",
                 "[S] DDR transfers on both clock edges"});
    t.push_back({"memory.efficiency", ParamKind::real, "0.8", 0.01, 1, {},
                 "Fraction of the peak bandwidth that sustained traffic gets",
                 "[A] ~80 % burst efficiency (PLATFORM_FACTS §5.5)"});
    t.push_back({"memory.latency", ParamKind::cycles, "25 cycles", 0, 1000, {},
                 "Read latency at the DDR clock, before the first data",
                 "[A] PLATFORM_FACTS: ~20-30 MPMC cycles read latency (no DS643 table retrieved)"});
    t.push_back({"memory.write_latency", ParamKind::cycles, "0 cycles", 0, 1000, {},
                 "Latency a write's master sees at the DDR clock (it still waits for the DRAM and its transfer)",
                 "[A] the MPMC's ports take writes into a write FIFO (DS643: ports with FIFOs): posted"});

    t.push_back({"intc.inputs", ParamKind::count, "12", 1, 32, {}, "Interrupt inputs of the XPS INTC",
                 "[S] ML507 DTS: xps_intc with 12 inputs"});
    add_register_latency(t, "intc", "XPS INTC registers");

    t.push_back({"dma.burst", ParamKind::beats, "16 beats", 1, 16, {}, "Burst length of the test DMA on PLB2",
                 "[A] the longest PLB burst"});
    add_register_latency(t, "dma", "Test DMA registers");

    add_iig(t);
    t.push_back({"pixelbus.width", ParamKind::bits, "32 bit", 8, 128, {}, "PixelBus width: integral values per IIG cycle x 32",
                 "[A] one 32-bit integral value per cycle (PLATFORM_FACTS table)"});
    add_fhg(t);

    t.push_back({"soc.accelerators", ParamKind::count, "1", 1, 4, {}, "SSA IIG + SSA FHG pairs on the chip",
                 "[S] paper §III-D: one pair; the library supports more"});
    add_surf(t);

    t.push_back({"smoke.buffer", ParamKind::bytes, "64 KiB", 1, 16 * MiB, {}, "Bytes the test DMA copies per copy",
                 "[-] test size: many bursts, well inside the L1-sized buffers of the chip's drivers"});
    t.push_back({"smoke.copies", ParamKind::count, "4", 1, 1000000, {}, "Copies the smoke software runs one after another",
                 "[-] test size"});
    t.push_back({"smoke.polls", ParamKind::count, "3", 0, 1000000, {},
                 "Status polls over PLB1 per copy before the CPU sleeps on the interrupt", "[-] test size"});
    t.push_back({"smoke.poll_interval", ParamKind::cycles, "200 cycles", 0, 1e9, {}, "CPU cycles between status polls",
                 "[-] test setting: a short delay loop"});
    t.push_back({"smoke.src", ParamKind::address, "0x0010_0000", 0, 0xFFFFFFFF, {}, "Source buffer address in DDR",
                 "[-] placement"});
    t.push_back({"smoke.dst", ParamKind::address, "0x0020_0000", 0, 0xFFFFFFFF, {}, "Destination buffer address in DDR",
                 "[-] placement"});
    for (const BandEntry& b : kBands) {
        auto it = std::find_if(t.begin(), t.end(), [&](const ParamSpec& p) { return p.key == b.key; });
        if (it == t.end()) throw std::logic_error(std::string("parameter band for an unknown parameter: ") + b.key);
        it->band = {b.low, b.high, b.why};
    }
    return t;
}

size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

double parse_address(const std::string& text) {
    std::string digits;
    for (char c : text)
        if (c != '_') digits += c;
    size_t used = 0;
    unsigned long long value = 0;
    try {
        value = std::stoull(digits, &used, 0);
    } catch (const std::exception&) {
        used = 0;
    }
    if (digits.empty() || used != digits.size() || digits[0] == '-')
        throw UnitError(fmt::format("'{}' is not an address: expected a number such as 0x0010_0000", text));
    return double(value);
}

double parse_plain(const std::string& text, bool integer) {
    size_t used = 0;
    double value = 0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size())
        throw UnitError(fmt::format("'{}' is not a {}", text, integer ? "whole number" : "number"));
    if (integer && value != std::floor(value)) throw UnitError(fmt::format("'{}' is not a whole number", text));
    return value;
}

}  // namespace

std::string format_value(const ParamSpec& spec, double value) {
    switch (spec.kind) {
        case ParamKind::frequency: return format_frequency(Frequency{value});
        case ParamKind::duration: return format_duration(Duration{uint64_t(value)});
        case ParamKind::bits: return fmt::format("{} bit", uint64_t(value));
        case ParamKind::bytes: return format_bytes(Bytes{uint64_t(value)});
        case ParamKind::cycles: return fmt::format("{} cycles", uint64_t(value));
        case ParamKind::beats: return fmt::format("{} beats", uint64_t(value));
        case ParamKind::address: return fmt::format("{:#x}", uint64_t(value));
        case ParamKind::count: return fmt::format("{}", uint64_t(value));
        default: return fmt::format("{}", value);
    }
}

const std::vector<ParamSpec>& parameter_table() {
    static const std::vector<ParamSpec> table = make_table();
    return table;
}

std::vector<const ParamSpec*> band_parameters() {
    std::vector<const ParamSpec*> out;
    for (const ParamSpec& p : parameter_table())
        if (!p.band.low.empty()) out.push_back(&p);
    return out;
}

const ParamSpec* find_parameter(std::string_view key) {
    for (const ParamSpec& p : parameter_table())
        if (p.key == key) return &p;
    return nullptr;
}

std::string closest_parameter(std::string_view key) {
    std::string best;
    size_t best_distance = 4;  // farther than three edits is no longer a typo
    for (const ParamSpec& p : parameter_table()) {
        const size_t d = edit_distance(key, p.key);
        if (d < best_distance) {
            best_distance = d;
            best = p.key;
        }
    }
    return best;
}

double parse_value(const ParamSpec& spec, const std::string& text) {
    double value = 0;
    switch (spec.kind) {
        case ParamKind::frequency: value = parse_frequency(text).hz; break;
        case ParamKind::duration: value = double(parse_duration(text).ps); break;
        case ParamKind::bits: value = parse_bits(text); break;
        case ParamKind::bytes: value = double(parse_bytes(text).n); break;
        case ParamKind::cycles: value = double(parse_cycles(text)); break;
        case ParamKind::beats: value = parse_beats(text); break;
        case ParamKind::count: value = parse_plain(text, true); break;
        case ParamKind::real: value = parse_plain(text, false); break;
        case ParamKind::address: value = parse_address(text); break;
        case ParamKind::text: return 0;
        case ParamKind::choice:
            if (std::find(spec.choices.begin(), spec.choices.end(), text) == spec.choices.end())
                throw UnitError(fmt::format("'{}' is not one of: {}", text, fmt::join(spec.choices, ", ")));
            return 0;
    }
    if (value < spec.min || value > spec.max)
        throw UnitError(fmt::format("'{}' is out of range: {} must be between {} and {}", text, spec.key,
                                    format_value(spec, spec.min), format_value(spec, spec.max)));
    return value;
}

std::string describe_kind(const ParamSpec& spec) {
    switch (spec.kind) {
        case ParamKind::frequency: return "frequency (Hz, kHz, MHz, GHz)";
        case ParamKind::duration: return "duration (ps, ns, us, ms, s)";
        case ParamKind::bits: return "width (bit)";
        case ParamKind::bytes: return "size (B, KiB, MiB, GiB)";
        case ParamKind::cycles: return "clock cycles (cycles)";
        case ParamKind::beats: return "bus beats (beats)";
        case ParamKind::count: return "whole number";
        case ParamKind::real: return "number";
        case ParamKind::address: return "address";
        case ParamKind::choice: return fmt::format("one of {}", fmt::join(spec.choices, ", "));
        case ParamKind::text: return "text";
    }
    return "";
}

std::string parameters_markdown() {
    std::string out =
        "# surfvp parameters\n\n"
        "Every parameter a scenario can set, with its default and where the default comes from:\n"
        "**[S]** sourced, **[D]** derived, **[A]** assumed (the reason follows), **[-]** a choice, not a\n"
        "fact. Generated by `surfvp params`; a test keeps this file equal to its output.\n\n"
        "| key | default | range | kind | what it is | source |\n|---|---|---|---|---|---|\n";
    for (const ParamSpec& p : parameter_table()) {
        std::string range = p.kind == ParamKind::choice || p.kind == ParamKind::text ? "" : fmt::format("{} .. {}", format_value(p, p.min), format_value(p, p.max));
        out += fmt::format("| `{}` | `{}` | {} | {} | {} | {} |\n", p.key, p.default_value, range, describe_kind(p),
                           p.description, p.source);
    }
    out += "\n## Assumption band\n\n"
           "Every assumed value, and a few uncertain others, with a plausible low and high. The budget\n"
           "verdict re-simulates with each at its low and at its high, one at a time (`verdict.band`).\n\n"
           "| key | default | low | high | why |\n|---|---|---|---|---|\n";
    for (const ParamSpec* p : band_parameters())
        out += fmt::format("| `{}` | `{}` | `{}` | `{}` | {} |\n", p->key, p->default_value, p->band.low, p->band.high, p->band.why);
    return out;
}

}  // namespace surfvp
