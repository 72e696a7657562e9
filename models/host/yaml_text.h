#pragma once
// YAML text through yaml-cpp, with yaml-cpp 0.7's known hangs refused first, and any other
// text it would never finish parsing stopped (a count of its parse events: yaml_text.cpp).
//
// Debian 12's yaml-cpp 0.7.0 never returns (it builds nodes until memory runs out) on a ','
// where a top-level node begins: as a document's first token (",", ",: a", "--- ,", a comment
// then ","), at column 0 ("- a\n,"), or after such a node's tag or anchor ("!t ,", "&a ,",
// "!,"). Found by tests/fuzz scenario (",: e!Un", then "!s,et ..."). Such text is never valid
// YAML: a ',' only separates the entries of a flow collection, and no node begins with one.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace surfvp {

// The 1-based line of the first ',' that would hang yaml-cpp, or 0 when there is none.
std::size_t yaml_hang_line(const std::string& text);

// YAML::LoadAll / YAML::Load after those checks: a YAML::ParserException (with the line) for
// text that would hang, as for any other text yaml-cpp refuses.
std::vector<YAML::Node> load_all_yaml(const std::string& text);
YAML::Node load_yaml(const std::string& text);

}  // namespace surfvp
