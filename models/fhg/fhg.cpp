#include "fhg.h"

#include <algorithm>
#include <fmt/format.h>

#include "block_row.h"
#include "fhg_regs.h"
#include "models/common/byte_order.h"
#include "models/common/clock.h"
#include "models/common/register_target.h"
#include "models/dma/dma_engine.h"
#include "sequence_cache.h"

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
      registers_(register_limits(params),
                 {[this](const FhgRegisters::Frame& f) { start(f); }, [this] { fail(r::ERR_ABORTED); },
                  [this] { changed(); }, [this] { reset(); }}),
      slots_(params.det_row_buffers + 1),
      det_rows_("det_rows", int(params.det_row_buffers)),
      line_series_(params.series_bin.ps),
      maxima_series_(params.series_bin.ps),
      worker_(params.parallel ? std::make_unique<Worker>() : nullptr) {
    if (params.det_row_buffers == 0)
        throw std::invalid_argument(fmt::format("{}: determinant row buffers must be above zero", basename()));
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

FhgRegisters::Limits Fhg::register_limits(const Params& p) {
    return {p.max_width, p.max_height, p.maxima_fifo_depth, p.precision.det_frac_bits,
            r::det_bytes_for(p.precision.det_bits)};
}

// A register write or a FIFO pop: the levels and the interrupt line may have changed.
void Fhg::changed() {
    trace_levels();
    irq_changed_.notify(sc_core::SC_ZERO_TIME);
}

void Fhg::b_transport(tlm::tlm_generic_payload& tx, sc_time& delay) {
    answer_register_access(tx, delay, params_.registers.latency(), registers_);
}

// Stops the frame: waiting units wake up and run out without doing more work; ERROR shows
// when the frame thread has finished (FrameStatus).
void Fhg::fail(uint32_t code) {
    if (!first_failure(frame_, code)) return;
    line_arrived_.notify(sc_core::SC_ZERO_TIME);
    room_.notify(sc_core::SC_ZERO_TIME);
}

// START accepted (FhgRegisters checked it and emptied the FIFO): listen for the frame.
void Fhg::start(const FhgRegisters::Frame& f) {
    if (worker_) worker_->drain();  // (nothing runs: the last frame's thread drained it)
    frame_ = {
        f.det_addr, f.width, f.height, (f.width + 1) / 2,       (f.height + 1) / 2, f.threshold, true, false, 0, 0, 0,
        0,          0,       0,        sc_core::sc_time_stamp()};
    lines_.assign(size_t(f.width) * f.height, 0);
    // Every row is written whole before the writer sends it: no need to clear.
    if (worker_) {
        ahead_rows_.resize(size_t(r::buffer_bytes(f.width, f.height, det_bytes())));
        ahead_found_.assign(frame_.blocks_y, {});
        row_jobs_.assign(frame_.blocks_y, 0);
    } else {
        for (auto& slot : slots_) slot.resize(r::row_bytes(f.width, det_bytes()));
    }
    if (datapath_) datapath_->start(int(f.width), int(f.height));
    busy_.write(true);
    faults_.irq_lost = false;
    corruption_.row = -1;
    start_.notify(sc_core::SC_ZERO_TIME);
}

// CTRL.RESET (BlockFaults::reset): a hung frame dropped (the registers clear the FIFO), one in
// progress aborted.
void Fhg::reset() {
    faults_.reset(registers_.status(), busy_, [this] { fail(r::ERR_ABORTED); });
    changed();
}

namespace {

// The software stage checks a candidate (and so reads its determinant) only when its whole
// 3x3x3 neighbourhood lies inside the image (sw/stage: the FHG writes 0 where a filter does
// not fit); these are the sizes of its three scales.
bool checked_by_software(const fhg::Candidate& c, uint32_t width, uint32_t height) {
    static constexpr int kOctave1[] = {9, 15, 21, 27}, kOctave2[] = {15, 27, 39, 51};
    const bool second = c.octave() == 2;
    const int layer = second ? c.size_index - 2 : c.size_index, step = second ? 2 : 1;
    for (int l = layer - 1; l <= layer + 1; ++l)
        for (int d : {-step, step})
            if (!fhg::HessianCore::inside(int(width), int(height), c.x + d, c.y + d,
                                          second ? kOctave2[l] : kOctave1[l]))
                return false;
    return true;
}

// Where a candidate's own determinant is among its block row's records (fhg_regs.h's layout).
size_t record_index(const fhg::Candidate& c) {
    const size_t bx = size_t(c.x / 2);
    const size_t k =
        c.octave() == 2 ? (c.size_index == 3 ? 12 : 16) : size_t(4 * c.size_index + 2 * (c.y % 2) + c.x % 2);
    return bx * fhg::kDeterminantsPerBlock + k;
}

}  // namespace

// corrupt_determinant: the first candidate the software will check has its determinant
// inverted on the way to memory (the row is written after its candidates are marked).
void Fhg::corrupt_first_checked(const std::vector<fhg::Candidate>& candidates, int by) {
    for (const fhg::Candidate& c : candidates)
        if (checked_by_software(c, frame_.width, frame_.height)) {
            if (strikes(FaultKind::corrupt_determinant)) corruption_ = {by, record_index(c)};
            return;
        }
}
// PixelBus: the IIG's send thread calls this; it waits while the line FIFO is full.
void Fhg::send_line(int y, const uint32_t* data, int width, const sc_time& transfer) {
    if (!frame_.running || frame_.failed) return;  // nobody listens: the line is lost
    if (uint32_t(width) != frame_.width || y != frame_.received) return fail(r::ERR_PIXELBUS);
    if (y == 0 && faults_.attached()) {  // the IIG has started: the frame is known
        faults_.irq_stuck = faults_.irq_stuck || strikes(FaultKind::stuck_interrupt);
        if (strikes(FaultKind::fifo_overflow)) registers_.refuse_candidates();
        changed();
    }
    while (y - frame_.oldest >= int(params_.sequence.fifo_lines) && frame_.running && !frame_.failed)
        sc_core::wait(room_);
    if (frame_.failed) return;
    sc_core::wait(transfer);
    std::copy(data, data + width, lines_.begin() + size_t(y) * frame_.width);
    frame_.received = y + 1;
    queue_ready_rows();
    stats_.lines_high_water = std::max(stats_.lines_high_water, unsigned(frame_.received - frame_.oldest));
    trace_levels();
    line_arrived_.notify(sc_core::SC_ZERO_TIME);
}

// The row's determinants and marked maxima: reads only lines_ up to the row's reach (received
// before the row began) and writes only `row`, so it may run beside the kernel.
std::vector<fhg::Candidate> Fhg::compute_block_row(int by, uint8_t* row) {
    return fhg::block_row(core_, frame_lines(), by, frame_.threshold, det_bytes(), row);
}

IntegralView Fhg::frame_lines() const { return {lines_.data(), int(frame_.width), int(frame_.height), frame_.width}; }

int Fhg::needed_line(uint32_t by) const { return std::min(int(frame_.height) - 1, int(2 * by) + fhg::kReachAfter); }

void Fhg::queue_ready_rows() {
    if (!worker_ || datapath_) return;  // a datapath of its own computes rows in order, on the kernel's thread
    while (frame_.rows_queued < frame_.blocks_y && frame_.received > needed_line(frame_.rows_queued)) {
        const uint32_t by = frame_.rows_queued++;
        uint8_t* row = row_bytes(by);
        row_jobs_[by] = worker_->submit([this, by, row] { ahead_found_[by] = compute_block_row(int(by), row); });
    }
}

uint8_t* Fhg::row_bytes(uint32_t by) {
    if (!worker_) return slots_[by % slots_.size()].data();
    return ahead_rows_.data() + size_t(by) * r::row_bytes(frame_.width, det_bytes());
}

// Row `by`'s marked maxima, its determinants at row_bytes(by): the worker's, once it has done
// them, or computed here.
std::vector<fhg::Candidate> Fhg::block_row_results(uint32_t by) {
    if (!worker_ || by >= frame_.rows_queued) return compute_block_row(int(by), row_bytes(by));
    worker_->wait(row_jobs_[by]);
    return std::move(ahead_found_[by]);
}

// fhg.model=rtl: the datapath computes the row from the lines received so far and says how
// many cycles it took; those pass, then its results are the row's.
void Fhg::compute_by_datapath(int by) {
    const fhg::Datapath::Row row = datapath_->row(frame_lines(), frame_.received, by);
    sc_core::wait(cycles(params_.clock, double(row.cycles)));
    finish_block_row(by, fhg::block_row(row.records, by, frame_.threshold, det_bytes(), row_bytes(uint32_t(by))));
}

void Fhg::finish_block_row(int by, const std::vector<fhg::Candidate>& found) {
    if (faults_.attached() && corruption_.row < 0) corrupt_first_checked(found, by);
    push_candidates(found);
}

void Fhg::frame_thread() {
    for (;;) {
        sc_core::wait(start_);
        for (uint32_t by = 0; by < frame_.blocks_y && !frame_.failed; ++by) {
            const int needed = needed_line(by);
            const sc_time waiting = sc_core::sc_time_stamp();
            while (frame_.received <= needed && !frame_.failed) sc_core::wait(line_arrived_);
            stats_.waiting_for_lines += sc_core::sc_time_stamp() - waiting;
            if (frame_.failed) break;
            const sc_time began = sc_core::sc_time_stamp();
            if (datapath_) {
                compute_by_datapath(int(by));
            } else {
                sc_core::wait(cycles(params_.clock, double(frame_.blocks_x) * block_cycles_));
                finish_block_row(int(by), block_row_results(by));  // the results exist once the row's cycles are spent
            }
            stats_.computing += sc_core::sc_time_stamp() - began;
            if (tracer_.perfetto_on())
                tracer_.slice(row_track_, "block row", began, sc_core::sc_time_stamp(),
                              TraceArgs().number("row", double(by)).number("blocks", double(frame_.blocks_x)));
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
        if (worker_) worker_->drain();  // rows queued past a failure: done before lines_ is reused
        const int tail = std::max(0, sequence_.span - sequence_.interval);  // the last block's x3 still adding
        sc_core::wait(cycles(params_.clock, double(tail + int(params_.pipeline_latency_cycles))));
        stats_.ended(frame_.began);
        frame_.running = false;
        if (strikes(FaultKind::never_finishes)) {
            faults_.hung = true;  // the units are idle, STATUS stays BUSY
        } else {
            registers_.status().end(frame_.failed, frame_.error);
            busy_.write(false);
        }
        faults_.irq_lost = strikes(FaultKind::lost_interrupt);
        room_.notify(sc_core::SC_ZERO_TIME);  // a sender still waiting gives up
        if (tracer_.perfetto_on())
            tracer_.slice(frame_track_, "determinants", frame_.began, sc_core::sc_time_stamp(),
                          TraceArgs().number("width", frame_.width).number("height", frame_.height));
        irq_changed_.notify(sc_core::SC_ZERO_TIME);
    }
}

void Fhg::writer_thread() {
    DmaEngine dma(mplb, params_.burst_beats * params_.bus_width_bits / 8, params_.dma_transaction_bytes);
    for (;;) {
        int by = 0;
        det_rows_.read(by);  // read(T&): the returning read() trips -Wmaybe-uninitialized in sc_fifo.h
        if (!frame_.failed) {
            const uint32_t n = det_bytes(), bytes = r::row_bytes(frame_.width, n);
            uint8_t* row = row_bytes(uint32_t(by));  // nothing reads it after this write
            if (corruption_.row == by) {
                uint8_t* det = row + n * corruption_.index;
                r::store_det(det, ~r::load_det(det, n), n);
                corruption_.row = -1;
            }
            if (!dma.write(frame_.det_addr + uint64_t(by) * bytes, row, bytes).ok) fail(r::ERR_WRITE);
        }
        ++frame_.rows_written;
        rows_written_.notify(sc_core::SC_ZERO_TIME);
    }
}

void Fhg::push_candidates(const std::vector<fhg::Candidate>& candidates) {
    stats_.candidates += candidates.size();
    stats_.dropped += registers_.push(candidates);
    stats_.fifo_high_water = std::max(stats_.fifo_high_water, registers_.fifo_level());
    changed();
}

void Fhg::trace_levels() {
    const uint64_t now = sc_core::sc_time_stamp().value();
    line_series_.level(now, double(frame_.received - frame_.oldest));
    maxima_series_.level(now, double(registers_.fifo_level()));
    if (tracer_.vcd_on()) {
        fifo_level_.write(registers_.fifo_level());
        line_level_.write(unsigned(frame_.received - frame_.oldest));
    }
    if (tracer_.perfetto_on()) {
        tracer_.counter(level_track_, "maxima FIFO", sc_core::sc_time_stamp(), double(registers_.fifo_level()));
        tracer_.counter(level_track_, "line FIFO", sc_core::sc_time_stamp(), double(frame_.received - frame_.oldest));
    }
}

void Fhg::update_irq() { irq.write(faults_.line(registers_.irq())); }

void Fhg::register_statistics(const Statistics::Scope& s) const {
    stats_.register_statistics(
        s, [this] { return errors(); }, "from START to the last determinants written, summed", "computing block rows");
    s.value("clock_hz", params_.clock.hz, "Hz", "the FHG's clock");
    s.value("cycles_per_block", block_cycles_, "cycles", "FHG cycles per 2x2 block");
    s.text(
        "block_limit", [this] { return std::string(block_limit()); }, "what sets the cycles per block");
    s.time(
        "waiting_for_lines_s", [this] { return stats_.waiting_for_lines; },
        "waiting for the line FIFO to hold a block row's window");
    s.time(
        "waiting_for_writer_s", [this] { return stats_.waiting_for_writer; },
        "waiting for a free determinant row buffer (PLB2)");
    s.count(
        "candidates", [this] { return stats_.candidates; }, "candidates", "local maxima marked");
    s.count(
        "candidates_dropped", [this] { return stats_.dropped; }, "candidates", "dropped on a full maxima FIFO");
    s.high_water(
        "maxima_fifo_high_water", [this] { return uint64_t(stats_.fifo_high_water); }, "entries",
        "the maxima FIFO's highest level");
    s.series("line_fifo_series", line_series_, "lines", "the line FIFO's highest level per time bin");
    s.series("maxima_fifo_series", maxima_series_, "entries", "the maxima FIFO's highest level per time bin");
    s.high_water(
        "line_fifo_high_water", [this] { return uint64_t(stats_.lines_high_water); }, "lines",
        "the line FIFO's highest level");
}

}  // namespace surfvp
