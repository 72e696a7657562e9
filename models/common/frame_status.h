#pragma once
// STATUS and ERROR_CODE as the IP blocks keep them (SSA IIG, SSA FHG): BUSY, DONE and ERROR
// in bits 0..2, DONE and ERROR cleared by writing 1. A refused command (START while busy, a
// size beyond the limit) flags ERROR at once; a frame that fails shows ERROR only when it
// has ended and BUSY is clear, so that the next START finds the block idle.
#include <cstdint>

namespace surfvp {

struct FrameStatus {
    static constexpr uint32_t kBusy = 1u << 0, kDone = 1u << 1, kError = 1u << 2;

    uint32_t bits = 0;
    uint32_t error_code = 0;
    uint64_t errors = 0;  // every ERROR flagged, for the report

    bool busy() const { return bits & kBusy; }
    bool finished() const { return bits & (kDone | kError); }
    void flag(uint32_t code) {
        error_code = code;
        bits |= kError;
        ++errors;
    }
    void start() { bits = kBusy; }
    void end(bool failed, uint32_t failure) {
        bits &= ~kBusy;
        if (failed) flag(failure);
        else bits |= kDone;
    }
    // A STATUS write: 1 clears DONE, ERROR and the block's own sticky bits in `sticky`.
    void write_one_to_clear(uint32_t value, uint32_t sticky = 0) { bits &= ~(value & (kDone | kError | sticky)); }
};

}  // namespace surfvp
