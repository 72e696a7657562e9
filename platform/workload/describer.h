#pragma once
// The software stage libSSA2 hands candidates to, built from the configuration.
#include <memory>
#include <string>
#include <nlohmann/json.hpp>

#include "platform/scenario/config.h"
#include "sw/cpu_cost/ppc440_pipeline.h"
#include "sw/libssa2/libssa2.h"

namespace surfvp {

class Worker;

// The PPC440 pipeline the configuration describes: fpu.precision's latency column unless a
// scenario sets an fpu.* latency itself, and every other knob as set.
sw::PipelineParams pipeline_params(const Config& config);

std::unique_ptr<sw::ssa2::Describer> make_describer(const Config& config, float threshold);

// Lends the describer the simulator's second thread, to describe a task's candidates ahead in
// its idle time (nullptr takes it back: nothing of the describer runs on it after the call).
void share_worker(sw::ssa2::Describer& describer, Worker* worker);

// `surfvp calibrate`: every describer made after this call appends each frame's buffers and
// FIFO words to `inputs`, and the native stage's result for each word to `expected`
// (sw/cpu_cost/calibration_dump.h). Empty paths stop the recording.
void record_stage_inputs(const std::string& inputs, const std::string& expected);
// `surfvp calibrate`: the describers made from now on may do units the table has no price for
// yet (M-SURF before its first calibration); elsewhere such a setting is refused.
void calibrating_stage(bool on);

// Where the software stage's cycles went (per step and per kind of work), its candidates
// and rejections, and the L1 hit rate, for the report.
nlohmann::ordered_json describer_report(const sw::ssa2::Describer& describer);

}  // namespace surfvp
