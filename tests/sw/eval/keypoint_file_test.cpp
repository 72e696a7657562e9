// Keypoint files: Mikolajczyk format plus the NAME.meta sibling (sw/eval/README.md).
#include "sw/eval/keypoint_file.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sw/eval/eval_test_support.h"

namespace surfvp::eval {
namespace {

using test::Random;
using test::TemporaryFolder;

std::string read_text(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void write_text(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::vector<std::string> tokens_of(const std::string& line) {
    std::vector<std::string> tokens;
    std::istringstream in(line);
    for (std::string t; in >> t;) tokens.push_back(t);
    return tokens;
}

// Floats compare bit for bit: %.9g round-trips every float.
void expect_identical(const surf::Keypoints& expected, const surf::Keypoints& actual) {
    ASSERT_EQ(expected.size(), actual.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        SCOPED_TRACE("keypoint " + std::to_string(i));
        EXPECT_EQ(expected[i].x, actual[i].x);
        EXPECT_EQ(expected[i].y, actual[i].y);
        EXPECT_EQ(expected[i].scale, actual[i].scale);
        EXPECT_EQ(expected[i].orientation, actual[i].orientation);
        EXPECT_EQ(expected[i].response, actual[i].response);
        EXPECT_EQ(expected[i].laplacian, actual[i].laplacian);
        EXPECT_EQ(expected[i].descriptor, actual[i].descriptor);
    }
}

surf::Keypoints sample(std::size_t n = 150) {
    Random random(7);
    return test::random_keypoints(random, n, 1024, 768, 1.2, 40.0);
}

TEST(KeypointFile, RoundTripWithLaplacianIsExact) {
    TemporaryFolder dir;
    auto keypoints = sample();
    write_keypoint_file(dir / "a.surf", keypoints);
    KeypointFile file = read_keypoint_file(dir / "a.surf");
    EXPECT_EQ(file.dimension, 65u);
    EXPECT_TRUE(file.meta_read);
    expect_identical(keypoints, file.keypoints);
}

TEST(KeypointFile, RoundTripWithoutLaplacianIsExact) {
    TemporaryFolder dir;
    auto keypoints = sample();
    write_keypoint_file(dir / "a.surf", keypoints, {/*laplacian=*/false, /*meta=*/true});
    KeypointFile file = read_keypoint_file(dir / "a.surf");
    EXPECT_EQ(file.dimension, 64u);
    EXPECT_TRUE(file.meta_read);
    expect_identical(keypoints, file.keypoints);  // the sign comes back from the meta file
}

TEST(KeypointFile, WithoutMetaScaleComesFromTheEllipse) {
    TemporaryFolder dir;
    auto keypoints = sample();
    write_keypoint_file(dir / "a.surf", keypoints);  // with meta ...
    write_keypoint_file(dir / "a.surf", keypoints, {/*laplacian=*/true, /*meta=*/false});
    EXPECT_FALSE(std::filesystem::exists(dir / "a.surf.meta"));  // ... which is now stale: gone
    KeypointFile file = read_keypoint_file(dir / "a.surf");
    EXPECT_FALSE(file.meta_read);
    ASSERT_EQ(file.keypoints.size(), keypoints.size());
    for (std::size_t i = 0; i < keypoints.size(); ++i) {
        const auto &k = keypoints[i], &r = file.keypoints[i];
        EXPECT_EQ(k.x, r.x);
        EXPECT_EQ(k.y, r.y);
        EXPECT_EQ(k.descriptor, r.descriptor);
        EXPECT_EQ(k.laplacian, r.laplacian);  // the 65th column
        // a = 1/(2.5 s)^2 printed to 9 digits: s comes back within a few float ulps.
        EXPECT_NEAR(r.scale, k.scale, 4e-7 * k.scale);
        EXPECT_EQ(r.orientation, 0.0f);
        EXPECT_EQ(r.response, 0.0f);
    }
}

TEST(KeypointFile, LayoutIsMikolajczykWithRadiusTwoAndAHalfScales) {
    TemporaryFolder dir;
    surf::Keypoint k;
    k.x = 10.5f;
    k.y = 20.25f;
    k.scale = 2.0f;  // r = 5, a = c = 1/25
    k.laplacian = -1;
    k.descriptor[0] = 0.6f;
    k.descriptor[63] = 0.8f;
    write_keypoint_file(dir / "one.surf", {k});
    auto lines = lines_of(read_text(dir / "one.surf"));
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[0], "65");
    EXPECT_EQ(lines[1], "1");
    auto t = tokens_of(lines[2]);
    ASSERT_EQ(t.size(), 5u + 65u);
    EXPECT_EQ(t[0], "10.5");
    EXPECT_EQ(t[1], "20.25");
    EXPECT_EQ(t[2], "0.04");
    EXPECT_EQ(t[3], "0");
    EXPECT_EQ(t[4], "0.04");
    EXPECT_EQ(t[5], "-1");
    EXPECT_EQ(t[6], "0.600000024");  // 0.6f to 9 significant digits
    EXPECT_EQ(t[69], "0.800000012");
    auto meta = lines_of(read_text(dir / "one.surf.meta"));
    ASSERT_EQ(meta.size(), 2u);
    EXPECT_EQ(meta[0], "1");
    EXPECT_EQ(meta[1], "10.5 20.25 2 0 0 -1");
    // Written through a temporary name: nothing else is left in the folder.
    std::size_t files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
        (void)e;
        ++files;
    }
    EXPECT_EQ(files, 2u);
}

// Every value is written as printf's %.9g writes it: tiny, huge, negative zero, subnormal,
// integral, and the random keypoints' values.
TEST(KeypointFile, ValuesAreWrittenAsPrintfWritesThemToNineDigits) {
    TemporaryFolder dir;
    surf::Keypoints keypoints = sample(20);
    const float awkward[] = {1e-5f, -0.0f, 1e-40f, 123456789.0f, 3.4e38f, -2.5e-7f, 100.0f, 0.1f, 1.0f / 3.0f};
    for (size_t i = 0; i < std::size(awkward); ++i) keypoints[0].descriptor[i] = awkward[i];
    keypoints[1].x = 1e-5f;
    keypoints[1].orientation = -0.0f;
    write_keypoint_file(dir / "k.surf", keypoints);
    auto printf_g9 = [](double v) {
        char text[40];
        std::snprintf(text, sizeof text, "%.9g", v);
        return std::string(text);
    };
    const auto lines = lines_of(read_text(dir / "k.surf"));
    const auto meta = lines_of(read_text(dir / "k.surf.meta"));
    ASSERT_EQ(lines.size(), keypoints.size() + 2);
    ASSERT_EQ(meta.size(), keypoints.size() + 1);
    for (size_t i = 0; i < keypoints.size(); ++i) {
        const surf::Keypoint& k = keypoints[i];
        const auto t = tokens_of(lines[i + 2]);
        ASSERT_EQ(t.size(), 5u + 65u);
        EXPECT_EQ(t[0], printf_g9(k.x));
        EXPECT_EQ(t[1], printf_g9(k.y));
        EXPECT_EQ(t[2], t[4]);
        for (size_t d = 0; d < 64; ++d)
            EXPECT_EQ(t[6 + d], printf_g9(k.descriptor[d])) << "keypoint " << i << " value " << d;
        EXPECT_EQ(meta[i + 1], printf_g9(k.x) + " " + printf_g9(k.y) + " " + printf_g9(k.scale) + " " +
                                   printf_g9(k.orientation) + " " + printf_g9(k.response) + " " +
                                   std::to_string(k.laplacian));
    }
    EXPECT_EQ(tokens_of(lines[2])[6], "9.99999975e-06");
    EXPECT_EQ(tokens_of(lines[2])[7], "-0");
}

TEST(KeypointFile, ReadsADetectorOnlyEllipseFile) {
    // Oxford detector output: header "1.0", no descriptors, a general ellipse.
    TemporaryFolder dir;
    write_text(dir / "img1.haraff", "1.0\n2\n100 200 0.01 0.002 0.04\n5.5 6.5 0.25 0 0.25\n");
    KeypointFile file = read_keypoint_file(dir / "img1.haraff");
    EXPECT_EQ(file.dimension, 0u);
    EXPECT_FALSE(file.meta_read);
    ASSERT_EQ(file.keypoints.size(), 2u);
    EXPECT_EQ(file.keypoints[0].x, 100.0f);
    EXPECT_EQ(file.keypoints[0].y, 200.0f);
    // Equal-area circle: r = (ac - b^2)^(-1/4) = (0.0004 - 0.000004)^(-1/4) = 7.0888...
    EXPECT_NEAR(file.keypoints[0].scale, std::pow(0.000396, -0.25) / 2.5, 1e-5);
    EXPECT_NEAR(file.keypoints[1].scale, 2.0 / 2.5, 1e-7);
    EXPECT_EQ(file.keypoints[1].laplacian, 0);
    EXPECT_EQ(file.keypoints[1].descriptor, surf::Keypoint{}.descriptor);
}

std::string zeros(int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += " 0";
    return s;
}

struct Malformed {
    const char* name;
    std::string text;
    std::size_t line;
    const char* problem;
};

TEST(KeypointFile, MalformedFilesNameFileLineAndProblem) {
    TemporaryFolder dir;
    std::string good64 = "1 2 0.04 0 0.04" + zeros(64) + "\n";
    const std::vector<Malformed> cases = {
        {"empty", "", 0, "file ends before the descriptor dimension"},
        {"dimension", "128\n1\n", 1, "descriptor dimension 128 is not supported"},
        {"two headers", "64 1\n", 1, "alone on the line"},
        {"count", "64\nmany\n", 2, "keypoint count 'many' is not a number"},
        {"short", "64\n2\n" + good64, 3, "file ends after 1 of 2 keypoints"},
        {"values", "64\n1\n1 2 0.04 0 0.04" + zeros(63) + "\n", 3, "expected 69 values"},
        {"number", "64\n1\n1 abc 0.04 0 0.04" + zeros(64) + "\n", 3, "y 'abc' is not a number"},
        {"ellipse", "64\n1\n1 2 -0.04 0 0.04" + zeros(64) + "\n", 3, "is not positive definite"},
        {"sign", "65\n1\n1 2 0.04 0 0.04 2" + zeros(64) + "\n", 3, "Laplacian sign '2'"},
        {"nan", "64\n1\n1 2 0.04 0 0.04 nan" + zeros(63) + "\n", 3, "is not a finite float"},
        {"extra", "64\n1\n" + good64 + "\n" + good64, 5, "more keypoint lines than the count 1"},
        // Found by tests/fuzz (keypoint_file): the count was reserved as it stood, 28 GB here.
        {"claims", "64\n100000000\n" + good64, 3, "file ends after 1 of 100000000 keypoints"},
        // Found by tests/fuzz (keypoint_file): an ellipse so narrow that its scale rounds to 0 as
        // a float read, and the file could not be written back.
        {"tiny", "64\n1\n1 2 25 0 6e250" + zeros(64) + "\n", 3, "gives a scale beyond a float's range"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        auto file = dir / (std::string(c.name) + ".surf");
        write_text(file, c.text);
        try {
            read_keypoint_file(file);
            ADD_FAILURE() << "no FormatError";
        } catch (const FormatError& e) {
            EXPECT_EQ(e.file(), file);
            EXPECT_EQ(e.line(), c.line);
            EXPECT_NE(e.problem().find(c.problem), std::string::npos) << e.what();
            std::string where = file.string() + (c.line ? ":" + std::to_string(c.line) : "") + ": ";
            EXPECT_EQ(std::string(e.what()).rfind(where, 0), 0u) << e.what();
        }
    }
}

TEST(KeypointFile, MetaFileMustDescribeTheSameKeypoints) {
    TemporaryFolder dir;
    auto keypoints = sample(3);
    write_keypoint_file(dir / "a.surf", keypoints);
    auto meta = lines_of(read_text(dir / "a.surf.meta"));
    auto t = tokens_of(meta[2]);
    t[0] = "1e6";  // second keypoint's x
    meta[2] = t[0] + " " + t[1] + " " + t[2] + " " + t[3] + " " + t[4] + " " + t[5];
    write_text(dir / "a.surf.meta", meta[0] + "\n" + meta[1] + "\n" + meta[2] + "\n" + meta[3] + "\n");
    try {
        read_keypoint_file(dir / "a.surf");
        ADD_FAILURE() << "no FormatError";
    } catch (const FormatError& e) {
        EXPECT_EQ(e.file(), dir / "a.surf.meta");
        EXPECT_EQ(e.line(), 3u);
        EXPECT_NE(e.problem().find("position 1e6"), std::string::npos) << e.what();
    }
    write_text(dir / "a.surf.meta", "2\n");
    EXPECT_THROW(read_keypoint_file(dir / "a.surf"), FormatError);  // count differs
}

TEST(KeypointFile, MissingFileIsNamed) {
    TemporaryFolder dir;
    try {
        read_keypoint_file(dir / "absent.surf");
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("absent.surf"), std::string::npos);
    }
}

TEST(KeypointFile, RefusesToWriteAKeypointWithoutScale) {
    TemporaryFolder dir;
    auto keypoints = sample(2);
    keypoints[1].scale = 0;
    EXPECT_THROW(write_keypoint_file(dir / "a.surf", keypoints), std::invalid_argument);
    EXPECT_FALSE(std::filesystem::exists(dir / "a.surf"));
}

}  // namespace
}  // namespace surfvp::eval
