#pragma once
// A sweep's results in SQLite (sweep.db in its folder): one row per point, so that resuming
// is "which points have no row", a shard is a database of its own, and merging shards is one
// INSERT from each. The sweep's fingerprint (its base scenario and fixed parameters) is kept
// beside the rows: points of another sweep are never mixed in.
#include <optional>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

struct sqlite3;

namespace surfvp {

struct SweepRow {
    size_t index = 0;
    std::string id;                // the point's values as text
    nlohmann::ordered_json params;  // {key: value}
    int exit = 0;                  // the point's exit code as `surfvp run` gives it (0 passed, 1 failed a check, 2, 3)
    std::string error;             // why it did not run, or ""
    nlohmann::ordered_json figures;  // frames/s, latency, bottleneck... (sweep.cpp)
    double wall_s = 0;
};

// Whether a point ran: it exited 0 (passed) or 1 (failed a check, missed its budget, or its
// software did not finish), as `surfvp run` would; its row is a result. Any other exit (2 bad
// input, 3 a crash or a killed point, 4 a refused write) is a point that could not run, which
// a resumed sweep runs again.
inline bool point_ran(int exit) { return exit == 0 || exit == 1; }

class SweepStore {
public:
    // Opens or creates `file`. Throws ConfigError when it holds another sweep (another
    // fingerprint), EnvironmentError when it cannot be opened or written.
    SweepStore(const std::string& file, const std::string& fingerprint);
    ~SweepStore();
    SweepStore(const SweepStore&) = delete;
    SweepStore& operator=(const SweepStore&) = delete;

    // What a sweep keeps beside its rows (its name, its axes): set once, read by sweep-merge.
    void set_meta(const std::string& key, const std::string& value);
    std::string meta(const std::string& key) const;
    // A database's fingerprint, to open another of the same sweep ("" when it has none).
    static std::string fingerprint_of(const std::string& file);

    // The exit code recorded for the point, or nothing when it has no row.
    std::optional<int> exit_of(const std::string& id) const;
    void record(const SweepRow& row);  // committed at once: a killed sweep keeps every row before
    std::vector<SweepRow> rows() const;  // in point order
    // The rows of another sweep database of the same sweep (a shard); returns how many were new.
    size_t merge(const std::string& other);

private:
    void exec(const std::string& sql) const;
    sqlite3* db_ = nullptr;
    std::string file_;
};

}  // namespace surfvp
