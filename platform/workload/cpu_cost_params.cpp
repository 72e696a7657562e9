#include "platform/workload/cpu_cost_params.h"

#include <fmt/format.h>
#include <string>

#include "sw/cpu_cost/ppc440_pipeline.h"

namespace surfvp {

// The software stage's cost model (sw/cpu_cost/README.md has the reasoning of each): the L1
// data cache, and the PPC440 pipeline the calibration priced the stage's instruction stream
// with (sw/cpu_cost/ppc440_pipeline.h), its probes the band where it has one.
const ParamTable<sw::CacheParams>& cache_parameter_table() {
    using P = sw::CacheParams;
    static const ParamTable<P> table(
        {field<P>({"cpu.dcache_size",
                   ParamKind::bytes,
                   "32 KiB",
                   1024,
                   1 << 20,
                   {},
                   "L1 data cache",
                   "[S] ML507 DTS; PPC440 32 KB D-cache"},
                  &P::size_bytes),
         field<P>({"cpu.dcache_ways",
                   ParamKind::count,
                   "64",
                   1,
                   1024,
                   {},
                   "L1 data cache associativity",
                   "[S] PPC440x5 manual Table 4-2: 32 KB, 64 ways"},
                  &P::ways),
         choice<P, sw::Replacement>({"cpu.dcache_replacement",
                                     ParamKind::choice,
                                     "lru",
                                     0,
                                     0,
                                     {},
                                     "L1 data cache replacement",
                                     "[A] LRU; the PPC440's round robin differs by 0.25 % in cycles"},
                                    &P::replacement,
                                    {{"lru", sw::Replacement::lru}, {"round_robin", sw::Replacement::round_robin}})});
    return table;
}

std::vector<ParamSpec> pipeline_parameters() {
    std::vector<ParamSpec> t;
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
    return t;
}

}  // namespace surfvp
