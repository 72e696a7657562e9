#pragma once
// report.html: one self-contained page (XHTML with inline SVG; no scripts, fonts or files
// of its own) that shows a run at a glance: the verdict and its figures, a Gantt of the first
// frames across the IIG, FHG, PLB2 (their DMA) and the CPU, busy/wait/idle per resource, bus
// and DDR utilisation over time, the FIFO levels over time, and the keypoints on the first
// frame. It is well-formed XML, so a test (and any XML tool) can read its charts' figures.
#include <nlohmann/json.hpp>
#include <string>

#include "models/host/xml_text.h"

namespace surfvp {

// `first_frame_svg`: the workload's picture of its first frame (an <svg> element), or "".
std::string report_html(const nlohmann::ordered_json& report, const std::string& first_frame_svg);

}  // namespace surfvp
