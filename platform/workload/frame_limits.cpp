#include "platform/workload/frame_limits.h"

#include <algorithm>
#include <fmt/format.h>
#include <string>
#include <utility>
#include <vector>

#include "platform/scenario/block_params.h"
#include "platform/workload/surf_settings.h"

namespace surfvp {
namespace {
using Json = nlohmann::ordered_json;

// A resource's time per frame, over the whole run: its totals divided by the frames it took,
// so busy + waits + idle is its mean period (the simulated time per frame, which includes
// filling and draining the pipeline). Its load is the same busy time against the steady-state
// period (1 / frames per second), what it must keep up with once the pipeline is full.
struct Account {
    std::string name;
    double period = 0;                                  // s: the run's time per frame as this resource sees it
    double steady = 0;                                  // s: the steady-state period as this resource sees it
    double busy = 0;                                    // s per frame
    std::vector<std::pair<std::string, double>> waits;  // s per frame, by cause
    double wait(const std::string& cause) const {
        for (const auto& [c, s] : waits)
            if (c == cause) return s;
        return 0;
    }
    double waited() const {
        double sum = 0;
        for (const auto& w : waits) sum += w.second;
        return sum;
    }
    double share(double seconds) const { return steady > 0 ? seconds / steady : 0; }  // load
};

// One block or an array of them (one per accelerator pair): the busiest by `key`.
const Json& busiest(const Json& blocks, const char* key) {
    if (!blocks.is_array()) return blocks;
    const Json* most = &blocks[0];
    for (const Json& b : blocks)
        if (b[key].get<double>() > (*most)[key].get<double>()) most = &b;
    return *most;
}

std::vector<Account> accounts(const Json& r) {
    const double steady = 1.0 / r["throughput_fps"].get<double>();
    const double frames = double(r["frames_done"].get<size_t>());
    const double period = r["sim_time_s"].get<double>() / frames;
    const double pairs = r["iig"].is_array() ? double(r["iig"].size()) : 1.0;
    const double per_pair = pairs / frames;  // per frame that one pair took
    const Json& iig = busiest(r["iig"], "computing_s");
    const Json& fhg = busiest(r["fhg"], "computing_s");
    std::vector<Account> a;
    a.push_back({"iig",
                 period * pairs,
                 steady * pairs,
                 iig["computing_s"].get<double>() * per_pair,
                 {{"image DMA read", iig["waiting_for_image_s"].get<double>() * per_pair},
                  {"integral DMA write", iig["blocked_by_write_s"].get<double>() * per_pair},
                  {"PixelBus back-pressure", iig["blocked_by_pixelbus_s"].get<double>() * per_pair}}});
    a.push_back({"fhg",
                 period * pairs,
                 steady * pairs,
                 fhg["computing_s"].get<double>() * per_pair,
                 {{"line FIFO empty", fhg["waiting_for_lines_s"].get<double>() * per_pair},
                  {"determinant DMA write", fhg["waiting_for_writer_s"].get<double>() * per_pair}}});
    if (!r["accelerator_pairs"].empty()) {
        const Json& pair = busiest(r["accelerator_pairs"], "working_s");
        a.push_back({"accelerator pair",
                     period * pairs,
                     steady * pairs,
                     pair["working_s"].get<double>() * per_pair,
                     {{"free task slot", pair["waiting_for_buffers_s"].get<double>() * per_pair}}});
    }
    const Json& cpu = r["cpu"];
    const double irq = cpu["irq_wait_s"].get<double>();
    a.push_back({"cpu", period, steady, (r["sim_time_s"].get<double>() - irq) / frames, {{"interrupt", irq / frames}}});
    const Json& plb2 = r["buses"]["plb2"];
    a.push_back({"plb2 write", period, steady, plb2["write"]["busy_s"].get<double>() / frames, {}});
    a.push_back({"plb2 read", period, steady, plb2["read"]["busy_s"].get<double>() / frames, {}});
    const Json& plb1 = r["buses"]["plb1"];
    a.push_back({"plb1",
                 period,
                 steady,
                 std::max(plb1["read"]["busy_s"].get<double>(), plb1["write"]["busy_s"].get<double>()) / frames,
                 {}});
    if (r.contains("mci"))
        a.push_back({"mci", period, steady, r["mci"]["busy_s"].get<double>() / frames, {}});  // absent on plb1
    a.push_back({"ddr", period, steady, r["memory"]["busy_s"].get<double>() / frames, {}});
    return a;
}

double ms(double s) { return s * 1e3; }

// Why the busiest resource is busy, in its own statistics (its clock among them).
std::string busy_reason(const Account& a, const Json& r) {
    const int width = r["image"]["width"], height = r["image"]["height"];
    if (a.name == "fhg") {
        const Json& fhg = r["fhg"].is_array() ? r["fhg"][0] : r["fhg"];
        return fmt::format(
            "the FHG computes {:.2f} ms a frame ({:.1f} % of the steady-state period): {} blocks x {} cycles "
            "per block ({}) at {:g} MHz (fhg.clock)",
            ms(a.busy), 100 * a.share(a.busy), ((width + 1) / 2) * ((height + 1) / 2),
            fhg["cycles_per_block"].get<int>(), fhg["block_limit"].get<std::string>(),
            fhg["clock_hz"].get<double>() / 1e6);
    }
    if (a.name == "iig") {
        const Json& iig = r["iig"].is_array() ? r["iig"][0] : r["iig"];
        return fmt::format(
            "the IIG adds {} pixels at {} a cycle at {:g} MHz (iig.clock): {:.2f} ms a frame ({:.1f} % of the "
            "steady-state period)",
            width * height, iig["pixels_per_clock"].get<double>(), iig["clock_hz"].get<double>() / 1e6, ms(a.busy),
            100 * a.share(a.busy));
    }
    if (a.name == "cpu") {
        const double stall = r["cpu"]["memory"]["fill_stall_s"].get<double>() / double(r["frames_done"].get<size_t>());
        return fmt::format(
            "the CPU is busy {:.2f} ms a frame ({:.1f} % of the steady-state period; {:.2f} ms of it stalled "
            "on line fills): {:.1f} keypoints at {:.0f} cycles each at {:g} MHz (cpu.clock)",
            ms(a.busy), 100 * a.share(a.busy), ms(stall), r["keypoints_per_frame"].get<double>(),
            r["software_cycles_per_keypoint"].get<double>(), r["cpu"]["clock_hz"].get<double>() / 1e6);
    }
    return fmt::format("{} is busy {:.2f} ms a frame ({:.1f} % of the steady-state period)", a.name, ms(a.busy),
                       100 * a.share(a.busy));
}

Json limit(const std::vector<Account>& accounts, const Json& r, const Config& c) {
    auto find = [&](const char* name) -> const Account* {
        for (const Account& a : accounts)
            if (a.name == name) return &a;
        return nullptr;
    };
    // 1. A resource busy with its own work all the time (a pair's "busy" is holding a task:
    //    what its blocks do is theirs).
    const Account* busiest = &accounts[0];
    for (const Account& a : accounts)
        if (a.name != "accelerator pair" && a.share(a.busy) > busiest->share(busiest->busy)) busiest = &a;
    if (busiest->share(busiest->busy) >= kBusyLimit)
        return {{"resource", busiest->name}, {"cause", "busy"}, {"reason", busy_reason(*busiest, r)}};
    // 2. A buffer between two blocks, both occupied.
    const Account* fhg = find("fhg");
    const Account* iig = find("iig");
    const Account* pair = find("accelerator pair");
    const double starved = fhg->wait("line FIFO empty"), held = iig->wait("PixelBus back-pressure");
    const double slot = pair ? pair->wait("free task slot") : 0;
    const bool fifo = fhg->share(fhg->busy + starved) >= kBusyLimit && iig->share(held) >= 0.5 && starved > 0;
    const bool tasks = pair && pair->share(pair->busy + slot) >= kBusyLimit && slot > 0;
    if (fifo && (!tasks || fhg->share(starved) >= pair->share(slot)))
        return {{"resource", "line fifo"},
                {"cause", "line FIFO empty"},
                {"reason",
                 fmt::format("line-FIFO starvation: the FHG waits {:.2f} ms per frame for lines while the IIG is held "
                             "{:.2f} ms by PixelBus back-pressure; {} lines (fhg.fifo_lines) cannot take the next "
                             "block row's lines while one computes",
                             ms(starved), ms(held), fhg_params(c).sequence.fifo_lines)}};
    if (tasks)
        return {
            {"resource", "task slots"},
            {"cause", "free task slot"},
            {"reason",
             fmt::format("the task limit: an accelerator pair waits {:.2f} ms a frame for a free buffer set ({:.1f} "
                         "% of its steady-state period); all {} tasks in flight (surf.tasks_in_flight) are held by "
                         "the hardware or by the CPU's descriptors",
                         ms(slot), 100 * pair->share(slot), surf_settings(c).tasks_in_flight)}};
    // 3. The largest wait.
    const Account* waiting = nullptr;
    std::string cause;
    double most = -1;
    for (const Account& a : accounts)
        for (const auto& [why, s] : a.waits)
            if (a.name != "cpu" && a.share(s) > most) most = a.share(s), waiting = &a, cause = why;
    if (!waiting || most <= 0)
        return {{"resource", busiest->name}, {"cause", "busy"}, {"reason", busy_reason(*busiest, r)}};
    return {
        {"resource", waiting->name},
        {"cause", cause},
        {"reason", fmt::format("{} waits {:.2f} ms a frame on {} ({:.1f} % of the steady-state period)", waiting->name,
                               ms(waiting->wait(cause)), cause, 100 * waiting->share(waiting->wait(cause)))}};
}

}  // namespace

void add_limits(Json& r, const Config& config) {
    if (r["throughput_fps"].get<double>() <= 0) return;  // fewer than two frames: no period
    const std::vector<Account> all = accounts(r);
    const double fps = r["throughput_fps"].get<double>();
    const double budget = r["budget"].is_null() ? 0 : r["budget"]["fps"].get<double>();
    Json table = Json::object();
    for (const Account& a : all) {
        Json waits = Json::object();
        for (const auto& [cause, s] : a.waits) waits[cause] = ms(s);
        // The idle time is what the period leaves; busy + waits exceed it only by rounding of
        // the models' totals, which no row may show as negative idle.
        const double idle = std::max(0.0, a.period - a.busy - a.waited());
        const double load = a.share(a.busy);
        Json row = {{"period_ms", ms(a.period)},
                    {"busy_ms", ms(a.busy)},
                    {"waits_ms", waits},
                    {"idle_ms", ms(idle)},
                    // a share: the busy total may pass the steady period by the models' rounding
                    {"busy_share", a.period > 0 ? std::min(1.0, a.busy / a.period) : 0.0},
                    {"load", load},
                    {"alone_fps", load > 0 ? Json(fps / load) : Json()}};
        if (budget > 0 && load > 0) row["slack"] = fps / load / budget - 1;
        table[a.name] = row;
    }
    r["time_per_frame_period_ms"] = {{"run", ms(r["sim_time_s"].get<double>() / r["frames_done"].get<double>())},
                                     {"steady", ms(1 / fps)}};
    r["time_per_frame"] = table;
    r["limit"] = limit(all, r, config);
    r["bottleneck"] = r["limit"]["resource"];
}

}  // namespace surfvp
