#include "sw/surf/parallel.h"

#include <algorithm>
#include <thread>
#include <vector>

namespace surfvp::surf {

int resolve_threads(int requested) {
    if (requested > 0) return requested;
    return std::max(1u, std::thread::hardware_concurrency());
}

void parallel_for(int count, int threads, const std::function<void(int, int)>& fn) {
    if (count <= 0) return;
    const int chunks = std::clamp(threads, 1, count);
    auto bounds = [&](int c) { return static_cast<int>(static_cast<long long>(count) * c / chunks); };
    std::vector<std::thread> workers;
    workers.reserve(static_cast<size_t>(chunks - 1));
    for (int c = 1; c < chunks; ++c) workers.emplace_back(fn, bounds(c), bounds(c + 1));
    fn(0, bounds(1));
    for (auto& w : workers) w.join();
}

}  // namespace surfvp::surf
