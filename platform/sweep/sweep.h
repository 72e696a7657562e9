#pragma once
// `surfvp sweep` and `surfvp sweep-merge` (docs/sweeps.md): the points of a sweep file run as
// re-simulations (platform/run/resimulation.h, the engine the verdict's analyses use too),
// `jobs` at a time, each recorded in the folder's SQLite database as it ends; then
// results.csv, results.json and a plot of frames/s against each axis, with the Pareto front
// marked.
#include <string>

namespace surfvp {

struct SweepOptions {
    std::string file;
    std::string out;     // default: traces/<sweep name>
    unsigned jobs = 0;   // 0: one per core
    std::string shard;   // "K/N": only the points whose index % N == K - 1, into shard-K-of-N.db
    unsigned slurm = 0;  // > 0: write and submit a Slurm job array of this many shards, and a merge after it
    bool quiet = false;
    // Start over: discard the folder's record of an earlier sweep (its databases, results and
    // plots) instead of refusing a sweep that differs from it.
    bool fresh = false;
    // Keep the rows of points that could not run (exit 2, 3, 4) as recorded, instead of
    // running them again.
    bool keep_failed = false;
};

// Runs the points not yet in the folder's database, and those recorded as not run (unless
// keep_failed); returns 0 when every point of the sweep (or shard) ran, whatever its verdict,
// 1 when some could not (the summary names them, their rows say why). Throws ConfigError for
// bad input.
int sweep_command(const SweepOptions& options);

// Merges DIR/shard-K-of-N.db (and DIR/sweep.db, when there is one) into DIR/sweep.db and
// writes the results. Everything is read and checked first: no shard, a missing shard (unless
// `partial`), an empty, foreign or damaged database is refused with ConfigError naming the
// file (and the point), and the folder is left as it was. Returns 0, or 1 when some merged
// point could not run.
int sweep_merge_command(const std::string& dir, bool partial = false);

}  // namespace surfvp
