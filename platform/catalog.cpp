#include "platform/catalog.h"

#include <algorithm>
#include <stdexcept>
#include <string_view>

#include "models/dma/dma.h"
#include "models/fhg/fhg.h"
#include "models/iig/iig.h"
#include "models/intc/intc.h"
#include "models/mci/mci_link.h"
#include "models/memory/ddr_memory.h"
#include "models/plb/plb_bus.h"
#include "models/ppc440/ppc440.h"
#include "platform/cost/power.h"
#include "platform/scenario/parameters.h"
#include "platform/scenario/run_settings.h"
#include "platform/workload/cpu_cost_params.h"
#include "platform/workload/smoke_params.h"
#include "platform/workload/surf_settings.h"

namespace surfvp {

const ParamTable<VerdictSettings>& VerdictSettings::parameter_table() {
    using P = VerdictSettings;
    static const ParamTable<P> table(
        {field<P>({"verdict.break_even",
                   ParamKind::choice,
                   "off",
                   0,
                   0,
                   {"on", "off"},
                   "Find the limiting block's clock (and the FHG's cycles per block) that just meets budget.fps, by "
                   "re-simulation, and check it with one more run of the whole scenario",
                   "[-] analysis (docs/architecture.md#principles, 7)"},
                  &P::break_even),
         field<P>(
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
              "[-] analysis (docs/architecture.md#principles, 7)"},
             &P::band),
         field<P>({"verdict.software",
                   ParamKind::choice,
                   "off",
                   0,
                   0,
                   {"on", "off"},
                   "Re-simulate with the software settings that move the CPU's time (surf.haar, surf.upright, "
                   "surf.descriptor, surf.target_keypoints): the frames/s and CPU time under each",
                   "[-] analysis: what the verdict rests on"},
                  &P::software),
         field<P>(
             {"verdict.frames",
              ParamKind::count,
              "2",
              2,
              1000,
              {},
              "Frames each of the verdict's re-simulations runs (at least soc.accelerators + 1, at most surf.frames)",
              "[-] the pipeline is in steady state once each pair has done its first frame (every frame alike in the "
              "budget scenario: the 2-frame rate equals the 20-frame rate to 0.01 %)"},
             &P::frames),
         field<P>({"verdict.samples",
                   ParamKind::count,
                   "200",
                   0,
                   100000,
                   {},
                   "Points of the joint sample of the unknowns (verdict.band; 0: none, the one-at-a-time band only)",
                   "[-] analysis: 200 points give the 5th and 95th percentiles to about +-2 points of rank"},
                  &P::samples),
         field<P>({"verdict.jobs",
                   ParamKind::count,
                   "0",
                   0,
                   256,
                   {},
                   "Re-simulations run at once (0: one per core); no figure depends on it",
                   "[-] simulation setting"},
                  &P::jobs)});
    return table;
}

VerdictSettings verdict_settings(const ParamValues& values) { return VerdictSettings::parameter_table().make(values); }

unsigned resimulation_frames(const ParamValues& values) {
    const uint64_t pairs = run_settings(values).accelerators;
    return unsigned(std::min(std::max(verdict_settings(values).frames, pairs + 1), surf_settings(values).frames));
}

namespace {

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

void append(std::vector<ParamSpec>& t, const std::vector<ParamSpec>& group) {
    t.insert(t.end(), group.begin(), group.end());
}

// The declarations of `group` whose key begins with `prefix`: the run's settings are listed
// where each belongs (the run's own first, the CPU's memory path beside the CPU, the pairs
// before the software), as the joint band's draws follow this order.
std::vector<ParamSpec> pick(const std::vector<ParamSpec>& group, std::string_view prefix) {
    std::vector<ParamSpec> out;
    for (const ParamSpec& p : group)
        if (p.key.rfind(prefix, 0) == 0) out.push_back(p);
    return out;
}

std::vector<ParamSpec> make_table() {
    std::vector<ParamSpec> t;
    const std::vector<ParamSpec> run = RunSettings::parameter_table().specs();
    append(t, pick(run, "run."));
    append(t, Ppc440::parameter_table().specs());
    append(t, pick(run, "cpu.memory_path"));
    append(t, MciLink::parameter_table().specs());
    append(t, cache_parameter_table().specs());
    append(t, pipeline_parameters());
    for (const PlbDeclaration& bus : plb_declarations()) append(t, bus.table.specs());
    append(t, DdrMemory::parameter_table().specs());
    append(t, Intc::parameter_table().specs());
    append(t, Dma::parameter_table().specs());
    append(t, Iig::parameter_table().specs());
    append(t, Fhg::parameter_table().specs());
    append(t, pick(run, "soc."));
    append(t, SurfWorkloadSettings::parameter_table().specs());
    append(t, VerdictSettings::parameter_table().specs());
    append(t, FpgaDevice::parameter_table().specs());
    append(t, PowerPrices::parameter_table().specs());
    append(t, EvalSettings::parameter_table().specs());
    append(t, smoke_parameter_table().specs());
    for (const BandEntry& b : kBands) {
        auto it = std::find_if(t.begin(), t.end(), [&](const ParamSpec& p) { return p.key == b.key; });
        if (it == t.end()) throw std::logic_error(std::string("parameter band for an unknown parameter: ") + b.key);
        it->band = {b.low, b.high, b.why};
        it->role = b.role;
    }
    return t;
}

}  // namespace

const std::vector<ParamSpec>& parameter_table() {
    static const std::vector<ParamSpec> table = make_table();
    return table;
}

}  // namespace surfvp
