#pragma once
// The chip without time, for `surfvp run --direct`: the same driver and software run on the
// same cores (IntegralCore, HessianCore, LocalMaxFinder), with the registers the driver uses
// answered at once. An IIG START computes the whole frame: integral image, determinants and
// candidates in memory and FIFO, DONE and interrupts set. There is no back-pressure and no
// FIFO limit (both depend on time); with a FIFO that does not overflow in the VP, the
// keypoints are the VP's byte for byte (a test holds this).
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "config.h"
#include "models/fhg/hessian_core.h"
#include "models/common/hal.h"

namespace surfvp {

class DirectChip : public sw::Hal {
public:
    DirectChip(const Config& config, unsigned accelerators);

    uint8_t* backdoor(uint64_t address, uint64_t bytes);
    uint64_t cycles_consumed() const { return cycles_; }

    uint32_t read32(uint32_t address) override;
    void write32(uint32_t address, uint32_t value) override;
    void read(uint32_t address, void* data, size_t bytes) override;
    void write(uint32_t address, const void* data, size_t bytes) override;
    const uint8_t* map(uint32_t address, size_t bytes) override;
    void wait_for_irq() override;
    bool irq_pending() override;
    uint64_t time_ps() override { return 0; }
    void consume(uint64_t cycles) override { cycles_ += cycles; }
    // No time here: each fill costs what an uncontended one costs on the chip's memory path.
    uint64_t compute(uint64_t cycles, const std::vector<sw::LineTransfer>& lines) override;
    void begin(const char*) override {}
    void end() override {}
    void mark(unsigned, int) override {}

private:
    struct Iig {
        uint32_t ctrl = 0, status = 0, error = 0, src = 0, dst = 0, width = 0, height = 0, src_stride = 0, dst_stride = 0;
    };
    struct Fhg {
        uint32_t ctrl = 0, status = 0, error = 0, det = 0, width = 0, height = 0, threshold = 0, fifo_threshold = 0;
        uint32_t candidates = 0;
        bool running = false;
        std::deque<uint32_t> fifo;
    };
    struct Pair {
        Iig iig;
        Fhg fhg;
    };

    bool access(uint32_t address, uint32_t& value, bool write);
    bool access_iig(Pair& p, uint32_t offset, uint32_t& value, bool write);
    bool access_fhg(Pair& p, uint32_t offset, uint32_t& value, bool write);
    void run_frame(Pair& p);
    bool in_memory(uint64_t address, uint64_t bytes) const;
    uint32_t pending() const;

    uint64_t memory_size_;
    std::unique_ptr<uint8_t[], void (*)(void*)> memory_;
    std::vector<Pair> pairs_;
    uint32_t ier_ = 0, mer_ = 0;
    unsigned sum_bits_, iig_max_width_, iig_max_height_, fhg_max_width_, fhg_max_height_;
    fhg::HessianCore core_;
    double fill_cycles_;  // an uncontended line fill, in CPU cycles
    uint64_t cycles_ = 0;
};

}  // namespace surfvp
