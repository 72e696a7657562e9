#pragma once
// The hardware abstraction the CPU's software is written against (docs/architecture.md#principles, 2), a
// contract like the registers' (models/*/*_regs.h): the software (sw/) and what runs it
// (models/ppc440, platform/direct_chip) both include it, so no model reaches up into sw/. The
// software reaches the chip only through MMIO, memory and interrupts, and says how much CPU
// time its own computation takes. The VP's PPC440 stub implements it with timed TLM
// transactions; a direct (untimed) implementation runs the same software without SystemC.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "models/common/byte_order.h"

namespace surfvp::sw {

// A bus transaction answered with an error; the software may catch it, else the run
// reports it.
struct BusError : std::runtime_error {
    BusError(const std::string& what, uint32_t address) : std::runtime_error(what), address(address) {}
    uint32_t address;
};

// One cache line the L1 moves while the software computes (sw/cpu_cost counts them): a fill
// the CPU waits for, or a write-back it does not wait for.
struct LineTransfer {
    uint32_t address;   // the line's bus address
    uint64_t at_cycle;  // cycles of work into the step when it is needed (non-decreasing)
    bool write_back;
};

class Hal {
public:
    virtual ~Hal() = default;

    // One uncached 32-bit register access (on the chip: over PLB1).
    virtual uint32_t read32(uint32_t address) = 0;
    virtual void write32(uint32_t address, uint32_t value) = 0;

    // Memory (DDR), bytes in address order (byte_order.h), timed as the memory serves them: a
    // copy through the caches, line by line over the CPU's memory path.
    virtual void read(uint32_t address, void* data, size_t bytes) = 0;
    virtual void write(uint32_t address, const void* data, size_t bytes) = 0;

    // Memory for reading in place: a pointer to `bytes` bytes at `address`, without time; it
    // stays valid while the platform exists (memory does not move), and the bytes behind it
    // change only when something writes them. Software that reads through it counts its own
    // accesses and their cache misses (sw/cpu_cost) and charges them with compute(). Throws
    // BusError outside memory.
    virtual const uint8_t* map(uint32_t address, size_t bytes) = 0;

    // Blocks until the CPU's interrupt input is high, or until `timeout_ps` of the time base
    // have passed (a watchdog): false on the timeout. Where there is no time (direct mode) the
    // timeout passes when nothing else can happen.
    virtual bool wait_for_irq(uint64_t timeout_ps) = 0;
    void wait_for_irq() { wait_for_irq(kNoTimeout); }
    static constexpr uint64_t kNoTimeout = UINT64_MAX;
    // The interrupt input's level now: software that computes for long checks it between
    // pieces of work, as an interrupt would preempt it.
    virtual bool irq_pending() = 0;

    // The time base (picoseconds since reset); 0 where there is no time (direct mode).
    virtual uint64_t time_ps() = 0;

    // The software's own computation: `cycles` CPU clock cycles.
    virtual void consume(uint64_t cycles) = 0;
    // Computation with the L1 traffic it causes: `cycles` cycles of work during which each of
    // `lines` is filled (the CPU stalls until it is in) or written back (posted), at the work's
    // cycle that needed it, and `untimed_fills` more lines are filled (only where the platform
    // does not time fills: times_fills()). Returns the CPU cycles it all took: the work plus
    // the stalls, as the memory path serves the fills.
    virtual uint64_t compute(uint64_t cycles, const std::vector<LineTransfer>& lines, uint64_t untimed_fills) = 0;
    // Whether compute() times each fill at the cycle that needed it (the VP). Where it does not
    // (direct mode: every fill costs an uncontended one), software may count its fills instead
    // of listing them, and so not stamp each with its cycle.
    virtual bool times_fills() const { return true; }

    // For the trace only: the next compute()'s cycles by the software's steps, in the order
    // they ran ({"check", 1200}, {"interpolation", 800}, ...: the names of the CPU's phase
    // signal). A platform that traces the CPU's phase spreads them over the time compute()
    // takes; no figure depends on it.
    virtual void split_next_compute(const std::vector<std::pair<const char*, uint64_t>>& steps) { (void)steps; }

    // Marks a span of software work on the CPU's timeline (spans may nest).
    virtual void begin(const char* what) = 0;
    virtual void end() = 0;
    // Sets marker `index` (the platform names them: e.g. which task an accelerator works on)
    // to `value`, shown as a VCD signal and a timeline counter.
    virtual void mark(unsigned index, int value) = 0;
};

// A big-endian 32-bit word in memory, as the PPC440 loads and stores it.
inline uint32_t load32(Hal& hal, uint32_t address) {
    uint8_t bytes[4];
    hal.read(address, bytes, 4);
    return load_be32(bytes);
}

inline void store32(Hal& hal, uint32_t address, uint32_t value) {
    uint8_t bytes[4];
    store_be32(bytes, value);
    hal.write(address, bytes, 4);
}

// Marks a span for the length of a scope.
class Span {
public:
    Span(Hal& hal, const char* what) : hal_(hal) { hal_.begin(what); }
    ~Span() { hal_.end(); }
    Span(const Span&) = delete;
    Span& operator=(const Span&) = delete;

private:
    Hal& hal_;
};

}  // namespace surfvp::sw
