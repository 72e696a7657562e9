#include "platform/report/correlation.h"

#include <cmath>
#include <fmt/format.h>
#include <optional>

#include "models/host/xml_text.h"

namespace surfvp {
namespace {
using Json = nlohmann::ordered_json;

using paper::kAbout;
constexpr double kPaperFps = paper::kFps, kPaperDescriptors = paper::kDescriptors, kPaperOverhead = paper::kOverhead,
                 kPaperWatts = paper::kWatts;
constexpr int kPaperWidth = paper::kWidth, kPaperHeight = paper::kHeight;

struct Row {
    std::string figure, paper_says, unit;
    double paper, low, high;
    std::optional<double> vp;
    std::string note;        // why the run cannot be compared, or what it counts
    bool comparable = true;  // false: `within` is left open
    bool missed = false;     // outside the paper's statement whatever the range says (a chip that could not be built)
};

Json row_json(const Row& r) {
    Json j = {{"figure", r.figure}, {"paper", r.paper}, {"paper_says", r.paper_says},
              {"unit", r.unit},     {"low", r.low},     {"high", r.high}};
    j["vp"] = r.vp ? Json(*r.vp) : Json();
    j["difference"] = r.vp ? Json(*r.vp - r.paper) : Json();
    j["within"] = r.vp && r.comparable ? Json(!r.missed && *r.vp >= r.low && *r.vp <= r.high) : Json();
    j["note"] = r.note;
    return j;
}

const Json& first_fhg(const Json& report) { return report["fhg"].is_array() ? report["fhg"][0] : report["fhg"]; }

Row frame_rate(const Json& r) {
    Row row{"frames/s at 1024x768 with ~100 descriptors",
            "approximately 10 images (1024x768 pixels) per second, around 100 descriptors per image (§I, note 1; §V)",
            "frames/s",
            kPaperFps,
            kPaperFps * (1 - kAbout),
            kPaperFps * (1 + kAbout),
            {},
            ""};
    if (!r.contains("throughput_fps")) {
        row.note = "the run has no frame rate (fewer than two frames)";
        return row;
    }
    row.vp = r["throughput_fps"].get<double>();
    const int width = r["image"]["width"], height = r["image"]["height"];
    const double keypoints = r.value("keypoints_per_frame", 0.0);
    if (width != kPaperWidth || height != kPaperHeight) {
        row.comparable = false;
        row.note = fmt::format("not comparable: the run's frames are {}x{}", width, height);
    } else if (std::abs(keypoints / kPaperDescriptors - 1) > kAbout) {
        row.comparable = false;
        row.note = fmt::format("not comparable: {:.1f} keypoints per frame, not around 100 (surf.target_keypoints)",
                               keypoints);
    } else {
        row.note = fmt::format("{:.1f} keypoints per frame", keypoints);
    }
    return row;
}

// Note 4's optimal state: the buses busy every cycle with the words the basic script carries.
Row script_overhead(const Json& r) {
    Row row{
        "basic script over the optimal state (note 4)",
        "approximately 11 % increase in determinant block processing time compared to optimal state (§III-C, note 4)",
        "%",
        100 * kPaperOverhead,
        100 * kPaperOverhead * (1 - kAbout),
        100 * kPaperOverhead * (1 + kAbout),
        {},
        ""};
    if (!r.contains("fhg") || !first_fhg(r).contains("schedules")) {
        row.note = "the run has no FHG";
        return row;
    }
    const Json& s = first_fhg(r)["schedules"];
    const Json& basic = s["basic"];
    row.vp = 100 * basic["idle_bus_overhead"].get<double>();
    row.note = fmt::format(
        "{} cycles against {} words over {} buses ({} cycles); over the structural bound ({} cycles: {}) "
        "{:+.1f} %",
        basic["cycles_per_block"].get<int>(), basic["words"].get<int>(), s["machine"]["read_buses"].get<int>(),
        basic["busy_bus_cycles"].get<int>(), s["optimal"]["cycles_per_block"].get<int>(),
        s["optimal"]["limit"].get<std::string>(), 100 * basic["overhead"].get<double>());
    if (s["scheduler"] != "basic") row.note += "; the run itself uses the improved script (fhg.scheduler)";
    return row;
}

Row power(const Json& r) {
    Row row{"power of the device", "consumes less than 10 W (§I, §V)", "W", kPaperWatts, 0, kPaperWatts, {}, ""};
    if (!r.contains("power")) {
        row.note = "the run has no power estimate";
        return row;
    }
    row.vp = r["power"]["watts"].get<double>();
    row.note = "the estimate of docs/power.md (its band in the power section)";
    return row;
}

// The paper's chip was built on an XC5VFX70T: it fitted, with room to place and route, and
// closed its clocks. The LUTs are what binds (docs/resources.md); the note gives the rest.
Row built(const Json& r) {
    Row row{"the chip was built",
            "a Virtex-5 XC5VFX70 with its PowerPC 440 and the two IP blocks (§III)",
            "%",
            0,
            0,
            0,
            {},
            ""};
    if (!r.contains("fpga_resources")) {
        row.note = "the run has no resource estimate";
        return row;
    }
    const Json& f = r["fpga_resources"];
    row.high = row.paper = 100 * f["max_utilisation"]["logic"].get<double>();
    row.vp = 100 * f["share"]["luts"].get<double>();
    row.figure = fmt::format("LUTs of the {} (the chip was built)", f["device"].get<std::string>());
    const bool closes = !r.contains("clock_closure") || r["clock_closure"]["closes"].get<bool>();
    row.note =
        fmt::format("{}; {} (docs/resources.md)",
                    f["fits"].get<bool>() ? "fits the device with its placement margin" : "does not fit the device",
                    closes ? "closes its clocks" : "does not close its clocks");
    row.missed = !f["fits"].get<bool>() || !closes;
    return row;
}

Row distinguishability() {
    Row row{"Table II: FPGA distinguishability against CPU SURF",
            "FPGA 0.53 / 0.53 / 0.27 / 0.26 against CPU 0.62 / 0.61 / 0.43 / 0.43 (§IV-A, Table II)",
            "",
            -0.09,
            0,
            0,
            {},
            "not measured by a timing run: `surfvp table2` measures it (docs/table2.md)"};
    row.comparable = false;
    return row;
}

std::string figure_text(const Json& row, const Json& value) {
    if (value.is_null()) return "-";
    const std::string unit = row["unit"];
    return unit == "%" ? fmt::format("{:.1f} %", value.get<double>())
                       : fmt::format("{:.2f}{}{}", value.get<double>(), unit.empty() ? "" : " ", unit);
}

std::string range_text(const Json& row) {
    const std::string unit = row["unit"];
    if (unit.empty()) return "-";
    if (row["low"].get<double>() == 0) return fmt::format("under {:g} {}", row["high"].get<double>(), unit);
    return fmt::format("{:.3g} to {:.3g} {}", row["low"].get<double>(), row["high"].get<double>(), unit);
}

std::string within_text(const Json& row) {
    if (row["within"].is_null()) return "-";
    return row["within"].get<bool>() ? "yes" : "**no**";
}

}  // namespace

Json correlation_json(const Json& report) {
    Json rows = Json::array();
    for (const Row& row :
         {frame_rate(report), script_overhead(report), power(report), built(report), distinguishability()})
        rows.push_back(row_json(row));
    return rows;
}

std::string correlation_markdown(const Json& correlation) {
    std::string md =
        "\n## Correlation with the published chip\n\nEach figure the paper states about its chip beside the VP's at "
        "this "
        "scenario's settings; \"about\" is read as within 10 % (docs/correlation.md).\n\n"
        "| figure | paper | within the paper's precision | VP | difference | reproduced | note "
        "|\n|---|---|---|---:|---:|---|---|\n";
    for (const Json& row : correlation) {
        const std::string difference =
            row["difference"].is_null() ? "-" : fmt::format("{:+.2f}", row["difference"].get<double>());
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", row["figure"].get<std::string>(),
                          row["paper_says"].get<std::string>(), range_text(row), figure_text(row, row["vp"]),
                          difference, within_text(row), row["note"].get<std::string>());
    }
    return md;
}

std::string correlation_html(const Json& correlation) {
    std::string rows;
    for (const Json& row : correlation) {
        const std::string within = row["within"].is_null() ? "-" : row["within"].get<bool>() ? "yes" : "NO";
        rows +=
            fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                        xml_escape(row["figure"].get<std::string>()), xml_escape(row["paper_says"].get<std::string>()),
                        xml_escape(range_text(row)), xml_escape(figure_text(row, row["vp"])), within,
                        xml_escape(row["note"].get<std::string>()));
    }
    return "<table id=\"correlation\"><tr><th>figure</th><th>paper</th>"
           "<th>within its precision</th><th>VP</th><th>reproduced</th><th>note</th></tr>" +
           rows + "</table>";
}

}  // namespace surfvp
