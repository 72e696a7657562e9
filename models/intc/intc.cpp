#include "intc.h"

#include <fmt/format.h>
#include <stdexcept>

#include "models/common/register_target.h"

namespace surfvp {

Intc::Intc(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer)
    : sc_module(name),
      regs("regs"),
      irq_in("irq_in", params.inputs),
      irq("irq"),
      params_(params),
      tracer_(tracer),
      registers_(
          params.inputs, [this] { return levels(); }, [this] { changed_.notify(sc_core::SC_ZERO_TIME); }) {
    regs.register_b_transport(this, &Intc::b_transport);
    regs.register_transport_dbg(this, &Intc::transport_dbg);
    SC_HAS_PROCESS(Intc);
    SC_METHOD(update);
    for (auto& in : irq_in) sensitive << in;
    sensitive << changed_;
    track_ = tracer_.track("intc", "pending");
    line_track_ = tracer_.track("intc", "interrupt to the CPU");
}

uint32_t Intc::levels() const {
    uint32_t high = 0;
    for (unsigned i = 0; i < params_.inputs; ++i)
        if (irq_in[i].read()) high |= 1u << i;
    return high;
}

void Intc::update() {
    registers_.latch();
    const bool level = registers_.output();
    if (level && !irq.read()) ++raised_;
    if (tracer_.perfetto_on()) trace_line(level);
    irq.write(level);
    if (tracer_.perfetto_on())
        tracer_.counter(track_, "intc pending", sc_core::sc_time_stamp(), __builtin_popcount(registers_.pending()));
}

// The line to the CPU as a slice from its rise to its fall, with a flow from the rise to the
// CPU's handling (the CPU takes it from the "cpu irq" channel when it wakes).
void Intc::trace_line(bool level) {
    const sc_core::sc_time now = sc_core::sc_time_stamp();
    if (level && !irq.read()) {
        raised_at_ = now;
        raised_lines_ = registers_.pending();
        flow_ = tracer_.flow_id();
        tracer_.flow(line_track_, now, flow_, Tracer::Flow::begin, "interrupt");
        tracer_.post_flow("cpu irq", flow_);
    } else if (!level && irq.read()) {
        tracer_.slice(line_track_, "interrupt", raised_at_, now,
                      TraceArgs().address("lines", raised_lines_).number("flow", double(flow_)));
    }
}

void Intc::b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay) {
    answer_register_access(tx, delay, params_.registers.latency(), registers_);
}

unsigned Intc::transport_dbg(tlm::tlm_generic_payload& tx) {
    if (tx.is_write()) return 0;  // debug reads only: a debug write must not acknowledge
    answer_register_access(tx, registers_);
    return tx.is_response_ok() ? 4 : 0;
}

void Intc::register_statistics(const Statistics::Scope& s) const {
    s.count(
        "raised", [this] { return raised_; }, "interrupts", "rising edges of the line to the CPU");
}

}  // namespace surfvp
