#include "sw/eval/text_io.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace surfvp::eval {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

void split(std::string_view text, std::vector<std::string_view>& tokens) {
    tokens.clear();
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && is_space(text[i])) ++i;
        std::size_t start = i;
        while (i < text.size() && !is_space(text[i])) ++i;
        if (i > start) tokens.push_back(text.substr(start, i - start));
    }
}

// std::from_chars is locale-independent (strtod would read "0,5" under a German locale) but
// does not take a leading '+', which some writers emit.
template <typename T>
bool parse_number(std::string_view token, T& value) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
    const char* end = token.data() + token.size();
    auto [ptr, ec] = std::from_chars(token.data(), end, value);
    return ec == std::errc() && ptr == end;
}

}  // namespace

TextReader::TextReader(std::filesystem::path file, bool comments)
    : file_(std::move(file)), in_(file_), comments_(comments) {
    if (!in_) {
        throw std::runtime_error(file_.string() + ": cannot open for reading (" + std::strerror(errno) + ")");
    }
}

bool TextReader::next(std::vector<std::string_view>& tokens) {
    while (std::getline(in_, line_text_)) {
        ++line_;
        if (comments_) {
            auto hash = line_text_.find('#');
            if (hash != std::string::npos) line_text_.erase(hash);
        }
        split(line_text_, tokens);
        if (!tokens.empty()) return true;
    }
    if (in_.bad()) fail("read error");
    tokens.clear();
    return false;
}

void TextReader::fail(const std::string& problem) const { throw FormatError(file_, line_, problem); }

double TextReader::real(std::string_view token, const char* what) const {
    double value = 0;
    if (!parse_number(token, value)) {
        fail(std::string(what) + " '" + std::string(token) + "' is not a number");
    }
    if (!std::isfinite(value)) {
        fail(std::string(what) + " '" + std::string(token) + "' is not finite");
    }
    return value;
}

float TextReader::real_float(std::string_view token, const char* what) const {
    float value = 0;
    if (!parse_number(token, value)) {
        fail(std::string(what) + " '" + std::string(token) + "' is not a number");
    }
    if (!std::isfinite(value)) {
        fail(std::string(what) + " '" + std::string(token) + "' is not a finite float");
    }
    return value;
}

std::size_t TextReader::count(std::string_view token, const char* what, std::size_t max) const {
    double value = real(token, what);
    if (value < 0 || value != std::floor(value) || value > static_cast<double>(max)) {
        fail(std::string(what) + " '" + std::string(token) + "' is not a whole number in 0.." + std::to_string(max));
    }
    return static_cast<std::size_t>(value);
}

}  // namespace surfvp::eval
