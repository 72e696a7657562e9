#include "end_of_instant.h"

namespace surfvp {

EndOfInstant& EndOfInstant::get() {
    static EndOfInstant instance;
    return instance;
}

EndOfInstant::EndOfInstant() : wake_("end_of_instant") {
    sc_core::sc_spawn_options options;
    options.spawn_method();
    options.dont_initialize();
    options.set_sensitivity(&wake_);
    sc_core::sc_spawn([this] { settle(); }, "end_of_instant_settler", &options);
}

void EndOfInstant::at_end(std::function<void()> work) {
    if (waiting_.empty()) wake_.notify(sc_core::SC_ZERO_TIME);
    waiting_.push_back(std::move(work));
}

void EndOfInstant::settle() {
    if (sc_core::sc_pending_activity_at_current_time()) {
        wake_.notify(sc_core::SC_ZERO_TIME);  // others still run at this instant
        return;
    }
    std::vector<std::function<void()>> work;
    work.swap(waiting_);
    for (auto& w : work) w();
}

}  // namespace surfvp
