#pragma once
// SSA IIG, the integral image generator (paper §III-B, Fig. 4). Arithmetic lives in
// IntegralCore; this module moves data and spends time. A frame runs as a pipeline of four
// units, each an SC_THREAD, joined by line queues of `line_buffers` entries:
//   fetch    DMA-reads image row y over its MPLB (PLB2)
//   compute  adds it to the row above at `pixels_per_clock`
//   write    DMA-writes the integral row (32-bit big-endian words) to DST
//   send     puts the integral row on PixelBus to the FHG (CTRL.STREAM), stalling while the
//            FHG has no room: back-pressure that fills the queues and stalls the rest
// The frame is done when the last row is written and sent; an error stops the work (the
// remaining rows pass through the queues untouched) and the frame ends with ERROR.
#include <cstdint>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <vector>

#include "iig_registers.h"
#include "models/common/fault_plan.h"
#include "integral_core.h"
#include "models/common/zeroed_memory.h"
#include "models/common/statistics.h"
#include "models/common/parameter.h"
#include "models/common/register_target.h"
#include "models/common/tracer.h"
#include "models/common/frame_stats.h"
#include "models/common/units.h"
#include "models/pixelbus/pixel_bus.h"

namespace surfvp {

class Iig : public sc_core::sc_module {
public:
    struct Params {
        Frequency clock{100e6};
        unsigned pixels_per_clock = 1;
        unsigned sum_bits = 28;
        unsigned burst_beats = 16;
        unsigned bus_width_bits = 128;  // of the bus its MPLB is on
        unsigned pixelbus_width_bits = 32;
        unsigned line_buffers = 2;
        unsigned max_width = 1024, max_height = 1024;
        uint64_t dma_transaction_bytes = 0;  // bytes per TLM transaction: 0 = a whole line (DmaEngine)
        RegisterTiming registers;            // a register access: its cycles (block.register_latency) of PLB1's clock
    };
    // Its scenario parameters with the Params field each sets (iig_params.cpp).
    static const ParamTable<Params>& parameter_table();

    // Where the integral core's time goes (its compute unit's view of the pipeline): adding
    // rows, waiting for the fetch unit's image rows (image DMA), or waiting for room to hand a
    // row on because the write unit (integral DMA) or the send unit (PixelBus back-pressure) is
    // behind; `busy` is the frames' whole time, start to last row written and sent.
    struct Stats : FrameStats {
        sc_core::sc_time stalled;  // the send unit waiting on PixelBus back-pressure
        sc_core::sc_time waiting_for_image, blocked_by_write, blocked_by_pixelbus;
    };

    tlm_utils::simple_target_socket<Iig> regs;     // SPLB on PLB1
    tlm_utils::simple_initiator_socket<Iig> mplb;  // DMA on PLB2
    PixelBusOut pixels;                            // to the FHG
    sc_core::sc_out<bool> irq;

    Iig(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer);

    const Stats& stats() const { return stats_; }
    uint64_t errors() const { return registers_.status().errors(); }
    const Params& params() const { return params_; }

    // Its statistics, registered at elaboration (after every connection) under `scope`.
    void register_statistics(const Statistics::Scope& scope) const;
    // Faults to inject (none by default); it is the IIG of accelerator pair `pair`.
    void set_faults(FaultPlan* faults, unsigned pair) { faults_.attach(faults, pair); }

private:
    void b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay);
    void start(const IigRegisters::Frame& frame);
    void fail(uint32_t code);
    void fetch_thread();
    void compute_thread();
    void write_thread();
    void send_thread();
    void finish_row();
    void update_irq();
    void reset();
    bool strikes(FaultKind kind) const { return faults_.strikes(kind, sc_core::sc_time_stamp().value()); }

    Params params_;
    Tracer& tracer_;
    IntegralCore core_;
    IigRegisters registers_;
    // The frame being worked on (its registers latched at START).
    struct Frame {
        uint32_t src, dst, width, height, src_stride, dst_stride;
        bool stream;
        bool failed;
        uint32_t error;          // ErrorCode of the failure, shown at the frame's end
        unsigned rows_finished;  // written and (if streaming) sent
        sc_core::sc_time began;
    } frame_{};
    FrameBuffer<uint8_t> image_;      // the frame's image rows as fetched
    FrameBuffer<uint32_t> integral_;  // the frame's integral rows
    std::vector<uint8_t> bytes_;      // one integral row as bus bytes
    sc_core::sc_fifo<int> fetched_, computed_for_write_, computed_for_send_;
    sc_core::sc_event start_, irq_changed_;
    sc_core::sc_signal<bool, sc_core::SC_UNCHECKED_WRITERS> busy_{"busy"};  // set by START, cleared by the last unit
    sc_core::sc_signal<bool> stalled_{"stalled"};
    Stats stats_;
    sc_core::sc_time stall_total_;
    int track_ = -1;
    BlockFaults faults_{"iig"};
};

}  // namespace surfvp
