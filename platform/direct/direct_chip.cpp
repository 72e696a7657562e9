#include "platform/direct/direct_chip.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <stdexcept>

#include "platform/address_map.h"
#include "models/common/byte_order.h"
#include "models/fhg/fhg_regs.h"
#include "models/fhg/block_row.h"
#include "models/iig/iig_regs.h"
#include "models/iig/integral_core.h"
#include "models/intc/intc_regs.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/run_settings.h"

namespace surfvp {
namespace f = fhg_regs;

namespace {

// The bytes an IIG frame reads and writes from its first address on.
uint64_t source_bytes(const IigRegisters::Frame& i) { return uint64_t(i.src_stride) * (i.height - 1) + i.width; }
uint64_t integral_bytes(const IigRegisters::Frame& i) {
    return uint64_t(i.dst_stride) * (i.height - 1) + 4ull * i.width;
}

}  // namespace

DirectChip::Pair::Pair(DirectChip& chip, const IigRegisters::Limits& iig_limits, const FhgRegisters::Limits& fhg_limits)
    : chip(chip),
      iig(iig_limits, {[this, &chip](const IigRegisters::Frame& f) {
                           integral = f;
                           chip.run_integral(*this);
                       },
                       [this] { iig.end(true, iig::ERR_ABORTED, 0); },
                       {},
                       {}}),
      fhg(fhg_limits, {[this](const FhgRegisters::Frame& f) {
                           stop_listening();  // first: rows still being computed read the frame before
                           determinants = f;
                           next_row = 0;
                       },
                       [this] { fhg.status().end(true, f::ERR_ABORTED); },
                       {},
                       [this] {  // RESET: a frame still listening is aborted at once (no time here)
                           if (fhg.status().busy()) fhg.status().end(true, f::ERR_ABORTED);
                           stop_listening();
                       }}) {}

// The rows being computed read `lines` and `determinants`, and the integral image being
// computed writes `lines`: they are done before either goes.
void DirectChip::Pair::stop_listening() {
    if (pending || integrating) chip.worker_->drain();
    pending = integrating = false;
    lines.clear();
}

DirectChip::DirectChip(const Config& config, unsigned accelerators)
    : memory_size_(memory_params(config).size.n),
      memory_(zeroed_memory(memory_size_, "the modelled DDR memory of direct mode (memory.size)")),
      intc_(intc_params(config).inputs, [this] { return levels(); }),
      sum_bits_(iig_params(config).sum_bits),
      core_(fhg_params(config).precision),
      fills_(uncontended_fills(config)),
      cpu_hz_(cpu_params(config).clock.hz),
      // The software's thread waits for rows only when it has nothing else to do.
      worker_(run_settings(config).parallel
                  ? std::make_unique<Worker>(std::chrono::microseconds(200), Worker::Waiter::runs_any)
                  : nullptr) {
    const Iig::Params iig = iig_params(config);
    const FhgRegisters::Limits fhg = Fhg::register_limits(fhg_params(config));
    for (unsigned k = 0; k < accelerators; ++k)
        pairs_.push_back(std::make_unique<Pair>(*this, IigRegisters::Limits{iig.max_width, iig.max_height}, fhg));
}

DirectChip::~DirectChip() {
    worker_.reset();  // its jobs write into memory_
    release_in_background(std::move(memory_));
}

bool DirectChip::in_memory(uint64_t address, uint64_t bytes) const { return address + bytes <= memory_size_; }

uint8_t* DirectChip::backdoor(uint64_t address, uint64_t bytes) {
    if (!in_memory(address, bytes)) throw std::out_of_range(fmt::format("direct memory: {:#x} +{} B", address, bytes));
    settle(address, bytes);
    return memory_.get() + address;
}

void DirectChip::read(uint32_t address, void* data, size_t bytes) {
    if (!in_memory(address, bytes)) throw sw::BusError(fmt::format("memory read at {:#010x}", address), address);
    settle(address, bytes);
    std::memcpy(data, memory_.get() + address, bytes);
}

void DirectChip::write(uint32_t address, const void* data, size_t bytes) {
    if (!in_memory(address, bytes)) throw sw::BusError(fmt::format("memory write at {:#010x}", address), address);
    settle(address, bytes);
    std::memcpy(memory_.get() + address, data, bytes);
}

const uint8_t* DirectChip::map(uint32_t address, size_t bytes) {
    if (!in_memory(address, bytes)) throw sw::BusError(fmt::format("no memory at {:#010x}", address), address);
    settle(address, bytes);
    return memory_.get() + address;
}

uint64_t DirectChip::compute(uint64_t cycles, const std::vector<sw::LineTransfer>& lines, uint64_t untimed_fills) {
    // Each burst (fills asked at one cycle) as the VP's CPU waits for it, uncontended.
    double stall = double(untimed_fills) * fills_.burst_stall(1).to_seconds();
    for (size_t i = 0; i < lines.size();) {
        size_t n = 0;
        const uint64_t at = lines[i].at_cycle;
        for (; i < lines.size() && lines[i].at_cycle == at && !lines[i].write_back; ++i) ++n;
        if (n)
            stall += fills_.burst_stall(n).to_seconds();
        else
            ++i;  // a write-back: posted
    }
    const uint64_t spent = cycles + uint64_t(std::llround(stall * cpu_hz_));
    cycles_ += spent;
    return spent;
}

// The blocks' interrupt lines, as the INTC's inputs see them.
uint32_t DirectChip::levels() const {
    uint32_t lines = 0;
    for (unsigned k = 0; k < pairs_.size(); ++k) {
        if (pairs_[k]->iig.irq()) lines |= 1u << map::irq::iig(k);
        if (pairs_[k]->fhg.irq()) lines |= 1u << map::irq::fhg(k);
    }
    return lines;
}

bool DirectChip::irq_pending() {
    intc_.latch();
    return intc_.output();
}

// The software waits: the hardware works until a line is up. Without time, a watchdog's
// timeout passes when nothing is left to do.
bool DirectChip::wait_for_irq(uint64_t timeout_ps) {
    while (!irq_pending())
        if (!step()) {
            if (timeout_ps != kNoTimeout) return false;
            throw std::runtime_error("direct mode: the software waits for an interrupt that nothing can raise");
        }
    return true;
}

// One block row of every FHG that has one to do; false when none had.
bool DirectChip::step() {
    bool worked = false;
    for (const auto& pair : pairs_) {
        Pair& p = *pair;
        if (!p.fhg.status().busy() || p.lines.empty()) continue;
        worked = true;
        const uint32_t code = block_row(p);
        if (code != f::ERR_NONE || p.next_row == (p.determinants.height + 1) / 2) {
            p.fhg.status().end(code != f::ERR_NONE, code);
            p.stop_listening();
        }
    }
    return worked;
}

uint32_t DirectChip::read32(uint32_t address) {
    uint32_t value = 0;
    if (!access(address, value, false)) throw sw::BusError(fmt::format("no register at {:#010x}", address), address);
    return value;
}

void DirectChip::write32(uint32_t address, uint32_t value) {
    if (!access(address, value, true)) throw sw::BusError(fmt::format("no register at {:#010x}", address), address);
}

bool DirectChip::access(uint32_t address, uint32_t& value, bool write) {
    if (address - map::intc.base < map::intc.size) return intc_.access(address - map::intc.base, value, write);
    for (unsigned k = 0; k < pairs_.size(); ++k) {
        Pair& p = *pairs_[k];
        if (address - map::iig_base(k) < map::iig.size) return p.iig.access(address - map::iig_base(k), value, write);
        if (address - map::fhg_base(k) < map::fhg.size) return p.fhg.access(address - map::fhg_base(k), value, write);
    }
    return false;
}

// The integral image of frame `i` into `integral` (native words, sized for it) and into memory
// (big-endian); false when a sum overflows (the rows before it are written, as the IIG's).
bool DirectChip::integrate(const IigRegisters::Frame& i, FrameBuffer<uint32_t>& integral) const {
    const IntegralCore integral_core(sum_bits_);
    for (uint32_t y = 0; y < i.height; ++y) {
        const uint32_t* above = y ? &integral[size_t(y - 1) * i.width] : nullptr;
        if (!integral_core.row(memory_.get() + i.src + size_t(y) * i.src_stride, above, &integral[size_t(y) * i.width],
                               int(i.width)))
            return false;
        store_be32_run(memory_.get() + i.dst + size_t(y) * i.dst_stride, &integral[size_t(y) * i.width], i.width);
    }
    return true;
}

// An IIG START: the whole integral image at once, streamed to the FHG when it listens. With
// run.parallel and sums that all fit, the image is a job on the worker, the stream's rows
// after it (each waits until the image is done: a waiter may take one early), and the
// software's thread goes on; memory it reaches is settled first, as the rows' is.
void DirectChip::run_integral(Pair& p) {
    if (p.integrating) worker_->wait(p.integral_job);  // the image before, into the buffers this one may take
    p.integrating = false;
    const IigRegisters::Frame& i = p.integral;
    if (!in_memory(i.src, source_bytes(i))) return p.iig.end(true, iig::ERR_READ, 0);
    if (!in_memory(i.dst, integral_bytes(i))) return p.iig.end(true, iig::ERR_WRITE, 0);
    settle(i.src, source_bytes(i));
    settle(i.dst, integral_bytes(i));
    const bool streams = i.stream && p.fhg.status().busy();
    const bool to_fhg = streams && p.determinants.width == i.width && p.determinants.height == i.height;
    if (to_fhg) p.stop_listening();  // a second stream replaces the first
    FrameBuffer<uint32_t>& integral = to_fhg ? p.lines : p.making;
    integral.resize(size_t(i.width) * i.height);            // every word is written before it is read
    auto done = std::make_shared<std::atomic<bool>>(true);  // this image's: the stream's rows wait for it
    if (worker_ && IntegralCore(sum_bits_).fits(memory_.get() + i.src, int(i.width), int(i.height), i.src_stride)) {
        done->store(false, std::memory_order_relaxed);
        p.integral_job = worker_->submit([this, i, &integral, done] {
            integrate(i, integral);
            done->store(true, std::memory_order_release);
        });
        p.integrating = true;
        p.integrating_frame = i;
    } else if (!integrate(i, integral)) {
        return p.iig.end(true, iig::ERR_OVERFLOW, 0);
    }
    if (streams && !to_fhg) p.fhg.status().end(true, f::ERR_PIXELBUS);
    if (to_fhg) {
        p.lines_done = done;
        compute_rows(p);
    }
    p.iig.end(false, iig::ERR_NONE, 0);  // no time, so no back-pressure: STALL_CYCLES 0
}

uint32_t DirectChip::row_bytes(const Pair& p) const {
    return f::row_bytes(p.determinants.width, f::det_bytes_for(core_.precision().det_bits));
}

// Block row `by`'s determinants stored into `out` as the FHG writes them, and its marked maxima.
std::vector<fhg::Candidate> DirectChip::compute_row(const Pair& p, uint32_t by, uint8_t* out) const {
    const FhgRegisters::Frame& h = p.determinants;
    const IntegralView view{p.lines.data(), int(h.width), int(h.height), h.width};
    return fhg::block_row(core_, view, int(by), h.threshold, f::det_bytes_for(core_.precision().det_bits), out);
}

// The stream's block rows from the next one on, into memory at once: with run.parallel on
// the worker, while the software goes on with the frame before; block_row() reports them in
// turn. A row beyond memory is not computed, nor those after it (block_row reports ERR_WRITE
// there). Rows still being computed for another stream where these go are done first, so the
// later stream's bytes are the ones left, as without the second thread.
void DirectChip::compute_rows(Pair& p) {
    const FhgRegisters::Frame& h = p.determinants;
    const uint32_t blocks_y = (h.height + 1) / 2;
    const uint64_t bytes = row_bytes(p);
    p.found.assign(blocks_y, {});
    p.jobs.assign(blocks_y, 0);
    p.first_row = p.end_row = p.next_row;
    while (p.end_row < blocks_y && in_memory(h.det_addr + p.end_row * bytes, bytes)) ++p.end_row;
    settle(h.det_addr + p.first_row * bytes, (p.end_row - p.first_row) * bytes);
    for (uint32_t by = p.first_row; by < p.end_row; ++by) {
        uint8_t* out = memory_.get() + h.det_addr + by * bytes;
        if (!worker_) {
            p.found[by] = compute_row(p, by, out);
            continue;
        }
        // Submitted after its image, so a row waits only when a waiter took it while the image
        // was being computed elsewhere: meanwhile it faults in the frame's rows from its own on
        // (such waits were ~3 ms of the first frame; a page takes ~1.6 us to fault in here).
        uint8_t* frame_end = memory_.get() + h.det_addr + p.end_row * bytes;
        p.jobs[by] = worker_->submit([this, &p, by, out, frame_end, done = p.lines_done] {
            populate_until(*done, out, frame_end);
            while (!done->load(std::memory_order_acquire)) Worker::relax();
            p.found[by] = compute_row(p, by, out);
        });
    }
    p.pending = worker_ && p.end_row > p.first_row;
}

// Memory about to be read or written besides the rows: an integral image still being computed
// that reads or writes there is finished first, and if rows still being computed reach it,
// every job is.
void DirectChip::settle(uint64_t address, uint64_t bytes) {
    for (const auto& pair : pairs_) {
        Pair& p = *pair;
        if (!p.integrating) continue;
        const IigRegisters::Frame& i = p.integrating_frame;
        const auto reaches = [&](uint64_t begin, uint64_t length) {
            return address < begin + length && begin < address + bytes;
        };
        if (reaches(i.src, source_bytes(i)) || reaches(i.dst, integral_bytes(i))) {
            worker_->wait(p.integral_job);
            p.integrating = false;
        }
    }
    for (const auto& pair : pairs_) {
        const Pair& p = *pair;
        if (!p.pending) continue;
        const uint64_t row = row_bytes(p), begin = p.determinants.det_addr + p.first_row * row;
        if (address < begin + (p.end_row - p.first_row) * row && begin < address + bytes) {
            worker_->drain();
            for (const auto& q : pairs_) q->pending = false;
            return;
        }
    }
}

// The FHG's next block row: its candidates into the maxima FIFO (its determinants are in
// memory). Returns the FHG's ErrorCode (ERR_NONE when the row went well).
uint32_t DirectChip::block_row(Pair& p) {
    const uint32_t by = p.next_row++;
    if (by >= p.end_row) return f::ERR_WRITE;
    if (p.pending) worker_->wait(p.jobs[by]);
    p.fhg.push(p.found[by]);
    p.found[by].clear();
    return f::ERR_NONE;
}

}  // namespace surfvp
