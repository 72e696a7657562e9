#pragma once
// A progress line on stderr for a long command. On a terminal it is drawn at the first update
// once `delay` seconds have gone, then rewritten in place every `tty_every` seconds, and ended
// with a newline when it goes, so
// that what follows is a line of its own. Elsewhere (a pipe, a log) it says nothing, unless
// asked (--progress: ProgressLine::show_in_logs), then a line of its own every `log_every`
// seconds.
//
// steps() shows work of a known size with its time to go:
//   "surfvp: NAME: [#######.................] 12/40 points, 0:35 gone, 1:10 to go"
// A total that is an estimate (the verdict's break-even searches end when they find their
// value) is shown as "about N": it never changes, and the count stops short of it until the
// work is done.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <unistd.h>

#include <fmt/format.h>

namespace surfvp {

class ProgressLine {
public:
    ProgressLine(bool quiet, std::string name, double delay, double tty_every, double log_every)
        : tty_(isatty(2)),
          quiet_(quiet || (!tty_ && !in_logs())),
          name_(std::move(name)),
          delay_(delay),
          every_(tty_ ? tty_every : log_every) {}
    ~ProgressLine() { end(); }

    // Ends the line on a terminal, so that what follows is a line of its own; no more updates.
    void end() {
        if (shown_ && tty_) std::fputc('\n', stderr);
        shown_ = false;
        quiet_ = true;
    }
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;

    // --progress: progress lines also when stderr is not a terminal.
    static void show_in_logs(bool on) { in_logs() = on; }

    double wall() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

    // Shows "surfvp: NAME: " and what `text(wall seconds)` returns, when it is time for a line.
    template <typename Text>
    void update(Text&& text) {
        const double now = wall();
        if (quiet_ || now < delay_ || now - last_ < every_) return;
        last_ = now;
        shown_ = true;
        std::fprintf(stderr, "%ssurfvp: %s: %s%s", tty_ ? "\r" : "", name_.c_str(), text(now).c_str(),
                     tty_ ? "\x1b[K" : "\n");
    }

    // `done` of `total` `unit` ("re-simulations"), with a bar and the time to go; `about`: the
    // total is an estimate. `extra` follows the count (", 1 not run").
    void steps(size_t done, size_t total, const std::string& unit, bool about = false, const std::string& extra = "") {
        update([&](double wall_s) { return steps_text(done, total, unit, about, extra, wall_s); });
    }

    static std::string steps_text(size_t done, size_t total, const std::string& unit, bool about,
                                  const std::string& extra, double wall_s) {
        constexpr size_t width = 24;
        const size_t shown = about && total > 0 ? std::min(done, total - 1) : std::min(done, total);
        const size_t filled = total ? shown * width / total : width;
        const std::string eta = shown ? clock(wall_s / double(shown) * double(total - shown)) : "?";
        const std::string count =
            about ? fmt::format("{} of about {}", shown, total) : fmt::format("{}/{}", shown, total);
        return fmt::format("[{}{}] {} {}{}, {} gone, {}{} to go", std::string(filled, '#'),
                           std::string(width - filled, '.'), count, unit, extra, clock(wall_s), about ? "about " : "",
                           eta);
    }

    // "1:05", "1:02:03"
    static std::string clock(double seconds) {
        const long s = std::lround(seconds);
        return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
                         : fmt::format("{}:{:02}", s / 60, s % 60);
    }

private:
    static bool& in_logs() {
        static bool on = false;
        return on;
    }

    bool tty_;
    bool quiet_;
    std::string name_;
    double delay_, every_;
    bool shown_ = false;
    double last_ = -1e300;  // the first line comes as soon as `delay` has gone, however fast the steps
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace surfvp
