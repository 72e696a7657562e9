#pragma once
// PixelBus: the dedicated one-way link that carries integral-image lines from SSA IIG to
// SSA FHG (paper §III-A, Fig. 3). One call moves one line: the receiver blocks the sender
// while it has no room for the line (back-pressure: the FHG's line FIFO is full), then the
// line spends `transfer` on the link (the sender computes it: width x 32 / link width
// cycles of its clock) and is the receiver's from then on.
#include <cstdint>
#include <systemc>

namespace surfvp {

struct PixelBusIf : virtual sc_core::sc_interface {
    // Called from the sender's SC_THREAD; returns when the line has crossed the link.
    // `data` holds `width` integral values of row `y`.
    virtual void send_line(int y, const uint32_t* data, int width, const sc_core::sc_time& transfer) = 0;
};

using PixelBusOut = sc_core::sc_port<PixelBusIf>;
using PixelBusIn = sc_core::sc_export<PixelBusIf>;

}  // namespace surfvp
