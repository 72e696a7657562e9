#include "platform/report/schedule_figures.h"

#include "models/fhg/sequence_cache.h"

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
    return {{"machine",
             {{"read_buses", s.read_buses},
              {"bus_word", fhg::bus_word_name(s.bus_word)},
              {"bus_word_bits", 32 * fhg::word_shape(s.bus_word).size()},
              {"reuse", s.reuse},
              {"line_fifo", fhg::line_fifo_name(s.line_fifo)},
              {"triple_macs", s.triple_macs},
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

}  // namespace surfvp
