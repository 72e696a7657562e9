#pragma once
// Line-oriented reading and atomic writing of the small text files the evaluation exchanges
// (keypoints, poses, homographies, image lists). Every parse error is a FormatError naming the
// file and line.
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "models/host/atomic_file.h"
#include "sw/eval/format_error.h"

namespace surfvp::eval {

class TextReader {
public:
    // Throws std::runtime_error naming the file when it cannot be opened. With `comments`,
    // everything from a '#' to the end of the line is ignored.
    explicit TextReader(std::filesystem::path file, bool comments = false);

    // Splits the next line holding at least one token into whitespace-separated tokens (views
    // into an internal buffer, valid until the next call). Blank lines are skipped; false at
    // the end of the file.
    bool next(std::vector<std::string_view>& tokens);

    // The raw text of the line last returned by next(), without its comment.
    const std::string& text() const { return line_text_; }
    std::size_t line() const { return line_; }
    const std::filesystem::path& file() const { return file_; }

    [[noreturn]] void fail(const std::string& problem) const;

    // A finite number; `what` names the field in the error message.
    double real(std::string_view token, const char* what) const;
    float real_float(std::string_view token, const char* what) const;
    // A number with an integral value in [0, max] ("1.0" is accepted: Mikolajczyk's files write
    // their headers that way).
    std::size_t count(std::string_view token, const char* what, std::size_t max) const;

private:
    std::filesystem::path file_;
    std::ifstream in_;
    bool comments_;
    std::string line_text_;
    std::size_t line_ = 0;
};

using surfvp::write_file_atomically;  // models/host/atomic_file.h

}  // namespace surfvp::eval
