#pragma once
// `surfvp surf`, `surfvp eval`, `surfvp eval-seq` and `surfvp draw`: the float reference
// SURF and the paper's evaluation (distinguishability, repeatability, precision) from the
// command line, on any image or sequence.
#include <CLI/CLI.hpp>
#include <optional>

namespace surfvp {

class QualityCommands {
public:
    explicit QualityCommands(CLI::App& app);  // registers the subcommands and their options
    // After parsing: the exit code of the chosen command, or nothing if none of these was
    // chosen. Bad input throws ConfigError (exit 2).
    std::optional<int> run();

private:
    struct State;
    std::shared_ptr<State> state_;
};

}  // namespace surfvp
