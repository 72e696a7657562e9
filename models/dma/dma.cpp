#include "dma.h"

#include <fmt/format.h>

#include "dma_regs.h"
#include "models/common/register_target.h"

namespace surfvp {

Dma::Dma(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer)
    : sc_module(name), regs("regs"), mplb("mplb"), irq("irq"), params_(params), tracer_(tracer), bank_(dma::table()) {
    bind_registers();
    regs.register_b_transport(this, &Dma::b_transport);
    SC_HAS_PROCESS(Dma);
    SC_THREAD(copy_thread);
    SC_METHOD(update_irq);
    sensitive << irq_changed_;
    dont_initialize();
    tracer_.signal(busy_, fmt::format("{}.busy", basename()));
    track_ = tracer_.track(basename(), "copy");
}

// Registers by the table (dma_regs.h); CTRL.START begins a copy.
void Dma::bind_registers() {
    bank_.on_write(dma::CTRL, [this](uint32_t value) {
        if (!(value & dma::CTRL_START)) return;
        if (reg(dma::STATUS) & dma::STATUS_BUSY)
            fail(dma::ERR_START_BUSY, 0);
        else if (reg(dma::LEN) == 0)
            fail(dma::ERR_ZERO_LENGTH, 0);
        else {
            reg(dma::STATUS) = dma::STATUS_BUSY;
            start_.notify(sc_core::SC_ZERO_TIME);
        }
    });
}

bool Dma::access(uint32_t offset, uint32_t& value, bool write) {
    if (!bank_.access(offset, value, write)) return false;
    if (write) irq_changed_.notify(sc_core::SC_ZERO_TIME);
    return true;
}

void Dma::b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay) {
    answer_register_access(
        tx, delay, params_.registers.latency(),
        [this](uint32_t offset, uint32_t& value, bool write) { return access(offset, value, write); });
}

// Records an error; a copy in progress (BUSY) goes on unless the caller stops it.
void Dma::fail(uint32_t code, uint64_t address) {
    reg(dma::ERROR_CODE) = code;
    reg(dma::ERROR_ADDR) = static_cast<uint32_t>(address);
    reg(dma::STATUS) |= dma::STATUS_ERROR;
}

void Dma::update_irq() {
    irq.write((reg(dma::CTRL) & dma::CTRL_IRQ_EN) && (reg(dma::STATUS) & (dma::STATUS_DONE | dma::STATUS_ERROR)));
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
        const uint32_t src = reg(dma::SRC), dst = reg(dma::DST), len = reg(dma::LEN);
        for (uint64_t done = 0; done < len && !failed;) {
            const auto n = std::min<uint64_t>(buffer.size(), len - done);
            if (auto r = engine.read(src + done, buffer.data(), n); !r.ok) {
                fail(dma::ERR_READ, r.failed_address);
                failed = true;
            } else if (auto w = engine.write(dst + done, buffer.data(), n); !w.ok) {
                fail(dma::ERR_WRITE, w.failed_address);
                failed = true;
            } else {
                done += n;
                bytes_copied_ += n;
            }
        }
        reg(dma::STATUS) = (reg(dma::STATUS) & ~dma::STATUS_BUSY) | (failed ? 0 : dma::STATUS_DONE);
        ++copies_;
        busy_.write(false);
        if (tracer_.perfetto_on())
            tracer_.slice(track_, "copy", began, sc_core::sc_time_stamp(), TraceArgs().number("bytes", double(len)));
        irq_changed_.notify(sc_core::SC_ZERO_TIME);
    }
}

void Dma::register_statistics(const Statistics::Scope& s) const {
    s.count(
        "copies", [this] { return copies_; }, "copies", "copies done");
    s.bytes(
        "bytes_copied", [this] { return bytes_copied_; }, "bytes copied");
}

}  // namespace surfvp
