#include "iig.h"

#include <cmath>
#include <fmt/format.h>

#include "models/common/byte_order.h"
#include "models/common/clock.h"
#include "models/common/register_target.h"
#include "models/dma/dma_engine.h"

namespace surfvp {
using sc_core::sc_time;

Iig::Iig(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer)
    : sc_module(name),
      regs("regs"),
      mplb("mplb"),
      pixels("pixels"),
      irq("irq"),
      params_(params),
      tracer_(tracer),
      core_(params.sum_bits),
      registers_({params.max_width, params.max_height},
                 {[this](const IigRegisters::Frame& f) { start(f); }, [this] { fail(iig::ERR_ABORTED); },
                  [this] { irq_changed_.notify(sc_core::SC_ZERO_TIME); }, [this] { reset(); }}),
      fetched_("fetched", int(params.line_buffers)),
      computed_for_write_("computed_for_write", int(params.line_buffers)),
      computed_for_send_("computed_for_send", int(params.line_buffers)) {
    if (params.pixels_per_clock == 0 || params.line_buffers == 0 || params.pixelbus_width_bits == 0)
        throw std::invalid_argument(
            fmt::format("{}: pixels per clock, line buffers and PixelBus width must be above zero", basename()));
    regs.register_b_transport(this, &Iig::b_transport);
    SC_HAS_PROCESS(Iig);
    SC_THREAD(fetch_thread);
    SC_THREAD(compute_thread);
    SC_THREAD(write_thread);
    SC_THREAD(send_thread);
    SC_METHOD(update_irq);
    sensitive << irq_changed_;
    dont_initialize();
    tracer_.signal(busy_, fmt::format("{}.busy", basename()));
    tracer_.signal(stalled_, fmt::format("{}.stalled", basename()));
    track_ = tracer_.track(basename(), "frame");
}

void Iig::b_transport(tlm::tlm_generic_payload& tx, sc_time& delay) {
    answer_register_access(tx, delay, params_.registers.latency(), registers_);
}

// Stops the frame in progress; its ERROR shows when the units have run out (FrameStatus).
void Iig::fail(uint32_t code) { first_failure(frame_, code); }

// START accepted (IigRegisters checked it): the units take the frame.
void Iig::start(const IigRegisters::Frame& f) {
    frame_ = {
        f.src, f.dst, f.width, f.height, f.src_stride, f.dst_stride, f.stream, false, 0, 0, sc_core::sc_time_stamp()};
    image_.assign(size_t(frame_.width) * frame_.height, 0);
    integral_.assign(size_t(frame_.width) * frame_.height, 0);
    bytes_.resize(size_t(frame_.width) * 4);
    stall_total_ = sc_core::SC_ZERO_TIME;
    busy_.write(true);
    faults_.irq_lost = false;
    if (faults_.attached()) {
        faults_.plan().frame_started(faults_.pair(), f.src);
        faults_.irq_stuck = faults_.irq_stuck || strikes(FaultKind::stuck_interrupt);
    }
    start_.notify(sc_core::SC_ZERO_TIME);
}

// CTRL.RESET (BlockFaults::reset): a hung frame dropped, one in progress aborted.
void Iig::reset() {
    faults_.reset(registers_.status(), busy_, [this] { fail(iig::ERR_ABORTED); });
    irq_changed_.notify(sc_core::SC_ZERO_TIME);
}

void Iig::fetch_thread() {
    DmaEngine dma(mplb, params_.burst_beats * params_.bus_width_bits / 8, params_.dma_transaction_bytes);
    for (;;) {
        sc_core::wait(start_);
        for (uint32_t y = 0; y < frame_.height; ++y) {
            if (!frame_.failed) {
                uint8_t* row = image_.data() + size_t(y) * frame_.width;
                if (!dma.read(frame_.src + uint64_t(y) * frame_.src_stride, row, frame_.width).ok) fail(iig::ERR_READ);
            }
            fetched_.write(int(y));
        }
    }
}

void Iig::compute_thread() {
    for (;;) {
        int y = 0;
        sc_time mark = sc_core::sc_time_stamp();
        fetched_.read(y);  // read(T&): the returning read() trips -Wmaybe-uninitialized in sc_fifo.h
        if (y > 0) stats_.waiting_for_image += sc_core::sc_time_stamp() - mark;  // before row 0: no frame yet
        if (!frame_.failed) {
            const size_t at = size_t(y) * frame_.width;
            const uint32_t* above = y ? integral_.data() + at - frame_.width : nullptr;
            if (!core_.row(image_.data() + at, above, integral_.data() + at, int(frame_.width)))
                fail(iig::ERR_OVERFLOW);
            const sc_time row =
                cycles(params_.clock, double((frame_.width + params_.pixels_per_clock - 1) / params_.pixels_per_clock));
            sc_core::wait(row);
            stats_.computing += row;
        }
        mark = sc_core::sc_time_stamp();
        computed_for_write_.write(y);
        stats_.blocked_by_write += sc_core::sc_time_stamp() - mark;
        mark = sc_core::sc_time_stamp();
        if (frame_.stream) computed_for_send_.write(y);
        stats_.blocked_by_pixelbus += sc_core::sc_time_stamp() - mark;
    }
}

void Iig::write_thread() {
    DmaEngine dma(mplb, params_.burst_beats * params_.bus_width_bits / 8, params_.dma_transaction_bytes);
    for (;;) {
        int y = 0;
        computed_for_write_.read(y);  // read(T&): the returning read() trips -Wmaybe-uninitialized in sc_fifo.h
        if (!frame_.failed) {
            const uint32_t* row = integral_.data() + size_t(y) * frame_.width;
            store_be32_run(bytes_.data(), row, frame_.width);
            if (!dma.write(frame_.dst + uint64_t(y) * frame_.dst_stride, bytes_.data(), bytes_.size()).ok)
                fail(iig::ERR_WRITE);
        }
        finish_row();
    }
}

void Iig::send_thread() {
    for (;;) {
        int y = 0;
        computed_for_send_.read(y);  // read(T&): the returning read() trips -Wmaybe-uninitialized in sc_fifo.h
        if (!frame_.failed) {
            const sc_time transfer = cycles(params_.clock, double(frame_.width) * 32 / params_.pixelbus_width_bits);
            const sc_time began = sc_core::sc_time_stamp();
            stalled_.write(true);
            pixels->send_line(y, integral_.data() + size_t(y) * frame_.width, int(frame_.width), transfer);
            stalled_.write(false);
            // An FHG that no longer listens takes the line at once, without its transfer.
            const sc_time took = sc_core::sc_time_stamp() - began;
            if (took > transfer) stall_total_ += took - transfer;
        }
        finish_row();
    }
}

// A row is finished when it is written and, when streaming, sent; the frame when all are.
void Iig::finish_row() {
    if (++frame_.rows_finished < frame_.height * (frame_.stream ? 2 : 1)) return;
    stats_.stalled += stall_total_;
    stats_.ended(frame_.began);
    if (strikes(FaultKind::never_finishes)) {
        faults_.hung = true;  // the units are idle, STATUS stays BUSY
    } else {
        registers_.end(frame_.failed, frame_.error,
                       uint32_t(std::lround(stall_total_.to_seconds() * params_.clock.hz)));
        busy_.write(false);
    }
    faults_.irq_lost = strikes(FaultKind::lost_interrupt);
    if (tracer_.perfetto_on())
        tracer_.slice(track_, "integral image", frame_.began, sc_core::sc_time_stamp(),
                      TraceArgs().number("width", frame_.width).number("height", frame_.height));
    irq_changed_.notify(sc_core::SC_ZERO_TIME);
}

void Iig::update_irq() { irq.write(faults_.line(registers_.irq())); }

void Iig::register_statistics(const Statistics::Scope& s) const {
    stats_.register_statistics(
        s, [this] { return errors(); }, "from START to the last row written and sent, summed",
        "the integral core adding rows");
    s.value("clock_hz", params_.clock.hz, "Hz", "the IIG's clock");
    s.value("pixels_per_clock", params_.pixels_per_clock, "pixels", "pixels the integral core adds a cycle");
    s.time(
        "waiting_for_image_s", [this] { return stats_.waiting_for_image; },
        "the core waiting for image rows (image DMA)");
    s.time(
        "blocked_by_write_s", [this] { return stats_.blocked_by_write; },
        "the core waiting for the write unit (integral DMA)");
    s.time(
        "blocked_by_pixelbus_s", [this] { return stats_.blocked_by_pixelbus; },
        "the core waiting for the send unit (PixelBus)");
    s.time(
        "send_stalled_s", [this] { return stats_.stalled; }, "the send unit waiting on PixelBus back-pressure");
}

}  // namespace surfvp
