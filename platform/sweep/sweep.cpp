#include "platform/sweep/sweep.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <regex>
#include <unistd.h>

#include "models/host/atomic_file.h"
#include "models/host/shell.h"
#include "platform/report/run_summary.h"
#include "platform/run/progress_line.h"
#include "platform/run/run.h"
#include "platform/scenario/scenario.h"
#include "platform/run/resimulation.h"
#include "platform/sweep/sweep_plan.h"
#include "platform/sweep/sweep_results.h"
#include "platform/sweep/sweep_store.h"

namespace surfvp {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

struct Shard {
    size_t k = 1, n = 1;
};

Shard parse_shard(const std::string& text) {
    if (text.empty()) return {};
    static const std::regex form(R"(([0-9]{1,6})/([0-9]{1,6}))");
    std::smatch m;
    if (!std::regex_match(text, m, form) || std::stoul(m[2]) == 0 || std::stoul(m[1]) == 0 ||
        std::stoul(m[1]) > std::stoul(m[2]))
        throw ConfigError(fmt::format("--shard '{}': expected K/N with 1 <= K <= N, e.g. 2/8", text));
    return {std::stoul(m[1]), std::stoul(m[2])};
}

std::string database_name(const Shard& s) { return s.n == 1 ? "sweep.db" : fmt::format("shard-{}-of-{}.db", s.k, s.n); }

// The sweep databases in `dir`: sweep.db and shard-K-of-N.db, whatever they hold.
std::vector<fs::path> sweep_databases(const fs::path& dir) {
    static const std::regex shard_name(R"(shard-[0-9]+-of-[0-9]+\.db)");
    std::vector<fs::path> out;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (name == "sweep.db" || std::regex_match(name, shard_name)) out.push_back(entry.path());
    }
    std::sort(out.begin(), out.end());
    return out;
}

// A database and SQLite's files beside it (a journal left by a killed sweep would otherwise be
// played back into the next database of that name).
void remove_database(const fs::path& db) {
    for (const char* suffix : {"", "-journal", "-wal", "-shm"}) {
        std::error_code ec;
        fs::remove(db.string() + suffix, ec);
        if (ec) throw EnvironmentError(fmt::format("{}{}: cannot remove it: {}", db.string(), suffix, ec.message()));
    }
}

// What a whole sweep writes besides sweep.db: results.csv, results.json, results.md, pareto.svg and
// plot_<parameter>.svg. Nothing else in the folder is touched.
void remove_results(const fs::path& dir) {
    std::error_code ec;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        const bool plot = name.size() > 9 && name.rfind("plot_", 0) == 0 && name.substr(name.size() - 4) == ".svg" &&
                          find_parameter(name.substr(5, name.size() - 9));
        if (plot || name == "results.csv" || name == "results.json" || name == "results.md" || name == "pareto.svg")
            files.push_back(entry.path());
    }
    for (const fs::path& f : files)
        if (!fs::remove(f, ec) && ec)
            throw EnvironmentError(fmt::format("{}: cannot remove it: {}", f.string(), ec.message()));
}

// The folder's databases against this sweep, before one is opened. One of another sweep is
// refused, saying what changed, so that two sweeps' points never mix; with --fresh it is
// discarded with the results. --fresh also starts this sweep over: a whole sweep (or its
// Slurm array) discards every database of the folder, a shard its own, so that no other
// shard's work is lost.
void prepare_folder(const fs::path& dir, const fs::path& mine, const SweepPlan& plan, bool fresh, bool whole) {
    bool discarded_sweep_db = false;
    for (const fs::path& db : sweep_databases(dir)) {
        const std::string theirs = SweepStore::fingerprint_of(db.string());
        const bool other = !theirs.empty() && theirs != plan.fingerprint;
        if (other && !fresh)
            throw ConfigError(
                fmt::format("{}: holds the points of another sweep: {}; give --fresh to discard them and start "
                            "over, or another --out",
                            db.string(), fmt::join(sweep_changes(theirs, plan.fingerprint), "; ")));
        if (fresh && (other || whole || db == mine)) {
            remove_database(db);
            discarded_sweep_db = discarded_sweep_db || db.filename() == "sweep.db";
        }
    }
    if (fresh && (whole || discarded_sweep_db)) remove_results(dir);
}

// ", 3 of 8 meet the budget of 10 frames/s" over the rows with a budget ("" when none has one).
std::string budget_count(const std::vector<SweepRow>& rows) {
    size_t with = 0, met = 0;
    double budget = 0;  // -1: the points' budgets differ
    for (const SweepRow& r : rows) {
        const Json& f = r.figures;
        if (!f.contains("budget_met") || !f["budget_met"].is_boolean()) continue;
        met += f["budget_met"].get<bool>();
        const double own = f.value("budget_fps", 0.0);
        budget = with++ == 0 || own == budget ? own : -1;
    }
    return with ? fmt::format(", {} of {} meet the budget{}", met, with,
                              budget > 0 ? fmt::format(" of {:g} frames/s", budget) : "")
                : "";
}

// What a point's child hands back: its row's figures, not its whole report.
Json sweep_summary(const Json& report) {
    const RunSummary run = RunSummary::of(report);
    Json s = {{"figures", run.figures()}, {"exit", exit_code_of(report)}, {"wall_time_s", run.wall_time_s}};
    if (!run.failure.empty()) s["failure"] = run.failure;
    return s;
}

Json params_of(const SweepPoint& p) {
    Json j = Json::object();
    for (const auto& [key, value] : p.values) j[key] = value;
    return j;
}

void write_results(const fs::path& dir, const SweepStore& store, const Json& notes = Json::object()) {
    const std::string name = store.meta("name");
    if (!is_utf8(name))
        throw ConfigError(fmt::format("{}: its record of the sweep's name is not UTF-8 text", store.file()));
    write_sweep_results(dir.string(), name, store.axes(), store.rows(), notes);
}

// Runs `command` through the shell; its standard output, or throws EnvironmentError with what
// it printed.
std::string run_tool(const std::string& command) {
    std::string out;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) throw EnvironmentError(fmt::format("cannot run {}", command));
    char buffer[512];
    while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
    const int status = pclose(pipe);
    if (status != 0) throw EnvironmentError(fmt::format("{} failed: {}", command, out));
    return out;
}

// The job array (one shard per task) and a merge that runs once every task has ended well;
// the sweep folder must be on a file system every node sees.
int submit_to_slurm(const SweepOptions& options, const SweepPlan& plan, const fs::path& dir) {
    const fs::path self = fs::read_symlink("/proc/self/exe");
    const fs::path file = fs::absolute(options.file), folder = fs::absolute(dir), logs = folder / "slurm";
    fs::create_directories(logs);
    const unsigned n = options.slurm, jobs = options.jobs ? options.jobs : 1;
    const std::string script = fmt::format(
        "#!/bin/sh\n"
        "# surfvp sweep {name}: {n} shards, one per array task (docs/sweeps.md)\n"
        "#SBATCH --array=1-{n}\n"
        "#SBATCH --cpus-per-task={jobs}\n"
        "#SBATCH --output={logs}/shard-%a.log\n"
        "exec {self} sweep {file} --out {folder} --jobs {jobs} --quiet --shard \"$SLURM_ARRAY_TASK_ID/{n}\"\n",
        fmt::arg("name", plan.name), fmt::arg("n", n), fmt::arg("jobs", jobs),
        fmt::arg("logs", shell_quoted(logs.string())), fmt::arg("self", shell_quoted(self.string())),
        fmt::arg("file", shell_quoted(file.string())), fmt::arg("folder", shell_quoted(folder.string())));
    const fs::path array = logs / "array.sh";
    write_file_atomically(array.string(), script);
    // The job names go on the command line, quoted: a sweep's name may hold spaces or quotes,
    // which neither an #SBATCH line nor the shell would take as they are.
    const std::string id = run_tool(fmt::format("sbatch --parsable --job-name={} {}",
                                                shell_quoted("surfvp-" + plan.name), shell_quoted(array.string())));
    const std::string array_id = id.substr(0, id.find_first_of(";\n"));
    const std::string merge = run_tool(fmt::format(
        "sbatch --parsable --job-name={} --dependency=afterok:{} --output={} --wrap={}",
        shell_quoted("surfvp-" + plan.name + "-merge"), array_id, shell_quoted((logs / "merge.log").string()),
        shell_quoted(shell_quoted(self.string()) + " sweep-merge " + shell_quoted(folder.string()))));
    std::fprintf(
        stderr, "surfvp: %s: job array %s (%u shards) and merge job %s submitted; results in %s when they end\n",
        plan.name.c_str(), array_id.c_str(), n, merge.substr(0, merge.find_first_of(";\n")).c_str(), folder.c_str());
    return kExitOk;
}

// 0 when every point named ran, whatever its verdict; 1 when some could not, now or in an
// earlier run whose rows were kept: one line names them (also with --quiet: it is why the
// command did not end well). `not_run`: "point 3 (ID, exit 2)" each.
int exit_for(const std::string& name, const std::vector<std::string>& not_run, const std::string& why_in) {
    if (not_run.empty()) return kExitOk;
    constexpr size_t named = 10;
    std::fprintf(
        stderr, "surfvp: %s: %zu points could not run: %s%s; %s says why\n", name.c_str(), not_run.size(),
        fmt::format("{}", fmt::join(not_run.begin(), not_run.begin() + long(std::min(named, not_run.size())), "; "))
            .c_str(),
        not_run.size() > named ? fmt::format("; and {} more", not_run.size() - named).c_str() : "", why_in.c_str());
    return kExitFailed;
}

std::string not_run_text(size_t index, const std::string& id, int exit) {
    return fmt::format("point {} ({}, exit {})", index, id, exit);
}

int exit_code(const SweepPlan& plan, const Shard& shard, const SweepStore& store) {
    std::vector<std::string> not_run;
    for (const SweepPoint& p : plan.points)
        if (p.index % shard.n == shard.k - 1)
            if (const auto exit = store.exit_of(p.id); exit && !point_ran(*exit))
                not_run.push_back(not_run_text(p.index, p.id, *exit));
    return exit_for(plan.name, not_run, shard.n == 1 ? "results.csv" : "the shard database");
}

// A shard database of the folder: shard-K-of-N.db.
struct ShardFile {
    fs::path path;
    size_t k, n;
};

std::vector<ShardFile> shard_files(const fs::path& dir) {
    static const std::regex form(R"(shard-([0-9]{1,6})-of-([0-9]{1,6})\.db)");
    std::vector<ShardFile> out;
    for (const fs::path& db : sweep_databases(dir)) {
        std::smatch m;
        const std::string name = db.filename().string();
        if (std::regex_match(name, m, form) && std::stoul(m[1]) >= 1 && std::stoul(m[1]) <= std::stoul(m[2]))
            out.push_back({db, std::stoul(m[1]), std::stoul(m[2])});
    }
    return out;
}

// The shards absent from the folder, of every split (N) of which one is there: "shard-2-of-4.db".
std::vector<std::string> missing_shards(const std::vector<ShardFile>& shards) {
    std::map<size_t, std::set<size_t>> present;
    for (const ShardFile& s : shards) present[s.n].insert(s.k);
    std::vector<std::string> out;
    for (const auto& [n, ks] : present)
        for (size_t k = 1; k <= n; ++k)
            if (!ks.count(k)) out.push_back(database_name({k, n}));
    return out;
}

// "shard 2 of 2 is missing (shard-2-of-2.db)", "shards 2, 4 of 4 are missing (...)": which K
// of which N, and their files.
std::string missing_text(const std::vector<std::string>& missing) {
    static const std::regex form(R"(shard-([0-9]+)-of-([0-9]+)\.db)");
    std::map<std::string, std::vector<std::string>> by_n;
    for (const std::string& name : missing) {
        std::smatch m;
        std::regex_match(name, m, form);
        by_n[m[2]].push_back(m[1]);
    }
    std::vector<std::string> parts;
    for (const auto& [n, ks] : by_n)
        parts.push_back(fmt::format("{} {} of {}", ks.size() == 1 ? "shard" : "shards", fmt::join(ks, ", "), n));
    return fmt::format("{} {} missing ({})", fmt::join(parts, " and "), missing.size() == 1 ? "is" : "are",
                       fmt::join(missing, ", "));
}

// One database to merge, read whole and checked before anything is written: a sweep
// database, not empty, of the sweep `fingerprint` (the reference's), each row undamaged, of
// its own shard (a renamed file is not), and named by its own values.
void check_merged(const fs::path& file, const std::string& fingerprint, const std::string& reference,
                  const Shard& shard) {
    const auto db = SweepStore::read_only(file.string());
    const std::string theirs = db->meta("fingerprint");
    if (theirs.empty()) throw ConfigError(fmt::format("{}: is empty: it holds no sweep", file.string()));
    if (theirs != fingerprint)
        throw ConfigError(fmt::format("{}: is not of the sweep of {}: {}", file.string(), reference,
                                      fmt::join(sweep_changes(fingerprint, theirs), "; ")));
    const std::vector<std::string> axes = db->axes();
    for (const SweepRow& r : db->rows()) {
        if (r.index % shard.n != shard.k - 1)
            throw ConfigError(fmt::format("{}: point {} ({}) is not of shard {} of {} (a file renamed?)", file.string(),
                                          r.index, r.id, shard.k, shard.n));
        std::vector<std::pair<std::string, std::string>> values;
        for (const std::string& a : axes) values.emplace_back(a, r.params.value(a, ""));
        if (point_id(values) != r.id)
            throw ConfigError(fmt::format("{}: point {} ({}): its values give another id ({})", file.string(), r.index,
                                          r.id, point_id(values)));
    }
}

// A file removed when it goes out of scope, unless kept: a merge that fails leaves nothing.
class Scratch {
public:
    explicit Scratch(fs::path path) : path_(std::move(path)) { remove_database(path_); }
    ~Scratch() {
        if (!kept_) try {
                remove_database(path_);
            } catch (const EnvironmentError&) {}
    }
    const fs::path& path() const { return path_; }
    void keep() { kept_ = true; }

private:
    fs::path path_;
    bool kept_ = false;
};

}  // namespace

int sweep_command(const SweepOptions& options) {
    const SweepPlan plan = load_sweep(options.file);
    if (options.slurm && !options.shard.empty())
        throw ConfigError("--slurm runs the shards itself: give --slurm or --shard, not both");
    const Shard shard = parse_shard(options.shard);
    const fs::path dir = options.out.empty() ? fs::path("traces") / plan.name : fs::path(options.out);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw EnvironmentError(fmt::format("{}: cannot make the sweep folder: {}", dir.string(), ec.message()));
    prepare_folder(dir, dir / database_name(shard), plan, options.fresh, shard.n == 1);
    SweepStore store((dir / database_name(shard)).string(), plan.fingerprint);
    store.rows();  // read whole now: a damaged row is refused before any point runs, not after them all
    store.set_meta("name", plan.name);
    Json axes = Json::array();
    for (const SweepAxis& a : plan.axes) axes.push_back(a.key);
    store.set_meta("axes", axes.dump());
    if (options.slurm) return submit_to_slurm(options, plan, dir);

    // A point is done when its row says it ran; one that could not run is run again (its
    // cause may be gone: a file now there, a machine no longer out of memory) unless kept.
    std::vector<const SweepPoint*> todo;
    size_t mine = 0, retried = 0, kept = 0;
    for (const SweepPoint& p : plan.points)
        if (p.index % shard.n == shard.k - 1) {
            ++mine;
            const std::optional<int> exit = store.exit_of(p.id);
            const bool retry = exit && !point_ran(*exit) && !options.keep_failed;
            if (!exit || retry) todo.push_back(&p);
            retried += retry;
            kept += exit && !point_ran(*exit) && options.keep_failed;
        }
    if (!options.quiet && (todo.size() < mine || retried))
        std::fprintf(stderr, "surfvp: %s: %zu of %zu points already done in %s%s\n", plan.name.c_str(),
                     mine - todo.size(), mine, (dir / database_name(shard)).c_str(),
                     retried ? fmt::format("; {} that could not run are run again", retried).c_str()
                     : kept  ? fmt::format(" ({} that could not run kept as recorded: --keep-failed)", kept).c_str()
                             : "");
    // Each point is checked and prepared here, in this process (so a child inherits the frames,
    // the threshold calibration and the FHG sequences), then simulated in a child.
    Resimulation pool(options.jobs, dir / fmt::format(".scratch-{}", getpid()));
    size_t done = 0, errors = 0;
    ProgressLine progress(options.quiet, plan.name, 0.0, 0.2, 10.0);
    auto show = [&] {
        progress.steps(done, todo.size(), "points", false, errors ? fmt::format(", {} not run", errors) : "");
    };
    auto record = [&](const SweepPoint& p, const Json& result) {
        SweepRow row{p.index, p.id, params_of(p), 0, "", Json::object(), 0};
        if (result.contains("error")) {
            row.exit = result.value("exit", 3);
            row.error = result["error"].get<std::string>();
        } else {
            row.figures = result["figures"];
            row.exit = result["exit"].get<int>();
            row.wall_s = result["wall_time_s"].get<double>();
            if (result.contains("failure")) row.error = result["failure"].get<std::string>();
        }
        errors += !point_ran(row.exit);
        store.record(row);
        ++done;
        show();
    };
    // Points are checked and prepared as the children go, one ahead of the free slots, so this
    // process prepares the next while they simulate.
    size_t next = 0;
    std::function<void()> submit_next = [&] {
        while (next < todo.size()) {
            const SweepPoint* p = todo[next++];
            try {
                Config config = plan.config(*p);
                check_scenario(config);
                Resimulation::prepare(config);
                pool.submit(
                    std::move(config),
                    [p, &record, &submit_next](const Json& r) {
                        record(*p, r);
                        submit_next();
                    },
                    sweep_summary);
                return;
            } catch (const ConfigError& e) {
                record(*p, Json{{"error", e.what()}, {"exit", 2}});
            }
        }
    };
    for (unsigned i = 0; i <= pool.jobs(); ++i) submit_next();
    pool.run([&](size_t, size_t) {});
    progress.end();
    if (shard.n == 1) write_results(dir, store);
    if (!options.quiet)
        std::fprintf(stderr, "surfvp: %s: %zu points run (%zu not run)%s; %s in %s\n", plan.name.c_str(), done, errors,
                     budget_count(store.rows()).c_str(),
                     shard.n == 1 ? "results.md, results.csv, results.json and plots" : "shard database", dir.c_str());
    return exit_code(plan, shard, store);
}

int sweep_merge_command(const std::string& folder, bool partial) {
    const fs::path dir(folder), whole = fs::path(folder) / "sweep.db";
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw ConfigError(fmt::format("{}: {}", folder,
                                      fs::exists(fs::symlink_status(dir, ec))
                                          ? "not a folder (give the sweep's --out folder)"
                                          : "no such sweep folder"));
    const std::vector<ShardFile> shards = shard_files(dir);
    if (shards.empty())
        throw ConfigError(fmt::format("{}: holds no shard databases (shard-K-of-N.db) to merge", folder));
    const std::vector<std::string> missing = missing_shards(shards);
    if (!missing.empty() && !partial)
        throw ConfigError(
            fmt::format("{}: {}: their points would not be in the results; give --partial to merge the others", folder,
                        missing_text(missing)));
    // sweep.db, when there is one, is the sweep the shards must be of; else the first shard.
    const bool has_whole = fs::exists(whole, ec);
    const fs::path reference = has_whole ? whole : shards.front().path;
    const std::string fingerprint = SweepStore::fingerprint_of(reference.string());
    if (has_whole) check_merged(whole, fingerprint, reference.string(), {1, 1});
    for (const ShardFile& s : shards) check_merged(s.path, fingerprint, reference.string(), {s.k, s.n});

    // Merged under a temporary name beside sweep.db, renamed over it once everything is in: a
    // refusal or a failure leaves the folder as it was.
    Scratch merging(dir / fmt::format(".sweep.db.merging-{}", getpid()));
    size_t added = 0;
    {
        SweepStore merged(merging.path().string(), fingerprint);
        if (has_whole) merged.merge(whole.string());
        for (const ShardFile& s : shards) added += merged.merge(s.path.string());
    }
    fs::rename(merging.path(), whole, ec);
    if (ec)
        throw EnvironmentError(
            fmt::format("{}: cannot put the merged database in place: {}", whole.string(), ec.message()));
    merging.keep();

    const SweepStore store(whole.string(), fingerprint);
    Json notes = Json::object();
    if (!missing.empty()) notes["missing_shards"] = missing;
    write_results(dir, store, notes);
    const std::vector<SweepRow> rows = store.rows();
    std::fprintf(
        stderr, "surfvp: %s: %zu shard databases, %zu new points, %zu in all; results in %s%s\n",
        store.meta("name").c_str(), shards.size(), added, rows.size(), folder.c_str(),
        missing.empty()
            ? ""
            : fmt::format(" (partial: {}, their points are not in the results)", missing_text(missing)).c_str());
    std::vector<std::string> not_run;
    for (const SweepRow& r : rows)
        if (!point_ran(r.exit)) not_run.push_back(not_run_text(r.index, r.id, r.exit));
    return exit_for(store.meta("name"), not_run, "results.csv");
}

}  // namespace surfvp
