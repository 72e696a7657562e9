// The FHG's datapath (paper III-C, Fig. 6): the MasterController's sequence memory driving
// the read buses and the TripleMACs, and HessianCalc after them. The line FIFO the buses read
// is outside this module (for now the testbench's): each cycle the datapath names, per bus, a
// word of the block's 52 x 52 window (line, column), and the FIFO answers with its values
// within the cycle.
//
// - "The MasterController ... runs a control and addressing sequence stored in block RAM": the
//   image `surfvp export-sequence` writes (docs/sequence-memory.md), read at the start from
//   the file given by +sequence=FILE (default fhg_sequence.mem), one word per cycle, the
//   sequence starting again after the word marked `last`, so blocks follow without a gap.
// - "The TripleMACs snoop the read buses": each takes, in a cycle its word says so, one value
//   of one bus word (bus, lane), with its coefficient and response.
// - Blocks run row by row over the frame, ceil(width / 2) x ceil(height / 2) of them, from
//   `start` until `done`. The block in flight is (block_x, block_y), its pixel (0, 0).
module fhg_datapath (clk, rst, start, width, height, bus_valid, bus_line, bus_column, bus_data, block_x,
                     block_y, det_valid, det_index, det_value, det_block_x, det_block_y, busy, done, overrun);
`include "fhg_params.vh"
    localparam DEPTH_MAX = 512;  // one RAMB36 deep at its widest (512 x 72)
    input  wire                                clk;
    input  wire                                rst;
    input  wire                                start;  // a frame: the sequence runs from its first word
    input  wire [15:0]                         width;
    input  wire [15:0]                         height;
    output wire [READ_BUSES-1:0]               bus_valid;
    output wire [READ_BUSES*COORD_BITS-1:0]    bus_line;    // in the window: y + WINDOW_BEFORE
    output wire [READ_BUSES*COORD_BITS-1:0]    bus_column;  // x + WINDOW_BEFORE
    input  wire [READ_BUSES*LANES*32-1:0]      bus_data;    // bus b, lane l at bit 32 (LANES b + l)
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

    reg [SEQ_WIDTH-1:0] memory [0:DEPTH_MAX-1];
    reg [1023:0] file;
    initial begin
        if (!$value$plusargs("sequence=%s", file)) file = "fhg_sequence.mem";
        $readmemh(file, memory);
    end

    // A block RAM reads synchronously: `word` is this cycle's, read last cycle from the address
    // that follows the previous word (or the first, after `last`).
    reg  [SEQ_WIDTH-1:0] word;
    reg  [8:0] pc;  // the next word's address
    wire last = busy && word[SEQ_LAST];
    wire [8:0] address = (start || last) ? 9'd0 : pc;
    always @(posedge clk) begin
        word <= memory[address];
        pc <= address + 9'd1;
    end
    wire [15:0] last_x = 2 * (((width + 1) >> 1) - 1), last_y = 2 * (((height + 1) >> 1) - 1);

    genvar b, t;
    generate
        for (b = 0; b < READ_BUSES; b = b + 1) begin : buses
            localparam AT = BUS_LSB + b * BUS_STRIDE;
            assign bus_valid[b] = busy && word[AT];
            assign bus_line[b * COORD_BITS +: COORD_BITS] = word[AT + BUS_LINE +: COORD_BITS];
            assign bus_column[b * COORD_BITS +: COORD_BITS] = word[AT + BUS_COLUMN +: COORD_BITS];
        end
    endgenerate

    wire [TRIPLE_MACS-1:0] latched;
    wire [TRIPLE_MACS*3*ACC_BITS-1:0] sums;
    generate
        for (t = 0; t < TRIPLE_MACS; t = t + 1) begin : macs
            localparam AT = MAC_LSB + t * MAC_STRIDE;
            wire [MAC_BUS_BITS-1:0] bus = word[AT + MAC_BUS +: MAC_BUS_BITS];
            wire [MAC_LANE_BITS-1:0] lane = word[AT + MAC_LANE +: MAC_LANE_BITS];
            // Bus b's lane l sits at bit 32 (LANES b + l); LANES is 1, 2 or 4.
            wire [ACC_BITS-1:0] value;
            if (LANES == 1) begin : scalar
                assign value = bus_data[{bus, 5'd0} +: ACC_BITS];
            end else begin : wide
                assign value = bus_data[{bus, lane[MAC_LANE_BITS-1:0], 5'd0} +: ACC_BITS];
            end
            triple_mac #(.ACC_BITS(ACC_BITS), .X3_CYCLES(X3_CYCLES)) mac (
                .clk(clk), .rst(rst), .take(busy && word[AT]), .value(value),
                .coefficient(word[AT + MAC_COEFFICIENT +: 2]), .response(word[AT + MAC_RESPONSE +: 2]),
                .last(last), .out_xx(sums[(3 * t + 0) * ACC_BITS +: ACC_BITS]),
                .out_yy(sums[(3 * t + 1) * ACC_BITS +: ACC_BITS]), .out_xy(sums[(3 * t + 2) * ACC_BITS +: ACC_BITS]),
                .out_valid(latched[t]));
        end
    endgenerate

    // HessianCalc starts once every TripleMAC has latched the block (the last of them after
    // its x3 tail); the block's position waits for it.
    reg [TRIPLE_MACS-1:0] have;
    reg [15:0] finished_x, finished_y;  // the block whose sums the TripleMACs latch
    reg        reading;                 // HessianCalc has a block it has not finished reading
    reg [4:0]  read_count;
    wire [TRIPLE_MACS-1:0] have_next = have | latched;
    wire all_latched = &have_next;

    hessian_calc calc (
        .clk(clk), .rst(rst), .start(all_latched), .block_x(finished_x), .block_y(finished_y), .width(width),
        .height(height), .sums(sums), .det_valid(det_valid), .det_index(det_index), .det_value(det_value),
        .det_block_x(det_block_x), .det_block_y(det_block_y));

    always @(posedge clk) begin
        if (rst) begin
            busy <= 0; done <= 0; overrun <= 0; have <= 0; block_x <= 0; block_y <= 0;
            reading <= 0; read_count <= 0;
        end else begin
            if (start) begin
                busy <= 1; done <= 0; block_x <= 0; block_y <= 0;
            end else if (busy) begin
                if (last) begin
                    finished_x <= block_x;
                    finished_y <= block_y;
                    if (block_x == last_x) begin
                        block_x <= 0;
                        block_y <= block_y + 2;
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
            if (all_latched) begin
                reading <= 1;
                read_count <= 0;
            end else if (reading) begin
                read_count <= read_count + 1;
                reading <= read_count != TRIPLE_MACS - 1;
            end
        end
    end
endmodule
