// Fuzz target: the scenario loader (platform/scenario/scenario.h) with `--set` overrides.
//
// Input: a scenario file as text. Every line that starts with "#set " (a YAML comment, so the
// file reads the same without it) is also given as a `--set KEY=VALUE` override, in order, up
// to eight of them, as `surfvp run FILE --set ...` would.
//
// Expected answer to bad input: ConfigError (the CLI's exit code 2). Any other exception, a
// crash or a sanitizer report is a bug. For a scenario that loads, what the loader promises is
// checked too, each broken promise being a bug:
//   - every value it accepted reads back as a number of its kind (Config::base_value);
//   - the configuration as config.yaml writes it (Config::to_yaml) loads again as a scenario,
//     with the same values, name and description;
//   - the blocks' parameters come from it (iig_params, fhg_params, Fhg::register_limits,
//     uncontended_fills, what direct mode builds), or a ConfigError says why not.
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "platform/scenario/scenario.h"
#include "platform/soc.h"

namespace {
using namespace surfvp;

std::vector<std::string> set_lines(std::string_view text) {
    std::vector<std::string> sets;
    size_t at = 0;
    while (at < text.size() && sets.size() < 8) {
        const size_t end = std::min(text.find('\n', at), text.size());
        const std::string_view line = text.substr(at, end - at);
        if (line.rfind("#set ", 0) == 0) sets.emplace_back(line.substr(5));
        at = end + 1;
    }
    return sets;
}

void check_loaded(const Config& config) {
    for (const Config::Entry& e : config.entries()) {
        try {
            config.base_value(e.spec->key);
        } catch (const UnitError& error) {
            fuzz::bug(e.spec->key + " = '" + e.value + "' was accepted but does not read back: " + error.what());
        }
    }
    const std::string yaml = config.to_yaml();
    const std::string again_path = fuzz::write_scratch("config.yaml", yaml);
    Config again;
    try {
        again = load_scenario(again_path, {});
    } catch (const ConfigError& error) {
        fuzz::bug(std::string("config.yaml does not load again: ") + error.what() + "\n" + yaml);
    }
    if (again.name != config.name || again.description != config.description)
        fuzz::bug("config.yaml changes the name or the description:\n" + yaml);
    for (size_t k = 0; k < config.entries().size(); ++k)
        if (again.entries()[k].value != config.entries()[k].value)
            fuzz::bug("config.yaml changes " + config.entries()[k].spec->key + " from '" + config.entries()[k].value +
                      "' to '" + again.entries()[k].value + "'");
    iig_params(config);
    Fhg::register_limits(fhg_params(config));
    uncontended_fills(config);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    // An absolute path: the text parameters a scenario gives become absolute, so the
    // round trip through config.yaml cannot move them.
    const std::string path = fuzz::write_scratch("scenario.yaml", text);
    try {
        const Config config = load_scenario(path, set_lines(text));
        check_loaded(config);
    } catch (const ConfigError&) {
        // the loader's answer to a bad scenario
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
