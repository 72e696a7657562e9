#pragma once
// report.html: the page an architecture review decides from, self-contained (XHTML with
// inline SVG; no scripts, fonts or files of its own), in this order: the verdict (the
// statement, margin, limit and its cause, the chain of limits, the break-even), how sure
// (the band, its tornado, the joint distribution), what you can change (design choices,
// software settings), the correlation with the paper, resources and power against the
// device and the power budget, then the timeline, each resource's frame, buses and DDR,
// FIFOs, the keypoints, and links to every other output of the run. Its charts follow the
// window's width and print; it is well-formed XML, so a test (and any XML tool) can read
// its figures.
#include <nlohmann/json.hpp>
#include <string>

#include "models/host/xml_text.h"

namespace surfvp {

// `figures`: what report.json does not hold: "first_frame_svg" (the workload's picture of its
// first frame) and "tornado_svg" (the verdict's), each an <svg> element, when the run has them.
std::string report_html(const nlohmann::ordered_json& report, const nlohmann::ordered_json& figures);

}  // namespace surfvp
