#pragma once
// Where each resource's time goes in a SURF run, per frame, and what limits the frame rate
// (docs/architecture.md#principles, 7: the bottleneck named with its cause). Read from the run's report.
//
// Every resource's frame splits into busy (its own work), waits by cause, and idle:
//   iig                 busy: adding rows; waits: image DMA read, integral DMA write,
//                       PixelBus back-pressure (the FHG's line FIFO full)
//   fhg                 busy: block rows; waits: line FIFO empty (the next rows' lines not in
//                       yet), determinant DMA write (no free row buffer)
//   accelerator pair    busy: holding a task; waits: free task slot (every buffer set held)
//   cpu                 busy: work, line-fill stalls and register accesses; waits: interrupt
//                       (nothing to describe yet)
//   plb2 read / write, plb1, mci, ddr: busy
// A frame is the steady-state period (1 / frames per second); a resource of the accelerator
// pairs counts its busiest pair over the frames that pair took (its period is pairs x the
// frame period).
//
// The limit, in this order:
// 1. a resource busy with its own work for at least kBusyLimit of its period: it (cause
//    "busy"; an accelerator pair's busy is holding a task, which its blocks' work explains);
// 2. else a coupling through a buffer, both sides occupied: the FHG waiting for lines while
//    the IIG is held by back-pressure means the line FIFO (fhg.fifo_lines) limits; a pair
//    waiting for a free task slot means the tasks in flight (surf.tasks_in_flight) limit;
// 3. else the largest wait, named by its cause.
#include <nlohmann/json.hpp>

#include "platform/scenario/config.h"

namespace surfvp {

constexpr double kBusyLimit = 0.95;

// Adds "time_per_frame" (per resource: busy, waits, idle, period, shares, the frame rate it
// alone would allow and its slack against the budget), "limit" ({resource, cause, reason})
// and "bottleneck" (the limit's resource) to a report with frames done.
void add_limits(nlohmann::ordered_json& report, const Config& config);

}  // namespace surfvp
