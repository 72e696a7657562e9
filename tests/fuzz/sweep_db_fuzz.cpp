// Fuzz target: the sweep database reader (platform/sweep/sweep_store.h): what a resumed sweep
// and sweep-merge read from sweep.db and shard-K-of-N.db.
//
// Input, one of two kinds:
//   - an SQLite file (it begins with SQLite's header, "SQLite format 3\0"): written as
//     sweep.db in a scratch folder and read as sweep-merge reads a shard (read only: its
//     fingerprint, axes and rows), then as a resumed sweep reads its database (opened to
//     write with a fingerprint: its rows, and the exit code of each row's point);
//   - anything else: a row's params and figures as a database holds them (JSON text), split
//     at the first newline, through decode_sweep_row.
//
// Expected answer to bad input: ConfigError (a database that is not a sweep's, or a damaged
// one; exit code 2). Any other exception (EnvironmentError too: a scratch file is always
// there to be read and written), a crash, a sanitizer report or a hang is a bug. For a row
// that decodes, what the results rely on is checked: params and figures dump as JSON (UTF-8),
// every param is text, and the figures the results read as numbers read as numbers.
#include <string>

#include "fuzz_support.h"
#include "platform/scenario/config.h"
#include "platform/sweep/sweep_store.h"

namespace {
using namespace surfvp;

void check_row(const SweepRow& row) {
    try {
        (void)row.params.dump();
        (void)row.figures.dump();
        for (const auto& [key, value] : row.params.items()) (void)value.get<std::string>();
        for (const char* key :
             {"fps", "budget_fps", "repeatability", "precision", "distinguishability", "bram36", "dsp48e", "watts"})
            (void)row.figures.value(key, 0.0);
        (void)nlohmann::ordered_json({row.id, row.error}).dump();
    } catch (const nlohmann::json::exception& e) {
        fuzz::bug(std::string("a decoded row the results cannot read: ") + e.what());
    }
    if (!point_ran(row.exit) && (row.exit < 0 || row.exit > 255)) fuzz::bug("an exit code out of 0..255 decoded");
}

void read_database(const std::string& bytes) {
    const std::string path = fuzz::write_scratch("sweep.db", bytes);
    for (const char* suffix : {"-journal", "-wal", "-shm"}) fuzz::remove_scratch(std::string("sweep.db") + suffix);
    std::string fingerprint;
    {
        const auto shard = SweepStore::read_only(path);
        fingerprint = shard->meta("fingerprint");
        shard->axes();
        for (const SweepRow& row : shard->rows()) check_row(row);
    }
    SweepStore store(path, fingerprint.empty() ? "{}" : fingerprint);
    for (const SweepRow& row : store.rows()) {
        check_row(row);
        if (store.exit_of(row.id) != row.exit) fuzz::bug("exit_of(" + row.id + ") is not the row's exit");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        if (bytes.compare(0, 16, std::string("SQLite format 3\0", 16)) == 0) {
            read_database(bytes);
        } else {
            const size_t newline = std::min(bytes.find('\n'), bytes.size());
            const std::string params = bytes.substr(0, newline),
                              figures = newline < size ? bytes.substr(newline + 1) : "{}";
            check_row(decode_sweep_row("sweep.db", 1, "plb2.width=64 bit", params, 0, "", figures, 0.5));
        }
    } catch (const ConfigError&) {
        // the reader's answer to a database that is not a sweep's, or a damaged one
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
