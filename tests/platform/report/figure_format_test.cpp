// Figures through their units: what compare's tables and a sweep's results.md show.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "platform/report/figure_format.h"

namespace surfvp {
namespace {
using Json = nlohmann::ordered_json;

TEST(FigureFormat, EachUnitIsScaledToWhatAPersonReads) {
    EXPECT_EQ(format_figure(Json(125e6), "Hz"), "125 MHz");
    EXPECT_EQ(format_figure(Json(0.0048), "s"), "4.8 ms");
    EXPECT_EQ(format_figure(Json(191.6), "ms"), "191.6 ms");
    EXPECT_EQ(format_figure(Json(1500.0), "ms"), "1.5 s");
    EXPECT_EQ(format_figure(Json(879.5), "us"), "879.5 µs");
    EXPECT_EQ(format_figure(Json(3 * 1048576.0), "B"), "3 MiB");
    EXPECT_EQ(format_figure(Json(212.5e6), "B/s"), "212.5 MB/s");
    EXPECT_EQ(format_figure(Json(0.82514), "share"), "82.5 %");
    EXPECT_EQ(format_figure(Json(9.5734), "frames/s"), "9.573 frames/s");
    EXPECT_EQ(format_figure(Json(84), "RAMB36"), "84 RAMB36");
    EXPECT_EQ(format_figure(Json(351812.7), ""), "351813");
    EXPECT_EQ(format_figure(Json(true), ""), "yes");
    EXPECT_EQ(format_figure(Json(), "ms"), "-");
    EXPECT_EQ(format_figure(Json("fhg"), ""), "fhg");
}

TEST(FigureFormat, AChangeIsSignedAndAShareMovesInPoints) {
    EXPECT_EQ(format_change(-0.214, "share"), "-21.4 points");
    EXPECT_EQ(format_change(-0.02329, "s"), "-23.29 ms");
    EXPECT_EQ(format_change(1.908, "frames/s"), "+1.908 frames/s");
}

}  // namespace
}  // namespace surfvp
