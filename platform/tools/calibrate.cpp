#include "platform/tools/calibrate.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ext/stdio_filebuf.h>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <functional>
#include <istream>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>
#include <unistd.h>

#include "platform/workload/describer.h"
#include "models/host/atomic_file.h"
#include "models/host/shell.h"
#include "platform/run/progress_line.h"
#include "platform/run/resimulation.h"
#include "platform/run/run.h"
#include "platform/scenario/scenario.h"
#include "sw/cpu_cost/calibration.h"
#include "sw/cpu_cost/calibration_dump.h"
#include "sw/stage/software_stage.h"

namespace surfvp {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

constexpr const char* kQemu = "qemu-ppc";
constexpr const char* kQemuCpu = "440-xilinx-w-dfpu";  // QEMU's Virtex-5 PPC440 with the APU FPU
// Float tolerance of the firmware's keypoints against the VP's: both are IEEE single precision
// without contraction; only libm (atan2f, sinf, cosf) may differ in the last place.
constexpr double kKeypointTolerance = 1e-4;

struct Frame {
    sw::calibration_dump::FrameHeader header;
    std::vector<uint8_t> integral, determinants;
    std::vector<uint32_t> words;
};

std::vector<Frame> read_inputs(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<Frame> frames;
    sw::calibration_dump::FrameHeader h;
    while (in.read(reinterpret_cast<char*>(&h), sizeof h)) {
        sw::calibration_dump::swap_words_to_big_endian(h);
        Frame f{h, std::vector<uint8_t>(h.integral_bytes), std::vector<uint8_t>(h.determinant_bytes),
                std::vector<uint32_t>(h.words)};
        in.read(reinterpret_cast<char*>(f.integral.data()), std::streamsize(f.integral.size()));
        in.read(reinterpret_cast<char*>(f.determinants.data()), std::streamsize(f.determinants.size()));
        in.read(reinterpret_cast<char*>(f.words.data()), std::streamsize(4 * f.words.size()));
        for (uint32_t& w : f.words) w = load_be32(reinterpret_cast<const uint8_t*>(&w));
        frames.push_back(std::move(f));
    }
    if (frames.empty()) throw std::runtime_error("calibrate: the VP run recorded no candidates in " + path.string());
    return frames;
}

std::vector<sw::calibration_dump::Result> read_results(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<sw::calibration_dump::Result> out;
    sw::calibration_dump::Result r;
    while (in.read(reinterpret_cast<char*>(&r), sizeof r)) {
        sw::calibration_dump::swap_words_to_big_endian(r);
        out.push_back(r);
    }
    return out;
}

// The units the native stage counts for each candidate, on the recorded input.
std::vector<std::array<uint64_t, sw::kUnits>> native_units(const std::vector<Frame>& frames) {
    std::vector<std::array<uint64_t, sw::kUnits>> units;
    for (const Frame& f : frames) {
        sw::SoftwareStage stage(sw::calibration_dump::stage_params(f.header), sw::CostCounter(sw::CostParams{}));
        const sw::FrameBuffers b =
            sw::calibration_dump::frame_buffers(f.header, f.integral.data(), f.determinants.data());
        for (uint32_t w : f.words) {
            std::array<uint64_t, sw::kUnits> before{};
            for (size_t u = 0; u < sw::kUnits; ++u) before[u] = stage.cost().counted(sw::Unit(u));
            stage.process(w, b);
            for (size_t u = 0; u < sw::kUnits; ++u) before[u] = stage.cost().counted(sw::Unit(u)) - before[u];
            units.push_back(before);
        }
    }
    return units;
}

// The firmware's results against the VP's: the same words became keypoints, with the same
// values within kKeypointTolerance.
Json compare_results(const std::vector<sw::calibration_dump::Result>& vp,
                     const std::vector<sw::calibration_dump::Result>& iss) {
    if (vp.size() != iss.size())
        throw std::runtime_error(fmt::format("calibrate: the firmware answered {} words of {}", iss.size(), vp.size()));
    size_t keypoints = 0, exact = 0, mismatched = 0;
    double worst = 0;
    for (size_t i = 0; i < vp.size(); ++i) {
        if (vp[i].keypoint != iss[i].keypoint || vp[i].laplacian != iss[i].laplacian) {
            ++mismatched;
            continue;
        }
        if (!vp[i].keypoint) continue;
        ++keypoints;
        const float* a = &vp[i].x;
        const float* b = &iss[i].x;
        double diff = 0;
        for (int k = 0; k < 5; ++k) diff = std::max(diff, double(std::fabs(a[k] - b[k])));
        for (int k = 0; k < 64; ++k)
            diff = std::max(diff, double(std::fabs(vp[i].descriptor[k] - iss[i].descriptor[k])));
        if (diff == 0) ++exact;
        if (diff > kKeypointTolerance) ++mismatched;
        worst = std::max(worst, diff);
    }
    return {{"words", vp.size()},      {"keypoints", keypoints},          {"bit_exact", exact},
            {"max_difference", worst}, {"tolerance", kKeypointTolerance}, {"mismatched", mismatched},
            {"agree", mismatched == 0}};
}

// The stream sample the table keeps (unit_prices re-times it): runs of candidates to a
// keypoint, one from every 100th candidate of the first fitting run; 6 with rounded Haar, 2
// with exact (4 times the instructions a keypoint): a few MB of table, ~20 ms to re-time.
constexpr size_t kSampleStride = 100;
size_t sample_keypoints(const std::string& haar) { return haar == "rounded" ? 6 : 2; }

sw::TraceReplay run_firmware(const CalibrateOptions& o, const fs::path& dir,
                             const std::vector<sw::PipelineParams>& sets, size_t sample) {
    std::ifstream map(o.firmware + ".map");
    if (!map) throw ConfigError("calibrate: no link map " + o.firmware + ".map beside the firmware");
    sw::TraceReplay replay(sw::read_link_map(map), sets);
    if (sample) replay.keep_sample(sample, kSampleStride);
    const std::string command =
        fmt::format("{} -cpu {} -d in_asm,exec,nochain -D /dev/stdout '{}' '{}' '{}'", kQemu, kQemuCpu, o.firmware,
                    (dir / "inputs.bin").string(), (dir / "iss_results.bin").string());
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) throw std::runtime_error("calibrate: cannot start " + command);
    __gnu_cxx::stdio_filebuf<char> buffer(pipe, std::ios::in);
    std::istream log(&buffer);
    replay.read(log);
    const int status = ::pclose(pipe);
    if (status != 0) throw std::runtime_error(fmt::format("calibrate: `{}` failed (status {})", command, status));
    return replay;
}

// The stream's cycles per step (at the defaults) beside what the table prices the same units at.
Json agreement(const std::vector<sw::CandidateStream>& stream_of,
               const std::vector<std::array<uint64_t, sw::kUnits>>& units, const std::array<double, sw::kUnits>& prices,
               uint64_t keypoints, size_t set) {
    std::array<double, sw::kSteps> stream{}, model{}, instructions{}, libm{};
    std::array<std::array<double, sw::kInsnClasses>, sw::kSteps> mix{};
    std::array<double, sw::kUnits> per_unit{};
    for (const auto& n : units)
        for (size_t u = 0; u < sw::kUnits; ++u) {
            per_unit[u] += double(n[u]);
            model[size_t(sw::step_of(sw::Unit(u)))] += double(n[u]) * prices[u];
        }
    for (const sw::CandidateStream& c : stream_of)
        for (size_t s = 0; s < sw::kSteps; ++s) {
            stream[s] += c[s].cycles[set];
            instructions[s] += double(c[s].instructions);
            libm[s] += double(c[s].libm_calls);
            for (size_t k = 0; k < sw::kInsnClasses; ++k) mix[s][k] += double(c[s].mix[k]);
        }
    double total_stream = 0, total_model = 0, worst = 0;
    for (size_t s = 0; s < sw::kSteps; ++s) total_stream += stream[s], total_model += model[s];
    Json steps = Json::object();
    const double per = keypoints ? double(keypoints) : 1.0;
    for (size_t s = 0; s < sw::kSteps; ++s) {
        const double error = stream[s] > 0 ? model[s] / stream[s] - 1 : 0;
        if (stream[s] > 0.01 * total_stream) worst = std::max(worst, std::fabs(error));
        Json classes = Json::object();
        for (size_t k = 0; k < sw::kInsnClasses; ++k)
            if (mix[s][k] > 0) classes[sw::insn_class_name(sw::InsnClass(k))] = mix[s][k] / per;
        steps[sw::step_name(sw::Step(s))] = {{"stream_cycles_per_keypoint", stream[s] / per},
                                             {"model_cycles_per_keypoint", model[s] / per},
                                             {"instructions_per_keypoint", instructions[s] / per},
                                             {"libm_calls_per_keypoint", libm[s] / per},
                                             {"mix_per_keypoint", classes},
                                             {"error", error}};
    }
    Json units_per_keypoint = Json::object();
    for (size_t u = 0; u < sw::kUnits; ++u) units_per_keypoint[sw::unit_name(sw::Unit(u))] = per_unit[u] / per;
    return {{"keypoints", keypoints},
            {"candidates", units.size()},
            {"units_per_keypoint", units_per_keypoint},
            {"steps", steps},
            {"stream_cycles", total_stream},
            {"model_cycles", total_model},
            {"total_error", total_stream > 0 ? total_model / total_stream - 1 : 0},
            {"worst_step_error", worst}};
}

struct RunResult {
    std::vector<std::array<uint64_t, sw::kUnits>> units;
    std::vector<sw::CandidateStream> stream;
    sw::StreamSample sample;
    Json record;
};

// The M-SURF run's frames: its unit's instruction stream hardly depends on the image (576
// samples, 16 sub-regions of 81 weighted samples), so one frame's ~100 keypoints price it.
constexpr int kMsurfFrames = 1;

// A scenario as the calibration runs it; with `msurf`, its M-SURF run.
Config calibration_scenario(const CalibrateOptions& o, const std::string& scenario, const std::string& haar,
                            bool msurf = false) {
    // The paper's budget of ~100 keypoints per frame unless the caller sets another.
    std::vector<std::string> sets_text{"surf.target_keypoints=100"};
    sets_text.insert(sets_text.end(), o.sets.begin(), o.sets.end());
    sets_text.push_back(fmt::format("surf.frames={}", msurf ? kMsurfFrames : o.frames));
    sets_text.push_back("surf.haar=" + haar);
    if (msurf) sets_text.push_back("surf.descriptor=msurf");
    sets_text.push_back("budget.fps=0");  // a frame rate needs frames the calibration need not run
    return load_scenario(resolve_scenario(scenario), sets_text);
}

// Everything the long work will need, checked before it starts: every scenario loads with the
// sets, and every file it ends by writing can be written.
void check_options(const CalibrateOptions& o) {
    if (o.frames < 1) throw ConfigError("calibrate: --frames must be at least 1");
    if (o.fit.empty()) throw ConfigError("calibrate: --fit needs at least one scenario");
    for (const auto& [option, list] : {std::pair{"--fit", &o.fit}, std::pair{"--check", &o.check}})
        for (const std::string& scenario : *list) try {
                if (scenario != "none")
                    for (const char* haar : {"exact", "rounded"})
                        check_scenario(calibration_scenario(o, scenario, haar));
            } catch (const ConfigError& e) {
                throw ConfigError(fmt::format("{} {}: {}", option, scenario, e.what()));
            }
    if (o.msurf != "none") try {
            for (const char* haar : {"exact", "rounded"}) check_scenario(calibration_scenario(o, o.msurf, haar, true));
        } catch (const ConfigError& e) {
            throw ConfigError(fmt::format("--msurf {}: {}", o.msurf, e.what()));
        }
    std::error_code ec;
    if (!o.table.empty()) {
        const fs::path folder = fs::path(o.table).has_parent_path() ? fs::path(o.table).parent_path() : fs::path(".");
        if (fs::is_directory(o.table, ec))
            throw ConfigError(fmt::format("--table {}: is a folder, not a file to write", o.table));
        if (!fs::is_directory(folder, ec))
            throw ConfigError(fmt::format("--table {}: no folder {} to write it in", o.table, folder.string()));
        if (::access(folder.c_str(), W_OK) != 0)
            throw EnvironmentError(
                fmt::format("--table {}: its folder cannot be written ({})", o.table, std::strerror(errno)));
    }
    fs::create_directories(o.out, ec);
    if (ec || ::access(o.out.c_str(), W_OK) != 0)
        throw EnvironmentError(
            fmt::format("--out {}: cannot be written ({})", o.out, ec ? ec.message() : std::strerror(errno)));
}

// `stage(text)` says what it is doing, for the progress line. With `msurf`, the scenario's
// M-SURF run (named "<scenario> with M-SURF" in the report).
RunResult calibration_run(const CalibrateOptions& o, const std::string& scenario, const std::string& haar,
                          const std::vector<sw::PipelineParams>& sets, const std::function<void(std::string)>& stage,
                          bool sample = false, bool msurf = false) {
    const fs::path dir =
        fs::path(o.out) / fmt::format("{}_{}{}", fs::path(scenario).stem().string(), haar, msurf ? "_msurf" : "");
    fs::create_directories(dir);
    for (const char* f : {"inputs.bin", "vp_results.bin", "iss_results.bin"}) fs::remove(dir / f);
    const Config config = calibration_scenario(o, scenario, haar, msurf);
    const std::string name = msurf ? scenario + " with M-SURF" : scenario;
    stage(fmt::format("{}, {} Haar: VP run", name, haar));
    // The VP run in a child (SystemC elaborates once per process), recording what its stage saw.
    record_stage_inputs((dir / "inputs.bin").string(), (dir / "vp_results.bin").string());
    Json vp;
    {
        Resimulation pool(1, dir / ".vp");
        pool.submit(config, [&](const Json& r) { vp = r; });
        pool.run([](size_t, size_t) {});
    }
    record_stage_inputs("", "");
    if (vp.contains("error"))
        throw ConfigError("calibrate: the VP run of " + scenario + " failed: " + vp["error"].dump());
    const std::vector<Frame> frames = read_inputs(dir / "inputs.bin");
    RunResult run;
    run.units = native_units(frames);
    stage(fmt::format("{}, {} Haar: {} candidates under qemu-ppc, {} parameter sets", name, haar, run.units.size(),
                      sets.size()));
    const sw::TraceReplay replay = run_firmware(o, dir, sets, sample ? sample_keypoints(haar) : 0);
    const Json results = compare_results(read_results(dir / "vp_results.bin"), read_results(dir / "iss_results.bin"));
    if (!results["agree"].get<bool>())
        throw std::runtime_error("calibrate: the PPC440 build's keypoints differ from the VP's: " + results.dump());
    run.stream = replay.candidates();
    run.sample = replay.sample();
    fs::remove_all(dir);  // tens of MB of buffers, reproducible from the scenario
    Json unknown = Json::object();
    for (const auto& [m, n] : replay.unknown_mnemonics()) unknown[m] = n;
    run.record = {{"scenario", name},
                  {"haar", haar},
                  {"frames", frames.size()},
                  {"results", results},
                  {"instructions_executed", replay.instructions()},
                  {"unclassified_mnemonics", unknown}};
    return run;
}

// "integer 22016, load 10526, ..." (classes of at least half an instruction).
std::string mix_text(const Json& mix) {
    std::string text;
    for (const auto& [cls, n] : mix.items())
        if (n.get<double>() >= 0.5) text += fmt::format("{}{} {:.0f}", text.empty() ? "" : ", ", cls, n.get<double>());
    return text;
}

// What an architect reads: per run, each step's stream and model cycles per keypoint; then
// the table's instructions per unit by class.
std::string calibration_markdown(const Json& out) {
    std::string md = "# PPC440 calibration of the software stage\n\n";
    const Json& prov = out["calibration"]["provenance"];
    md += fmt::format("Firmware: `{}` with `{}`, run under `{}`; table fitted on {}.\n\n",
                      prov["toolchain"].get<std::string>(), prov["flags"].get<std::string>(),
                      prov["iss"].get<std::string>(), prov["fitted_on"].get<std::string>());
    md +=
        "The firmware contracts `a * b + c` into `fmadds` as GCC does by default (an EDK build), the native "
        "build does not: the same keypoints, with float values that differ in the last bits (compared "
        "within the tolerance). Cycles per keypoint are all candidates' work divided by the keypoints; "
        "the stream's are the pipeline model on qemu's instruction stream, every access an L1 hit (the fills "
        "are timed by the platform).\n\n";
    for (const Json& r : out["runs"])
        for (const char* which : {"agreement", "agreement_double"}) {
            const Json& a = r[which];
            md += fmt::format("## {}, {} Haar, {} precision ({}; {} frames, {} candidates, {} keypoints)\n\n",
                              r["scenario"].get<std::string>(), r["haar"].get<std::string>(),
                              std::string(which) == "agreement" ? "single" : "double",
                              r.value("fitted", false) ? "fitted" : "held out", r["frames"].get<int>(),
                              a["candidates"].get<size_t>(), a["keypoints"].get<uint64_t>());
            md += fmt::format(
                "Keypoints: {} of {} words, {} bit-exact, largest difference {:.2g} (tolerance {:.0e}).\n\n",
                r["results"]["keypoints"].get<size_t>(), r["results"]["words"].get<size_t>(),
                r["results"]["bit_exact"].get<size_t>(), r["results"]["max_difference"].get<double>(),
                kKeypointTolerance);
            md +=
                "| step | instructions / keypoint | stream cycles / keypoint | model cycles / keypoint | model vs "
                "stream | "
                "libm calls / keypoint | mix / keypoint |\n|---|---:|---:|---:|---:|---:|---|\n";
            for (const auto& [step, v] : a["steps"].items())
                md += fmt::format("| {} | {:.0f} | {:.0f} | {:.0f} | {:+.2f} % | {:.1f} | {} |\n", step,
                                  v["instructions_per_keypoint"].get<double>(),
                                  v["stream_cycles_per_keypoint"].get<double>(),
                                  v["model_cycles_per_keypoint"].get<double>(), 100 * v["error"].get<double>(),
                                  v["libm_calls_per_keypoint"].get<double>(), mix_text(v["mix_per_keypoint"]));
            md += fmt::format("| **total** | | {:.0f} | {:.0f} | **{:+.2f} %** | | |\n\n",
                              a["stream_cycles"].get<double>() / std::max<double>(1, a["keypoints"].get<double>()),
                              a["model_cycles"].get<double>() / std::max<double>(1, a["keypoints"].get<double>()),
                              100 * a["total_error"].get<double>());
        }
    const Json& checks = out["calibration"]["checks"];
    if (!checks.empty()) {
        md +=
            "## Several knobs at once: the prices against the stream re-timed\n\n"
            "Each point moves every knob of the band at once (spread over the band by a fixed rule, precision "
            "alternating); the "
            "whole stream is timed there. The model scales the table by the stream sample re-timed at the point; "
            "the linear column is the sum of the one-knob probes' changes (not used: the knobs interact).\n\n"
            "| scenario | Haar | point | precision | stream cycles / keypoint | model cycles / keypoint | model vs "
            "stream | "
            "linear vs stream |\n|---|---|---:|---|---:|---:|---:|---:|\n";
        for (const Json& c : checks)
            md +=
                fmt::format("| {} | {} | {} | {} | {:.0f} | {:.0f} | {:+.2f} % | {:+.2f} % |\n",
                            c["scenario"].get<std::string>(), c["haar"].get<std::string>(), c["point"].get<int>(),
                            c["knobs"]["fpu.precision"].get<double>() > 0.5 ? "double" : "single",
                            c["stream_cycles_per_keypoint"].get<double>(), c["model_cycles_per_keypoint"].get<double>(),
                            100 * c["error"].get<double>(), 100 * c["linear_error"].get<double>());
        md += "\n";
    }
    for (const auto& [haar, units] : out["calibration"]["single"]["haar"].items()) {
        md += fmt::format(
            "## Instructions per unit of work, {} Haar (cycles: single precision)\n\n| unit | cycles | instructions | "
            "IPC | libm calls | mix |\n|---|---:|---:|---:|---:|---|\n",
            haar);
        for (const auto& [unit, u] : units.items()) {
            const std::string mix = mix_text(u["mix"]);
            const double cycles = u["cycles"].get<double>();
            md += fmt::format(
                "| {} | {:.1f} | {:.1f} | {:.2f} | {:.1f} | {} |\n", unit, cycles, u["instructions"].get<double>(),
                cycles > 0 ? u["instructions"].get<double>() / cycles : 0.0, u["libm_calls"].get<double>(), mix);
        }
        md += "\n";
    }
    return md;
}

// The pipeline a table is measured at: the fitting scenario's with the caller's --set, in
// each precision (its latency column unless the caller set a latency).
std::array<sw::PipelineParams, 2> table_bases(const CalibrateOptions& o) {
    std::array<sw::PipelineParams, 2> bases;
    for (int p = 0; p < 2; ++p) {
        std::vector<std::string> sets = o.sets;
        sets.push_back(std::string("fpu.precision=") + (p ? "double" : "single"));
        bases[size_t(p)] = pipeline_params(load_scenario(resolve_scenario(o.fit.front()), sets));
    }
    return bases;
}

// Points where every knob of the band moves at once: each knob's band in n strata, point i
// taking stratum (i (2k + 3) + k) mod n of knob k, precision alternating. A Latin hypercube
// only for the knobs whose multiplier 2k + 3 is coprime to n (with n = 6, those not a
// multiple of 3); the others repeat strata. Deterministic, so a recalibration re-times the
// same points.
std::vector<sw::PipelineParams> check_points(const std::array<sw::PipelineParams, 2>& bases, size_t n) {
    std::vector<sw::PipelineParams> points;
    const auto& knobs = sw::pipeline_knobs();
    for (size_t i = 0; i < n; ++i) {
        sw::PipelineParams p = bases[i % 2];
        for (size_t k = 0; k < knobs.size(); ++k) {
            const sw::PipelineKnob& knob = knobs[k];
            if (!knob.band || std::string(knob.key) == "fpu.precision") continue;
            const size_t stratum = (i * (2 * k + 3) + k) % n;
            const double f = (double(stratum) + 0.5) / double(n);
            const double v = knob.low + f * (knob.high - knob.low);
            p.*knob.field = sw::knob_choice(knob, 0) || std::string(knob.unit) == "count" ? std::round(v) : v;
        }
        points.push_back(p);
    }
    return points;
}

Json knob_values(const sw::PipelineParams& p) {
    Json j = Json::object();
    for (const sw::PipelineKnob& k : sw::pipeline_knobs()) j[k.key] = p.*k.field;
    return j;
}

constexpr size_t kCheckPoints = 6;

}  // namespace

int calibrate_command(const CalibrateOptions& options) {
    CalibrateOptions o = options;
    if (o.firmware.empty()) o.firmware = SURFVP_FIRMWARE_PATH;
    if (!fs::exists(o.firmware))
        throw ConfigError("calibrate: no PPC440 firmware at " + o.firmware +
                          ": install g++-powerpc-linux-gnu and rebuild (./scripts/bootstrap.sh does both)");
    if (!fs::is_regular_file(o.firmware))
        throw ConfigError("calibrate: --firmware " + o.firmware + ": not a regular file (a PPC440 ELF is)");
    if (!fs::is_regular_file(o.firmware + ".map"))  // read after the VP's runs: checked before them
        throw ConfigError("calibrate: no link map " + o.firmware + ".map beside the firmware");
    if (std::system((std::string("command -v ") + kQemu + " > /dev/null").c_str()) != 0)
        throw ConfigError(std::string("calibrate: no ") + kQemu + ": install qemu-user (./scripts/bootstrap.sh does)");
    calibrating_stage(true);  // the M-SURF run measures the price it has not got yet
    check_options(o);
    cv::setNumThreads(0);

    // Every parameter set the stream is timed at, in one pass: per precision its base and
    // each knob's probes (the table), then the multi-knob check points.
    const std::array<sw::PipelineParams, 2> bases = table_bases(o);
    std::vector<sw::PipelineParams> sets;
    std::array<size_t, 2> first{};
    for (size_t p = 0; p < 2; ++p) {
        first[p] = sets.size();
        const auto table_sets = o.probes ? sw::calibration_parameter_sets(bases[p]) : std::vector{bases[p]};
        sets.insert(sets.end(), table_sets.begin(), table_sets.end());
    }
    const size_t first_check = sets.size();
    const std::vector<sw::PipelineParams> checks =
        o.probes ? check_points(bases, kCheckPoints) : std::vector<sw::PipelineParams>{};
    sets.insert(sets.end(), checks.begin(), checks.end());

    sw::Calibration table;
    for (size_t p = 0; p < 2; ++p) {
        sw::PrecisionTable& t = table.precision[p];
        for (const sw::PipelineKnob& k : sw::pipeline_knobs()) {
            t.defaults.push_back(bases[p].*k.field);
            const double base = bases[p].*k.field;
            const auto [low, high] = o.probes ? sw::probe_values(k, base) : std::pair{base, base};
            t.low_at.push_back(low);
            t.high_at.push_back(high);
        }
    }
    Json runs = Json::array();
    std::vector<std::pair<RunResult, int>> done;
    const char* modes[2] = {"exact", "rounded"};
    const size_t total =
        2 * (o.fit.size() + size_t(o.msurf != "none") +
             size_t(std::count_if(o.check.begin(), o.check.end(), [](const std::string& c) { return c != "none"; })));
    ProgressLine progress(o.quiet, "calibrate", 0, 0, 0);  // a line per stage: each takes seconds to minutes
    auto stage = [&](const std::string& text) { progress.steps(done.size(), total, "runs", false, ": " + text); };
    for (int h = 0; h < 2; ++h) {
        RunResult pooled;
        auto fitted_run = [&](RunResult fit) {
            pooled.stream.insert(pooled.stream.end(), fit.stream.begin(), fit.stream.end());
            pooled.units.insert(pooled.units.end(), fit.units.begin(), fit.units.end());
            fit.record["fitted"] = true;
            done.emplace_back(std::move(fit), h);
        };
        for (const std::string& scenario : o.fit) {
            RunResult fit = calibration_run(o, scenario, modes[h], sets, stage, scenario == o.fit.front());
            if (scenario == o.fit.front()) table.sample[size_t(h)] = fit.sample;
            fitted_run(std::move(fit));
        }
        // The msurf unit's price: fitted with the rest, from its own run.
        if (o.msurf != "none") {
            RunResult fit = calibration_run(o, o.msurf, modes[h], sets, stage, true, true);
            table.msurf_sample[size_t(h)] = fit.sample;
            fitted_run(std::move(fit));
        }
        for (size_t p = 0; p < 2; ++p) {
            sw::UnitTable fitted = sw::fit_units(pooled.stream, pooled.units, first[p], o.probes);
            if (!o.probes)  // not probed: no sensitivity (the probes sit at the defaults)
                for (sw::UnitCalibration& u : fitted)
                    u.low = u.high = std::vector<double>(sw::pipeline_knobs().size(), u.cycles);
            table.precision[p].haar[size_t(h)] = fitted;
        }
        for (const std::string& check : o.check)
            if (check != "none") done.emplace_back(calibration_run(o, check, modes[h], sets, stage), h);
    }
    table.provenance = {
        {"toolchain", first_output_line("powerpc-linux-gnu-g++ --version")},
        {"flags", SURFVP_FIRMWARE_FLAGS},
        {"iss", fmt::format("{} -cpu {}", kQemu, kQemuCpu)},
        {"fitted_on", fmt::format("{}, {} frames each per Haar mode{}", fmt::join(o.fit, " + "), o.frames,
                                  o.msurf == "none" ? std::string(" (M-SURF not priced)")
                                                    : fmt::format(", + {} with M-SURF descriptors, {} frame", o.msurf,
                                                                  kMsurfFrames))},
        {"set", o.sets}};
    for (auto& [run, h] : done) {
        uint64_t keypoints = 0;
        for (const auto& n : run.units) keypoints += sw::described_keypoints(n);
        const surf::HaarMode haar = h ? surf::HaarMode::rounded : surf::HaarMode::exact;
        for (size_t p = 0; p < 2; ++p) {
            const Json a =
                agreement(run.stream, run.units, sw::unit_prices(haar, bases[p], table), keypoints, first[p]);
            run.record[p ? "agreement_double" : "agreement"] = a;
            Json summary = {{"scenario", run.record["scenario"]},
                            {"haar", run.record["haar"]},
                            {"precision", p ? "double" : "single"},
                            {"fitted", run.record.value("fitted", false)}};
            summary.update(a);
            table.agreement.push_back(summary);
        }
        const double per = double(std::max<uint64_t>(1, keypoints));
        for (size_t i = 0; i < checks.size(); ++i) {
            const Json a =
                agreement(run.stream, run.units, sw::unit_prices(haar, checks[i], table), keypoints, first_check + i);
            const Json linear = agreement(run.stream, run.units, sw::linear_unit_prices(haar, checks[i], table),
                                          keypoints, first_check + i);
            table.checks.push_back({{"scenario", run.record["scenario"]},
                                    {"haar", run.record["haar"]},
                                    {"point", i},
                                    {"knobs", knob_values(checks[i])},
                                    {"units_per_keypoint", a["units_per_keypoint"]},
                                    {"stream_cycles_per_keypoint", a["stream_cycles"].get<double>() / per},
                                    {"model_cycles_per_keypoint", a["model_cycles"].get<double>() / per},
                                    {"error", a["total_error"]},
                                    {"linear_cycles_per_keypoint", linear["model_cycles"].get<double>() / per},
                                    {"linear_error", linear["total_error"]}});
        }
        runs.push_back(run.record);
    }
    const Json out = {{"calibration", sw::calibration_to_json(table)}, {"runs", runs}};
    const std::string table_json = sw::calibration_to_json(table).dump(1) + "\n";
    write_file_atomically(fs::path(o.out) / "calibration_report.json", out.dump(1) + "\n");
    write_file_atomically(fs::path(o.out) / "calibration.json", table_json);
    if (!o.table.empty()) write_file_atomically(o.table, table_json);
    const std::string md = calibration_markdown(out);
    write_file_atomically(fs::path(o.out) / "calibration.md", md);
    std::fputs(md.c_str(), stdout);
    return kExitOk;
}

}  // namespace surfvp
