#include "models/host/shell.h"

#include <cstdio>

namespace surfvp {

std::string shell_quoted(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string first_output_line(const std::string& command) {
    FILE* pipe = ::popen(command.c_str(), "r");
    char line[256] = {};
    if (pipe) {
        if (!std::fgets(line, sizeof line, pipe)) line[0] = 0;
        ::pclose(pipe);
    }
    std::string s = line;
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    return s;
}

}  // namespace surfvp
