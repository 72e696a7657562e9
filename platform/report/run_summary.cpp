#include "platform/report/run_summary.h"

#include "platform/report/json_input.h"

namespace surfvp {
using Json = nlohmann::ordered_json;

namespace {

// Where each extra figure is in report.json.
const std::pair<const char*, const char*> kExtras[] = {
    {"bram36", "/fpga_resources/total/ramb36"},
    {"dsp48e", "/fpga_resources/total/dsp48e"},
    {"luts", "/fpga_resources/total/luts"},
    {"fits", "/fpga_resources/fits"},
    {"closes", "/clock_closure/closes"},
    {"watts", "/power/watts"},
    {"joules_per_frame", "/power/joules_per_frame"},
    {"within_power_budget", "/power/within_budget"},
    // Feature quality, when the scenario's eval.* asks for it (a homography or camera poses).
    {"repeatability", "/workload/evaluation/homography/repeatability"},
    {"precision", "/workload/evaluation/homography/precision"},
    {"distinguishability", "/workload/evaluation/distinguishability_gap1/ransac"},
};

}  // namespace

RunSummary RunSummary::of(const Json& r) {
    RunSummary s;
    s.passed = flag_at(r, "/passed");
    s.broken = flag_at(r, "/broken");
    s.failure = text_at(r, "/failure");
    s.fps = number_at(r, "/throughput_fps");
    s.budget_fps = number_at(r, "/budget/fps");
    if (value_at(r, "/budget/met").is_boolean()) s.budget_met = value_at(r, "/budget/met").get<bool>();
    s.latency_ms = number_at(r, "/latency_ms");
    s.limit = text_at(r, "/limit/resource");
    s.limit_cause = text_at(r, "/limit/cause");
    s.keypoints_per_frame = number_at(r, "/keypoints_per_frame");
    s.sim_time_s = number_at(r, "/sim_time_s");
    s.wall_time_s = number_at(r, "/wall_time_s");
    if (value_at(r, "/time_per_frame").is_object())
        for (const auto& [name, row] : r["time_per_frame"].items()) {
            Resource resource{name, number_at(row, "/busy_share"), {}};
            if (value_at(row, "/alone_fps").is_number()) resource.alone_fps = number_at(row, "/alone_fps");
            s.resources.push_back(resource);
        }
    if (value_at(r, "/time_per_frame/cpu").is_object()) {
        const double frames = number_at(r, "/frames_done");
        s.cpu = Cpu{number_at(r, "/time_per_frame/cpu/busy_ms"), number_at(r, "/time_per_frame/cpu/alone_fps"),
                    frames > 0 ? number_at(r, "/cpu/memory/fill_stall_s") / frames * 1e3 : 0};
    }
    for (const auto& [name, pointer] : kExtras)
        if (!value_at(r, pointer).is_null()) s.extras.emplace_back(name, value_at(r, pointer));
    return s;
}

Json RunSummary::point() const {
    auto or_null = [](const std::string& text) { return text.empty() ? Json() : Json(text); };
    Json p = {{"fps", fps},
              {"passed", passed},
              {"limit", or_null(limit)},
              {"limit_cause", or_null(limit_cause)},
              {"keypoints_per_frame", keypoints_per_frame}};
    if (cpu) {
        p["cpu_ms_per_frame"] = cpu->ms_per_frame;
        p["cpu_alone_fps"] = cpu->alone_fps;
        p["cpu_fill_stall_ms"] = cpu->fill_stall_ms;
    }
    if (!resources.empty()) {
        Json alone = Json::object();
        for (const Resource& r : resources)
            if (r.alone_fps) alone[r.name] = *r.alone_fps;
        p["alone_fps"] = alone;
    }
    if (!failure.empty()) p["failure"] = failure;
    return p;
}

std::string RunSummary::unit_of(const std::string& figure) {
    static const std::map<std::string, std::string> units = {
        {"fps", "frames/s"},  {"budget_fps", "frames/s"},
        {"latency_ms", "ms"}, {"bram36", "RAMB36"},
        {"dsp48e", "DSP48E"}, {"luts", "LUTs"},
        {"watts", "W"},       {"joules_per_frame", "J"},
        {"sim_time_s", "s"},  {"keypoints_per_frame", "keypoints"}};
    if (figure.rfind("busy.", 0) == 0) return "share";
    const auto it = units.find(figure);
    return it == units.end() ? "" : it->second;
}

Json RunSummary::figures() const {
    Json f;
    f["fps"] = fps;
    f["budget_fps"] = budget_fps;
    f["budget_met"] = budget_met ? Json(*budget_met) : Json();
    f["latency_ms"] = latency_ms;
    f["bottleneck"] = limit;
    f["bottleneck_cause"] = limit_cause;
    for (const Resource& r : resources) f["busy." + r.name] = r.busy_share;
    for (const auto& [name, value] : extras) f[name] = value;
    f["keypoints_per_frame"] = keypoints_per_frame;
    f["sim_time_s"] = sim_time_s;
    f["passed"] = passed;
    return f;
}

}  // namespace surfvp
