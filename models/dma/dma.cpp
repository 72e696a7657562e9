#include "dma.h"

#include <fmt/format.h>

#include "dma_regs.h"
#include "models/common/register_target.h"

namespace surfvp {

Dma::Dma(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer)
    : sc_module(name), regs("regs"), mplb("mplb"), irq("irq"), params_(params), tracer_(tracer) {
    regs.register_b_transport(this, &Dma::b_transport);
    SC_HAS_PROCESS(Dma);
    SC_THREAD(copy_thread);
    SC_METHOD(update_irq);
    sensitive << irq_changed_;
    dont_initialize();
    tracer_.signal(busy_, fmt::format("{}.busy", basename()));
    track_ = tracer_.track(basename(), "copy");
}

bool Dma::access(uint32_t offset, uint32_t& value, bool write) {
    if (!write) {
        switch (offset) {
            case dma::CTRL: value = ctrl_; return true;
            case dma::STATUS: value = status_; return true;
            case dma::SRC: value = src_; return true;
            case dma::DST: value = dst_; return true;
            case dma::LEN: value = len_; return true;
            case dma::ERROR_CODE: value = error_code_; return true;
            case dma::ERROR_ADDR: value = error_addr_; return true;
            default: return false;
        }
    }
    switch (offset) {
        case dma::CTRL:
            ctrl_ = value & dma::CTRL_IRQ_EN;
            if (!(value & dma::CTRL_START)) break;
            if (status_ & dma::STATUS_BUSY) fail(dma::ERR_START_BUSY, 0);
            else if (len_ == 0) fail(dma::ERR_ZERO_LENGTH, 0);
            else {
                status_ = dma::STATUS_BUSY;
                start_.notify(sc_core::SC_ZERO_TIME);
            }
            break;
        case dma::STATUS: status_ &= ~(value & (dma::STATUS_DONE | dma::STATUS_ERROR)); break;
        case dma::SRC: src_ = value; break;
        case dma::DST: dst_ = value; break;
        case dma::LEN: len_ = value; break;
        case dma::ERROR_CODE: case dma::ERROR_ADDR: break;  // read-only
        default: return false;
    }
    irq_changed_.notify(sc_core::SC_ZERO_TIME);
    return true;
}

void Dma::b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay) {
    answer_register_access(tx, delay, params_.register_latency, [this](uint32_t offset, uint32_t& value, bool write) {
        return access(offset, value, write);
    });
}

// Records an error; a copy in progress (BUSY) goes on unless the caller stops it.
void Dma::fail(uint32_t code, uint64_t address) {
    error_code_ = code;
    error_addr_ = static_cast<uint32_t>(address);
    status_ |= dma::STATUS_ERROR;
}

void Dma::update_irq() {
    irq.write((ctrl_ & dma::CTRL_IRQ_EN) && (status_ & (dma::STATUS_DONE | dma::STATUS_ERROR)));
}

void Dma::copy_thread() {
    // The buffer is a member: a thread that never returns is not unwound at the end of the
    // simulation, so its locals would never be freed.
    DmaEngine engine(mplb, params_.burst_beats * params_.bus_width_bits / 8);
    buffer_.resize(engine.burst_bytes());
    std::vector<uint8_t>& buffer = buffer_;
    for (;;) {
        sc_core::wait(start_);
        busy_.write(true);
        const sc_core::sc_time began = sc_core::sc_time_stamp();
        bool failed = false;
        for (uint64_t done = 0; done < len_ && !failed;) {
            const auto n = std::min<uint64_t>(buffer.size(), len_ - done);
            if (auto r = engine.read(src_ + done, buffer.data(), n); !r.ok) {
                fail(dma::ERR_READ, r.failed_address);
                failed = true;
            } else if (auto w = engine.write(dst_ + done, buffer.data(), n); !w.ok) {
                fail(dma::ERR_WRITE, w.failed_address);
                failed = true;
            } else {
                done += n;
                bytes_copied_ += n;
            }
        }
        status_ = (status_ & ~dma::STATUS_BUSY) | (failed ? 0 : dma::STATUS_DONE);
        ++copies_;
        busy_.write(false);
        if (tracer_.perfetto_on())
            tracer_.slice(track_, fmt::format("copy {} B", len_), began, sc_core::sc_time_stamp());
        irq_changed_.notify(sc_core::SC_ZERO_TIME);
    }
}

}  // namespace surfvp
