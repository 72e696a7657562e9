#include "platform/report/chart_ticks.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace surfvp {

Ticks round_ticks(double lo, double hi, int count) {
    if (!(hi > lo)) hi = lo + (lo == 0 ? 1 : std::abs(lo) * 0.1);
    const double raw = (hi - lo) / std::max(count, 1);
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    double step = 10 * power;
    for (const double m : {1.0, 2.0, 5.0})
        if (raw <= m * power * (1 + 1e-9)) {
            step = m * power;
            break;
        }
    Ticks t;
    t.step = step;
    const double first = std::floor(lo / step + 1e-9) * step, last = std::ceil(hi / step - 1e-9) * step;
    for (double v = first; v <= last + step * 0.5; v += step) t.at.push_back(std::abs(v) < step * 1e-9 ? 0 : v);
    return t;
}

std::string tick_label(double value, double step) {
    const int decimals = std::max(0, int(-std::floor(std::log10(step) + 1e-9)));
    return fmt::format("{:.{}f}", value, decimals);
}

}  // namespace surfvp
