#pragma once
// Text inside the XML surfvp writes (report.html, the sweep's SVG plots, the keypoint
// picture): anything a file name or a scenario's name may hold, made safe.
#include <string>

namespace surfvp {

// Text made safe for XML character data and attribute values (a control character XML cannot
// hold becomes U+FFFD).
std::string xml_escape(const std::string& text);

}  // namespace surfvp
