#pragma once
// Runs work once every process due at the current simulated instant has run: when no process
// is runnable and no delta notification or update is pending (SystemC has no stage callback
// in this build). Arbiters use it so that every request made at an instant competes,
// whichever delta it was made in: an arbiter that decided one delta after its first request
// would see or miss a same-time request depending on how many deltas the requester took to
// get there, which differs between simulation settings (a DMA issuing one transaction per
// line or per burst). One instance for the whole simulation: two would keep each other busy.
#include <functional>
#include <systemc>
#include <vector>

namespace surfvp {

class EndOfInstant {
public:
    static EndOfInstant& get();  // created during elaboration by its first user

    // `work` runs at the end of the current instant (in the order asked).
    void at_end(std::function<void()> work);

private:
    EndOfInstant();
    void settle();

    sc_core::sc_event wake_;
    std::vector<std::function<void()>> waiting_;
};

}  // namespace surfvp
