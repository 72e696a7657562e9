#include "platform/scenario/consistency.h"

#include <fmt/format.h>

#include "platform/address_map.h"
#include "platform/scenario/block_params.h"
#ifdef SURFVP_WITH_RTL
#include "models/fhg/rtl/rtl_datapath.h"
#endif

namespace surfvp {
namespace {

// config.yaml gives every parameter: one at its default changes nothing, wherever it is.
bool at_default(const Config::Entry& e) {
    if (e.spec->kind == ParamKind::text || e.spec->kind == ParamKind::choice) return e.value == e.spec->default_value;
    return parse_value(*e.spec, e.value) == parse_value(*e.spec, e.spec->default_value);
}

bool in_section(const std::string& key, const char* section) { return key.rfind(std::string(section) + ".", 0) == 0; }

// fhg.model=rtl runs the datapath the build verilated, as the model's rules time it: only the
// build's configuration, with the sequence's interval as the block's time.
void check_rtl_model(const Config& c) {
#ifdef SURFVP_WITH_RTL
    const Fhg::Params p = fhg_params(c);
    std::string difference;
    try {
        difference = fhg::rtl_build_difference(p.precision, p.sequence, p.max_width);
    } catch (const std::invalid_argument& e) {  // a machine the RTL does not build at all (fhg.x3_cycles)
        throw ConfigError(fmt::format("{}: rtl cannot run this configuration: {}", c.where("fhg.model"), e.what()));
    }
    if (!difference.empty())
        throw ConfigError(
            fmt::format("{}: rtl runs the FHG datapath verilated for the defaults, but {}: set the "
                        "fhg parameters back to their defaults (docs/rtl.md)",
                        c.where("fhg.model"), difference));
    for (const auto& [key, rtl] :
         {std::pair{"fhg.cycles_per_block", 0}, std::pair{"fhg.hessian_cycles_per_triple_mac", 1}})
        if (c.cycles(key) != uint64_t(rtl))
            throw ConfigError(
                fmt::format("{}: rtl times a block by its sequence and reads one TripleMAC a cycle, but "
                            "{} is {} (from {}); the RTL's is {}",
                            c.where("fhg.model"), key, c.value(key), c.source_of(key), rtl));
#else
    throw ConfigError(
        fmt::format("{}: rtl needs the verilated FHG datapath, and this surfvp was built without "
                    "Verilator: install it (scripts/packages.sh test) and build again",
                    c.where("fhg.model")));
#endif
}

}  // namespace

void check_consistency(const Config& c) {
    for (const char* bus : {"plb1", "plb2"}) {
        const std::string key = std::string(bus) + ".width";
        const unsigned width = c.bits(key);
        if (width != 32 && width != 64 && width != 128)
            throw ConfigError(fmt::format("{}: {} bit: a PLB is 32, 64 or 128 bit wide", c.where(key), width));
    }
    const uint64_t pairs = c.count("soc.accelerators");
    const uint64_t needed = map::irq::fhg(unsigned(pairs) - 1) + 1;
    if (c.count("intc.inputs") < needed)
        throw ConfigError(
            fmt::format("{}: {} inputs are too few for {} accelerator pairs (soc.accelerators): they need {}",
                        c.where("intc.inputs"), c.count("intc.inputs"), pairs, needed));
    if (c.choice("fhg.model") == "rtl") check_rtl_model(c);
    if (c.choice("run.workload") != "surf") return;

    // surf.width and surf.height resize together: one alone would be ignored.
    if ((c.count("surf.width") == 0) != (c.count("surf.height") == 0)) {
        const std::string zero = c.count("surf.width") == 0 ? "surf.width" : "surf.height";
        const std::string other = zero == "surf.width" ? "surf.height" : "surf.width";
        throw ConfigError(
            fmt::format("{}: {} with {} = 0 (from {}): frames are resized only when both are set; set both, "
                        "or both to 0 to keep the frames as they are",
                        c.where(other), c.count(other), zero, c.source_of(zero)));
    }
    if (c.choice("surf.threshold_control") == "track" && c.count("surf.target_keypoints") == 0)
        throw ConfigError(
            fmt::format("{}: track holds the keypoints per frame near surf.target_keypoints, which is 0 (from "
                        "{}): set a target, or surf.threshold_control = hold",
                        c.where("surf.threshold_control"), c.source_of("surf.target_keypoints")));
    const uint64_t frames = c.count("surf.frames");
    for (const char* key : {"eval.homography", "eval.poses"})
        if (!c.text(key).empty() && frames < 2)
            throw ConfigError(
                fmt::format("{}: the evaluation compares frames, and surf.frames is {} (from {}): it needs at "
                            "least 2",
                            c.where(key), frames, c.source_of("surf.frames")));
    // A frame rate needs one whole round of the pairs after the first frame.
    if (c.real("budget.fps") > 0 && frames <= pairs)
        throw ConfigError(
            fmt::format("{}: {} frames cannot give a frame rate with {} accelerator pair(s): the steady-state "
                        "rate needs {}; set more frames or budget.fps = 0 (from {})",
                        c.where("surf.frames"), frames, pairs, pairs + 1, c.source_of("budget.fps")));
}

std::vector<Ineffective> ineffective_parameters(const Config& c) {
    std::vector<Ineffective> out;
    const std::string workload = c.choice("run.workload");
    const bool verdict =
        workload == "surf" && (c.choice("verdict.band") == "on" || c.choice("verdict.break_even") == "on" ||
                               c.choice("verdict.software") == "on");
    for (const Config::Entry& e : c.entries()) {
        const std::string& key = e.spec->key;
        if (e.origin == "default" || at_default(e)) continue;
        std::string reason;
        if ((workload != "surf" && (in_section(key, "surf") || in_section(key, "budget") || in_section(key, "eval") ||
                                    in_section(key, "verdict") || in_section(key, "fault"))) ||
            (workload != "smoke" && in_section(key, "smoke")))
            reason = fmt::format("run.workload is {}", workload);
        else if (key == "surf.threshold" && c.count("surf.target_keypoints") > 0)
            reason = fmt::format("surf.target_keypoints is {}, so the threshold is calibrated on frame 0",
                                 c.count("surf.target_keypoints"));
        else if ((key == "verdict.frames" || key == "verdict.jobs") && !verdict)
            reason = "verdict.band, verdict.break_even and verdict.software are all off";
        else if (key == "verdict.samples" && c.choice("verdict.band") != "on")
            reason = "verdict.band is off: the joint sample is part of the band";
        else if (key == "verdict.break_even" && e.value == "on" && c.real("budget.fps") <= 0)
            reason = "budget.fps is 0: there is no budget to break even with";
        else if (key == "verdict.frames" && c.count("verdict.frames") > c.count("surf.frames"))
            reason = fmt::format("the re-simulations run at most surf.frames = {} frames", c.count("surf.frames"));
        else if (in_section(key, "mci") && c.choice("cpu.memory_path") == "plb1" &&
                 !(verdict && c.choice("verdict.band") == "on"))  // the band tries the MCI too
            reason = "cpu.memory_path is plb1: the CPU reaches DDR over PLB1, not the MCI";
        if (!reason.empty()) out.push_back({key, reason});
    }
    return out;
}

}  // namespace surfvp
