// surfvp: the command line of the FPGA-SURF virtual platform.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <opencv2/core/utils/logger.hpp>
#include <string>
#include <systemc>
#include <vector>

#include "models/host/atomic_file.h"
#include "models/common/zeroed_memory.h"
#include "platform/tools/bench.h"
#include "platform/tools/calibrate.h"
#include "platform/scenario/config.h"
#include "platform/scenario/parameters.h"
#include "platform/quality/quality_commands.h"
#include "platform/cli/run_command.h"
#include "platform/run/progress_line.h"
#include "platform/run/run.h"
#include "platform/scenario/scenario.h"
#include "platform/compare/compare.h"
#include "platform/correlation/correlate.h"
#include "platform/table2/precision_study.h"
#include "platform/table2/quality_budget.h"
#include "platform/table2/table2.h"
#include "platform/sweep/sweep.h"
#include "platform/tools/export_sequence.h"
#include "platform/tools/synthesize.h"
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

// A command: the subcommand CLI11 fills in, and what runs when it is the one given. Its
// options live as long as the action that reads them.
struct Command {
    CLI::App* app;
    std::function<int()> action;
};

template <class Options>
std::shared_ptr<Options> options_for() {
    return std::make_shared<Options>();
}

Command add_run(CLI::App& app) {
    auto o = options_for<RunOptions>();
    CLI::App* run = app.add_subcommand("run", "Simulate a scenario; write report.json/.md, config.yaml and traces");
    add_scenario_options(*run, o->scenario, o->sets);
    run->add_option("--out", o->out, "Output folder (default: traces/<scenario name>)");
    run->add_option("--trace", o->trace, "Which traces to write")
        ->check(CLI::IsMember({"none", "vcd", "perfetto", "all"}))
        ->default_val("all");
    run->add_flag("--quiet,-q", o->quiet, "No progress or summary lines on stderr");
    run->add_option(
        "--compare-to", o->compare_to,
        "Also write compare.md and compare.json: this run against a run folder or a sweep point (SWEEP_DIR@N)");
    run->add_flag("--quick", o->quick,
                  "One run, without the verdict's re-simulations (verdict.break_even, verdict.band and "
                  "verdict.software off): the frame rate, the limit and where the time goes in seconds, but no "
                  "break-even, no band of doubt and no software what-ifs (the default scenario: about 1 s, against "
                  "20-30 s for its verdict's ~310 re-simulations on 2 cores)");
    run->add_flag("--direct", o->direct,
                  "Run the driver and software on the cores without SystemC (no time): keypoints only");
    return {run, [o] { return run_scenario(*o); }};
}

Command add_validate(CLI::App& app) {
    auto o = options_for<RunOptions>();
    CLI::App* validate = app.add_subcommand("validate", "Check a scenario (and --set overrides) without running it");
    add_scenario_options(*validate, o->scenario, o->sets);
    return {validate, [o] { return validate_scenario(*o); }};
}

// A command without options that prints a text.
Command add_listing(CLI::App& app, const char* name, const char* description, std::function<std::string()> text) {
    return {app.add_subcommand(name, description), [text = std::move(text)] {
                std::fputs(text().c_str(), stdout);
                return kExitOk;
            }};
}

Command add_seqgen(CLI::App& app) {
    auto o = options_for<SeqgenOptions>();
    CLI::App* seqgen =
        app.add_subcommand("seqgen", "Generate the FHG's control sequence and print its statistics (JSON)");
    seqgen->add_option("scenario", o->scenario, "Scenario to take the parameters from (default: the defaults)");
    seqgen->add_option("--set", o->sets, "Override a parameter: --set fhg.read_buses=6 (repeatable)")
        ->type_name("KEY=VALUE");
    seqgen->add_option("--width", o->width, "Image width for the implied frame rate")->capture_default_str();
    seqgen->add_option("--height", o->height, "Image height for the implied frame rate")->capture_default_str();
    return {seqgen, [o] { return seqgen_command(*o); }};
}

Command add_export_sequence(CLI::App& app) {
    auto o = options_for<ExportSequenceOptions>();
    CLI::App* cmd = app.add_subcommand(
        "export-sequence", "Write the FHG's control sequence as its block RAM image (COE and $readmemh), or check one");
    cmd->add_option("scenario", o->scenario, "Scenario to take the parameters from (default: the defaults)");
    cmd->add_option("--set", o->sets, "Override a parameter: --set fhg.scheduler=improved (repeatable)")
        ->type_name("KEY=VALUE");
    cmd->add_option("--out", o->out, "Folder for fhg_sequence.coe, .mem and .json")->capture_default_str();
    cmd->add_option("--check", o->check,
                    "Read this image (.coe or .mem) under the configuration's layout and replay it instead")
        ->type_name("FILE");
    return {cmd, [o] { return export_sequence_command(*o); }};
}

Command add_synthesize(CLI::App& app) {
    auto o = options_for<SynthesizeOptions>();
    CLI::App* cmd = app.add_subcommand(
        "synthesize", "Synthesize the FHG datapath's Verilog (yosys) part by part beside the resource model");
    cmd->add_option("scenario", o->scenario, "Scenario to take the parameters from (default: the defaults)");
    cmd->add_option("--set", o->sets, "Override a parameter: --set 'fhg.response_bits=16 bit' (repeatable)")
        ->type_name("KEY=VALUE");
    cmd->add_option("--out", o->out, "Folder for rtl/, yosys/ and synthesis.{md,json}")->capture_default_str();
    cmd->add_option("--family", o->family, "synth_xilinx's family (default: fpga.device's): xc5v, xc6s, xc6v, xc7");
    cmd->add_flag("--whole-fifo", o->whole_fifo,
                  "Also the whole line FIFO: its BRAMs and the routing of the bus lanes to their ports (about 4 "
                  "minutes and 2 GB at the default)");
    return {cmd, [o] { return synthesize_command(*o); }};
}

Command add_bench(CLI::App& app) {
    auto o = options_for<BenchOptions>();
    o->self = "/proc/self/exe";
    CLI::App* bench = app.add_subcommand(
        "bench",
        "Measure the simulator: wall time per frame (traces off and on), start-up, peak memory, real-time factor, "
        "the float reference's time on the same frame, against their targets");
    bench->add_option("scenario", o->scenario, "Scenario to run")->capture_default_str();
    bench->add_flag("--scaling", o->scaling, "Also 640x480 and 1024x1024 frames, and ten times as many frames");
    bench
        ->add_option("--frames", o->frames,
                     "Frames each run simulates (its time per frame is from the last three quarters)")
        ->capture_default_str();
    return {bench, [o] { return bench_command(*o); }};
}

Command add_calibrate(CLI::App& app) {
    auto o = options_for<CalibrateOptions>();
    CLI::App* calibrate = app.add_subcommand(
        "calibrate",
        "Price the software stage from its PPC440 instruction stream (qemu-ppc); write the table and agreement");
    calibrate->add_option("--fit", o->fit, "Scenarios the table is fitted on (repeatable)")->capture_default_str();
    calibrate->add_option("--check", o->check, "Scenarios the table is checked on (repeatable; none: no check)")
        ->capture_default_str();
    calibrate
        ->add_option("--msurf", o->msurf,
                     "Scenario run again with M-SURF descriptors to price them (none: M-SURF not priced)")
        ->capture_default_str();
    calibrate->add_option("--set", o->sets, "Override a parameter in every run (repeatable)")->type_name("KEY=VALUE");
    calibrate->add_option("--frames", o->frames, "Frames per scenario")->capture_default_str();
    calibrate->add_option("--out", o->out, "Output folder")->capture_default_str();
    calibrate->add_option("--table", o->table, "Also write the fitted table here (sw/cpu_cost/calibration.json)");
    calibrate->add_option("--firmware", o->firmware, "The PPC440 build of the stage (default: the build's)");
    calibrate->add_flag("!--no-probes", o->probes,
                        "Time the stream at the defaults only (keeps the recorded sensitivities)");
    calibrate->add_flag("--quiet,-q", o->quiet, "No progress lines on stderr");
    return {calibrate, [o] { return calibrate_command(*o); }};
}

Command add_sweep(CLI::App& app) {
    auto o = options_for<SweepOptions>();
    CLI::App* sweep = app.add_subcommand(
        "sweep", "Run a sweep's points (docs/sweeps.md): results.csv/.json, plots, the Pareto front");
    sweep->add_option("sweep", o->file, "Sweep file (YAML: scenario, set, axes, combine)")->required();
    sweep->add_option("--out", o->out, "Sweep folder (default: traces/<sweep name>); a sweep run again there resumes");
    sweep->add_option("--jobs,-j", o->jobs, "Points at once (default: one per core)");
    sweep->add_option("--shard", o->shard, "Run only shard K of N (K/N), into shard-K-of-N.db; merge with sweep-merge")
        ->type_name("K/N");
    sweep
        ->add_option(
            "--slurm", o->slurm,
            "Submit a Slurm job array of N shard tasks (sbatch; SBATCH_* variables pass options) and a merge after it")
        ->type_name("N")
        ->check(CLI::Range(1u, 100000u));
    sweep->add_flag("--quiet,-q", o->quiet, "No progress or summary lines on stderr");
    sweep->add_flag(
        "--fresh", o->fresh,
        "Start over: discard the folder's sweep databases and results (another sweep's, or this one's) first");
    sweep->add_flag("--keep-failed", o->keep_failed,
                    "Keep the points that could not run (exit 2, 3, 4) as recorded instead of running them again");
    return {sweep, [o] { return sweep_command(*o); }};
}

Command add_sweep_merge(CLI::App& app) {
    struct MergeOptions {
        std::string folder;
        bool partial = false;
    };
    auto o = options_for<MergeOptions>();
    CLI::App* merge = app.add_subcommand("sweep-merge", "Merge a sweep folder's shard databases and write its results");
    merge->add_option("folder", o->folder, "The sweep folder")->required();
    merge->add_flag("--partial", o->partial, "Merge although shards are missing (the results name them)");
    return {merge, [o] { return sweep_merge_command(o->folder, o->partial); }};
}

Command add_compare(CLI::App& app) {
    auto o = options_for<CompareOptions>();
    CLI::App* compare = app.add_subcommand(
        "compare", "Runs side by side: parameters that differ, every figure with its change, budgets");
    compare->add_option("runs", o->sides, "Run folders or sweep points (SWEEP_DIR@N); the first is the reference")
        ->required();
    compare->add_option("--json", o->json, "Also write the comparison as JSON to this file");
    return {compare, [o] { return compare_command(*o); }};
}

Command add_table2(CLI::App& app) {
    auto o = options_for<Table2Options>();
    CLI::App* table2 = app.add_subcommand("table2",
                                          "The paper's Table II: a sequence through the chip and the float reference, "
                                          "distinguishability in four rows (docs/table2.md)");
    add_scenario_options(*table2, o->scenario, o->sets);
    table2->add_option("--out", o->out, "Output folder (default: traces/<scenario name>)");
    table2->add_flag("--quiet,-q", o->quiet, "No summary lines on stderr");
    return {table2, [o] { return table2_command(*o); }};
}

Command add_precision(CLI::App& app) {
    auto o = options_for<PrecisionOptions>();
    CLI::App* precision = app.add_subcommand("precision",
                                             "How many bits the FHG needs: each width narrowed alone, Table II rows, "
                                             "repeatability, precision and cost per point (docs/precision.md)");
    precision->add_option("scenario", o->scenario, "A sequence scenario (castle_sequence): the Table II rows")
        ->required();
    precision->add_option("--pair", o->pair, "A pair under a homography (graf): repeatability and precision too");
    precision
        ->add_option("--axis", o->axes,
                     "A width and its values: --axis 'fhg.det_bits=24 bit,20 bit' "
                     "(repeatable; default: the built-in widths)")
        ->type_name("KEY=V1,V2,...");
    precision
        ->add_option(
            "--set", o->sets,
            "Override a parameter of the sequence scenario (repeatable; the pair takes only each point's widths)")
        ->type_name("KEY=VALUE ...");
    precision->add_option("--out", o->out, "Output folder (default: traces/precision_<scenario name>)");
    precision->add_option("--jobs", o->jobs, "Points at once (default: one per core)")->check(CLI::Range(0u, 256u));
    precision->add_flag("--quiet,-q", o->quiet, "No progress or summary lines on stderr");
    return {precision, [o] { return precision_command(*o); }};
}

Command add_quality_budget(CLI::App& app) {
    auto o = options_for<QualityBudgetOptions>();
    CLI::App* qb = app.add_subcommand("quality-budget",
                                      "The best feature quality the chip affords at its frame budget: each software "
                                      "setting priced in CPU time and scored on Table II, the front of quality "
                                      "against frames/s (docs/quality_budget.md)");
    qb->add_option("budget", o->budget, "The budget scenario (a timed run per setting)")->capture_default_str();
    qb->add_option("--sequence", o->sequences,
                   "A Table II sequence the best setting is chosen on (repeatable; default: castle_sequence, "
                   "vtest_sequence)");
    qb->add_option("--held-out", o->held_out,
                   "A sequence scored but never chosen on (repeatable; default: castel_sequence)");
    qb->add_option("--pair", o->pair, "A pair under a homography: repeatability and precision ('none': no pair)")
        ->capture_default_str();
    qb->add_option("--axis", o->axes,
                   "A setting and its values, combined with the other axes: --axis 'surf.max_offset=0.5,1' "
                   "(repeatable; default: the built-in software settings)")
        ->type_name("KEY=V1,V2,...");
    qb->add_option("--set", o->sets, "Override a parameter of every scenario of the study (repeatable)")
        ->type_name("KEY=VALUE");
    qb->add_option("--out", o->out, "Output folder (default: traces/quality_budget)");
    qb->add_option("--jobs", o->jobs, "Runs at once (default: one per core)")->check(CLI::Range(0u, 256u));
    qb->add_flag("--quiet,-q", o->quiet, "No progress or summary lines on stderr");
    return {qb, [o] { return quality_budget_command(*o); }};
}

Command add_correlate(CLI::App& app) {
    auto o = options_for<CorrelateOptions>();
    CLI::App* correlate = app.add_subcommand("correlate",
                                             "Where the VP reproduces the paper's figures: the unknowns over their "
                                             "bands, the region that agrees, whether the defaults lie in it "
                                             "(docs/correlation.md)");
    correlate->add_option("scenario", o->scenario, "Scenario file or shipped name")->capture_default_str();
    correlate->add_option("--set", o->sets, "Override a parameter (repeatable)")->type_name("KEY=VALUE");
    correlate->add_option("--out", o->out, "Output folder (default: traces/correlate_<scenario name>)");
    correlate->add_option("--jobs", o->jobs, "Re-simulations at once (default: one per core)")
        ->check(CLI::Range(0u, 256u));
    correlate->add_flag("--quiet,-q", o->quiet, "No progress or summary lines on stderr");
    return {correlate, [o] { return correlate_command(*o); }};
}

// Parses the command line: nothing when a command is to run, else the exit code (0 for --help
// and --version, 2 for a command line that is wrong, said on stderr).
std::optional<int> parse(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
        return std::nullopt;
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
}

// Runs a command; what it throws becomes its documented exit code (README.md, docs/errors.md)
// and one line on stderr.
int with_exit_codes(const char* command, const std::function<int()>& action) {
    try {
        return action();
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
        std::fprintf(stderr, "surfvp: out of memory: an allocation of `surfvp %s` failed\n", command);
        return kExitOutOfMemory;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "surfvp: internal error: %s\n", e.what());
        return kExitInternal;
    }
}

int dispatch(int argc, char** argv) {
    CLI::App app{"surfvp: a SystemC/TLM-2.0 virtual platform of the FPGA-SURF system-on-chip"};
    app.set_version_flag("--version", std::string("surfvp ") + SURFVP_VERSION);
    app.require_subcommand(1);
    const std::vector<Command> commands = {
        add_run(app),
        add_validate(app),
        {app.add_subcommand("list", "List the shipped scenarios with their descriptions"), list_scenarios},
        add_listing(app, "params", "Print every parameter with its default, range and source (Markdown)",
                    parameters_markdown),
        add_listing(app, "registers",
                    "Print every block's registers with their access, reset value and fields (Markdown)",
                    [] { return registers_markdown(chip_registers()); }),
        add_seqgen(app),
        add_export_sequence(app),
        add_synthesize(app),
        add_bench(app),
        add_calibrate(app),
        add_sweep(app),
        add_sweep_merge(app),
        add_compare(app),
        add_table2(app),
        add_precision(app),
        add_quality_budget(app),
        add_correlate(app)};
    QualityCommands quality(app);
    // A long command's progress line is for a terminal; --progress asks for it in a log too.
    bool progress_in_logs = false;
    for (const Command& c : commands)
        if (c.app->get_option_no_throw("--quiet"))
            c.app->add_flag("--progress", progress_in_logs,
                            "Progress lines also when stderr is not a terminal (a log): one line of its own every "
                            "few seconds, with the count, the time gone and the time to go");
    if (const auto code = parse(app, argc, argv)) return *code;
    ProgressLine::show_in_logs(progress_in_logs);
    return with_exit_codes(argv[1], [&]() -> int {
        if (const auto code = quality.run()) return *code;
        for (const Command& c : commands)
            if (*c.app) return c.action();
        return kExitBadInput;
    });
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
