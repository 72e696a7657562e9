#pragma once
// The chip without time, for `surfvp run --direct`: the same driver and software run on the
// same cores (IntegralCore, HessianCore, LocalMaxFinder) and the same register behaviour as
// the models (IigRegisters, FhgRegisters, IntcRegisters), answered at once. An IIG START
// computes the integral image at once (DONE); an FHG listening to it computes the frame's
// determinants into memory at once too (with run.parallel both on the second thread, the
// image first, while the software goes on), and reports one block row at a time whenever the
// software waits for an interrupt, its candidates going into the maxima FIFO of the configured
// depth, so the driver drains the FIFO at its threshold interrupt as on the chip. Without time
// there is no back-pressure (STALL_CYCLES reads 0); the keypoints are the VP's byte for byte,
// and a FIFO that is never drained during the frame overflows by the same count (tests hold
// both).
//
// Memory the software reads or writes (read, write, map, backdoor, an IIG's image and
// integral image) waits for the integral image and the determinants being computed that reach
// it, so that it holds the same bytes with and without the second thread. A pointer from map()
// shows memory as of the call: software that starts hardware writing there maps it again.
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "platform/scenario/config.h"
#include "platform/scenario/block_params.h"
#include "models/common/hal.h"
#include "models/host/worker.h"
#include "models/common/zeroed_memory.h"
#include "models/fhg/local_max_finder.h"
#include "models/fhg/fhg_registers.h"
#include "models/fhg/hessian_core.h"
#include "models/iig/iig_registers.h"
#include "models/intc/intc_registers.h"

namespace surfvp {

class DirectChip : public sw::Hal {
public:
    DirectChip(const Config& config, unsigned accelerators);
    ~DirectChip() override;  // its worker stopped, its memory given back in the background

    uint8_t* backdoor(uint64_t address, uint64_t bytes);
    uint64_t cycles_consumed() const { return cycles_; }
    // Its second thread (run.parallel), or nullptr: lent to the software for its idle time.
    Worker* worker() const { return worker_.get(); }

    uint32_t read32(uint32_t address) override;
    void write32(uint32_t address, uint32_t value) override;
    void read(uint32_t address, void* data, size_t bytes) override;
    void write(uint32_t address, const void* data, size_t bytes) override;
    const uint8_t* map(uint32_t address, size_t bytes) override;
    using Hal::wait_for_irq;
    bool wait_for_irq(uint64_t timeout_ps) override;
    bool irq_pending() override;
    uint64_t time_ps() override { return 0; }
    void consume(uint64_t cycles) override { cycles_ += cycles; }
    // No time here: each burst of fills (those stamped at one cycle) costs what it costs the
    // CPU on the chip's memory path with nothing else on it (FillTiming::burst_stall).
    uint64_t compute(uint64_t cycles, const std::vector<sw::LineTransfer>& lines, uint64_t untimed_fills) override;
    void begin(const char*) override {}
    void end() override {}
    void mark(unsigned, int) override {}

private:
    // One IIG + FHG pair: their registers, and the frame each has taken.
    struct Pair {
        Pair(DirectChip& chip, const IigRegisters::Limits& iig, const FhgRegisters::Limits& fhg);
        void stop_listening();  // the FHG's integral lines go (the frame is over, or a new stream replaces them)
        DirectChip& chip;
        IigRegisters iig;
        FhgRegisters fhg;
        IigRegisters::Frame integral{};
        FhgRegisters::Frame determinants{};
        FrameBuffer<uint32_t> lines;  // the integral image streamed to the FHG
        // The IIG's integral image when it is not streamed (or streamed to an FHG of another
        // size); kept from frame to frame, so a frame does not allocate one.
        FrameBuffer<uint32_t> making;
        uint32_t next_row = 0;  // the FHG's next block row to report; its frame has work while BUSY
        // The stream's rows from first_row on, computed into memory when the integral image
        // came: rows up to end_row (those after a row beyond memory are not), row r's
        // candidates in found[r]. With run.parallel row r is the worker's job jobs[r] (the
        // worker runs others' jobs too: the keypoint files), and `pending` until the jobs are
        // known to be done.
        std::vector<std::vector<fhg::Candidate>> found;
        uint32_t first_row = 0, end_row = 0;
        std::vector<size_t> jobs;
        bool pending = false;
        // With run.parallel, the integral image is the worker's job integral_job (integrating
        // until it is known done: memory it reads or writes is settled first); the stream's rows
        // wait for lines_done, the image in `lines` done (a later image, not streamed, has its own).
        size_t integral_job = 0;
        bool integrating = false;
        IigRegisters::Frame integrating_frame{};
        std::shared_ptr<const std::atomic<bool>> lines_done = std::make_shared<std::atomic<bool>>(true);
    };

    bool access(uint32_t address, uint32_t& value, bool write);
    void run_integral(Pair& p);
    bool integrate(const IigRegisters::Frame& i, FrameBuffer<uint32_t>& integral) const;
    uint32_t block_row(Pair& p);
    uint32_t row_bytes(const Pair& p) const;  // one block row of stored determinants
    std::vector<fhg::Candidate> compute_row(const Pair& p, uint32_t by, uint8_t* out) const;  // any thread
    void compute_rows(Pair& p);
    void settle(uint64_t address, uint64_t bytes);
    bool step();
    bool in_memory(uint64_t address, uint64_t bytes) const;
    uint32_t levels() const;

    uint64_t memory_size_;
    ZeroedMemory memory_;
    std::vector<std::unique_ptr<Pair>> pairs_;
    IntcRegisters intc_;
    unsigned sum_bits_;
    fhg::HessianCore core_;
    FillTiming fills_;  // line fills, uncontended
    double cpu_hz_;
    uint64_t cycles_ = 0;
    std::unique_ptr<Worker> worker_;  // with run.parallel; last, so it stops before the rest goes
};

}  // namespace surfvp
