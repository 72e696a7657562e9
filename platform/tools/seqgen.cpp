#include "platform/tools/seqgen.h"

#include <cstdio>

#include "platform/scenario/config.h"
#include "models/fhg/sequence_cache.h"
#include "platform/scenario/scenario.h"
#include "platform/soc.h"

namespace surfvp {

namespace {

// A schedule's cycles and both its overheads: over the paper's optimal state (its note 4: the
// buses never idle, carrying the words this schedule carries) and over the structural bound.
nlohmann::ordered_json schedule_json(const fhg::Sequence& s) {
    nlohmann::ordered_json j = {{"cycles_per_block", s.interval},
                                {"words", s.words_delivered},
                                {"busy_bus_cycles", s.busy_bus_cycles},
                                {"idle_bus_overhead", s.idle_bus_overhead()},
                                {"overhead", s.overhead()}};
    if (s.spread[1] > 0) j["passes_spread"] = {s.spread[0], s.spread[1]};
    return j;
}

}  // namespace

nlohmann::ordered_json schedule_figures(const Fhg::Params& p) {
    fhg::SequenceParams machine = p.sequence;
    machine.scheduler = fhg::Scheduler::basic;
    const fhg::Sequence& basic = fhg::cached_sequence(machine);
    machine.scheduler = fhg::Scheduler::improved;
    const fhg::Sequence& improved = fhg::cached_sequence(machine);
    const fhg::Sequence& used = p.sequence.scheduler == fhg::Scheduler::basic ? basic : improved;
    const auto& s = p.sequence;
    return {{"machine", {{"read_buses", s.read_buses}, {"bus_word", fhg::bus_word_name(s.bus_word)},
                         {"bus_word_bits", 32 * fhg::word_shape(s.bus_word).size()}, {"reuse", s.reuse},
                         {"line_fifo", fhg::line_fifo_name(s.line_fifo)}, {"triple_macs", s.triple_macs},
                         {"x3_cycles", s.x3_cycles}}},
            {"reads_per_block", basic.reads_per_block},
            {"distinct_reads_per_block", basic.distinct_reads_per_block},
            {"basic", schedule_json(basic)},
            {"improved", schedule_json(improved)},
            {"optimal", {{"cycles_per_block", basic.optimal_cycles}, {"limit", basic.optimal_limit}}},
            {"scheduler", fhg::scheduler_name(s.scheduler)},
            {"sequence_cycles_per_block", used.interval},
            {"hessian_cycles_per_block", Fhg::hessian_cycles(p)},
            {"cycles_per_block", Fhg::block_cycles(used, p)},
            {"block_limit", Fhg::block_limit(used, p)}};
}

int seqgen_command(const SeqgenOptions& options) {
    Config config;
    if (!options.scenario.empty()) {
        config = load_scenario(resolve_scenario(options.scenario), options.sets);
    } else {
        apply_overrides(config, options.sets);
    }
    if (options.width == 0 || options.height == 0) throw ConfigError("--width and --height must be above zero");
    const Fhg::Params p = fhg_params(config);
    nlohmann::ordered_json out;
    try {
        out = schedule_figures(p);
    } catch (const std::invalid_argument& e) {
        throw ConfigError(e.what());
    }
    const double blocks = double((options.width + 1) / 2) * ((options.height + 1) / 2);
    const double frame_s = blocks * out["cycles_per_block"].get<int>() / p.clock.hz;
    out["frame"] = {{"width", options.width}, {"height", options.height}, {"blocks", uint64_t(blocks)},
                    {"fhg_clock_hz", p.clock.hz}, {"fhg_compute_s", frame_s}, {"frames_per_second", 1.0 / frame_s},
                    {"note", "FHG compute only: blocks x cycles_per_block / clock; a run adds pipeline fill and the software"}};
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
}

}  // namespace surfvp
