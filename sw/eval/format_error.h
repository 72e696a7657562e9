#pragma once
// The one error type of the evaluation's readers: a file that exists but does not say what its
// format requires. The message names the file, the line and the problem, so that a bad file
// out of a thousand-frame run can be found and fixed by hand.
#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace surfvp::eval {

class FormatError : public std::runtime_error {
public:
    // `line` is 1-based; 0 means the problem concerns the file as a whole.
    FormatError(const std::filesystem::path& file, std::size_t line, const std::string& problem);

    const std::filesystem::path& file() const { return file_; }
    std::size_t line() const { return line_; }
    const std::string& problem() const { return problem_; }

private:
    std::filesystem::path file_;
    std::size_t line_;
    std::string problem_;
};

}  // namespace surfvp::eval
