#pragma once
// Every scenario parameter, declared once beside the code that reads it: a block's beside its
// Params (models/*/*_params.cpp, models/common/parameter.h), the platform's beside their
// readers (platform/catalog.h lists where). Each has its key ("section.name"), the kind
// of value (and so its units), its default, its range, a one-line description, and the source
// of the default or the assumption behind it ([S] sourced, [D] derived, [A] assumed; see
// docs/parameters.md, which `surfvp params` prints).
#include <string>
#include <string_view>
#include <vector>

#include "models/common/parameter.h"
#include "models/plb/plb_bus.h"

namespace surfvp {

// The two PLBs' declarations (models/plb/plb_params.cpp), by bus name.
struct PlbDeclaration {
    std::string bus;
    ParamTable<PlbBus::Params> table;
};
const std::vector<PlbDeclaration>& plb_declarations();

// Every parameter, in the order docs/parameters.md lists them. Defined by the chip's catalog
// (platform/catalog.cpp), which gathers the declarations.
const std::vector<ParamSpec>& parameter_table();
const ParamSpec* find_parameter(std::string_view key);

// The closest known key to a misspelt one, or "" when none is close.
std::string closest_parameter(std::string_view key);

// Parses `text` as a value of `spec` and checks its range; returns the value in the kind's
// base unit. Throws UnitError with a message naming what is wrong.
double parse_value(const ParamSpec& spec, const std::string& text);
// The other way: a value in the kind's base unit as a scenario writes it ("118.353 MHz").
std::string format_value(const ParamSpec& spec, double value);

// What values of this kind look like, for messages and docs ("a frequency, e.g. 100 MHz").
std::string describe_kind(const ParamSpec& spec);

// The parameters that have an assumption band, in table order.
std::vector<const ParamSpec*> band_parameters();

// docs/parameters.md: the whole table as Markdown.
std::string parameters_markdown();

}  // namespace surfvp
