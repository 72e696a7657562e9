#include "fhg.h"

#include <algorithm>
#include <fmt/format.h>

#include "fhg_regs.h"

static_assert(surfvp::fhg_regs::STATUS_BUSY == surfvp::FrameStatus::kBusy &&
              surfvp::fhg_regs::STATUS_DONE == surfvp::FrameStatus::kDone &&
              surfvp::fhg_regs::STATUS_ERROR == surfvp::FrameStatus::kError);
#include "models/common/byte_order.h"
#include "models/common/clock.h"
#include "models/common/register_target.h"
#include "models/dma/dma_engine.h"

namespace surfvp {
namespace r = fhg_regs;
using sc_core::sc_time;

Fhg::Fhg(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer)
    : sc_module(name),
      regs("regs"),
      mplb("mplb"),
      pixels("pixels"),
      irq("irq"),
      params_(params),
      tracer_(tracer),
      core_(params.precision),
      sequence_(fhg::cached_sequence(params.sequence)),
      block_cycles_(block_cycles(sequence_, params)),
      slots_(params.det_row_buffers + 1),
      det_rows_("det_rows", int(params.det_row_buffers)) {
    if (params.maxima_fifo_depth == 0 || params.det_row_buffers == 0)
        throw std::invalid_argument(fmt::format("{}: FIFO depth and determinant row buffers must be above zero", basename()));
    pixels.bind(*this);
    regs.register_b_transport(this, &Fhg::b_transport);
    SC_HAS_PROCESS(Fhg);
    SC_THREAD(frame_thread);
    SC_THREAD(writer_thread);
    SC_METHOD(update_irq);
    sensitive << irq_changed_;
    dont_initialize();
    tracer_.signal(busy_, fmt::format("{}.busy", basename()));
    tracer_.signal(fifo_level_, fmt::format("{}.maxima_fifo_level", basename()));
    tracer_.signal(line_level_, fmt::format("{}.line_fifo_level", basename()));
    frame_track_ = tracer_.track(basename(), "frame");
    row_track_ = tracer_.track(basename(), "block rows");
    level_track_ = tracer_.track(basename(), "levels");
}

int Fhg::hessian_cycles(const Params& params) {
    return int(fhg::kDeterminantsPerBlock * params.hessian_cycles_per_triple_mac);
}

int Fhg::block_cycles(const fhg::Sequence& sequence, const Params& params) {
    if (params.cycles_per_block) return int(params.cycles_per_block);
    return std::max(sequence.interval, hessian_cycles(params));
}

const char* Fhg::block_limit(const fhg::Sequence& sequence, const Params& params) {
    if (params.cycles_per_block) return "fhg.cycles_per_block";
    return sequence.interval >= hessian_cycles(params) ? "sequence" : "HessianCalc";
}

uint32_t Fhg::det_bytes() const { return r::det_bytes_for(params_.precision.det_bits); }

bool Fhg::access(uint32_t offset, uint32_t& value, bool write) {
    uint32_t* reg = nullptr;
    switch (offset) {
        case r::CTRL: reg = &ctrl_; break;
        case r::DET_ADDR: reg = &det_addr_; break;
        case r::WIDTH: reg = &width_; break;
        case r::HEIGHT: reg = &height_; break;
        case r::THRESHOLD: reg = &threshold_; break;
        case r::FIFO_THRESHOLD: reg = &fifo_threshold_; break;
        case r::STATUS: case r::ERROR_CODE: case r::FIFO_DATA: case r::FIFO_LEVEL:
        case r::OVERFLOW_COUNT: case r::CANDIDATES: case r::DET_FRAC_BITS: case r::DET_BYTES: break;
        default: return false;
    }
    if (!write) {
        switch (offset) {
            case r::STATUS:
                value = status_.bits | (fifo_threshold_ && maxima_.size() >= fifo_threshold_ ? r::STATUS_FIFO_IRQ : 0);
                break;
            case r::ERROR_CODE: value = status_.error_code; break;
            case r::FIFO_DATA: value = pop_candidate(); break;
            case r::FIFO_LEVEL: value = uint32_t(maxima_.size()); break;
            case r::OVERFLOW_COUNT: value = overflow_count_; break;
            case r::CANDIDATES: value = candidate_count_; break;
            case r::DET_FRAC_BITS: value = params_.precision.det_frac_bits; break;
            case r::DET_BYTES: value = det_bytes(); break;
            default: value = *reg;
        }
        return true;
    }
    if (offset == r::STATUS) {
        status_.write_one_to_clear(value, r::STATUS_FIFO_OVERFLOW);
    } else if (offset == r::CTRL) {
        ctrl_ = value & (r::CTRL_IRQ_EN_DONE | r::CTRL_IRQ_EN_FIFO);
        if (value & r::CTRL_ABORT) {
            if (frame_.running) fail(r::ERR_ABORTED);
        } else if (value & r::CTRL_START) {
            start();
        }
    } else if (reg) {
        *reg = value;
    }
    irq_changed_.notify(sc_core::SC_ZERO_TIME);
    return true;
}

void Fhg::b_transport(tlm::tlm_generic_payload& tx, sc_time& delay) {
    answer_register_access(tx, delay, params_.register_latency, [this](uint32_t offset, uint32_t& value, bool write) {
        return access(offset, value, write);
    });
}

// Stops the frame: waiting units wake up and run out without doing more work; ERROR shows
// when the frame thread has finished (FrameStatus).
void Fhg::fail(uint32_t code) {
    if (frame_.failed) return;  // the first cause stands
    frame_.failed = true;
    frame_.error = code;
    line_arrived_.notify(sc_core::SC_ZERO_TIME);
    room_.notify(sc_core::SC_ZERO_TIME);
}

void Fhg::start() {
    if (frame_.running) return status_.flag(r::ERR_START_BUSY);
    if (width_ == 0 || height_ == 0 || width_ > params_.max_width || height_ > params_.max_height)
        return status_.flag(r::ERR_SIZE);
    frame_ = {det_addr_, width_, height_, (width_ + 1) / 2, (height_ + 1) / 2, int32_t(threshold_), true, false, 0, 0, 0,
              0, 0, sc_core::sc_time_stamp()};
    lines_.assign(size_t(width_) * height_, 0);
    for (auto& slot : slots_) slot.assign(size_t(frame_.blocks_x) * fhg::kDeterminantsPerBlock, 0);
    maxima_.clear();
    overflow_count_ = candidate_count_ = 0;
    status_.start();
    busy_.write(true);
    start_.notify(sc_core::SC_ZERO_TIME);
}

// PixelBus: the IIG's send thread calls this; it waits while the line FIFO is full.
void Fhg::send_line(int y, const uint32_t* data, int width, const sc_time& transfer) {
    if (!frame_.running || frame_.failed) return;  // nobody listens: the line is lost
    if (uint32_t(width) != frame_.width || y != frame_.received) return fail(r::ERR_PIXELBUS);
    while (y - frame_.oldest >= int(params_.sequence.fifo_lines) && frame_.running && !frame_.failed)
        sc_core::wait(room_);
    if (frame_.failed) return;
    sc_core::wait(transfer);
    std::copy(data, data + width, lines_.begin() + size_t(y) * frame_.width);
    frame_.received = y + 1;
    stats_.lines_high_water = std::max(stats_.lines_high_water, unsigned(frame_.received - frame_.oldest));
    trace_levels();
    line_arrived_.notify(sc_core::SC_ZERO_TIME);
}

void Fhg::compute_block_row(int by, int32_t* records) {
    const IntegralView view{lines_.data(), int(frame_.width), int(frame_.height), frame_.width};
    core_.block_row(view, by, records);
    std::vector<fhg::Candidate> found;
    fhg::LocalMaxFinder(frame_.threshold).block_row(records, int(frame_.blocks_x), by, found);
    push_candidates(found);
}

void Fhg::frame_thread() {
    for (;;) {
        sc_core::wait(start_);
        for (uint32_t by = 0; by < frame_.blocks_y && !frame_.failed; ++by) {
            const int needed = std::min(int(frame_.height) - 1, int(2 * by) + fhg::kReachAfter);
            const sc_time waiting = sc_core::sc_time_stamp();
            while (frame_.received <= needed && !frame_.failed) sc_core::wait(line_arrived_);
            stats_.waiting_for_lines += sc_core::sc_time_stamp() - waiting;
            if (frame_.failed) break;
            const sc_time began = sc_core::sc_time_stamp();
            int32_t* records = slots_[by % slots_.size()].data();
            sc_core::wait(cycles(params_.clock, double(frame_.blocks_x) * block_cycles_));
            compute_block_row(int(by), records);  // the results exist once the row's cycles are spent
            stats_.computing += sc_core::sc_time_stamp() - began;
            if (tracer_.perfetto_on()) tracer_.slice(row_track_, fmt::format("block row {}", by), began, sc_core::sc_time_stamp());
            frame_.oldest = std::max(frame_.oldest, int(2 * (by + 1)) - fhg::kReachBefore);
            trace_levels();
            room_.notify(sc_core::SC_ZERO_TIME);
            ++frame_.rows_sent;
            const sc_time handing = sc_core::sc_time_stamp();
            det_rows_.write(int(by));
            stats_.waiting_for_writer += sc_core::sc_time_stamp() - handing;
        }
        // Failed or not, the writer finishes the rows it was given before the frame ends, so
        // that nothing of this frame reaches the next one.
        while (frame_.rows_written < frame_.rows_sent) sc_core::wait(rows_written_);
        const int tail = std::max(0, sequence_.span - sequence_.interval);  // the last block's x3 still adding
        sc_core::wait(cycles(params_.clock, double(tail + int(params_.pipeline_latency_cycles))));
        stats_.busy += sc_core::sc_time_stamp() - frame_.began;
        ++stats_.frames;
        frame_.running = false;
        status_.end(frame_.failed, frame_.error);
        busy_.write(false);
        room_.notify(sc_core::SC_ZERO_TIME);  // a sender still waiting gives up
        if (tracer_.perfetto_on())
            tracer_.slice(frame_track_, fmt::format("determinants {}x{}", frame_.width, frame_.height), frame_.began,
                          sc_core::sc_time_stamp());
        irq_changed_.notify(sc_core::SC_ZERO_TIME);
    }
}

void Fhg::writer_thread() {
    DmaEngine dma(mplb, params_.burst_beats * params_.bus_width_bits / 8, params_.dma_transaction_bytes);
    std::vector<uint8_t> bytes;
    for (;;) {
        int by = 0;
        det_rows_.read(by);  // read(T&): the returning read() trips -Wmaybe-uninitialized in sc_fifo.h
        if (!frame_.failed) {
            const std::vector<int32_t>& records = slots_[size_t(by) % slots_.size()];
            const uint32_t n = det_bytes();
            bytes.resize(records.size() * n);
            for (size_t i = 0; i < records.size(); ++i) r::store_det(bytes.data() + n * i, records[i], n);
            const uint64_t at = frame_.det_addr + uint64_t(by) * frame_.blocks_x * r::record_bytes(n);
            if (!dma.write(at, bytes.data(), bytes.size()).ok) fail(r::ERR_WRITE);
        }
        ++frame_.rows_written;
        rows_written_.notify(sc_core::SC_ZERO_TIME);
    }
}

void Fhg::push_candidates(const std::vector<fhg::Candidate>& candidates) {
    for (const fhg::Candidate& c : candidates) {
        ++candidate_count_;
        ++stats_.candidates;
        if (maxima_.size() >= params_.maxima_fifo_depth) {
            ++overflow_count_;
            ++stats_.dropped;
            status_.bits |= r::STATUS_FIFO_OVERFLOW;
            continue;
        }
        maxima_.push_back(fhg::pack_candidate(c));
    }
    stats_.fifo_high_water = std::max(stats_.fifo_high_water, unsigned(maxima_.size()));
    trace_levels();
    irq_changed_.notify(sc_core::SC_ZERO_TIME);
}

uint32_t Fhg::pop_candidate() {
    if (maxima_.empty()) return 0;
    const uint32_t word = maxima_.front();
    maxima_.pop_front();
    trace_levels();
    irq_changed_.notify(sc_core::SC_ZERO_TIME);
    return word;
}

void Fhg::trace_levels() {
    if (tracer_.vcd_on()) {
        fifo_level_.write(unsigned(maxima_.size()));
        line_level_.write(unsigned(frame_.received - frame_.oldest));
    }
    if (tracer_.perfetto_on()) {
        tracer_.counter(level_track_, "maxima FIFO", sc_core::sc_time_stamp(), double(maxima_.size()));
        tracer_.counter(level_track_, "line FIFO", sc_core::sc_time_stamp(), double(frame_.received - frame_.oldest));
    }
}

void Fhg::update_irq() {
    const bool done = (ctrl_ & r::CTRL_IRQ_EN_DONE) && status_.finished();
    const bool fifo = (ctrl_ & r::CTRL_IRQ_EN_FIFO) && fifo_threshold_ && maxima_.size() >= fifo_threshold_;
    irq.write(done || fifo);
}

}  // namespace surfvp
