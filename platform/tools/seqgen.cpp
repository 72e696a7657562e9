#include "platform/tools/seqgen.h"

#include <cstdio>

#include "platform/scenario/config.h"
#include "platform/scenario/scenario.h"
#include "platform/report/schedule_figures.h"
#include "platform/scenario/block_params.h"

namespace surfvp {

int seqgen_command(const SeqgenOptions& options) {
    const Config config = scenario_or_defaults(options.scenario, options.sets);
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
    out["frame"] = {
        {"width", options.width},
        {"height", options.height},
        {"blocks", uint64_t(blocks)},
        {"fhg_clock_hz", p.clock.hz},
        {"fhg_compute_s", frame_s},
        {"frames_per_second", 1.0 / frame_s},
        {"note", "FHG compute only: blocks x cycles_per_block / clock; a run adds pipeline fill and the software"}};
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
}

}  // namespace surfvp
