#pragma once
// Re-simulations of a scenario at other parameter values, each in a child process forked from
// this one: SystemC elaborates once per process, and a child inherits what this process has
// prepared (frames, the threshold calibration, FHG sequences), so it only elaborates and
// simulates. The caller must not have elaborated SystemC itself. At most `jobs` children run
// at once; a finished child's result is handed to its callback in this process, which may
// submit more. POSIX fork/waitpid.
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/types.h>
#include <vector>

#include "platform/scenario/config.h"

namespace surfvp {

// The sets that make a run only the run: none of the verdict's analyses, which re-simulate the
// scenario many times. For studies that need a timed run's own figures (frames/s, CPU time).
inline const std::vector<std::string> kWithoutVerdictAnalyses{"verdict.band=off", "verdict.break_even=off",
                                                              "verdict.software=off"};

class Resimulation {
public:
    // `result` is what the child's summarise made of its report, or {"error": ..., "exit":
    // code} when it failed.
    using Done = std::function<void(const nlohmann::ordered_json& result)>;
    // Run in the child on its report: the less it hands back, the less there is to write and
    // read (point_summary: fps, passed, limit, keypoints per frame; whole: the report).
    using Summarise = std::function<nlohmann::ordered_json(const nlohmann::ordered_json& report)>;

    Resimulation(unsigned jobs, std::filesystem::path scratch);
    ~Resimulation();
    Resimulation(const Resimulation&) = delete;
    Resimulation& operator=(const Resimulation&) = delete;

    // One re-simulation of `config`; `out`/`trace` as simulate_scenario's (empty/none for a
    // point that writes nothing). An urgent one starts before those already waiting (a
    // search whose next step waits for it).
    void submit(Config config, Done done, Summarise summarise = point_summary, std::string out = "",
                std::string trace = "none", bool urgent = false);
    // Other work on `config` in a child instead of a simulation (a study that runs the chip
    // in direct mode and measures its keypoints); `work`'s result goes to `done`.
    using Work = std::function<nlohmann::ordered_json(const Config& config)>;
    void submit_work(Config config, Done done, Work work);
    // Runs until every submitted re-simulation, and every one their callbacks submit, is done;
    // `progress(done, submitted)` after each.
    void run(const std::function<void(size_t, size_t)>& progress);
    size_t submitted() const { return submitted_; }

    // Prepares in this process what a child of `config` would otherwise compute itself: its
    // frames and threshold calibration, and every FHG sequence its report names (the one it
    // runs and the other schedule). Also stops OpenCV's worker threads, which a forked child
    // would inherit half-alive.
    static void prepare(const Config& config);

    static nlohmann::ordered_json point_summary(const nlohmann::ordered_json& report);
    static nlohmann::ordered_json whole(const nlohmann::ordered_json& report) { return report; }

    unsigned jobs() const { return jobs_; }

private:
    struct Job {
        Config config;
        Done done;
        Summarise summarise;
        std::string out, trace;
        Work work;  // set: run instead of the simulation
    };
    void start(Job job);
    void start_queued();

    unsigned jobs_;
    std::filesystem::path scratch_;
    std::deque<Job> queue_;
    std::map<pid_t, std::pair<Job, std::filesystem::path>> running_;
    size_t submitted_ = 0, finished_ = 0, started_ = 0;
};

}  // namespace surfvp
