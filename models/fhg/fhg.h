#pragma once
// SSA FHG, the Fast-Hessian generator (paper §III-C, Figs. 5-8). Arithmetic lives in
// HessianCore, LocalMaxFinder and SequenceGenerator; this module moves data and spends time.
//
// Integral lines arrive over PixelBus into the MasterController's line FIFO (`fifo_lines`
// lines; a sender waits while it is full). A block row (2 image rows) starts when the FIFO
// holds every line its 52-line window needs; it takes blocks x block_cycles FHG cycles,
// where block_cycles is the generated sequence's steady-state interval (blocks follow each
// other back to back) or HessianCalc's reading of the 18 TripleMAC outputs, whichever is
// longer (or `cycles_per_block` when a what-if sets it). Then the lines no later block row needs leave
// the FIFO, the block row's determinants go to the writer (DMA over PLB2, 72-byte records),
// and LocMaxFinder's candidates enter the maxima FIFO, which raises the interrupt at its
// threshold and counts what it drops when full. The frame is done when the last
// determinants are written plus the last block's tail (x3 additions still running after its
// last word) and the HessianCalc/LocMaxFinder pipeline latency.
#include <cstdint>
#include <memory>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <vector>

#include "datapath.h"
#include "fhg_registers.h"
#include "models/common/fault_plan.h"
#include "hessian_core.h"
#include "local_max_finder.h"
#include "models/common/statistics.h"
#include "models/common/parameter.h"
#include "models/common/register_target.h"
#include "models/common/tracer.h"
#include "models/host/worker.h"
#include "models/common/zeroed_memory.h"
#include "models/common/frame_stats.h"
#include "models/common/units.h"
#include "models/pixelbus/pixel_bus.h"
#include "sequence_generator.h"

namespace surfvp {

class Fhg : public sc_core::sc_module, public PixelBusIf {
public:
    struct Params {
        Frequency clock{100e6};
        fhg::SequenceParams sequence;
        fhg::Precision precision;
        unsigned hessian_cycles_per_triple_mac = 1;  // HessianCalc reads one TripleMAC's 3 responses per cycle
        unsigned pipeline_latency_cycles = 8;
        unsigned cycles_per_block = 0;  // what-if: a block's cycles instead of the sequence's (0: the sequence)
        unsigned maxima_fifo_depth = 1024;
        unsigned burst_beats = 16;
        unsigned bus_width_bits = 128;
        unsigned det_row_buffers = 2;  // block rows of determinants waiting for the writer
        unsigned max_width = 1024, max_height = 1024;
        uint64_t dma_transaction_bytes = 0;  // bytes per TLM transaction: 0 = a whole line (DmaEngine)
        Duration series_bin{1'000'000'000};  // report.html's time bins (the wiring's run.series_bin)
        RegisterTiming registers;            // a register access: its cycles (block.register_latency) of PLB1's clock
        // Block rows' determinants and maxima computed on a second thread as soon as their
        // lines have arrived, while the kernel simulates the rest (the wiring's run.parallel;
        // the results are the same).
        bool parallel = true;
        // What computes the determinants and times the block rows (fhg.model): with rtl, the
        // datapath given to use_datapath.
        fhg::DatapathModel model = fhg::DatapathModel::core;
    };
    // Its scenario parameters with the Params field each sets (fhg_params.cpp).
    static const ParamTable<Params>& parameter_table();

    // busy: the frames' whole time; computing: block rows; waiting for lines: the line FIFO
    // did not yet hold the next block row's window (the IIG and PixelBus behind); waiting for
    // the writer: every determinant row buffer still waiting for the DMA (PLB2 behind).
    struct Stats : FrameStats {
        uint64_t candidates = 0, dropped = 0;
        unsigned fifo_high_water = 0, lines_high_water = 0;
        sc_core::sc_time waiting_for_lines, waiting_for_writer;
    };

    tlm_utils::simple_target_socket<Fhg> regs;     // SPLB on PLB1
    tlm_utils::simple_initiator_socket<Fhg> mplb;  // determinants to DDR on PLB2
    PixelBusIn pixels;                             // integral lines from the IIG
    sc_core::sc_out<bool> irq;

    Fhg(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer);

    const fhg::Sequence& sequence() const { return sequence_; }  // the one `sequence.scheduler` generates
    int block_cycles() const { return block_cycles_; }           // per 2x2 block, at the FHG clock
    const char* block_limit() const { return block_limit(sequence_, params_); }

    // HessianCalc reading the 18 TripleMAC outputs; a block takes the longer of that and the
    // sequence's interval, and the longer one is its limit ("sequence" or "HessianCalc"),
    // unless `cycles_per_block` sets it ("fhg.cycles_per_block").
    static int hessian_cycles(const Params& params);
    static int block_cycles(const fhg::Sequence& sequence, const Params& params);
    static const char* block_limit(const fhg::Sequence& sequence, const Params& params);
    const fhg::HessianCore& core() const { return core_; }
    uint32_t det_bytes() const;  // bytes of one determinant in memory (fhg_regs.h)
    // What its registers check START against and report (the model and direct mode alike).
    static FhgRegisters::Limits register_limits(const Params& params);
    const Stats& stats() const { return stats_; }
    uint64_t errors() const { return registers_.status().errors(); }
    const Params& params() const { return params_; }
    // Its second thread (Params::parallel), or nullptr: the platform lends it to the software
    // for its idle time (Worker::set_background).
    Worker* worker() const { return worker_.get(); }

    void send_line(int y, const uint32_t* data, int width, const sc_core::sc_time& transfer) override;

    // Its statistics, registered at elaboration (after every connection) under `scope`.
    void register_statistics(const Statistics::Scope& scope) const;
    // fhg.model=rtl: the datapath that computes and times every block row from now on (the
    // platform gives it: the verilated one lives outside the models' library).
    void use_datapath(std::unique_ptr<fhg::Datapath> datapath) { datapath_ = std::move(datapath); }
    // Faults to inject (none by default); it is the FHG of accelerator pair `pair`.
    void set_faults(FaultPlan* faults, unsigned pair) { faults_.attach(faults, pair); }

private:
    void b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay);
    void changed();
    void start(const FhgRegisters::Frame& frame);
    void fail(uint32_t code);
    void frame_thread();
    void writer_thread();
    // Row `by`'s determinants stored into `row` as the writer sends them, and its marked maxima.
    std::vector<fhg::Candidate> compute_block_row(int by, uint8_t* row);  // plain C++: any thread
    void finish_block_row(int by, const std::vector<fhg::Candidate>& found);
    void compute_by_datapath(int by);    // fhg.model=rtl
    IntegralView frame_lines() const;    // the frame's integral lines (those received so far hold values)
    int needed_line(uint32_t by) const;  // the last integral line block row `by` reads
    void queue_ready_rows();             // hands the worker the rows whose lines have all arrived
    uint8_t* row_bytes(uint32_t by);     // where block row `by`'s stored determinants are kept
    std::vector<fhg::Candidate> block_row_results(uint32_t by);
    void push_candidates(const std::vector<fhg::Candidate>& candidates);
    void update_irq();
    void trace_levels();
    void reset();
    bool strikes(FaultKind kind) const { return faults_.strikes(kind, sc_core::sc_time_stamp().value()); }
    void corrupt_first_checked(const std::vector<fhg::Candidate>& candidates, int by);

    Params params_;
    Tracer& tracer_;
    fhg::HessianCore core_;
    std::unique_ptr<fhg::Datapath> datapath_;  // fhg.model=rtl
    const fhg::Sequence& sequence_;
    int block_cycles_;
    FhgRegisters registers_;
    struct Frame {
        uint32_t det_addr, width, height, blocks_x, blocks_y;
        int32_t threshold;
        bool running, failed;
        uint32_t error;      // ErrorCode of the failure, shown at the frame's end
        int received;        // lines received: rows 0 .. received-1
        int oldest;          // first line still held in the FIFO
        unsigned rows_sent;  // block rows handed to the writer
        unsigned rows_written;
        uint32_t rows_queued;  // block rows handed to the worker (Params::parallel)
        sc_core::sc_time began;
    } frame_{};
    FrameBuffer<uint32_t> lines_;              // received integral rows (the FIFO's contents live here)
    std::vector<std::vector<uint8_t>> slots_;  // block rows for the writer (without Params::parallel)
    sc_core::sc_fifo<int> det_rows_;           // block rows ready for the writer
    sc_core::sc_event start_, line_arrived_, room_, rows_written_, irq_changed_;
    sc_core::sc_signal<bool, sc_core::SC_UNCHECKED_WRITERS> busy_{"busy"};
    sc_core::sc_signal<unsigned, sc_core::SC_UNCHECKED_WRITERS> fifo_level_{"maxima_fifo_level"};
    sc_core::sc_signal<unsigned, sc_core::SC_UNCHECKED_WRITERS> line_level_{"line_fifo_level"};
    Stats stats_;
    TimeSeries line_series_, maxima_series_;  // FIFO levels per time bin
    int frame_track_ = -1, row_track_ = -1, level_track_ = -1;
    // The worker's results, every block row of the frame: stored determinants (the writer
    // sends them from here) and marked maxima. Row r is the worker's job row_jobs_[r] (the
    // worker runs others' jobs too: the keypoint files the workload hands it).
    FrameBuffer<uint8_t> ahead_rows_;
    std::vector<std::vector<fhg::Candidate>> ahead_found_;
    std::vector<size_t> row_jobs_;
    std::unique_ptr<Worker> worker_;  // with Params::parallel; last, so it stops before the rest goes
    BlockFaults faults_{"fhg"};
    struct Corruption {    // a determinant to invert as its row is written
        int row = -1;      // block row
        size_t index = 0;  // determinant within the row's records
    } corruption_;
};

}  // namespace surfvp
