#include "sw/eval/format_error.h"

namespace surfvp::eval {

namespace {

std::string describe(const std::filesystem::path& file, std::size_t line, const std::string& problem) {
    std::string where = file.string();
    if (line > 0) where += ":" + std::to_string(line);
    return where + ": " + problem;
}

}  // namespace

FormatError::FormatError(const std::filesystem::path& file, std::size_t line, const std::string& problem)
    : std::runtime_error(describe(file, line, problem)), file_(file), line_(line), problem_(problem) {}

}  // namespace surfvp::eval
