// Fuzz target: `surfvp precision --axis KEY=V1,V2,...` (platform/table2/precision_axis.h),
// once a crash after every point had run when the key was no parameter.
//
// Input: the option's text.
//
// Expected answer to a malformed axis: ConfigError. Any other exception, a crash or a sanitizer
// report is a bug, and so is an axis returned that is not what the parser promises: a key
// that is a parameter, at least one value, none empty.
#include <string>

#include "fuzz_support.h"
#include "platform/scenario/config.h"
#include "platform/scenario/parameters.h"
#include "platform/table2/precision_axis.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace surfvp;
    try {
        const PrecisionAxis a = parse_precision_axis(std::string(reinterpret_cast<const char*>(data), size));
        if (!find_parameter(a.key)) fuzz::bug("the axis key " + a.key + " is no parameter");
        if (a.values.empty()) fuzz::bug("an axis without values");
        for (const std::string& v : a.values)
            if (v.find_first_not_of(' ') == std::string::npos) fuzz::bug("an empty value");
    } catch (const ConfigError&) {
        // the parser's answer to a malformed axis
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
