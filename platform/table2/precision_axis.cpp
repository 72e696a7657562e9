#include "platform/table2/precision_axis.h"

#include <fmt/format.h>

#include "platform/scenario/config.h"
#include "platform/scenario/parameters.h"

namespace surfvp {

PrecisionAxis parse_precision_axis(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
        throw ConfigError(fmt::format("--axis {}: give KEY=VALUE,VALUE,... (fhg.det_bits=24 bit,20 bit)", text));
    PrecisionAxis a{text.substr(0, eq), {}};
    if (!find_parameter(a.key))
        throw ConfigError(
            fmt::format("--axis {}: '{}' is not a parameter; a study varies one (fhg.det_bits, surf.haar, ...; "
                        "`surfvp params` lists them)",
                        text, a.key));
    for (size_t from = eq + 1;;) {
        const size_t comma = text.find(',', from);
        a.values.push_back(text.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
        if (a.values.back().find_first_not_of(' ') == std::string::npos)
            throw ConfigError(fmt::format("--axis {}: value {} is empty", text, a.values.size()));
        if (comma == std::string::npos) break;
        from = comma + 1;
    }
    return a;
}

std::vector<PrecisionAxis> parse_axes(const std::vector<std::string>& given, std::vector<PrecisionAxis> defaults) {
    std::vector<PrecisionAxis> axes;
    for (const std::string& a : given) {
        axes.push_back(parse_precision_axis(a));
        for (size_t i = 0; i + 1 < axes.size(); ++i)
            if (axes[i].key == axes.back().key)
                throw ConfigError(fmt::format("--axis {}: '{}' has an --axis already ({}); give its values in one", a,
                                              axes.back().key, given[i]));
    }
    return axes.empty() ? defaults : axes;
}

}  // namespace surfvp
