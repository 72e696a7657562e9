#include "platform/run/resimulation.h"

#include "platform/report/run_summary.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <opencv2/core/utility.hpp>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "models/host/atomic_file.h"
#include "models/common/zeroed_memory.h"
#include "platform/run/run.h"
#include "platform/scenario/block_params.h"
#include "platform/report/schedule_figures.h"
#include "platform/workload/workload.h"

namespace surfvp {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

Resimulation::Resimulation(unsigned jobs, fs::path scratch)
    : jobs_(jobs ? jobs : std::max(1u, std::thread::hardware_concurrency())), scratch_(std::move(scratch)) {
    fs::create_directories(scratch_);
}

Resimulation::~Resimulation() {
    for (const auto& [pid, job] : running_) {  // an exception left children behind: stop them
        kill(pid, SIGKILL);
        waitpid(pid, nullptr, 0);
    }
    std::error_code ignored;
    fs::remove_all(scratch_, ignored);
}

void Resimulation::prepare(const Config& config) {
    cv::setNumThreads(0);
    make_workload(config);
    schedule_figures(fhg_params(config));
}

Json Resimulation::point_summary(const Json& r) { return RunSummary::of(r).point(); }

void Resimulation::submit(Config config, Done done, Summarise summarise, std::string out, std::string trace,
                          bool urgent) {
    ++submitted_;
    Job job{std::move(config), std::move(done), std::move(summarise), std::move(out), std::move(trace), {}};
    if (urgent)
        queue_.push_front(std::move(job));
    else
        queue_.push_back(std::move(job));
}

void Resimulation::submit_work(Config config, Done done, Work work) {
    ++submitted_;
    queue_.push_back(Job{std::move(config), std::move(done), {}, "", "none", std::move(work)});
}

// The child simulates, writes its result as JSON and leaves at once (no destructors of the
// parent's state run twice).
void Resimulation::start(Job job) {
    const fs::path result = scratch_ / fmt::format("{}.json", started_++);
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error(std::string("cannot fork a re-simulation: ") + std::strerror(errno));
    if (pid == 0) {
        use_huge_pages();  // the children before this one freed the same blocks (zeroed_memory.h)
        int code = 3;
        Json out;
        try {
            out = job.work ? job.work(job.config)
                           : job.summarise(simulate_scenario(job.config, job.out, job.trace, true));
            code = 0;
        } catch (const ConfigError& e) {
            out = {{"error", e.what()}, {"exit", 2}};
            code = 2;
        } catch (const EnvironmentError& e) {  // a write the machine refused (a trace on a full disk)
            out = {{"error", std::string("cannot write: ") + e.what()}, {"exit", 4}};
            code = 4;
        } catch (const OutOfMemory& e) {
            out = {{"error", std::string("out of memory: ") + e.what()}, {"exit", 5}};
            code = 5;
        } catch (const std::bad_alloc&) {
            out = {{"error", "out of memory"}, {"exit", 5}};
            code = 5;
        } catch (const std::exception& e) {
            out = {{"error", e.what()}, {"exit", 3}};
        }
        {
            std::ofstream file(result);
            file << out.dump();
        }
        std::_Exit(code);
    }
    running_.emplace(pid, std::make_pair(std::move(job), result));
}

void Resimulation::start_queued() {
    while (running_.size() < jobs_ && !queue_.empty()) {
        Job job = std::move(queue_.front());
        queue_.pop_front();
        start(std::move(job));
    }
}

void Resimulation::run(const std::function<void(size_t, size_t)>& progress) {
    while (!queue_.empty() || !running_.empty()) {
        start_queued();
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0 && errno == EINTR) continue;
        if (pid < 0) throw std::runtime_error(std::string("waiting for a re-simulation: ") + std::strerror(errno));
        auto it = running_.find(pid);
        if (it == running_.end()) continue;
        auto [job, path] = std::move(it->second);
        running_.erase(it);
        std::ifstream file(path);
        std::stringstream text;
        text << file.rdbuf();
        Json result = Json::parse(text.str(), nullptr, false);
        if (result.is_discarded() || !result.is_object()) {
            // A child that exited with its code but could not write its result (a full disk: it
            // exits 0 after the failed write) keeps the code; one killed by a signal is a bug's.
            const int code = WIFEXITED(status) ? (WEXITSTATUS(status) ? WEXITSTATUS(status) : 4) : 3;
            result = {{"error", fmt::format("the re-simulation ended without a result ({})",
                                            WIFSIGNALED(status) ? fmt::format("signal {}", WTERMSIG(status))
                                                                : fmt::format("exit {}", WEXITSTATUS(status)))},
                      {"exit", code}};
        }
        std::error_code ignored;
        fs::remove(path, ignored);
        ++finished_;
        start_queued();  // the freed slot works while the callback does (it may prepare the next job)
        job.done(result);
        if (progress) progress(finished_, submitted_);
    }
}

}  // namespace surfvp
