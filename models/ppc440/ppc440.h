#pragma once
// The PPC440 "ISS stub" (DESIGN: models/ppc440): it does not interpret PowerPC code; it runs
// the software natively in an SC_THREAD and gives it the HAL (models/common/hal.h). Time comes
// from what the software does: MMIO is a timed PLB1 transaction; memory goes line by line
// over the CPU's memory path (`mem`: the MCI link to DDR, or PLB1), and so do the L1 fills
// and write-backs the software's counted work reports (compute()), each at the time the work
// asks for it (the memory path reaches the DRAM at that time in the kernel, so the DDR grants
// the CPU and the DMA in request order). Fills asked together (a burst: the loads of one sample, issued
// before any is used) overlap up to `outstanding_fills`; the CPU waits for each burst's data,
// the critical word first; computation is charged at the CPU clock.
// Local time runs ahead of the kernel up to the global quantum (TLM-2.0 temporal
// decoupling); it is synchronised at every register access, interrupt wait and compute step,
// so what the CPU puts on the memory path does not depend on the quantum.
#include <cstdint>
#include <functional>
#include <string>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/tlm_quantumkeeper.h>
#include <vector>

#include "models/common/statistics.h"
#include "models/common/parameter.h"
#include "models/common/tracer.h"
#include "models/common/units.h"
#include "models/common/hal.h"

namespace surfvp {

class Ppc440 : public sc_core::sc_module, private sw::Hal {
public:
    struct Params {
        Frequency clock{400e6};
        Duration quantum{1000000};         // 1 us
        unsigned line_bytes = 32;          // the L1 line: memory goes in lines of this size
        unsigned outstanding_fills = 3;    // line fills in flight at once
        bool critical_word_first = true;   // read by the wiring, which sets the lead
        Duration critical_word_lead{0};    // how much sooner than the whole line the missed word arrives (0: off)
        std::vector<std::string> markers;  // names of the software's markers (HAL mark())
    };
    // Its scenario parameters with the Params field each sets (ppc440_params.cpp).
    static const ParamTable<Params>& parameter_table();
    using Software = std::function<void(sw::Hal&)>;

    struct Stats {
        uint64_t mmio_reads = 0, mmio_writes = 0;
        uint64_t bytes_read = 0, bytes_written = 0;  // on the memory path: copies, fills, write-backs
        uint64_t fills = 0, write_backs = 0;
        sc_core::sc_time fill_stall;   // the CPU waiting for its line fills
        uint64_t fill_slot_waits = 0;  // fills that waited for one of the outstanding ones to finish
        uint64_t cycles_consumed = 0;  // work, without the stalls
        uint64_t irq_waits = 0;
        sc_core::sc_time irq_wait_time;
    };

    tlm_utils::simple_initiator_socket<Ppc440> bus;  // MPLB on PLB1: registers
    tlm_utils::simple_initiator_socket<Ppc440> mem;  // memory: the MCI link (or PLB1)
    sc_core::sc_in<bool> irq;

    Ppc440(const sc_core::sc_module_name& name, const Params& params, Software software, Tracer& tracer);

    bool finished() const { return finished_; }
    const sc_core::sc_event& done_event() const { return done_; }  // notified when the software returns
    const sc_core::sc_time& finish_time() const { return finish_time_; }
    const std::string& error() const { return error_; }  // empty unless the software threw
    const Stats& stats() const { return stats_; }

    // Its statistics, registered at elaboration (after every connection) under `scope`.
    void register_statistics(const Statistics::Scope& scope) const;

private:
    void run();
    uint32_t read32(uint32_t address) override;
    void write32(uint32_t address, uint32_t value) override;
    void read(uint32_t address, void* data, size_t bytes) override;
    void write(uint32_t address, const void* data, size_t bytes) override;
    const uint8_t* map(uint32_t address, size_t bytes) override;
    using Hal::wait_for_irq;
    bool wait_for_irq(uint64_t timeout_ps) override;
    bool irq_pending() override;
    uint64_t time_ps() override;
    void consume(uint64_t cycles) override;
    // Every fill is timed: `untimed_fills` must be 0 (std::logic_error otherwise).
    uint64_t compute(uint64_t cycles, const std::vector<sw::LineTransfer>& lines, uint64_t untimed_fills) override;
    void split_next_compute(const std::vector<std::pair<const char*, uint64_t>>& steps) override;
    void begin(const char* what) override;
    void end() override;
    void mark(unsigned index, int value) override;
    // The phase signal (VCD): what the CPU does, from the spans, the waits and the split of a
    // compute(); changes are given at the CPU's own time.
    void set_phase(const sc_core::sc_time& at, unsigned phase);
    unsigned phase_of_spans() const;
    void take_irq_flows();
    void trace_compute(const sc_core::sc_time& start, const sc_core::sc_time& end);

    void mmio(tlm::tlm_command command, uint32_t address, uint8_t* data);
    void memory(tlm::tlm_command command, uint32_t address, uint8_t* data, size_t bytes);
    sc_core::sc_time line_access(tlm::tlm_command command, uint32_t address, uint8_t* data, size_t bytes,
                                 const sc_core::sc_time& at);
    sc_core::sc_time fill_burst(const std::vector<sw::LineTransfer>& lines, size_t& i, sc_core::sc_time at);
    bool dmi_covers(uint32_t address, size_t bytes);
    void invalidate_dmi(sc_dt::uint64 start, sc_dt::uint64 end);
    sc_core::sc_time now() const;

    Params params_;
    Software software_;
    Tracer& tracer_;
    tlm_utils::tlm_quantumkeeper keeper_;
    tlm::tlm_dmi dmi_;  // for map(): reading memory in place
    bool dmi_valid_ = false;
    std::vector<uint8_t> line_;                // a fill's data (the software reads in place) or a write-back's
    std::vector<sc_core::sc_time> in_flight_;  // when each outstanding fill's whole line is in
    tlm::tlm_generic_payload line_tx_;         // every line access's (a payload allocates on construction)
    bool finished_ = false;
    sc_core::sc_event done_;
    sc_core::sc_time finish_time_;
    std::string error_;
    Stats stats_;
    sc_core::sc_signal<bool> waiting_{"waiting_irq"};
    struct OpenSpan {
        std::string name;
        sc_core::sc_time start;
    };
    std::vector<OpenSpan> spans_;
    int track_ = -1;
    int phase_signal_ = -1;
    unsigned phase_ = 0;
    std::vector<std::pair<const char*, uint64_t>> next_split_;
    std::vector<uint64_t> irq_flows_;  // flows from the interrupts that woke it, to its next span
    sc_core::sc_vector<sc_core::sc_signal<int>> markers_{"marker"};
    std::vector<int> marker_tracks_;
};

}  // namespace surfvp
