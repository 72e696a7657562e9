// The FHG's datapath (paper III-C, Fig. 6): integral lines into the MasterController's line
// FIFO, its sequence memory driving the read buses and the TripleMACs, HessianCalc after them.
//
// - The MasterController's control and addressing sequence, too large for logic, sits in block
//   RAM and runs once per 2 x 2 block (paper III-C): sequence_memory.v, one word per cycle,
//   the sequence starting again after the word marked `last`, so blocks follow without a gap.
// - A word names, per bus, a word of the block's window and the read port of each value it
//   wants; the line FIFO (line_fifo.v) reads them at the next edge, so the word's TripleMAC
//   fields wait one cycle for their values.
// - The 18 TripleMACs are connected to the read buses and capture their data (III-C): each
//   takes, in a cycle its word says so, one value
//   of one bus word (bus, lane), with its coefficient and response.
// - Blocks run row by row over the frame, ceil(width / 2) x ceil(height / 2) of them, from
//   `start` until `done`; a block row waits until the FIFO holds its whole window. The block
//   in flight is (block_x, block_y), its pixel (0, 0).
module fhg_datapath (clk, clk2x, rst, start, width, height, in_valid, in_value, in_ready, block_x, block_y, det_valid,
                     det_index, det_value, det_block_x, det_block_y, busy, done, overrun, stalled);
`include "fhg_params.vh"
    input  wire                                clk;
    input  wire                                clk2x;  // twice clk, edges aligned: a `tdp_x2` line FIFO's BRAMs
    input  wire                                rst;
    input  wire                                start;  // a frame: the sequence runs from its first word
    input  wire [15:0]                         width;   // the frame's, taken at `start`
    input  wire [15:0]                         height;
    input  wire                                in_valid;  // integral values, row by row (the PixelBus)
    input  wire [31:0]                         in_value;
    output wire                                in_ready;
    output reg  [15:0]                         block_x;
    output reg  [15:0]                         block_y;
    output wire                                det_valid;
    output wire [4:0]                          det_index;
    output wire [DET_BITS-1:0]                 det_value;
    output wire [15:0]                         det_block_x;
    output wire [15:0]                         det_block_y;
    output reg                                 busy;
    output reg                                 done;
    output reg                                 overrun;  // a TripleMAC latched before HessianCalc read the last block
    output wire                                stalled;  // the sequence waits for lines

    // The frame's size, held from `start` on as the FHG's registers hold it.
    reg [15:0] frame_width, frame_height;
    always @(posedge clk)
        if (start) begin
            frame_width <= width;
            frame_height <= height;
        end

    // A block RAM reads synchronously: `word` is this cycle's, read last cycle from the address
    // that follows the previous word (or the first, after `last`).
    wire [SEQ_WIDTH-1:0] word;
    reg  [8:0] pc;  // the next word's address
    wire [15:0] rows_written;
    wire [16:0] window_end = {1'b0, block_y} + WINDOW_BEFORE;  // rows the block row needs
    assign stalled = busy && {1'b0, rows_written} < (window_end < {1'b0, frame_height} ? window_end : {1'b0, frame_height});
    wire issue = busy && !stalled;  // this cycle's word goes out
    wire last = issue && word[SEQ_LAST];
    wire [8:0] address = (start || last) ? 9'd0 : (issue ? pc : pc - 9'd1);
    sequence_memory control_store (.clk(clk), .address(address), .word(word));
    always @(posedge clk) pc <= address + 9'd1;
    // The word's TripleMAC fields and `last`, a cycle later, with the values the FIFO read.
    reg [SEQ_WIDTH-1:0] taking;
    reg                 taking_valid;
    always @(posedge clk) begin
        taking <= word;
        taking_valid <= rst ? 1'b0 : issue;
    end
    wire [READ_BUSES*LANES*32-1:0] bus_data;
    wire [READ_BUSES-1:0] bus_valid;
    wire [READ_BUSES*COORD_BITS-1:0] bus_line, bus_column;
    wire [READ_BUSES*LANES-1:0] lane_read;
    // The slot of the window's top line (row block_y - 26) in the line FIFO.
    localparam SLOT_BITS = $clog2(FIFO_LINES);
    localparam [SLOT_BITS-1:0] FIRST_TOP = (FIFO_LINES - WINDOW_BEFORE % FIFO_LINES) % FIFO_LINES;
    reg [SLOT_BITS-1:0] top_slot;
    wire [15:0] last_x = 2 * (((frame_width + 1) >> 1) - 1), last_y = 2 * (((frame_height + 1) >> 1) - 1);

    genvar b, t, l;
    generate
        for (b = 0; b < READ_BUSES; b = b + 1) begin : buses
            localparam AT = BUS_LSB + b * BUS_STRIDE;
            assign bus_valid[b] = issue && word[AT];
            assign bus_line[b * COORD_BITS +: COORD_BITS] = word[AT + BUS_LINE +: COORD_BITS];
            assign bus_column[b * COORD_BITS +: COORD_BITS] = word[AT + BUS_COLUMN +: COORD_BITS];
            for (l = 0; l < LANES; l = l + 1) begin : lanes
                localparam LANE = AT + LANE_LSB + l * LANE_STRIDE;
                assign lane_read[LANES * b + l] = word[LANE];
            end
        end
    endgenerate

    wire [TRIPLE_MACS-1:0] latched;
    wire [TRIPLE_MACS*3*ACC_BITS-1:0] sums;
    generate
        for (t = 0; t < TRIPLE_MACS; t = t + 1) begin : macs
            localparam AT = MAC_LSB + t * MAC_STRIDE;
            wire [MAC_BUS_BITS-1:0] bus = taking[AT + MAC_BUS +: MAC_BUS_BITS];
            // Bus b's lane l sits at bit 32 (LANES b + l); LANES is 1, 2 or 4.
            wire [ACC_BITS-1:0] value;
            if (LANES == 1) begin : scalar  // the lane field is there (one bit), but always 0
                assign value = bus_data[{bus, 5'd0} +: ACC_BITS];
            end else begin : wide
                wire [MAC_LANE_BITS-1:0] lane = taking[AT + MAC_LANE +: MAC_LANE_BITS];
                assign value = bus_data[{bus, lane, 5'd0} +: ACC_BITS];
            end
            triple_mac #(.ACC_BITS(ACC_BITS), .X3_CYCLES(X3_CYCLES)) mac (
                .clk(clk), .rst(rst), .take(taking_valid && taking[AT]), .value(value),
                .coefficient(taking[AT + MAC_COEFFICIENT +: 2]), .response(taking[AT + MAC_RESPONSE +: 2]),
                .last(taking_valid && taking[SEQ_LAST]), .out_xx(sums[(3 * t + 0) * ACC_BITS +: ACC_BITS]),
                .out_yy(sums[(3 * t + 1) * ACC_BITS +: ACC_BITS]), .out_xy(sums[(3 * t + 2) * ACC_BITS +: ACC_BITS]),
                .out_valid(latched[t]));
        end
    endgenerate

    // HessianCalc starts once every TripleMAC has latched the block (the last of them after
    // its x3 tail); the block's position waits for it.
    reg [TRIPLE_MACS-1:0] have;
    reg [15:0] finished_x, finished_y;  // the block whose sums the TripleMACs latch
    wire       reading;                 // HessianCalc has a block it has not finished reading
    wire [TRIPLE_MACS-1:0] have_next = have | latched;
    wire all_latched = &have_next;

    line_fifo fifo (
        .clk(clk), .clk2x(clk2x), .rst(rst), .start(start), .width(frame_width), .height(frame_height), .in_valid(in_valid),
        .in_value(in_value), .in_ready(in_ready), .rows_written(rows_written), .block_x(block_x), .block_y(block_y),
        .top_slot(top_slot), .bus_valid(bus_valid), .bus_line(bus_line), .bus_column(bus_column),
        .lane_read(lane_read), .bus_data(bus_data));

    hessian_calc calc (
        .clk(clk), .rst(rst), .start(all_latched), .block_x(finished_x), .block_y(finished_y), .width(frame_width),
        .height(frame_height), .sums(sums), .reading(reading), .det_valid(det_valid), .det_index(det_index),
        .det_value(det_value), .det_block_x(det_block_x), .det_block_y(det_block_y));

    always @(posedge clk) begin
        if (rst) begin
            busy <= 0; done <= 0; overrun <= 0; have <= 0; block_x <= 0; block_y <= 0; top_slot <= FIRST_TOP;
        end else begin
            if (start) begin
                busy <= 1; done <= 0; block_x <= 0; block_y <= 0; top_slot <= FIRST_TOP;
            end else if (busy) begin
                if (last) begin
                    finished_x <= block_x;
                    finished_y <= block_y;
                    if (block_x == last_x) begin
                        block_x <= 0;
                        block_y <= block_y + 2;
                        top_slot <= top_slot >= FIFO_LINES - 2 ? top_slot + 2 - FIFO_LINES : top_slot + 2;
                        if (block_y == last_y) begin
                            busy <= 0;
                            done <= 1;
                        end
                    end else begin
                        block_x <= block_x + 2;
                    end
                end
            end
            have <= all_latched ? {TRIPLE_MACS{1'b0}} : have_next;
            if (|latched && reading) overrun <= 1;
        end
    end
endmodule
