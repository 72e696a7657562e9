// Stored sequences: what is read back is what was generated, field by field; a file that is
// not one for its key is made again; concurrent runs share the folder.
#include <cstdlib>
#include <optional>
#include <filesystem>
#include <fstream>
#include <functional>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <sys/stat.h>
#include <unistd.h>

#include "models/host/disk_cache.h"
#include "models/fhg/sequence_cache.h"

namespace surfvp::fhg {
namespace {
namespace fs = std::filesystem;

void expect_same(const Sequence& a, const Sequence& b) {
    EXPECT_EQ(a.interval, b.interval);
    EXPECT_EQ(a.span, b.span);
    EXPECT_EQ(a.optimal_cycles, b.optimal_cycles);
    EXPECT_EQ(a.optimal_limit, b.optimal_limit);
    EXPECT_EQ(a.spread, b.spread);
    EXPECT_EQ(a.reads_per_block, b.reads_per_block);
    EXPECT_EQ(a.distinct_reads_per_block, b.distinct_reads_per_block);
    EXPECT_EQ(a.words_delivered, b.words_delivered);
    ASSERT_EQ(a.steps.size(), b.steps.size());
    for (size_t i = 0; i < a.steps.size(); ++i) {
        const Step &s = a.steps[i], &t = b.steps[i];
        ASSERT_EQ(std::tie(s.cycle, s.bus, s.x, s.y), std::tie(t.cycle, t.bus, t.x, t.y)) << "step " << i;
        ASSERT_EQ(s.taps.size(), t.taps.size()) << "step " << i;
        for (size_t k = 0; k < s.taps.size(); ++k)
            ASSERT_EQ(std::tie(s.taps[k].triple_mac, s.taps[k].lane, s.taps[k].coefficient, s.taps[k].response),
                      std::tie(t.taps[k].triple_mac, t.taps[k].lane, t.taps[k].coefficient, t.taps[k].response))
                << "step " << i << " tap " << k;
    }
}

fs::path fresh_folder(const char* name) {
    const fs::path dir = fs::temp_directory_path() / fmt::format("surfvp_{}_{}", name, ::getpid());
    fs::remove_all(dir);
    return dir;
}

fs::path only_file(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
    EXPECT_EQ(files.size(), 1u);
    return files.empty() ? fs::path() : files[0];
}

TEST(SequenceCache, TextReadsBackAsTheSameSequence) {
    SequenceParams p;
    for (auto [word, scheduler, buses] :
         {std::tuple{BusWord::quad, Scheduler::basic, 4u}, std::tuple{BusWord::scalar, Scheduler::improved, 2u},
          std::tuple{BusWord::pair, Scheduler::improved, 6u}}) {
        p.bus_word = word, p.scheduler = scheduler, p.read_buses = buses;
        const Sequence s = generate_sequence(p);
        const auto back = read_sequence_text(sequence_text(sequence_key(p), s), sequence_key(p));
        ASSERT_TRUE(back.has_value()) << bus_word_name(word);
        expect_same(*back, s);
    }
}

TEST(SequenceCache, KeyNamesEveryParameterAndTheGenerator) {
    SequenceParams p;
    const std::string key = sequence_key(p);
    for (const auto& change : std::vector<std::function<void(SequenceParams&)>>{
             [](SequenceParams& q) { q.read_buses = 6; }, [](SequenceParams& q) { q.triple_macs = 17; },
             [](SequenceParams& q) { q.fifo_lines = 40; }, [](SequenceParams& q) { q.x3_cycles = 1; },
             [](SequenceParams& q) { q.bus_word = BusWord::pair; }, [](SequenceParams& q) { q.reuse = false; },
             [](SequenceParams& q) { q.line_fifo = LineFifo::tdp; },
             [](SequenceParams& q) { q.line_fifo = LineFifo::banked; },
             [](SequenceParams& q) { q.scheduler = Scheduler::improved; }, [](SequenceParams& q) { q.attempts = 3; }}) {
        SequenceParams q = p;
        change(q);
        EXPECT_NE(sequence_key(q), key);
    }
    // "generator " and the build's fingerprint: 16 hex digits.
    ASSERT_GT(key.size(), 27u);
    EXPECT_EQ(key.substr(0, 10), "generator ") << key;
    EXPECT_EQ(key.find_first_not_of("0123456789abcdef", 10), 26u) << key;
}

TEST(SequenceCache, AStoredFileIsReadAndABadOneMadeAgain) {
    const fs::path dir = fresh_folder("seqcache");
    SequenceParams p;
    p.attempts = 2;
    const Sequence generated = generate_sequence(p);
    expect_same(stored_sequence(p, dir), generated);
    const fs::path file = only_file(dir);
    // Read back: a (valid) file whose figures were changed gives the changed figures.
    Sequence changed = generated;
    changed.interval += 1000;
    { std::ofstream(file) << cache_entry(sequence_key(p), sequence_text(sequence_key(p), changed)); }
    EXPECT_EQ(stored_sequence(p, dir).interval, generated.interval + 1000);
    // Cut short, of another key, not a sequence at all, without its seal, or with a flipped
    // bit: made again and stored again.
    const std::string text = sequence_text(sequence_key(p), generated);
    const std::string entry = cache_entry(sequence_key(p), text);
    std::string flipped = entry;  // a bit of the last step's last figure flipped, the checksum left
    flipped[flipped.size() - 2] ^= 1;
    for (const std::string& bad :
         {entry.substr(0, entry.size() / 2), "generator 0000 " + entry, std::string("hello\n"), text, flipped}) {
        { std::ofstream(file) << bad; }
        expect_same(stored_sequence(p, dir), generated);
        std::ifstream in(file);
        EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), entry);
    }
    // A FIFO or a link to an endless device under the entry's name: made again, never blocking.
    for (const bool fifo : {true, false}) {
        fs::remove(file);
        if (fifo)
            ASSERT_EQ(::mkfifo(file.c_str(), 0644), 0);
        else
            fs::create_symlink("/dev/zero", file);
        expect_same(stored_sequence(p, dir), generated);
    }
    fs::remove_all(dir);
}

TEST(SequenceCache, AFolderThatCannotBeWrittenCostsOnlyTime) {
    const fs::path blocker = fresh_folder("seqcache_file");
    { std::ofstream(blocker) << "a file where the folder should be"; }
    SequenceParams p;
    p.attempts = 2;
    expect_same(stored_sequence(p, blocker / "cache"), generate_sequence(p));
    fs::remove(blocker);
}

TEST(SequenceCache, ConcurrentRunsShareTheFolder) {
    const fs::path dir = fresh_folder("seqcache_shared");
    SequenceParams p;
    p.attempts = 4;
    std::vector<pid_t> children;
    for (int i = 0; i < 4; ++i) {
        const pid_t pid = fork();
        if (pid == 0) {
            const Sequence s = stored_sequence(p, dir);
            _exit(s.interval == generate_sequence(p).interval ? 0 : 1);
        }
        children.push_back(pid);
    }
    for (pid_t pid : children) {
        int status = 0;
        waitpid(pid, &status, 0);
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
    only_file(dir);  // no temporaries left behind
    const auto text = read_cached_in(dir, "sequence", sequence_key(p));
    ASSERT_TRUE(text.has_value());
    const auto back = read_sequence_text(*text, sequence_key(p));
    ASSERT_TRUE(back.has_value());
    expect_same(*back, generate_sequence(p));
    fs::remove_all(dir);
}

TEST(SequenceCache, FolderFromTheEnvironment) {
    auto saved = [](const char* name) {
        const char* v = std::getenv(name);
        return v ? std::optional<std::string>(v) : std::nullopt;
    };
    const auto cache = saved("SURFVP_CACHE"), xdg = saved("XDG_CACHE_HOME");
    setenv("SURFVP_CACHE", "off", 1);
    EXPECT_FALSE(sequence_cache_folder().has_value());
    setenv("SURFVP_CACHE", "/some/where", 1);
    EXPECT_EQ(sequence_cache_folder(), fs::path("/some/where"));
    unsetenv("SURFVP_CACHE");
    setenv("XDG_CACHE_HOME", "/xdg", 1);
    EXPECT_EQ(sequence_cache_folder(), fs::path("/xdg/surfvp"));
    if (cache) setenv("SURFVP_CACHE", cache->c_str(), 1);
    if (xdg)
        setenv("XDG_CACHE_HOME", xdg->c_str(), 1);
    else
        unsetenv("XDG_CACHE_HOME");
}

}  // namespace
}  // namespace surfvp::fhg
