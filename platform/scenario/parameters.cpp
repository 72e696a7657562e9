#include "platform/scenario/parameters.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <limits>

#include "models/common/time_series.h"
#include "models/common/units.h"
#include "models/dma/dma.h"
#include "models/fhg/fhg.h"
#include "models/iig/iig.h"
#include "models/intc/intc.h"
#include "models/mci/mci_link.h"
#include "models/memory/ddr_memory.h"
#include "models/plb/plb_bus.h"
#include "models/ppc440/ppc440.h"
#include "sw/cpu_cost/ppc440_pipeline.h"

namespace surfvp {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using unit::MHz, unit::us, unit::s, unit::MiB;

// The software stage's cost model (sw/cpu_cost/README.md has the reasoning of each).
void add_cpu_cost(std::vector<ParamSpec>& t) {
    t.push_back({"cpu.dcache_size",
                 ParamKind::bytes,
                 "32 KiB",
                 1024,
                 1 << 20,
                 {},
                 "L1 data cache",
                 "[S] ML507 DTS; PPC440 32 KB D-cache"});
    t.push_back({"cpu.dcache_ways",
                 ParamKind::count,
                 "64",
                 1,
                 1024,
                 {},
                 "L1 data cache associativity",
                 "[S] PPC440x5 manual Table 4-2: 32 KB, 64 ways"});
    t.push_back({"cpu.dcache_replacement",
                 ParamKind::choice,
                 "lru",
                 0,
                 0,
                 {"lru", "round_robin"},
                 "L1 data cache replacement",
                 "[A] LRU; the PPC440's round robin differs by 0.25 % in cycles"});
    // The PPC440 pipeline the calibration priced the stage's instruction stream with
    // (sw/cpu_cost/ppc440_pipeline.h); its probes are the band where it has one.
    for (const sw::PipelineKnob& k : sw::pipeline_knobs()) {
        const std::string unit = k.unit;
        auto text = [&](double v) {
            if (const char* choice = sw::knob_choice(k, v)) return std::string(choice);
            if (unit == "count") return fmt::format("{}", v);
            return fmt::format("{} {}", v, v == 1 ? "cycle" : "cycles");
        };
        ParamSpec spec{k.key, ParamKind::cycles, text(sw::PipelineParams{}.*k.field), 0, 1000, {}, k.help, k.source};
        if (unit == "switch") spec.kind = ParamKind::choice, spec.choices = {"on", "off"};
        if (unit == "precision") spec.kind = ParamKind::choice, spec.choices = {"single", "double"};
        if (unit == "count") spec.kind = ParamKind::count, spec.min = 1, spec.max = 8;
        if (k.band) spec.band = {text(k.low), text(k.high), k.why};
        t.push_back(spec);
    }
}

void add_surf(std::vector<ParamSpec>& t) {
    t.push_back({"surf.source",
                 ParamKind::text,
                 "/usr/share/doc/opencv-doc/examples/data/graf1.png",
                 0,
                 0,
                 {},
                 "Frames: an image (repeated), a folder of images, a list file or a video",
                 "[-] Debian opencv-doc's graf1"});
    t.push_back({"surf.frames", ParamKind::count, "20", 1, 100000, {}, "Frames to process", "[-] scenario size"});
    t.push_back({"surf.width",
                 ParamKind::count,
                 "1024",
                 0,
                 4096,
                 {},
                 "Frames are resized to this width (0: as they are)",
                 "[S] paper: 1024 x 768 frames"});
    t.push_back({"surf.height",
                 ParamKind::count,
                 "768",
                 0,
                 4096,
                 {},
                 "Frames are resized to this height (0: as they are)",
                 "[S] paper: 1024 x 768 frames"});
    t.push_back({"surf.target_keypoints",
                 ParamKind::count,
                 "100",
                 0,
                 100000,
                 {},
                 "Calibrate the threshold on the first frame (float reference) to give about this many keypoints; 0: "
                 "use surf.threshold",
                 "[S] paper: ~100 descriptors per image"});
    t.push_back({"surf.threshold",
                 ParamKind::real,
                 "500",
                 0,
                 1e9,
                 {},
                 "Determinant threshold (units of sw/surf/README.md) when not calibrated",
                 "[A] a middle value for 1024x768 scenes"});
    t.push_back(
        {"surf.threshold_control",
         ParamKind::choice,
         "hold",
         0,
         0,
         {"hold", "track"},
         "hold: the calibrated threshold for every frame; track: each frame's threshold from the keypoint count "
         "of the frame surf.tasks_in_flight before it, aiming at surf.target_keypoints",
         "[-] a software setting: hold is the paper's one THRESHOLD register, track what a camera pipeline does"});
    t.push_back({"surf.upright",
                 ParamKind::choice,
                 "off",
                 0,
                 0,
                 {"on", "off"},
                 "Skip the orientation (U-SURF)",
                 "[S] paper §II: orientation is optional"});
    t.push_back({"surf.haar",
                 ParamKind::choice,
                 "rounded",
                 0,
                 0,
                 {"rounded", "exact"},
                 "The CPU's Haar wavelets: at whole pixels with integer sizes (6 reads each), or exact at sub-pixel "
                 "positions like the float reference",
                 "[A] embedded SURF of the time (OpenSURF) samples at whole pixels; what each costs the CPU is a run's "
                 "software_time_per_keypoint_us (verdict.software runs both; docs/sources.md#surf)"});
    t.push_back({"surf.max_offset",
                 ParamKind::real,
                 "0.5",
                 0.5,
                 2,
                 {},
                 "The CPU's interpolation drops a local maximum whose fitted offset exceeds this, in samples, in x, y "
                 "or scale (1 keeps the maxima that lie between two samples)",
                 "[S] paper §II: 0.5; OpenCV's SURF keeps up to 1, which the float reference uses (docs/quality.md)"});
    t.push_back({"surf.tasks_in_flight",
                 ParamKind::count,
                 "2",
                 1,
                 16,
                 {},
                 "Tasks between hardware start and descriptors done (buffer sets in memory: a frame, its integral "
                 "image, determinants and descriptors; a frame arrives in its set as its task starts)",
                 "[S] paper §III-D: tasks overlap; two let the CPU describe one while the hardware does the next"});
    t.push_back({"surf.fifo_irq_level",
                 ParamKind::count,
                 "256",
                 1,
                 1 << 20,
                 {},
                 "Maxima FIFO level that interrupts the CPU to drain it",
                 "[A] a quarter of the default FIFO"});
    t.push_back({"surf.watchdog",
                 ParamKind::duration,
                 "0 s",
                 0,
                 3600 * s,
                 {},
                 "libSSA2's watchdog: a task's hardware still unfinished this long after its start is checked "
                 "(a block found finished lost its interrupt; one still BUSY fails the task); 0: off",
                 "[-] off unless a scenario arms it (scenarios/faults.yaml: 100 ms): an armed timeout moves one PLB2 "
                 "burst in 10^5 by a wait bin between DMA granularities (an open kernel-ordering sensitivity)"});
    t.push_back(
        {"surf.spurious_irq_limit",
         ParamKind::count,
         "64",
         0,
         1 << 20,
         {},
         "Interrupts in a row from one line with nothing to serve that make libSSA2 call the line stuck "
         "(fail the task, reset the pair); 0: never",
         "[-] driver setting (no fault-free figure depends on it): a line that has just let go can give one; in "
         "scenarios/faults.yaml all 64 came from the stuck line"});
    t.push_back({"budget.fps",
                 ParamKind::real,
                 "10",
                 0,
                 1e6,
                 {},
                 "Frames per second the scenario must sustain (0: no budget)",
                 "[S] paper: ~10 FPS at 1024 x 768"});
    t.push_back({"verdict.break_even",
                 ParamKind::choice,
                 "off",
                 0,
                 0,
                 {"on", "off"},
                 "Find the limiting block's clock (and the FHG's cycles per block) that just meets budget.fps, by "
                 "re-simulation, and check it with one more run of the whole scenario",
                 "[-] analysis (docs/architecture.md#principles, 7)"});
    t.push_back(
        {"verdict.band",
         ParamKind::choice,
         "off",
         0,
         0,
         {"on", "off"},
         "Re-simulate the unknowns about the chip jointly (verdict.samples points over their bands: the frames/s "
         "percentiles, the probability of meeting the budget, each unknown's sensitivity) and each at its low and "
         "its high (tornado.svg); and each design choice and workload setting with a band, one at a time (what a "
         "review can change)",
         "[-] analysis (docs/architecture.md#principles, 7)"});
    t.push_back({"verdict.software",
                 ParamKind::choice,
                 "off",
                 0,
                 0,
                 {"on", "off"},
                 "Re-simulate with the software settings that move the CPU's time (surf.haar, surf.upright, "
                 "surf.target_keypoints): the frames/s and CPU time under each",
                 "[-] analysis: what the verdict rests on"});
    t.push_back(
        {"verdict.frames",
         ParamKind::count,
         "2",
         2,
         1000,
         {},
         "Frames each of the verdict's re-simulations runs (at least soc.accelerators + 1, at most surf.frames)",
         "[-] the pipeline is in steady state once each pair has done its first frame (every frame alike in the "
         "budget scenario: the 2-frame rate equals the 20-frame rate to 0.01 %)"});
    t.push_back({"verdict.samples",
                 ParamKind::count,
                 "200",
                 0,
                 100000,
                 {},
                 "Points of the joint sample of the unknowns (verdict.band; 0: none, the one-at-a-time band only)",
                 "[-] analysis: 200 points give the 5th and 95th percentiles to about +-2 points of rank"});
    t.push_back({"verdict.jobs",
                 ParamKind::count,
                 "0",
                 0,
                 256,
                 {},
                 "Re-simulations run at once (0: one per core); no figure depends on it",
                 "[-] simulation setting"});
    // The FPGA's capacity and what the resource estimate cannot derive (platform/cost,
    // docs/resources.md). None enters the simulation.
    t.push_back({"fpga.device",
                 ParamKind::choice,
                 "XC5VFX70T",
                 0,
                 0,
                 {"XC5VFX70T", "XC5VFX100T", "XC6SLX150T", "other"},
                 "The FPGA the resources are counted against, by name (its capacities are fpga.ramb36, fpga.dsp48e and "
                 "fpga.slices)",
                 "[S] paper §III: XC5VFX70"});
    t.push_back({"fpga.ramb36",
                 ParamKind::count,
                 "148",
                 1,
                 100000,
                 {},
                 "Block RAMs (RAMB36) the device has",
                 "[A] XC5VFX70T: 148 (recalled from DS100; docs/sources.md#fpga-resources)"});
    t.push_back({"fpga.dsp48e",
                 ParamKind::count,
                 "128",
                 0,
                 100000,
                 {},
                 "DSP48E slices the device has",
                 "[A] XC5VFX70T: 128 (recalled from DS100; docs/sources.md#fpga-resources)"});
    t.push_back({"fpga.slices",
                 ParamKind::count,
                 "11200",
                 1,
                 10000000,
                 {},
                 "Logic slices the device has (4 LUT6 and 4 flip-flops each)",
                 "[A] XC5VFX70T: 11,200 (recalled from DS100; docs/sources.md#fpga-resources); 4 LUTs and 4 FFs a "
                 "slice (UG190, recalled)"});
    t.push_back(
        {"fpga.bram_fmax",
         ParamKind::frequency,
         "450 MHz",
         1 * unit::MHz,
         2000 * unit::MHz,
         {},
         "Highest clock the device's block RAM runs at (a line FIFO clocked at a multiple of fhg.clock must stay "
         "under it)",
         "[A] Virtex-5 block RAM in the slowest (-1) speed grade: 450 MHz (data sheet DS202, recalled, not "
         "retrieved); faster grades are higher"});
    t.push_back({"fpga.ip_interface_luts",
                 ParamKind::count,
                 "700",
                 0,
                 1000000,
                 {},
                 "LUTs of one IP block's PLB interfaces (a slave for its registers, a master for its DMA)",
                 "[A] order of magnitude of Xilinx's PLBv46 slave and master-burst IPIF (not retrieved)"});
    t.push_back({"fpga.ip_interface_ffs",
                 ParamKind::count,
                 "900",
                 0,
                 1000000,
                 {},
                 "Flip-flops of one IP block's PLB interfaces",
                 "[A] as fpga.ip_interface_luts"});
    t.push_back({"fpga.infrastructure_luts",
                 ParamKind::count,
                 "6000",
                 0,
                 10000000,
                 {},
                 "LUTs of the rest of the system: MPMC, two PLBs, INTC, UART, debug",
                 "[A] an EDK system of the time around an MPMC (not retrieved)"});
    t.push_back({"fpga.infrastructure_ffs",
                 ParamKind::count,
                 "7000",
                 0,
                 10000000,
                 {},
                 "Flip-flops of the rest of the system",
                 "[A] as fpga.infrastructure_luts"});
    t.push_back({"fpga.infrastructure_ramb36",
                 ParamKind::count,
                 "6",
                 0,
                 100000,
                 {},
                 "Block RAMs of the rest of the system (the MPMC's port FIFOs)",
                 "[A] as fpga.infrastructure_luts"});
    // The power estimate's prices (platform/cost/power.cpp, docs/power.md). None enters the
    // simulation.
    t.push_back({"power.budget_w",
                 ParamKind::real,
                 "10",
                 0,
                 1e6,
                 {},
                 "Power the system must stay within (W)",
                 "[S] paper §I, §V: less than 10 W"});
    t.push_back({"power.static_w",
                 ParamKind::real,
                 "1.2",
                 0,
                 1e3,
                 {},
                 "FPGA static power at a typical junction temperature (W)",
                 "[A] an FX70T-sized Virtex-5 at 50-85 C (XPower estimates of the time, not retrieved)"});
    t.push_back({"power.ddr_background_w",
                 ParamKind::real,
                 "0.5",
                 0,
                 1e3,
                 {},
                 "DDR2 background power of the 256 MB memory, idle or refreshing (W)",
                 "[A] four x16 DDR2 chips at 100-150 mW each (datasheets of the time, recalled)"});
    t.push_back({"power.infrastructure_w",
                 ParamKind::real,
                 "0.6",
                 0,
                 1e3,
                 {},
                 "MPMC, PLBs, INTC, clock managers and I/O of the rest of the system (W)",
                 "[A] not retrieved"});
    t.push_back({"power.ppc440_mw_per_mhz",
                 ParamKind::real,
                 "0.5",
                 0,
                 100,
                 {},
                 "PPC440 core while it computes (mW per MHz)",
                 "[A] Xilinx quoted about 0.35-0.9 mW/MHz for the Virtex-5 FXT's PowerPC 440 (recalled)"});
    t.push_back(
        {"power.logic_pj_per_cell_cycle",
         ParamKind::real,
         "0.05",
         0,
         100,
         {},
         "Energy of one LUT or flip-flop per clock cycle while its block computes, at a typical toggle rate (pJ)",
         "[A] order of magnitude of Virtex-5 logic at 12.5 % toggle (XPower, recalled)"});
    t.push_back({"power.bram_pj_per_access",
                 ParamKind::real,
                 "20",
                 0,
                 1e4,
                 {},
                 "Energy of one RAMB36 port access (pJ)",
                 "[A] order of magnitude (XPower, recalled)"});
    t.push_back({"power.dsp_pj_per_product",
                 ParamKind::real,
                 "10",
                 0,
                 1e4,
                 {},
                 "Energy of one DSP48E product (pJ)",
                 "[A] order of magnitude (XPower, recalled)"});
    t.push_back({"power.bus_pj_per_bit",
                 ParamKind::real,
                 "2",
                 0,
                 1e4,
                 {},
                 "Energy of one bit moved on a PLB (pJ)",
                 "[A] on-chip wiring of a 128-bit bus (order of magnitude)"});
    t.push_back({"power.bus_pj_per_burst",
                 ParamKind::real,
                 "50",
                 0,
                 1e6,
                 {},
                 "Energy of arbitrating and addressing one PLB burst (pJ)",
                 "[A] order of magnitude"});
    t.push_back({"power.ddr_pj_per_bit",
                 ParamKind::real,
                 "60",
                 0,
                 1e5,
                 {},
                 "DDR2 energy per bit read or written, I/O included (pJ)",
                 "[A] DDR2 of the time: 40-100 pJ/bit (recalled)"});
    t.push_back({"eval.homography",
                 ParamKind::text,
                 "",
                 0,
                 0,
                 {},
                 "Homography from frame 0 to frame 1 (Oxford or OpenCV file): report repeatability and precision",
                 "[-] evaluation"});
    t.push_back({"eval.poses",
                 ParamKind::text,
                 "",
                 0,
                 0,
                 {},
                 "Folder of Camera_NNN.txt poses (ViSP castle): report distinguishability with the true F too",
                 "[-] evaluation"});
    t.push_back({"eval.gap",
                 ParamKind::count,
                 "2",
                 1,
                 1000,
                 {},
                 "Pairs (i, i + gap) evaluated besides consecutive frames (camera poses, surfvp table2)",
                 "[-] evaluation"});
}

// The assumption band: for each assumed value the plausible low and high and why (the verdict
// re-simulates with each, one at a time). A low or high equal to the default means no
// plausible value on that side.
struct BandEntry {
    const char* key;
    const char* low;
    const char* high;
    const char* why;
    ParamRole role = ParamRole::unknown;
};
constexpr BandEntry kBands[] = {
    {"cpu.memory_path", "plb1", "mci", "if the DDR were on PLB1 rather than the PPC440's MCI"},
    {"cpu.dcache_replacement", "round_robin", "lru", "the PPC440 itself is round robin per set"},
    {"surf.target_keypoints", "80", "140", "~100 descriptors per image (TePRA 2009), ~140 (MVA 2014)",
     ParamRole::workload},
    {"surf.threshold", "400", "600", "used only when surf.target_keypoints is 0", ParamRole::workload},
    {"surf.haar", "exact", "rounded", "exact sub-pixel wavelets like the float reference", ParamRole::design},
    {"surf.fifo_irq_level", "64", "512", "the driver drains the maxima FIFO earlier or later", ParamRole::design},
    {"fpga.ramb36", "148", "148", "the FX70T's count, recalled, not retrieved"},
    {"fpga.dsp48e", "128", "128", "the FX70T's count, recalled, not retrieved"},
    {"fpga.slices", "11200", "11200", "the FX70T's count, recalled, not retrieved"},
    {"fpga.bram_fmax", "450 MHz", "550 MHz", "the slowest to the fastest speed grade (DS202, recalled)"},
    {"fpu.precision", "single", "double", "the other FPU DS693 offers: its latencies, size and DSP48E",
     ParamRole::design},
    {"fpga.ip_interface_luts", "400", "1200", "lighter or heavier IPIF options"},
    {"fpga.ip_interface_ffs", "500", "1500", "lighter or heavier IPIF options"},
    {"fpga.infrastructure_luts", "4000", "9000", "MPMC ports and options"},
    {"fpga.infrastructure_ffs", "5000", "10000", "MPMC ports and options"},
    {"fpga.infrastructure_ramb36", "4", "12", "MPMC port FIFO depths"},
    {"power.static_w", "0.8", "2", "junction temperature and process corner"},
    {"power.ddr_background_w", "0.3", "0.8", "chip count and power-down use"},
    {"power.infrastructure_w", "0.3", "1.2", "MPMC ports, clocking and I/O standards"},
    {"power.ppc440_mw_per_mhz", "0.35", "0.9", "the range Xilinx quoted"},
    {"power.logic_pj_per_cell_cycle", "0.02", "0.2", "toggle rate and routing"},
    {"power.bram_pj_per_access", "10", "40", "width and enable pattern"},
    {"power.dsp_pj_per_product", "5", "20", "pipelining and widths"},
    {"power.bus_pj_per_bit", "1", "5", "bus length and toggle rate"},
    {"power.bus_pj_per_burst", "20", "200", "arbiter and address decode"},
    {"power.ddr_pj_per_bit", "40", "100", "DDR2 of the time"},
};

void append(std::vector<ParamSpec>& t, const std::vector<ParamSpec>& block) {
    t.insert(t.end(), block.begin(), block.end());
}

std::vector<ParamSpec> make_table() {
    std::vector<ParamSpec> t;
    t.push_back({"run.workload",
                 ParamKind::choice,
                 "smoke",
                 0,
                 0,
                 {"smoke", "surf"},
                 "What the CPU runs: the bus smoke test, or libSSA2 and SURF on frames",
                 "[-] scenario choice"});
    t.push_back({"run.max_time",
                 ParamKind::duration,
                 "600 s",
                 1,
                 36000 * s,
                 {},
                 "Simulated time after which a run that has not finished is stopped as stalled",
                 "[-] tool setting: a guard against a livelocked run, far above any shipped scenario (castle, exact "
                 "Haar: 11 s)"});

    t.push_back(
        {"run.series_bin",
         ParamKind::duration,
         "1 ms",
         1 * us,
         1 * s,
         {},
         fmt::format("Width of the time bins of report.html's charts (bus utilisation and FIFO levels over time); a "
                     "run longer than {} bins merges them by twos, so a series never holds more",
                     TimeSeries::kMaxBins),
         "[-] report setting: a 118 ms frame in about a hundred bins"});
    t.push_back({"run.parallel",
                 ParamKind::choice,
                 "on",
                 0,
                 0,
                 {"on", "off"},
                 "Compute each FHG block row's determinants and maxima on a second thread while the kernel simulates "
                 "the row's cycles; off: in the simulation's own thread. The results are the same either way",
                 "[-] simulation setting (no figure depends on it)"});
    t.push_back({"run.dma_granularity",
                 ParamKind::choice,
                 "line",
                 0,
                 0,
                 {"line", "burst"},
                 "IP blocks' DMA: one TLM transaction per line or per burst; the bus arbitrates every burst either "
                 "way, so the figures are the same",
                 "[-] simulation setting (no figure depends on it)"});
    append(t, Ppc440::parameter_table().specs());
    t.push_back({"cpu.memory_path",
                 ParamKind::choice,
                 "mci",
                 0,
                 0,
                 {"mci", "plb1"},
                 "How the CPU's line fills, write-backs and copies reach DDR: its crossbar and memory controller "
                 "interface (the MPMC's PPC440MC port), or PLB1",
                 "[A] the PPC440 block has a PPC440MC interface (docs/sources.md#mci); EDK designs for the ML507 wire "
                 "the MPMC to it (recalled, not retrieved)"});
    append(t, MciLink::parameter_table().specs());
    add_cpu_cost(t);
    for (const PlbDeclaration& bus : plb_declarations()) append(t, bus.table.specs());
    append(t, DdrMemory::parameter_table().specs());
    append(t, Intc::parameter_table().specs());
    append(t, Dma::parameter_table().specs());
    append(t, Iig::parameter_table().specs());
    append(t, Fhg::parameter_table().specs());

    t.push_back({"soc.accelerators",
                 ParamKind::count,
                 "1",
                 1,
                 4,
                 {},
                 "SSA IIG + SSA FHG pairs on the chip",
                 "[S] paper §III-D: one pair; the library supports more"});
    add_surf(t);

    t.push_back({"smoke.buffer",
                 ParamKind::bytes,
                 "64 KiB",
                 1,
                 16 * MiB,
                 {},
                 "Bytes the test DMA copies per copy",
                 "[-] test size: many bursts, well inside the L1-sized buffers of the chip's drivers"});
    t.push_back({"smoke.copies",
                 ParamKind::count,
                 "4",
                 1,
                 1000000,
                 {},
                 "Copies the smoke software runs one after another",
                 "[-] test size"});
    t.push_back({"smoke.polls",
                 ParamKind::count,
                 "3",
                 0,
                 1000000,
                 {},
                 "Status polls over PLB1 per copy before the CPU sleeps on the interrupt",
                 "[-] test size"});
    t.push_back({"smoke.poll_interval",
                 ParamKind::cycles,
                 "200 cycles",
                 0,
                 1e9,
                 {},
                 "CPU cycles between status polls",
                 "[-] test setting: a short delay loop"});
    t.push_back({"smoke.src",
                 ParamKind::address,
                 "0x0010_0000",
                 0,
                 0xFFFFFFFF,
                 {},
                 "Source buffer address in DDR",
                 "[-] placement"});
    t.push_back({"smoke.dst",
                 ParamKind::address,
                 "0x0020_0000",
                 0,
                 0xFFFFFFFF,
                 {},
                 "Destination buffer address in DDR",
                 "[-] placement"});
    for (const BandEntry& b : kBands) {
        auto it = std::find_if(t.begin(), t.end(), [&](const ParamSpec& p) { return p.key == b.key; });
        if (it == t.end()) throw std::logic_error(std::string("parameter band for an unknown parameter: ") + b.key);
        it->band = {b.low, b.high, b.why};
        it->role = b.role;
    }
    return t;
}

}  // namespace

const std::vector<PlbDeclaration>& plb_declarations() {
    static const std::vector<PlbDeclaration> buses{
        {"plb1", PlbBus::parameter_table("plb1", "128 bit", "[S] ML507 DTS: mplb-dwidth = 0x80",
                                         "PLB1 (CPU and register slaves)")},
        {"plb2", PlbBus::parameter_table(
                     "plb2", "128 bit",
                     "[A] the paper: PLB2 \"has accordingly increased capacity\" (Fig. 3 lost); 64 bit would do",
                     "PLB2 (IP DMA traffic)")}};
    return buses;
}

namespace {

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

// Both return infinity for a number too large for any type, so that the range check calls it
// out of range (never wrapped, never "not a number").
double parse_address(const std::string& text) {
    std::string digits;
    for (char c : text)
        if (c != '_') digits += c;
    size_t used = 0;
    unsigned long long value = 0;
    try {
        value = std::stoull(digits, &used, 0);
    } catch (const std::out_of_range&) {
        return kInf;
    } catch (const std::exception&) {
        used = 0;
    }
    if (digits.empty() || used != digits.size() || digits[0] == '-')
        throw UnitError(fmt::format("'{}' is not an address: expected a number such as 0x0010_0000", text));
    return double(value);
}

double parse_plain(const std::string& text, bool integer) {
    const char* begin = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(begin, &end);
    const bool too_large = errno == ERANGE && std::isinf(value);  // "1e400": a number, beyond any double
    if (end == begin || size_t(end - begin) != text.size() || std::isspace(static_cast<unsigned char>(text[0])) ||
        (!std::isfinite(value) && !too_large))
        throw UnitError(fmt::format("'{}' is not a {}", text, integer ? "whole number" : "finite number"));
    if (integer && !too_large && value != std::floor(value))
        throw UnitError(fmt::format("'{}' is not a whole number", text));
    return value;
}

}  // namespace

std::string format_value(const ParamSpec& spec, double value) {
    switch (spec.kind) {
        case ParamKind::frequency:
            return format_frequency(Frequency{value});
        case ParamKind::duration:
            return format_duration(Duration{uint64_t(value)});
        case ParamKind::bits:
            return fmt::format("{} bit", uint64_t(value));
        case ParamKind::bytes:
            return format_bytes(Bytes{uint64_t(value)});
        case ParamKind::cycles:
            return fmt::format("{} cycles", uint64_t(value));
        case ParamKind::beats:
            return fmt::format("{} beats", uint64_t(value));
        case ParamKind::address:
            return fmt::format("{:#x}", uint64_t(value));
        case ParamKind::count:
            return fmt::format("{}", uint64_t(value));
        default:
            return fmt::format("{}", value);
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
        case ParamKind::frequency:
            value = parse_frequency(text).hz;
            break;
        case ParamKind::duration:
            value = double(parse_duration(text).ps);
            break;
        case ParamKind::bits:
            value = parse_bits(text);
            break;
        case ParamKind::bytes:
            value = double(parse_bytes(text).n);
            break;
        case ParamKind::cycles:
            value = double(parse_cycles(text));
            break;
        case ParamKind::beats:
            value = parse_beats(text);
            break;
        case ParamKind::count:
            value = parse_plain(text, true);
            break;
        case ParamKind::real:
            value = parse_plain(text, false);
            break;
        case ParamKind::address:
            value = parse_address(text);
            break;
        case ParamKind::text:
            return 0;
        case ParamKind::choice:
            if (std::find(spec.choices.begin(), spec.choices.end(), text) == spec.choices.end())
                throw UnitError(fmt::format("'{}' is not one of: {}", text, fmt::join(spec.choices, ", ")));
            return 0;
    }
    if (!(value >= spec.min && value <= spec.max))  // NaN is out of every range
        throw UnitError(fmt::format("'{}' is out of range: {} must be between {} and {}", text, spec.key,
                                    format_value(spec, spec.min), format_value(spec, spec.max)));
    return value;
}

std::string describe_kind(const ParamSpec& spec) {
    switch (spec.kind) {
        case ParamKind::frequency:
            return "frequency (Hz, kHz, MHz, GHz)";
        case ParamKind::duration:
            return "duration (ps, ns, us, ms, s)";
        case ParamKind::bits:
            return "width (bit)";
        case ParamKind::bytes:
            return "size (B, KiB, MiB, GiB)";
        case ParamKind::cycles:
            return "clock cycles (cycles)";
        case ParamKind::beats:
            return "bus beats (beats)";
        case ParamKind::count:
            return "whole number";
        case ParamKind::real:
            return "number";
        case ParamKind::address:
            return "address";
        case ParamKind::choice:
            return fmt::format("one of {}", fmt::join(spec.choices, ", "));
        case ParamKind::text:
            return "text";
    }
    return "";
}

std::string parameters_markdown() {
    std::string out =
        "# surfvp parameters\n\n"
        "Every parameter a scenario can set, with its default and where the default comes from:\n"
        "**[S]** sourced, **[D]** derived, **[A]** assumed (the reason follows), **[-]** a choice, not a\n"
        "fact. Generated by `surfvp params`; a test keeps this file equal to its output. A block's parameters are\n"
        "declared beside its Params (`models/<block>/*_params.cpp`), the platform's own in\n"
        "`platform/scenario/parameters.cpp`.\n\n"
        "| key | default | range | kind | what it is | source |\n|---|---|---|---|---|---|\n";
    for (const ParamSpec& p : parameter_table()) {
        std::string range = p.kind == ParamKind::choice || p.kind == ParamKind::text
                                ? ""
                                : fmt::format("{} .. {}", format_value(p, p.min), format_value(p, p.max));
        out += fmt::format("| `{}` | `{}` | {} | {} | {} | {} |\n", p.key, p.default_value, range, describe_kind(p),
                           p.description, p.source);
    }
    out +=
        "\n## Assumption band\n\n"
        "Every assumed value, and a few uncertain others, with a plausible low and high, and its role: an\n"
        "**unknown** about the published chip (the verdict samples the unknowns jointly over their bands,\n"
        "and re-simulates each at its low and its high for the tornado), a **design** choice an RTL or\n"
        "software change sets, or the **workload**; the verdict shows design and workload apart, as what a\n"
        "review can change (`verdict.band`).\n\n"
        "| key | role | default | low | high | why |\n|---|---|---|---|---|---|\n";
    for (const ParamSpec* p : band_parameters())
        out += fmt::format("| `{}` | {} | `{}` | `{}` | `{}` | {} |\n", p->key, role_name(p->role), p->default_value,
                           p->band.low, p->band.high, p->band.why);
    return out;
}

}  // namespace surfvp
