#include "platform/cost/power.h"

#include <fmt/format.h>

#include "models/fhg/fhg.h"
#include "models/fhg/sequence_cache.h"
#include "platform/scenario/parameters.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/run_settings.h"
#include "platform/workload/describer.h"

namespace surfvp {
namespace {

using Json = nlohmann::ordered_json;

// A block's figure as its first (or only) instance reports it: every pair runs at one clock.
double first(const Json& r, const char* block, const char* figure) {
    if (!r.contains(block)) return 0;
    const Json& b = r[block];
    return (b.is_array() ? (b.empty() ? Json() : b[0]) : b).value(figure, 0.0);
}

// A block's figure summed over its accelerator pairs (an array when there are several).
double summed(const Json& r, const char* block, const char* figure) {
    if (!r.contains(block)) return 0;
    const Json& b = r[block];
    if (!b.is_array()) return b.value(figure, 0.0);
    double sum = 0;
    for (const Json& one : b) sum += one.value(figure, 0.0);
    return sum;
}

double cells(const FpgaResources& res, const std::string& block) {
    for (const BlockResources& b : res.blocks)
        if (b.block.rfind(block, 0) == 0) return b.luts + b.ffs;
    return 0;
}

}  // namespace

Json power_estimate(const Config& c, const Json& r, const FpgaResources& res) {
    const double seconds = r.value("sim_time_s", 0.0);
    const double frames = r.value("frames_done", 0.0);
    const double pj = 1e-12;
    const PowerPrices price = power_prices(c);
    const double cell = price.logic_pj_per_cell_cycle * pj;
    Json blocks = Json::object();
    double total_j = 0;
    auto add = [&](const std::string& name, double joules, const std::string& basis) {
        blocks[name] = {{"watts", seconds > 0 ? joules / seconds : 0.0}, {"joules", joules}, {"basis", basis}};
        total_j += joules;
    };
    // Always on.
    const double static_w = price.static_w, ddr_w = price.ddr_background_w, infra_w = price.infrastructure_w;
    add("fpga static", static_w * seconds, "power.static_w");
    add("ddr background", ddr_w * seconds, "power.ddr_background_w");
    add("infrastructure", infra_w * seconds, "power.infrastructure_w: MPMC, PLBs, INTC, clocks");
    // The CPU and its FPU while they compute (the PPC440 waits for interrupts clock-gated).
    // The clocks as the run's statistics report them (cpu.clock_hz, fhg.clock_hz, iig.clock_hz).
    const double cpu_hz = first(r, "cpu", "clock_hz");
    const double cpu_s = cpu_hz > 0 ? first(r, "cpu", "cycles_consumed") / cpu_hz : 0.0;
    add("ppc440", price.ppc440_mw_per_mhz * 1e-3 * cpu_hz * 1e-6 * cpu_s,
        fmt::format("{:.3f} s computing at {:g} MHz x power.ppc440_mw_per_mhz", cpu_s, cpu_hz * 1e-6));
    const double fpu_hz = cpu_hz / pipeline_params(c).fpu_ratio;
    add("apu fpu", cells(res, "apu fpu") * cell * fpu_hz * cpu_s,
        "its LUT-FF pairs x power.logic_pj_per_cell_cycle, while the CPU computes");
    // The accelerators while they compute: their logic cells each cycle, the FHG's line-FIFO
    // reads (a quad word reads two lines, other words one) and writes, its three products per
    // determinant.
    const Fhg::Params fhg = fhg_params(c);
    const double fhg_hz = first(r, "fhg", "clock_hz"), iig_hz = first(r, "iig", "clock_hz");
    const double fhg_s = summed(r, "fhg", "computing_s"), iig_s = summed(r, "iig", "computing_s");
    const double pairs = run_settings(c).accelerators;
    const double fhg_cycles = fhg_s * fhg_hz;
    const double determinants = fhg_cycles / Fhg::block_cycles(fhg::cached_sequence(fhg.sequence), fhg) * 18;
    const double lines_per_word = fhg.sequence.bus_word == fhg::BusWord::quad ? 2 : 1;
    const double bram_accesses =
        fhg_cycles * fhg.sequence.read_buses * lines_per_word + iig_s * iig_hz;  // reads + line writes
    add("fhg",
        cells(res, "fhg") / pairs * cell * fhg_cycles + bram_accesses * price.bram_pj_per_access * pj +
            determinants * 3 * price.dsp_pj_per_product * pj,
        fmt::format("{:.3g} cycles computing, {:.3g} block-RAM accesses, {:.3g} determinants x 3 products", fhg_cycles,
                    bram_accesses, determinants));
    add("iig", cells(res, "iig") / pairs * cell * iig_s * iig_hz,
        fmt::format("{:.3g} cycles computing", iig_s * iig_hz));
    // Buses: every bit moved and every burst arbitrated; DDR2: every bit read or written.
    double bus_bits = 0, bursts = 0;
    if (r.contains("buses"))
        for (const auto& [name, bus] : r["buses"].items())
            for (const char* dir : {"read", "write"}) {
                bus_bits += 8.0 * bus[dir].value("bytes", 0.0);
                bursts += bus[dir].value("bursts", 0.0);
            }
    add("buses", bus_bits * price.bus_pj_per_bit * pj + bursts * price.bus_pj_per_burst * pj,
        fmt::format("{:.3g} bits in {:.3g} bursts on the PLBs", bus_bits, bursts));
    const double ddr_bits = r.contains("memory")
                                ? 8.0 * (r["memory"].value("bytes_read", 0.0) + r["memory"].value("bytes_written", 0.0))
                                : 0;
    add("ddr traffic", ddr_bits * price.ddr_pj_per_bit * pj, fmt::format("{:.3g} bits read and written", ddr_bits));
    const double watts = seconds > 0 ? total_j / seconds : 0.0;
    const double budget = price.budget_w;
    return {{"watts", watts},
            {"joules_per_frame", frames > 0 ? total_j / frames : 0.0},
            {"budget_w", budget},
            {"within_budget", watts <= budget},
            {"blocks", blocks}};
}

Json cost_band(const Config& config, const Json& report) {
    const FpgaResources base = fpga_resources(config);
    double low_w = power_estimate(config, report, base)["watts"].get<double>(), high_w = low_w;
    Json parameters = Json::array();
    for (const ParamSpec* p : band_parameters()) {
        if (p->key.rfind("fpga.", 0) != 0 && p->key.rfind("power.", 0) != 0) continue;
        Json entry = {{"parameter", p->key}, {"value", config.value(p->key)}};
        for (const auto& [side, value] : {std::pair{"low", p->band.low}, std::pair{"high", p->band.high}}) {
            Config c = config;
            c.set(p->key, value, "band");
            const FpgaResources res = fpga_resources(c);
            const double watts = power_estimate(c, report, res)["watts"].get<double>();
            low_w = std::min(low_w, watts);
            high_w = std::max(high_w, watts);
            entry[side] = {{"value", value},
                           {"watts", watts},
                           {"ramb36", res.total.ramb36},
                           {"luts", res.total.luts},
                           {"fits", res.fits()}};
        }
        parameters.push_back(entry);
    }
    return {{"watts_range", {low_w, high_w}}, {"parameters", parameters}};
}

}  // namespace surfvp
