#pragma once
// A progress line on stderr for a long command: once `delay` seconds of wall time have gone,
// rewritten in place on a terminal every `tty_every` seconds, or a line of its own elsewhere
// (a log) every `log_every` seconds; ended with a newline when it goes.
#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace surfvp {

class ProgressLine {
public:
    ProgressLine(bool quiet, std::string name, double delay, double tty_every, double log_every)
        : quiet_(quiet), name_(std::move(name)), tty_(isatty(2)), delay_(delay), every_(tty_ ? tty_every : log_every) {}
    ~ProgressLine() {
        if (shown_ && tty_) std::fputc('\n', stderr);
    }
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;

    double wall() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

    // Shows "surfvp: NAME: " and what `text(wall seconds)` returns, when it is time for a line.
    template <typename Text>
    void update(Text&& text) {
        const double now = wall();
        if (quiet_ || now < delay_ || now - last_ < every_) return;
        last_ = now;
        shown_ = true;
        std::fprintf(stderr, "%ssurfvp: %s: %s%s", tty_ ? "\r" : "", name_.c_str(), text(now).c_str(),
                     tty_ ? "" : "\n");
    }

private:
    bool quiet_;
    std::string name_;
    bool tty_;
    double delay_, every_;
    bool shown_ = false;
    double last_ = 0;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace surfvp
