// surfvp: the command line of the FPGA-SURF virtual platform.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <opencv2/core/utils/logger.hpp>
#include <string>
#include <systemc>

#include "models/host/atomic_file.h"
#include "models/common/zeroed_memory.h"
#include "platform/tools/bench.h"
#include "platform/tools/calibrate.h"
#include "platform/scenario/config.h"
#include "platform/scenario/parameters.h"
#include "platform/quality/quality_commands.h"
#include "platform/cli/run_command.h"
#include "platform/run/run.h"
#include "platform/scenario/scenario.h"
#include "platform/compare/compare.h"
#include "platform/correlation/correlate.h"
#include "platform/table2/precision_study.h"
#include "platform/table2/table2.h"
#include "platform/sweep/sweep.h"
#include "platform/tools/seqgen.h"
#include "platform/soc.h"

namespace {

using namespace surfvp;

void add_scenario_options(CLI::App& command, std::string& scenario, std::vector<std::string>& sets) {
    command.add_option("scenario", scenario, "Scenario file, or the name of a shipped one (see `surfvp list`)")
        ->required();
    command.add_option("--set", sets, "Override a parameter: --set plb2.width='64 bit' (repeatable)")
        ->type_name("KEY=VALUE");
}

int list_scenarios() {
    for (const auto& s : shipped_scenarios()) std::printf("%-24s %s\n", s.name.c_str(), s.description.c_str());
    return kExitOk;
}

int dispatch(int argc, char** argv) {
    CLI::App app{"surfvp: a SystemC/TLM-2.0 virtual platform of the FPGA-SURF system-on-chip"};
    app.set_version_flag("--version", std::string("surfvp ") + SURFVP_VERSION);
    app.require_subcommand(1);
    RunOptions options;

    CLI::App* run = app.add_subcommand("run", "Simulate a scenario; write report.json/.md, config.yaml and traces");
    add_scenario_options(*run, options.scenario, options.sets);
    run->add_option("--out", options.out, "Output folder (default: traces/<scenario name>)");
    run->add_option("--trace", options.trace, "Which traces to write")
        ->check(CLI::IsMember({"none", "vcd", "perfetto", "all"}))
        ->default_val("all");
    run->add_flag("--quiet,-q", options.quiet, "No progress or summary lines on stderr");
    run->add_option(
        "--compare-to", options.compare_to,
        "Also write compare.md and compare.json: this run against a run folder or a sweep point (SWEEP_DIR@N)");
    run->add_flag("--direct", options.direct,
                  "Run the driver and software on the cores without SystemC (no time): keypoints only");

    CLI::App* validate = app.add_subcommand("validate", "Check a scenario (and --set overrides) without running it");
    add_scenario_options(*validate, options.scenario, options.sets);
    app.add_subcommand("list", "List the shipped scenarios with their descriptions");
    app.add_subcommand("params", "Print every parameter with its default, range and source (Markdown)");
    app.add_subcommand("registers",
                       "Print every block's registers with their access, reset value and fields (Markdown)");
    SeqgenOptions seqgen_options;
    CLI::App* seqgen =
        app.add_subcommand("seqgen", "Generate the FHG's control sequence and print its statistics (JSON)");
    seqgen->add_option("scenario", seqgen_options.scenario,
                       "Scenario to take the parameters from (default: the defaults)");
    seqgen->add_option("--set", seqgen_options.sets, "Override a parameter: --set fhg.read_buses=6 (repeatable)")
        ->type_name("KEY=VALUE");
    seqgen->add_option("--width", seqgen_options.width, "Image width for the implied frame rate")
        ->capture_default_str();
    seqgen->add_option("--height", seqgen_options.height, "Image height for the implied frame rate")
        ->capture_default_str();
    BenchOptions bench_options;
    bench_options.self = "/proc/self/exe";
    CLI::App* bench = app.add_subcommand(
        "bench",
        "Measure the simulator: wall time per frame (traces off and on), start-up, peak memory, real-time factor, "
        "the float reference's time on the same frame, against their targets");
    bench->add_option("scenario", bench_options.scenario, "Scenario to run")->capture_default_str();
    bench->add_flag("--scaling", bench_options.scaling,
                    "Also 640x480 and 1024x1024 frames, and ten times as many frames");
    bench
        ->add_option("--frames", bench_options.frames,
                     "Frames each run simulates (its time per frame is from the last three quarters)")
        ->capture_default_str();
    CalibrateOptions calibrate_options;
    CLI::App* calibrate = app.add_subcommand(
        "calibrate",
        "Price the software stage from its PPC440 instruction stream (qemu-ppc); write the table and agreement");
    calibrate->add_option("--fit", calibrate_options.fit, "Scenarios the table is fitted on (repeatable)")
        ->capture_default_str();
    calibrate
        ->add_option("--check", calibrate_options.check,
                     "Scenarios the table is checked on (repeatable; none: no check)")
        ->capture_default_str();
    calibrate->add_option("--set", calibrate_options.sets, "Override a parameter in every run (repeatable)")
        ->type_name("KEY=VALUE");
    calibrate->add_option("--frames", calibrate_options.frames, "Frames per scenario")->capture_default_str();
    calibrate->add_option("--out", calibrate_options.out, "Output folder")->capture_default_str();
    calibrate->add_option("--table", calibrate_options.table,
                          "Also write the fitted table here (sw/cpu_cost/calibration.json)");
    calibrate->add_option("--firmware", calibrate_options.firmware,
                          "The PPC440 build of the stage (default: the build's)");
    calibrate->add_flag("!--no-probes", calibrate_options.probes,
                        "Time the stream at the defaults only (keeps the recorded sensitivities)");
    calibrate->add_flag("--quiet,-q", calibrate_options.quiet, "No progress lines on stderr");
    SweepOptions sweep_options;
    CLI::App* sweep = app.add_subcommand(
        "sweep", "Run a sweep's points (docs/sweeps.md): results.csv/.json, plots, the Pareto front");
    sweep->add_option("sweep", sweep_options.file, "Sweep file (YAML: scenario, set, axes, combine)")->required();
    sweep->add_option("--out", sweep_options.out,
                      "Sweep folder (default: traces/<sweep name>); a sweep run again there resumes");
    sweep->add_option("--jobs,-j", sweep_options.jobs, "Points at once (default: one per core)");
    sweep
        ->add_option("--shard", sweep_options.shard,
                     "Run only shard K of N (K/N), into shard-K-of-N.db; merge with sweep-merge")
        ->type_name("K/N");
    sweep
        ->add_option(
            "--slurm", sweep_options.slurm,
            "Submit a Slurm job array of N shard tasks (sbatch; SBATCH_* variables pass options) and a merge after it")
        ->type_name("N")
        ->check(CLI::Range(1u, 100000u));
    sweep->add_flag("--quiet,-q", sweep_options.quiet, "No progress or summary lines on stderr");
    sweep->add_flag(
        "--fresh", sweep_options.fresh,
        "Start over: discard the folder's sweep databases and results (another sweep's, or this one's) first");
    sweep->add_flag("--keep-failed", sweep_options.keep_failed,
                    "Keep the points that could not run (exit 2, 3, 4) as recorded instead of running them again");
    std::string merge_dir;
    bool merge_partial = false;
    CLI::App* sweep_merge =
        app.add_subcommand("sweep-merge", "Merge a sweep folder's shard databases and write its results");
    sweep_merge->add_option("folder", merge_dir, "The sweep folder")->required();
    sweep_merge->add_flag("--partial", merge_partial, "Merge although shards are missing (the results name them)");
    CompareOptions compare_options;
    CLI::App* compare = app.add_subcommand(
        "compare", "Runs side by side: parameters that differ, every figure with its change, budgets");
    compare
        ->add_option("runs", compare_options.sides,
                     "Run folders or sweep points (SWEEP_DIR@N); the first is the reference")
        ->required();
    compare->add_option("--json", compare_options.json, "Also write the comparison as JSON to this file");
    Table2Options table2_options;
    CLI::App* table2 = app.add_subcommand("table2",
                                          "The paper's Table II: a sequence through the chip and the float reference, "
                                          "distinguishability in four rows (docs/table2.md)");
    add_scenario_options(*table2, table2_options.scenario, table2_options.sets);
    table2->add_option("--out", table2_options.out, "Output folder (default: traces/<scenario name>)");
    table2->add_flag("--quiet,-q", table2_options.quiet, "No summary lines on stderr");
    PrecisionOptions precision_options;
    CLI::App* precision = app.add_subcommand("precision",
                                             "How many bits the FHG needs: each width narrowed alone, Table II rows, "
                                             "repeatability, precision and cost per point (docs/precision.md)");
    precision
        ->add_option("scenario", precision_options.scenario, "A sequence scenario (castle_sequence): the Table II rows")
        ->required();
    precision->add_option("--pair", precision_options.pair,
                          "A pair under a homography (graf): repeatability and precision too");
    precision
        ->add_option("--axis", precision_options.axes,
                     "A width and its values: --axis 'fhg.det_bits=24 bit,20 bit' "
                     "(repeatable; default: the built-in widths)")
        ->type_name("KEY=V1,V2,...");
    precision
        ->add_option(
            "--set", precision_options.sets,
            "Override a parameter of the sequence scenario (repeatable; the pair takes only each point's widths)")
        ->type_name("KEY=VALUE ...");
    precision->add_option("--out", precision_options.out, "Output folder (default: traces/precision_<scenario name>)");
    precision->add_option("--jobs", precision_options.jobs, "Points at once (default: one per core)")
        ->check(CLI::Range(0u, 256u));
    precision->add_flag("--quiet,-q", precision_options.quiet, "No progress or summary lines on stderr");
    CorrelateOptions correlate_options;
    CLI::App* correlate = app.add_subcommand("correlate",
                                             "Where the VP reproduces the paper's figures: the unknowns over their "
                                             "bands, the region that agrees, whether the defaults lie in it "
                                             "(docs/correlation.md)");
    correlate->add_option("scenario", correlate_options.scenario, "Scenario file or shipped name")
        ->capture_default_str();
    correlate->add_option("--set", correlate_options.sets, "Override a parameter (repeatable)")->type_name("KEY=VALUE");
    correlate->add_option("--out", correlate_options.out, "Output folder (default: traces/correlate_<scenario name>)");
    correlate->add_option("--jobs", correlate_options.jobs, "Re-simulations at once (default: one per core)")
        ->check(CLI::Range(0u, 256u));
    correlate->add_flag("--quiet,-q", correlate_options.quiet, "No progress or summary lines on stderr");
    QualityCommands quality(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::string message = e.what();
        if (argc > 1 && argv[1][0] != '-') {  // CLI11 says only that a command is required
            try {
                app.get_subcommand(argv[1]);
            } catch (const CLI::OptionNotFound&) {
                message = std::string("'") + argv[1] + "' is not a command (run, validate, list, params, ...)";
            }
        }
        std::fprintf(stderr, "surfvp: error: %s\nRun with --help for more information.\n", message.c_str());
        return kExitBadInput;
    }
    try {
        if (const auto code = quality.run()) return *code;
        if (*run) return run_scenario(options);
        if (*validate) return validate_scenario(options);
        if (*seqgen) return seqgen_command(seqgen_options);
        if (*bench) return bench_command(bench_options);
        if (*calibrate) return calibrate_command(calibrate_options);
        if (*sweep) return sweep_command(sweep_options);
        if (*compare) return compare_command(compare_options);
        if (*table2) return table2_command(table2_options);
        if (*correlate) return correlate_command(correlate_options);
        if (*precision) return precision_command(precision_options);
        if (*sweep_merge) return sweep_merge_command(merge_dir, merge_partial);
        if (app.got_subcommand("list")) return list_scenarios();
        if (app.got_subcommand("registers")) {
            std::fputs(registers_markdown(chip_registers()).c_str(), stdout);
            return kExitOk;
        }
        if (app.got_subcommand("params")) {
            std::fputs(parameters_markdown().c_str(), stdout);
            return kExitOk;
        }
    } catch (const ConfigError& e) {
        std::fprintf(stderr, "surfvp: error: %s\n", e.what());
        return kExitBadInput;
    } catch (const EnvironmentError& e) {
        std::fprintf(stderr, "surfvp: cannot write: %s\n", e.what());
        return kExitEnvironment;
    } catch (const OutOfMemory& e) {
        std::fprintf(stderr, "surfvp: out of memory: %s\n", e.what());
        return kExitOutOfMemory;
    } catch (const std::bad_alloc&) {  // an allocation of no named block: the command is what we know
        std::fprintf(stderr, "surfvp: out of memory: an allocation of `surfvp %s` failed\n", argv[1]);
        return kExitOutOfMemory;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "surfvp: internal error: %s\n", e.what());
        return kExitInternal;
    }
    return kExitBadInput;
}

}  // namespace

int sc_main(int argc, char** argv) {
    // SystemC's informational notes (e.g. the VCD time unit) are not the user's business.
    sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
    // Nor are OpenCV's warnings about a file it cannot open: the message that names the file
    // and the key is ours, and comes first.
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    return dispatch(argc, argv);
}

// Our own main, ahead of libsystemc's: SystemC prints its banner before sc_main runs unless
// this is set.
int main(int argc, char** argv) {
    setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
    setenv("OPENCV_FFMPEG_LOGLEVEL", "-8", 0);  // FFmpeg's own complaints about a damaged video: AV_LOG_QUIET
    return sc_core::sc_elab_and_sim(argc, argv);
}
