#include "intc.h"

#include <fmt/format.h>
#include <stdexcept>

#include "intc_regs.h"
#include "models/common/register_target.h"

namespace surfvp {

Intc::Intc(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer)
    : sc_module(name), regs("regs"), irq_in("irq_in", params.inputs), irq("irq"), params_(params), tracer_(tracer) {
    if (params.inputs == 0 || params.inputs > 32)
        throw std::invalid_argument(fmt::format("{}: the XPS INTC has 1 to 32 inputs, not {}", basename(), params.inputs));
    regs.register_b_transport(this, &Intc::b_transport);
    regs.register_transport_dbg(this, &Intc::transport_dbg);
    SC_HAS_PROCESS(Intc);
    SC_METHOD(update);
    for (auto& in : irq_in) sensitive << in;
    sensitive << changed_;
    track_ = tracer_.track("intc", "pending");
}

void Intc::latch_inputs() {
    if (!(mer_ & intc::MER_HIE)) return;
    for (unsigned i = 0; i < params_.inputs; ++i)
        if (irq_in[i].read()) isr_ |= 1u << i;
}

void Intc::update() {
    latch_inputs();
    const bool level = (mer_ & intc::MER_ME) && (isr_ & ier_) != 0;
    if (level && !irq.read()) ++raised_;
    irq.write(level);
    if (tracer_.perfetto_on())
        tracer_.counter(track_, "intc pending", sc_core::sc_time_stamp(), __builtin_popcount(isr_ & ier_));
}

bool Intc::access(uint32_t offset, uint32_t& value, bool write) {
    const uint32_t valid = params_.inputs == 32 ? ~0u : (1u << params_.inputs) - 1;
    if (!write) {
        switch (offset) {
            case intc::ISR: value = isr_; return true;
            case intc::IPR: value = isr_ & ier_; return true;
            case intc::IER: value = ier_; return true;
            case intc::MER: value = mer_; return true;
            case intc::IVR: {
                const uint32_t pending = isr_ & ier_;
                value = pending ? static_cast<uint32_t>(__builtin_ctz(pending)) : intc::kNoVector;
                return true;
            }
            case intc::IAR: case intc::SIE: case intc::CIE: value = 0; return true;  // write-only: read as zero
            default: return false;
        }
    }
    switch (offset) {
        case intc::ISR: if (!(mer_ & intc::MER_HIE)) isr_ = value & valid; break;
        case intc::IER: ier_ = value & valid; break;
        case intc::IAR: isr_ &= ~value; break;
        case intc::SIE: ier_ |= value & valid; break;
        case intc::CIE: ier_ &= ~value; break;
        case intc::MER: mer_ = (value & (intc::MER_ME | intc::MER_HIE)) | (mer_ & intc::MER_HIE); break;
        case intc::IPR: case intc::IVR: break;  // read-only: writes are ignored, as on the chip
        default: return false;
    }
    latch_inputs();  // an acknowledged input that is still high is pending again at once
    changed_.notify(sc_core::SC_ZERO_TIME);
    return true;
}

void Intc::b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay) {
    answer_register_access(tx, delay, params_.register_latency, [this](uint32_t offset, uint32_t& value, bool write) {
        return access(offset, value, write);
    });
}

unsigned Intc::transport_dbg(tlm::tlm_generic_payload& tx) {
    if (tx.is_write()) return 0;  // debug reads only: a debug write must not acknowledge
    answer_register_access(tx, [this](uint32_t offset, uint32_t& value, bool write) {
        return access(offset, value, write);
    });
    return tx.is_response_ok() ? 4 : 0;
}

}  // namespace surfvp
