// Fuzz target: what `surfvp compare` reads back from a run folder or a sweep's results
// (platform/report/json_input.h: parse_json and the checked lookups; platform/compare/
// run_figures.h: all_figures), someone else's files, so untrusted.
//
// Input: the JSON text. Its first line, when it starts with '/', is also a JSON pointer looked
// up with every checked accessor.
//
// Expected answer to a malformed or too deeply nested text: ConfigError. Any other exception,
// a crash (a deep nesting once overflowed compare's stack) or a sanitizer report is a bug, and
// so is a figure that is not a number.
#include <string>

#include "fuzz_support.h"
#include "platform/compare/run_figures.h"
#include "platform/scenario/config.h"
#include "platform/report/json_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace surfvp;
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::string pointer = text.rfind('/', 0) == 0 ? text.substr(0, text.find('\n')) : "/points/0/point";
    try {
        const nlohmann::ordered_json j =
            parse_json(text.rfind('/', 0) == 0 ? text.substr(pointer.size()) : text, "fuzz");
        const nlohmann::ordered_json figures = all_figures(j);  // items() of a temporary would dangle
        for (const auto& [path, value] : figures.items())
            if (!value.is_number()) fuzz::bug("the figure " + path + " is not a number");
        const nlohmann::ordered_json& at = value_at(j, pointer);
        if (number_at(j, pointer, 7) != (at.is_number() ? at.get<double>() : 7))
            fuzz::bug("number_at disagrees with value_at");
        text_at(j, pointer);
        flag_at(j, pointer);
    } catch (const ConfigError&) {
        // the answer to a text that is not JSON or nests too deep
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
