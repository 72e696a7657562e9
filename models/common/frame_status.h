#pragma once
// STATUS and ERROR_CODE as the IP blocks keep them (SSA IIG, SSA FHG): BUSY, DONE and ERROR
// in bits 0..2 of the block's STATUS register (DONE and ERROR are W1C in its table). A
// refused command (START while busy, a size beyond the limit) flags ERROR at once; a frame
// that fails shows ERROR only when it has ended and BUSY is clear, so that the next START
// finds the block idle. The bits live in the block's RegisterBank; this names their rules.
#include <cstdint>
#include <functional>

namespace surfvp {

class FrameStatus {
public:
    static constexpr uint32_t kBusy = 1u << 0, kDone = 1u << 1, kError = 1u << 2;

    FrameStatus(uint32_t& status, uint32_t& error_code) : bits_(status), code_(error_code) {}

    uint32_t bits() const { return bits_; }
    bool busy() const { return bits_ & kBusy; }
    bool finished() const { return bits_ & (kDone | kError); }
    uint64_t errors() const { return errors_; }  // every ERROR flagged, for the report
    void flag(uint32_t code) {
        code_ = code;
        bits_ |= kError;
        ++errors_;
    }
    void set(uint32_t sticky) { bits_ |= sticky; }  // a block's own STATUS flag
    void start() { bits_ = kBusy; }
    void reset() { bits_ = code_ = 0; }  // CTRL.RESET once idle
    void end(bool failed, uint32_t failure) {
        bits_ &= ~kBusy;
        if (failed)
            flag(failure);
        else
            bits_ |= kDone;
    }

private:
    uint32_t& bits_;
    uint32_t& code_;
    uint64_t errors_ = 0;
};

// A frame that fails keeps its first cause: true when this call is that cause (`Frame` has
// `failed` and `error`).
template <class Frame>
bool first_failure(Frame& frame, uint32_t code) {
    if (frame.failed) return false;
    frame.failed = true;
    frame.error = code;
    return true;
}

// What a block's registers call in the block: START, CTRL.ABORT and CTRL.RESET accepted, and
// a change the interrupt line may follow. `Frame` is what START programmed.
template <class Frame>
struct FrameHooks {
    std::function<void(const Frame&)> start;  // STATUS is BUSY: the units take the frame
    std::function<void()> abort;              // CTRL.ABORT while busy
    std::function<void()> changed;            // a write (or a FIFO pop): levels and the interrupt may change
    std::function<void()> reset;              // CTRL.RESET: abort a running frame, drop one that never ended
};

}  // namespace surfvp
