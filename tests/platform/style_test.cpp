// Every C++ file of the project is laid out as .clang-format says (clang-format 14, Debian
// 12's, from the test packages). A file that is not fails here by name; `clang-format -i FILE`
// fixes it.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {
namespace fs = std::filesystem;

const fs::path kRoot = SURFVP_SOURCE_DIR;

struct Output {
    int status;
    std::string text;
};

Output shell(const std::string& command) {
    Output out{-1, ""};
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return out;
    std::array<char, 4096> buffer;
    while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) out.text.append(buffer.data(), n);
    out.status = pclose(pipe);
    return out;
}

std::vector<fs::path> cpp_files() {
    std::vector<fs::path> files;
    for (const char* top : {"models", "sw", "platform", "tests"})
        for (const auto& entry : fs::recursive_directory_iterator(kRoot / top)) {
            const auto ext = entry.path().extension();
            const auto relative = fs::relative(entry.path(), kRoot).string();
            if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp") &&
                relative.rfind("tests/fuzz/corpus", 0) != 0)
                files.push_back(entry.path());
        }
    return files;
}

void expect_clang_format_14() {
    const Output version = shell("clang-format --version");
    ASSERT_EQ(version.status, 0) << "clang-format is missing: install the Debian package clang-format "
                                    "(scripts/packages.sh lists it with the test packages)";
    ASSERT_NE(version.text.find("version 14."), std::string::npos)
        << "the layout is clang-format 14's (Debian 12); this is " << version.text;
}

}  // namespace

TEST(Style, TheCheckSeesAFileThatIsNotFormatted) {
    expect_clang_format_14();
    const Output badly = shell(
        "printf 'int  f( int a ){return a;}\\n' | clang-format --dry-run -Werror "
        "--assume-filename=" +
        (kRoot / "platform/x.cpp").string());
    EXPECT_NE(badly.status, 0) << badly.text;
}

TEST(Style, EveryFileIsFormatted) {
    expect_clang_format_14();
    const auto files = cpp_files();
    ASSERT_GT(files.size(), 300u) << "the project's C++ files were not found under " << kRoot;
    std::string command = "clang-format --dry-run -Werror";
    for (const auto& file : files) command += " '" + file.string() + "'";
    const Output check = shell(command);
    EXPECT_EQ(check.status, 0) << "files not laid out as .clang-format says (run clang-format -i on each):\n"
                               << check.text.substr(0, 4000);
}
