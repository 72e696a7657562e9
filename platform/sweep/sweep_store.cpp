#include "platform/sweep/sweep_store.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sqlite3.h>

#include "models/host/atomic_file.h"
#include "platform/scenario/config.h"
#include "platform/scenario/scenario.h"

namespace surfvp {
namespace fs = std::filesystem;
namespace {

using Json = nlohmann::ordered_json;

// SQLite's refusal, as the user's input (a file that is not a sweep database, or a damaged
// one: ConfigError) or as the machine's (a read or write it refused: EnvironmentError).
[[noreturn]] void fail(sqlite3* db, int rc, const std::string& file, const char* what) {
    const std::string why = db ? sqlite3_errmsg(db) : sqlite3_errstr(rc);
    switch (rc & 0xff) {
        case SQLITE_NOTADB:
        case SQLITE_CORRUPT:
        case SQLITE_FORMAT:
        case SQLITE_ERROR:  // our statements are fixed: an error in one is the database's tables
        case SQLITE_MISMATCH:
        case SQLITE_SCHEMA:
        case SQLITE_RANGE:
        case SQLITE_CONSTRAINT:
        case SQLITE_TOOBIG:
        case SQLITE_NOMEM:  // a damaged file can declare a size SQLite will not allocate (found by fuzzing)
            throw ConfigError(fmt::format("{}: not a sweep database, or a damaged one ({}: {})", file, what, why));
        default:
            throw EnvironmentError(fmt::format("{}: sqlite {}: {}", file, what, why));
    }
}

// A prepared statement that finalises itself.
class Statement {
public:
    Statement(sqlite3* db, const std::string& sql, const std::string& file) : db_(db), file_(file) {
        if (const int rc = sqlite3_prepare_v2(db, sql.c_str(), -1, &s_, nullptr); rc != SQLITE_OK)
            fail(db_, rc, file_, "prepare");
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
        if (rc != SQLITE_DONE) fail(db_, rc, file_, "step");
        return false;
    }
    // The whole text, NUL bytes included.
    std::string text(int col) const {
        const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(s_, col));
        return p ? std::string(p, size_t(sqlite3_column_bytes(s_, col))) : "";
    }
    int64_t integer(int col) const { return sqlite3_column_int64(s_, col); }
    double real(int col) const { return sqlite3_column_double(s_, col); }
    int type(int col) const { return sqlite3_column_type(s_, col); }

private:
    sqlite3* db_;
    sqlite3_stmt* s_ = nullptr;
    std::string file_;
};

constexpr const char* kSchema =
    "CREATE TABLE IF NOT EXISTS sweep (key TEXT PRIMARY KEY, value TEXT NOT NULL);"
    "CREATE TABLE IF NOT EXISTS points ("
    "  idx INTEGER NOT NULL, id TEXT PRIMARY KEY, params TEXT NOT NULL, exit INTEGER NOT NULL,"
    "  error TEXT NOT NULL, figures TEXT NOT NULL, wall_s REAL NOT NULL);";
const std::vector<std::string> kSweepColumns = {"key", "value"};
const std::vector<std::string> kPointColumns = {"idx", "id", "params", "exit", "error", "figures", "wall_s"};

// The figures the results read as numbers (sweep_results.cpp: the Pareto objectives;
// sweep_plots.cpp: frames/s and the budget).
const char* const kNumericFigures[] = {"fps",    "budget_fps", "repeatability", "precision", "distinguishability",
                                       "bram36", "dsp48e",     "watts"};

const char* type_name(int sqlite_type) {
    switch (sqlite_type) {
        case SQLITE_INTEGER:
            return "an integer";
        case SQLITE_FLOAT:
            return "a real";
        case SQLITE_TEXT:
            return "text";
        case SQLITE_BLOB:
            return "a blob";
        default:
            return "null";
    }
}

Json parse_object(const std::string& where, const char* column, const std::string& text) {
    Json j;
    try {
        j = Json::parse(text);
    } catch (const Json::exception& e) {
        throw ConfigError(fmt::format("{}: {} is not JSON: {}", where, column, e.what()));
    }
    if (!j.is_object())
        throw ConfigError(fmt::format("{}: {} is a JSON {}, not an object", where, column, j.type_name()));
    return j;
}

// SQLite takes a file shorter than its header for an empty database (and would write over
// it): a file that has bytes must begin as an SQLite database does.
void check_header(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    std::string head(16, '\0');
    in.read(head.data(), 16);
    const auto got = size_t(in.gcount());
    if (got > 0 && head.compare(0, 16, std::string("SQLite format 3\0", 16)) != 0)
        throw ConfigError(fmt::format("{}: not a sweep database, or a damaged one (not an SQLite file)", file));
}

}  // namespace

SweepRow decode_sweep_row(const std::string& file, int64_t index, const std::string& id, const std::string& params,
                          int64_t exit, const std::string& error, const std::string& figures, double wall_s) {
    const std::string where = fmt::format("{}: point {} ({})", file, index, is_utf8(id) ? id : "id not UTF-8 text");
    if (index < 0) throw ConfigError(fmt::format("{}: its index is negative", where));
    if (id.empty() || !is_utf8(id)) throw ConfigError(fmt::format("{}: its id is empty or not UTF-8 text", where));
    if (exit < 0 || exit > 255) throw ConfigError(fmt::format("{}: exit {} is not an exit code", where, exit));
    if (!is_utf8(error)) throw ConfigError(fmt::format("{}: its error is not UTF-8 text", where));
    if (!std::isfinite(wall_s)) throw ConfigError(fmt::format("{}: its wall time is not a number", where));
    SweepRow row{size_t(index), id,    parse_object(where, "params", params),
                 int(exit),     error, parse_object(where, "figures", figures),
                 wall_s};
    for (const auto& [key, value] : row.params.items())
        if (!value.is_string())
            throw ConfigError(fmt::format("{}: params.{} is a JSON {}, not a text", where, key, value.type_name()));
    for (const auto& [key, value] : row.figures.items())
        if (value.is_structured())
            throw ConfigError(fmt::format("{}: figures.{} is a JSON {}, not a value", where, key, value.type_name()));
    for (const char* key : kNumericFigures)
        if (row.figures.contains(key) && !row.figures[key].is_number())
            throw ConfigError(
                fmt::format("{}: figures.{} is a JSON {}, not a number", where, key, row.figures[key].type_name()));
    return row;
}

SweepStore::SweepStore(const std::string& file, int flags) : file_(file) {
    check_header(file);
    if (sqlite3_open_v2(file.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
        const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
        sqlite3_close(db_);
        db_ = nullptr;
        throw EnvironmentError(fmt::format("{}: cannot open the sweep database: {}", file, why));
    }
    sqlite3_busy_timeout(db_, 10000);  // a merge reading while a shard writes waits, not fails
    try {
        check_tables();
    } catch (...) {
        sqlite3_close(db_);
        throw;
    }
}

// (Once the delegated constructor has returned, the destructor closes the database if the
// rest throws.)
SweepStore::SweepStore(const std::string& file, const std::string& fingerprint)
    : SweepStore(file, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE) {
    exec(kSchema);
    Statement get(db_, "SELECT value FROM sweep WHERE key = 'fingerprint'", file_);
    if (get.step()) {
        if (get.text(0) != fingerprint)
            throw ConfigError(
                fmt::format("{}: holds the points of another sweep; give --fresh to discard them and start over, "
                            "or another --out",
                            file));
    } else {
        Statement put(db_, "INSERT INTO sweep (key, value) VALUES ('fingerprint', ?)", file_);
        put.bind(1, fingerprint).step();
    }
}

std::unique_ptr<SweepStore> SweepStore::read_only(const std::string& file) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        throw ConfigError(fmt::format("{}: is not a sweep database (not a regular file)", file));
    return std::unique_ptr<SweepStore>(new SweepStore(file, SQLITE_OPEN_READONLY));
}

SweepStore::~SweepStore() { sqlite3_close(db_); }

void SweepStore::exec(const std::string& sql) const {
    char* message = nullptr;
    if (const int rc = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message); rc != SQLITE_OK) {
        sqlite3_free(message);
        fail(db_, rc, file_, "exec");
    }
}

// A database with tables of our names but other columns is another program's, or damaged:
// refused before a statement of ours meets it. (This first read also finds a file that is
// not SQLite.) SQLite's integrity check finds the damage it would otherwise read through,
// such as an index that lacks a row (found by tests/fuzz sweep_db: a point's row was there,
// but not when looked up by its id).
void SweepStore::check_tables() const {
    {
        Statement check(db_, "PRAGMA integrity_check(1)", file_);
        if (check.step() && check.text(0) != "ok")
            throw ConfigError(
                fmt::format("{}: not a sweep database, or a damaged one (integrity check: {})", file_, check.text(0)));
    }
    {  // another program's tables: a sweep would add its own beside them
        Statement others(db_,
                         "SELECT name FROM sqlite_master WHERE type = 'table' AND name NOT IN ('sweep', 'points') "
                         "AND name NOT LIKE 'sqlite_%'",
                         file_);
        if (others.step())
            throw ConfigError(fmt::format("{}: is not a sweep database: it holds a table '{}' a sweep's has not", file_,
                                          is_utf8(others.text(0)) ? others.text(0) : "?"));
    }
    for (const auto& [table, expected] :
         {std::make_pair("sweep", kSweepColumns), std::make_pair("points", kPointColumns)}) {
        Statement info(db_, fmt::format("PRAGMA table_info({})", table), file_);
        std::vector<std::string> columns;
        while (info.step()) columns.push_back(info.text(1));
        if (!columns.empty() && columns != expected)
            throw ConfigError(fmt::format("{}: is not a sweep database: its table {} has the columns ({}), not ({})",
                                          file_, table, fmt::join(columns, ", "), fmt::join(expected, ", ")));
    }
}

void SweepStore::set_meta(const std::string& key, const std::string& value) {
    Statement s(db_, "INSERT OR REPLACE INTO sweep (key, value) VALUES (?, ?)", file_);
    s.bind(1, key).bind(2, value).step();
}

std::string SweepStore::meta(const std::string& key) const {
    Statement has(db_, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'sweep'", file_);
    if (!has.step()) return "";  // a database that holds no sweep (read only: nothing was created)
    Statement s(db_, "SELECT value FROM sweep WHERE key = ?", file_);
    return s.bind(1, key).step() ? s.text(0) : "";
}

std::vector<std::string> SweepStore::axes() const {
    const std::string text = meta("axes");
    if (text.empty()) return {};
    // The axes name the plot files: each must be a parameter.
    const Json j = Json::parse(text, nullptr, false);
    const ConfigError damaged(
        fmt::format("{}: its record of the sweep's axes is damaged: {}", file_, text.substr(0, 200)));
    if (!j.is_array()) throw damaged;
    std::vector<std::string> out;
    for (const Json& a : j) {
        if (!a.is_string() || !find_parameter(a.get<std::string>())) throw damaged;
        out.push_back(a.get<std::string>());
    }
    return out;
}

std::string SweepStore::fingerprint_of(const std::string& file) {
    std::error_code ec;
    if (!fs::exists(file, ec)) return "";
    return read_only(file)->meta("fingerprint");
}

std::optional<int> SweepStore::exit_of(const std::string& id) const {
    Statement s(db_, "SELECT exit FROM points WHERE id = ?", file_);
    if (!s.bind(1, id).step()) return std::nullopt;
    if (s.type(0) != SQLITE_INTEGER || s.integer(0) < 0 || s.integer(0) > 255)
        throw ConfigError(fmt::format("{}: point ({}): its exit is not an exit code", file_, id));
    return int(s.integer(0));
}

void SweepStore::record(const SweepRow& row) {
    Statement s(
        db_,
        "INSERT OR REPLACE INTO points (idx, id, params, exit, error, figures, wall_s) VALUES (?, ?, ?, ?, ?, ?, ?)",
        file_);
    s.bind(1, int64_t(row.index))
        .bind(2, row.id)
        .bind(3, row.params.dump())
        .bind(4, int64_t(row.exit))
        .bind(5, row.error);
    s.bind(6, row.figures.dump()).bind(7, row.wall_s).step();
}

std::vector<SweepRow> SweepStore::rows() const {
    std::vector<SweepRow> out;
    Statement has(db_, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'points'", file_);
    if (!has.step()) return out;
    Statement s(db_, "SELECT idx, id, params, exit, error, figures, wall_s, rowid FROM points ORDER BY idx", file_);
    constexpr int kTypes[] = {SQLITE_INTEGER, SQLITE_TEXT, SQLITE_TEXT, SQLITE_INTEGER,
                              SQLITE_TEXT,    SQLITE_TEXT, SQLITE_FLOAT};
    while (s.step()) {
        for (int c = 0; c < 7; ++c)
            if (s.type(c) != kTypes[c] &&
                !(c == 6 && s.type(c) == SQLITE_INTEGER))  // a whole number of seconds is a real
                throw ConfigError(fmt::format("{}: point {} ({}): its {} is {}, not {}", file_,
                                              s.type(0) == SQLITE_INTEGER ? std::to_string(s.integer(0))
                                                                          : "in row " + std::to_string(s.integer(7)),
                                              s.type(1) == SQLITE_TEXT && is_utf8(s.text(1)) ? s.text(1) : "?",
                                              kPointColumns[size_t(c)], type_name(s.type(c)), type_name(kTypes[c])));
        out.push_back(
            decode_sweep_row(file_, s.integer(0), s.text(1), s.text(2), s.integer(3), s.text(4), s.text(5), s.real(6)));
    }
    return out;
}

size_t SweepStore::merge(const std::string& other) {
    {
        Statement attach(db_, "ATTACH DATABASE ? AS shard", file_);
        attach.bind(1, other).step();
    }
    const auto count = [&] {
        Statement n(db_, "SELECT count(*) FROM points", file_);
        n.step();
        return size_t(n.integer(0));
    };
    const size_t before = count();
    try {
        // A point the other database ran replaces one this one could not run (a shard run again).
        exec(
            "BEGIN;"
            "INSERT INTO points (idx, id, params, exit, error, figures, wall_s)"
            "  SELECT idx, id, params, exit, error, figures, wall_s FROM shard.points WHERE true"
            "  ON CONFLICT(id) DO UPDATE SET idx = excluded.idx, params = excluded.params, exit = excluded.exit,"
            "    error = excluded.error, figures = excluded.figures, wall_s = excluded.wall_s"
            "  WHERE points.exit NOT IN (0, 1) AND excluded.exit IN (0, 1);"
            "INSERT OR IGNORE INTO sweep SELECT key, value FROM shard.sweep;"
            "COMMIT;");
    } catch (...) {
        sqlite3_exec(db_, "ROLLBACK; DETACH DATABASE shard", nullptr, nullptr, nullptr);
        throw;
    }
    exec("DETACH DATABASE shard");
    return count() - before;
}

}  // namespace surfvp
