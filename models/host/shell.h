#pragma once
// Commands surfvp hands to the shell (sh -c): the sweep's Slurm submissions, the calibration's
// and the synthesis's tools.
#include <string>

namespace surfvp {

// `text` as one shell word: in single quotes, each ' written as '\''.
std::string shell_quoted(const std::string& text);
// The first line `command` prints on its standard output, without its line end; "" when it
// prints nothing or cannot be started (a tool's version, or whether it is there at all).
std::string first_output_line(const std::string& command);

}  // namespace surfvp
