#include "seqgen.h"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "config.h"
#include "models/fhg/sequence_generator.h"
#include "scenario.h"
#include "soc.h"

namespace surfvp {

int seqgen_command(const SeqgenOptions& options) {
    Config config;
    if (!options.scenario.empty()) {
        config = load_scenario(resolve_scenario(options.scenario), options.sets);
    } else {
        apply_overrides(config, options.sets);
    }
    if (options.width == 0 || options.height == 0) throw ConfigError("--width and --height must be above zero");
    const Fhg::Params p = fhg_params(config);
    fhg::Sequence s;
    try {
        s = fhg::generate_sequence(p.sequence);
    } catch (const std::invalid_argument& e) {
        throw ConfigError(e.what());
    }
    const int block = Fhg::block_cycles(s, p);
    const double blocks = double((options.width + 1) / 2) * ((options.height + 1) / 2);
    const double frame_s = blocks * block / p.clock.hz;
    nlohmann::ordered_json out = {
        {"bus_word", config.choice("fhg.bus_word")},
        {"reuse", p.sequence.reuse},
        {"read_buses", p.sequence.read_buses},
        {"triple_macs", p.sequence.triple_macs},
        {"x3_cycles", p.sequence.x3_cycles},
        {"reads_per_block", s.reads_per_block},
        {"distinct_reads_per_block", s.distinct_reads_per_block},
        {"words_per_block", s.words_delivered},
        {"sequence_cycles_per_block", s.cycles},
        {"hessian_cycles_per_block", Fhg::hessian_cycles(p)},
        {"cycles_per_block", block},
        {"block_limit", Fhg::block_limit(s, p)},
        {"optimal_cycles_per_block", s.optimal_cycles},
        {"overhead", s.overhead()},
        {"bus_utilisation", double(s.words_delivered) / (double(s.cycles) * p.sequence.read_buses)},
        {"frame", {{"width", options.width}, {"height", options.height}, {"blocks", uint64_t(blocks)},
                   {"fhg_clock_hz", p.clock.hz}, {"fhg_compute_s", frame_s},
                   {"frames_per_second", 1.0 / frame_s},
                   {"note", "FHG compute only: blocks x cycles_per_block / clock; a run adds pipeline fill and the software"}}}};
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
}

}  // namespace surfvp
