#pragma once
// The only threading in the reference: split an index range into contiguous chunks.
#include <functional>

namespace surfvp::surf {

// Number of worker threads for a Params::threads value (0 means all hardware threads).
int resolve_threads(int requested);

// Calls fn(begin, end) on `threads` contiguous, nearly equal chunks of [0, count), the first
// on the calling thread, and returns when all are done. Chunks never overlap, so fn may write
// per-index results without locks.
void parallel_for(int count, int threads, const std::function<void(int begin, int end)>& fn);

}  // namespace surfvp::surf
