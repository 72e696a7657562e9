#include "platform/sweep/sweep_store.h"

#include <fmt/format.h>
#include <sqlite3.h>

#include "models/common/atomic_file.h"
#include "platform/scenario/config.h"

namespace surfvp {
namespace {

using Json = nlohmann::ordered_json;

// A prepared statement that finalises itself.
class Statement {
public:
    Statement(sqlite3* db, const std::string& sql, const std::string& file) : db_(db), file_(file) {
        if (sqlite3_prepare_v2(db, sql.c_str(), -1, &s_, nullptr) != SQLITE_OK) fail("prepare");
    }
    ~Statement() { sqlite3_finalize(s_); }
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;

    Statement& bind(int i, const std::string& text) {
        sqlite3_bind_text(s_, i, text.c_str(), int(text.size()), SQLITE_TRANSIENT);
        return *this;
    }
    Statement& bind(int i, int64_t n) {
        sqlite3_bind_int64(s_, i, n);
        return *this;
    }
    Statement& bind(int i, double x) {
        sqlite3_bind_double(s_, i, x);
        return *this;
    }
    bool step() {
        const int rc = sqlite3_step(s_);
        if (rc == SQLITE_ROW) return true;
        if (rc != SQLITE_DONE) fail("step");
        return false;
    }
    std::string text(int col) const {
        const auto* p = sqlite3_column_text(s_, col);
        return p ? reinterpret_cast<const char*>(p) : "";
    }
    int64_t integer(int col) const { return sqlite3_column_int64(s_, col); }
    double real(int col) const { return sqlite3_column_double(s_, col); }

private:
    [[noreturn]] void fail(const char* what) const {
        throw EnvironmentError(fmt::format("{}: sqlite {}: {}", file_, what, sqlite3_errmsg(db_)));
    }
    sqlite3* db_;
    sqlite3_stmt* s_ = nullptr;
    std::string file_;
};

constexpr const char* kSchema =
    "CREATE TABLE IF NOT EXISTS sweep (key TEXT PRIMARY KEY, value TEXT NOT NULL);"
    "CREATE TABLE IF NOT EXISTS points ("
    "  idx INTEGER NOT NULL, id TEXT PRIMARY KEY, params TEXT NOT NULL, exit INTEGER NOT NULL,"
    "  error TEXT NOT NULL, figures TEXT NOT NULL, wall_s REAL NOT NULL);";

}  // namespace

SweepStore::SweepStore(const std::string& file, const std::string& fingerprint) : file_(file) {
    if (sqlite3_open(file.c_str(), &db_) != SQLITE_OK) {
        const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
        sqlite3_close(db_);
        throw EnvironmentError(fmt::format("{}: cannot open the sweep database: {}", file, why));
    }
    sqlite3_busy_timeout(db_, 10000);  // a merge reading while a shard writes waits, not fails
    exec(kSchema);
    Statement get(db_, "SELECT value FROM sweep WHERE key = 'fingerprint'", file_);
    if (get.step()) {
        if (get.text(0) != fingerprint)
            throw ConfigError(fmt::format("{}: holds the points of another sweep (its base scenario or fixed parameters "
                                          "differ, or another surfvp made it); give another --out, or remove the folder",
                                          file));
    } else {
        Statement put(db_, "INSERT INTO sweep (key, value) VALUES ('fingerprint', ?)", file_);
        put.bind(1, fingerprint).step();
    }
}

SweepStore::~SweepStore() { sqlite3_close(db_); }

void SweepStore::exec(const std::string& sql) const {
    char* message = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
        const std::string why = message ? message : "unknown";
        sqlite3_free(message);
        throw EnvironmentError(fmt::format("{}: sqlite: {}", file_, why));
    }
}

void SweepStore::set_meta(const std::string& key, const std::string& value) {
    Statement s(db_, "INSERT OR REPLACE INTO sweep (key, value) VALUES (?, ?)", file_);
    s.bind(1, key).bind(2, value).step();
}

std::string SweepStore::meta(const std::string& key) const {
    Statement s(db_, "SELECT value FROM sweep WHERE key = ?", file_);
    return s.bind(1, key).step() ? s.text(0) : "";
}

std::string SweepStore::fingerprint_of(const std::string& file) {
    sqlite3* db = nullptr;
    std::string out;
    if (sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
        sqlite3_stmt* s = nullptr;
        if (sqlite3_prepare_v2(db, "SELECT value FROM sweep WHERE key = 'fingerprint'", -1, &s, nullptr) == SQLITE_OK &&
            sqlite3_step(s) == SQLITE_ROW)
            out = reinterpret_cast<const char*>(sqlite3_column_text(s, 0));
        sqlite3_finalize(s);
    }
    sqlite3_close(db);
    return out;
}

std::optional<int> SweepStore::exit_of(const std::string& id) const {
    Statement s(db_, "SELECT exit FROM points WHERE id = ?", file_);
    return s.bind(1, id).step() ? std::optional<int>(int(s.integer(0))) : std::nullopt;
}

void SweepStore::record(const SweepRow& row) {
    Statement s(db_, "INSERT OR REPLACE INTO points (idx, id, params, exit, error, figures, wall_s) VALUES (?, ?, ?, ?, ?, ?, ?)",
                file_);
    s.bind(1, int64_t(row.index)).bind(2, row.id).bind(3, row.params.dump()).bind(4, int64_t(row.exit)).bind(5, row.error);
    s.bind(6, row.figures.dump()).bind(7, row.wall_s).step();
}

std::vector<SweepRow> SweepStore::rows() const {
    std::vector<SweepRow> out;
    Statement s(db_, "SELECT idx, id, params, exit, error, figures, wall_s FROM points ORDER BY idx", file_);
    while (s.step())
        out.push_back({size_t(s.integer(0)), s.text(1), Json::parse(s.text(2)), int(s.integer(3)), s.text(4),
                       Json::parse(s.text(5)), s.real(6)});
    return out;
}

size_t SweepStore::merge(const std::string& other) {
    // The other database must be of this sweep.
    if (fingerprint_of(other) != meta("fingerprint"))
        throw ConfigError(fmt::format("{}: is not a shard of this sweep (another fingerprint, or not a sweep database)", other));
    {
        Statement attach(db_, "ATTACH DATABASE ? AS shard", file_);
        attach.bind(1, other).step();
    }
    const int before = sqlite3_total_changes(db_);
    exec("INSERT OR IGNORE INTO points SELECT * FROM shard.points");
    const size_t added = size_t(sqlite3_total_changes(db_) - before);
    exec("INSERT OR IGNORE INTO sweep SELECT * FROM shard.sweep");
    exec("DETACH DATABASE shard");
    return added;
}

}  // namespace surfvp
