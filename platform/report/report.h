#pragma once
// report.json and report.md of a run. The JSON is the machine-readable record (stable key
// order, so that the same scenario gives the same bytes but for the wall-clock fields it
// lists); the Markdown is the same content for a person.
#include <nlohmann/json.hpp>
#include <string>

#include "models/host/atomic_file.h"

namespace surfvp {

std::string report_markdown(const nlohmann::ordered_json& report);

// The answer in one line, as report.md's first line gives it (without its Markdown): the
// verdict's statement when the run has one, else the frame rate against the budget and the
// limit; why the run broke when it did; "" for a run without a frame rate (the smoke test). The
// terminal's last line says it.
std::string answer_line(const nlohmann::ordered_json& report);
// The frame rate against the budget and what limits it: "9.40 frames/s against a budget of 10.00: MISSED; ...".
std::string frame_rate_answer(const nlohmann::ordered_json& report);

// A workload's per-frame list (report.json's workload.per_frame) as CSV: a header of its keys,
// a row per frame.
std::string frames_csv(const nlohmann::ordered_json& per_frame);

}  // namespace surfvp
