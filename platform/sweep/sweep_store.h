#pragma once
// A sweep's results in SQLite (sweep.db in its folder): one row per point, so that resuming
// is "which points have no row", a shard is a database of its own, and merging shards is one
// INSERT from each. The sweep's fingerprint (its identity: sweep_plan.h) is kept beside the
// rows: points of another sweep are never mixed in.
//
// A database is read as input: one that is not SQLite, has other tables, or holds a row whose
// values are not what a sweep writes is refused with ConfigError naming the file (and the
// point), never taken for a bug. EnvironmentError is for the machine refusing a read or write.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "platform/run/run.h"

struct sqlite3;

namespace surfvp {

struct SweepRow {
    size_t index = 0;
    std::string id;                 // the point's values as text
    nlohmann::ordered_json params;  // {key: value}
    int exit = 0;                   // the point's exit code as `surfvp run` gives it (0 passed, 1 missed, 6 broke, 2-5)
    std::string error;              // why it did not run, or ""
    nlohmann::ordered_json figures;  // frames/s, latency, bottleneck... (sweep.cpp)
    double wall_s = 0;
};

// Whether a point ran: it exited 0 (passed), 1 (missed its budget or a goal) or 6 (broke: its
// software stalled, failed or ran past `run.max_time`, a frame was lost), as `surfvp run`
// would; its row is a result. Any other exit (2 bad input, 3 a crash or a killed point, 4 a
// refused write, 5 out of memory) is a point that could not run, which a resumed sweep runs
// again.
inline bool point_ran(int exit) { return exit == kExitOk || exit == kExitFailed || exit == kExitBroken; }

// A row's columns as a database holds them, decoded and checked: params a JSON object of
// texts, figures a JSON object of numbers, texts, booleans or nulls (those the results read
// as numbers: numbers), index not negative, exit 0 to 255, texts UTF-8. Throws ConfigError
// naming `file` and the point.
SweepRow decode_sweep_row(const std::string& file, int64_t index, const std::string& id, const std::string& params,
                          int64_t exit, const std::string& error, const std::string& figures, double wall_s);

class SweepStore {
public:
    // Opens or creates `file`. Throws ConfigError when it holds another sweep (another
    // fingerprint) or is not a sweep database, EnvironmentError when it cannot be opened or
    // written.
    SweepStore(const std::string& file, const std::string& fingerprint);
    // Opens an existing database to read (a shard to merge). Throws ConfigError when it is not
    // a sweep database; its fingerprint is "" when it holds no sweep.
    static std::unique_ptr<SweepStore> read_only(const std::string& file);
    ~SweepStore();
    SweepStore(const SweepStore&) = delete;
    SweepStore& operator=(const SweepStore&) = delete;

    const std::string& file() const { return file_; }
    // What a sweep keeps beside its rows (its name, its axes): set once, read by sweep-merge.
    void set_meta(const std::string& key, const std::string& value);
    std::string meta(const std::string& key) const;
    // The axes the sweep recorded, in order (ConfigError when the record is damaged).
    std::vector<std::string> axes() const;
    // A database's fingerprint, to open another of the same sweep: "" when there is no such
    // file or it holds no sweep; ConfigError when it is not a sweep database.
    static std::string fingerprint_of(const std::string& file);

    // The exit code recorded for the point, or nothing when it has no row.
    std::optional<int> exit_of(const std::string& id) const;
    void record(const SweepRow& row);    // committed at once: a killed sweep keeps every row before
    std::vector<SweepRow> rows() const;  // in point order; ConfigError naming a damaged one
    // The rows of another database of the same sweep (a shard, checked by the caller); a row
    // that ran replaces one that could not. Returns how many points were new.
    size_t merge(const std::string& other);

private:
    SweepStore(const std::string& file, int flags);
    void exec(const std::string& sql) const;
    void check_tables() const;
    sqlite3* db_ = nullptr;
    std::string file_;
};

}  // namespace surfvp
