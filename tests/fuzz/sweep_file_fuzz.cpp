// Fuzz target: the sweep file loader (platform/sweep/sweep_plan.h) and the comparison of two
// sweeps' records (sweep_changes).
//
// Input: a sweep file as text, written to a file in a scratch folder of its own and loaded
// with load_sweep, as `surfvp sweep FILE` does (its scenario: may name a shipped scenario).
// The same text is also given to sweep_changes as the record a database holds, on either
// side, against a loaded sweep's: a database's record may be anything.
//
// Expected answer to bad input: ConfigError (the CLI's exit code 2). Any other exception, a
// crash, a sanitizer report or a hang is a bug. For a sweep that loads, what the loader
// promises is checked too, each broken promise being a bug:
//   - at most kMaxSweepPoints points, numbered 0, 1, ... in order, each with one value per
//     axis (every point of a zip has the values of one row) and point_id of them as its id;
//   - the name is one folder's name, and the name, values and ids are text results.json can
//     hold (nlohmann's dump does not throw);
//   - the fingerprint is the identity's text, and sweep_changes finds no change between it
//     and itself.
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "platform/scenario/scenario.h"
#include "platform/sweep/sweep_plan.h"

namespace {
using namespace surfvp;

// A sweep's record as this surfvp writes it: the other side of sweep_changes.
const std::string kRecord = R"({"surfvp":"0.1.0","scenario":"name: x\n","set":{"surf.frames":"3"},)"
                            R"("axes":[{"key":"fhg.clock","values":["25 MHz","50 MHz"]}],"combine":"cartesian"})";

void check_loaded(const SweepPlan& plan) {
    if (plan.points.size() > kMaxSweepPoints)
        fuzz::bug("more points than the limit: " + std::to_string(plan.points.size()));
    for (size_t i = 0; i < plan.points.size(); ++i) {
        const SweepPoint& p = plan.points[i];
        if (p.index != i) fuzz::bug("point " + std::to_string(i) + " has index " + std::to_string(p.index));
        if (p.values.size() != plan.axes.size()) fuzz::bug("point " + p.id + " has not one value per axis");
        for (size_t a = 0; a < p.values.size(); ++a)
            if (p.values[a].first != plan.axes[a].key) fuzz::bug("point " + p.id + ": values out of the axes' order");
        if (p.id != point_id(p.values)) fuzz::bug("point " + p.id + " is not named by its values");
    }
    try {
        check_folder_name("name", plan.name);
    } catch (const ConfigError& e) {
        fuzz::bug(std::string("a name that cannot name a folder was accepted: ") + e.what());
    }
    nlohmann::ordered_json points = nlohmann::ordered_json::array();
    for (const SweepPoint& p : plan.points) points.push_back({p.id, p.values});
    try {
        (void)nlohmann::ordered_json({plan.name, plan.description, points}).dump();
    } catch (const nlohmann::json::exception& e) {
        fuzz::bug(std::string("results.json could not hold the sweep: ") + e.what());
    }
    if (plan.fingerprint != plan.identity.dump()) fuzz::bug("the fingerprint is not the identity's text");
    if (!sweep_changes(plan.fingerprint, plan.fingerprint).empty()) fuzz::bug("a sweep differs from itself");
    if (sweep_changes(kRecord, plan.fingerprint).empty()) fuzz::bug("no change found between two sweeps");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        // A database's record of any content: described, never thrown at.
        sweep_changes(text, kRecord);
        sweep_changes(kRecord, text);
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    const std::string path = fuzz::write_scratch("sweep.yaml", text);
    try {
        check_loaded(load_sweep(path));
    } catch (const ConfigError&) {
        // the loader's answer to a bad sweep file
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
