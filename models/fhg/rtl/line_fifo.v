// The MasterController's line FIFO (paper III-C: 56 integral-image lines, reached through 4
// independent buses, because a block reads its 52 x 52 window many times and out of order):
// FIFO_LINES lines of up to LINE_WORDS integral values, each line the block RAM fhg.line_fifo
// names (line_ram.v: LINE_BANKS banks of it, LINE_READS reads of each a cycle), written row by
// row as the PixelBus delivers them and read by the buses.
//
// - Writing: a line's slot is its row modulo FIFO_LINES. Row r waits (in_ready low) until the
//   row FIFO_LINES before it has left the window of the block row in flight (rows
//   block_y - 26 .. block_y + 25), so no value a block still needs is overwritten, and a line
//   being written is never one a block reads.
// - Reading: each bus names a word of the block's window, and the sequence says which of its
//   values to read (lane_read): the sequence memory carries the addressing (III-C). Each lane
//   is wired to one read port of every BRAM (lane_port in sequence_generator.h: port
//   (bus x columns + the lane's column) mod LINE_READS), and the sequence never gives a port
//   two addresses in a cycle, so a port's address is the OR of its lanes' and a lane's value
//   comes from its port of the BRAM it names. Wiring the ports rather than choosing them keeps
//   the routing to a FIFO_LINES x LINE_BANKS : 1 multiplexer a lane (docs/rtl.md); with
//   LINE_GROUPS > 1 a lane is wired to one group of the lines only (slot mod LINE_GROUPS), a
//   multiplexer of 1 / LINE_GROUPS of that, the buses turned so that every read finds its
//   group's lane (below). The values are bus_data in the next cycle. A value left of column 0
//   or above row 0 is 0 (the integral image's I(-1, .) = I(., -1) = 0); one right of or below
//   the image is never needed.
// - `rows_written` tells the sequence when a block row's window is complete; `top_slot` is the
//   slot of the window's top line, row block_y - 26 (fhg_datapath.v keeps it).
module line_fifo (clk, clk2x, rst, start, width, height, in_valid, in_value, in_ready, rows_written, block_x,
                  block_y, top_slot, bus_valid, bus_line, bus_column, lane_read, bus_data);
`include "fhg_params.vh"
    localparam REQUESTS = READ_BUSES * LANES;
    localparam PER_WORD = LINE_BANKS * (LINE_PAIRS + 1);  // columns a bank's word covers over the banks
    localparam BANK_WORDS = (LINE_WORDS + PER_WORD - 1) / PER_WORD;  // an odd last column too
    localparam ADDR_BITS = $clog2(BANK_WORDS);
    localparam DATA = (LINE_PAIRS + 1) * 32;
    localparam RAMS = FIFO_LINES * LINE_BANKS;
    localparam SLOT_BITS = $clog2(FIFO_LINES);
    localparam SHIFT = LINE_BANKS == 2 || LINE_PAIRS == 1 ? 1 : 0;  // a column's address: column >> SHIFT
    localparam REACH = RAMS / LINE_GROUPS;  // the BRAMs one lane is wired to: its line group's
    localparam REACH_BITS = $clog2(REACH);
    input  wire                               clk;
    input  wire                               clk2x;
    input  wire                               rst;
    input  wire                               start;
    input  wire [15:0]                        width;
    input  wire [15:0]                        height;
    input  wire                               in_valid;
    input  wire [31:0]                        in_value;
    output wire                               in_ready;
    output reg  [15:0]                        rows_written;
    input  wire [15:0]                        block_x;  // the block in flight, pixel (0, 0)
    input  wire [15:0]                        block_y;
    input  wire [SLOT_BITS-1:0]               top_slot;
    input  wire [READ_BUSES-1:0]              bus_valid;
    input  wire [READ_BUSES*COORD_BITS-1:0]   bus_line;
    input  wire [READ_BUSES*COORD_BITS-1:0]   bus_column;
    input  wire [REQUESTS-1:0]                lane_read;
    output wire [REQUESTS*32-1:0]             bus_data;  // the values named last cycle, 0 where none

    reg [15:0]          column;  // the next value's place in row rows_written
    reg [SLOT_BITS-1:0] write_slot;
    reg                 busy_frame;

    // The row FIFO_LINES before the one being written is free once it is above the window.
    wire [16:0] window_top = {1'b0, block_y} - WINDOW_BEFORE;  // may be "negative": bit 16 set
    wire free = rows_written < FIFO_LINES ||
                (!window_top[16] && {1'b0, rows_written} - FIFO_LINES < window_top);
    assign in_ready = busy_frame && rows_written < height && free;
    wire write = in_valid && in_ready;

    always @(posedge clk) begin
        if (rst) begin
            rows_written <= 0; column <= 0; write_slot <= 0; busy_frame <= 0;
        end else if (start) begin
            rows_written <= 0; column <= 0; write_slot <= 0; busy_frame <= 1;
        end else if (write) begin
            if (column == width - 1) begin
                column <= 0;
                rows_written <= rows_written + 1;
                write_slot <= write_slot == FIFO_LINES - 1 ? 0 : write_slot + 1;
            end else begin
                column <= column + 1;
            end
        end
    end

    // The port of every BRAM that read r (bus r / LANES, lane r % LANES) is wired to.
    function integer lane_port;
        input integer r;
        lane_port = ((r / LANES) * (LANES == 1 ? 1 : 2) + (LANES == 1 ? 0 : (r % LANES) % 2)) % LINE_READS;
    endfunction
    // The line group whose BRAMs read r is wired to: its bus's, a line lower for a quad's lower lanes.
    function integer lane_group;
        input integer r;
        lane_group = (r / LANES + (LANES == 4 ? (r % LANES) / 2 : 0)) % LINE_GROUPS;
    endfunction

    // Each read as the sequence names it: `wanted` if it reads, its BRAM among its group's
    // (`reach`: the slot's place in its group, then the bank), address and half.
    reg [REQUESTS-1:0]             wanted;
    reg [REQUESTS*REACH_BITS-1:0]  reach_of;
    reg [REQUESTS*ADDR_BITS-1:0]   address;
    reg [REQUESTS-1:0]             half;
    genvar b, l, m;
    generate
        for (b = 0; b < READ_BUSES; b = b + 1) begin : buses
            for (l = 0; l < LANES; l = l + 1) begin : lanes
                // The lane's offset in the word: quad (dx, dy) = (l % 2, l / 2), pair dx = l.
                localparam DX = LANES == 1 ? 0 : l % 2, DY = LANES == 4 ? l / 2 : 0;
                localparam R = LANES * b + l;
                wire [COORD_BITS-1:0] line = bus_line[b * COORD_BITS +: COORD_BITS];
                wire signed [17:0] y = $signed({2'b0, block_y}) + $signed({12'b0, line}) + DY - WINDOW_BEFORE;
                wire signed [17:0] x = $signed({2'b0, block_x}) +
                                       $signed({12'b0, bus_column[b * COORD_BITS +: COORD_BITS]}) + DX - WINDOW_BEFORE;
                // The window's lines are consecutive slots from top_slot on.
                // top_slot + line + 1 < 2 FIFO_LINES, as the window's 52 lines fit the FIFO.
                wire [SLOT_BITS:0] sum = {1'b0, top_slot} + {{(SLOT_BITS + 1 - COORD_BITS){1'b0}}, line} + DY;
                /* verilator lint_off UNUSEDSIGNAL */
                wire [SLOT_BITS:0] slot = sum >= FIFO_LINES ? sum - FIFO_LINES : sum;  // its top bit is 0
                wire [SLOT_BITS:0] in_group = slot / LINE_GROUPS;
                wire [15:0] column_of = x[15:0];
                /* verilator lint_on UNUSEDSIGNAL */
                always @* begin
                    wanted[R] = bus_valid[b] && lane_read[R] && y >= 0 && x >= 0 && x < $signed({2'b0, width});
                    // (place in the group, bank) as bit fields: banks are one or two.
                    reach_of[REACH_BITS * R +: REACH_BITS] = LINE_BANKS == 2 ? {in_group[REACH_BITS-2:0], column_of[0]}
                                                                             : in_group[REACH_BITS-1:0];
                    address[ADDR_BITS * R +: ADDR_BITS] = column_of[SHIFT +: ADDR_BITS];
                    half[R] = LINE_PAIRS == 1 && column_of[0];
                end
            end
        end
    endgenerate

    // The buses turned by the window's top group: the sequence puts a word whose top line is
    // window line L on a bus of group L mod LINE_GROUPS, written for a window whose top slot is
    // in group 0; at a top slot in group g its lines are in groups L + g, so read r goes out on
    // bus (its bus + g) mod READ_BUSES, whose lanes are wired to them (a multiple of LINE_GROUPS
    // buses keeps the groups). The top slot moves two lines a block row: g is 0, or 0 and 2.
    localparam [SLOT_BITS-1:0] GROUP_MASK = LINE_GROUPS - 1;
    /* verilator lint_off UNUSEDSIGNAL */
    wire [SLOT_BITS-1:0] top_group = top_slot & GROUP_MASK;
    /* verilator lint_on UNUSEDSIGNAL */
    wire [2:0] turn = top_group[2:0];
    function integer turned;  // the read whose fields wired lane r carries at turn `by`
        input integer r, by;
        turned = ((r / LANES + READ_BUSES - by) % READ_BUSES) * LANES + r % LANES;
    endfunction
    reg [REQUESTS-1:0]            wired_wanted, wired_half;
    reg [REQUESTS*REACH_BITS-1:0] wired_reach;
    reg [REQUESTS*ADDR_BITS-1:0]  wired_address;
    integer w, g;
    always @* begin
        wired_wanted = 0; wired_half = 0; wired_reach = 0; wired_address = 0;
        for (w = 0; w < REQUESTS; w = w + 1)
            for (g = 0; g < LINE_GROUPS; g = g + 1)
                if (turn == g[2:0]) begin
                    wired_wanted[w] = wanted[turned(w, g)];
                    wired_half[w] = half[turned(w, g)];
                    wired_reach[REACH_BITS * w +: REACH_BITS] = reach_of[REACH_BITS * turned(w, g) +: REACH_BITS];
                    wired_address[ADDR_BITS * w +: ADDR_BITS] = address[ADDR_BITS * turned(w, g) +: ADDR_BITS];
                end
    end

    // Each BRAM port's read address: that of the wired reads of its group that name its BRAM,
    // if any. Reads that share a port name the same unit (the sequence memory's decoder holds
    // every image to that), so their addresses are ORed.
    reg [RAMS*LINE_READS*ADDR_BITS-1:0] ram_address;
    generate
        for (m = 0; m < RAMS * LINE_READS; m = m + 1) begin : port_address
            localparam integer RAM = m / LINE_READS, PORT = m % LINE_READS;
            localparam integer SLOT = RAM / LINE_BANKS, GROUP = SLOT % LINE_GROUPS;
            localparam integer PLACE = (SLOT / LINE_GROUPS) * LINE_BANKS + RAM % LINE_BANKS;  // in its group
            integer r;
            always @* begin
                ram_address[m * ADDR_BITS +: ADDR_BITS] = 0;
                for (r = 0; r < REQUESTS; r = r + 1)
                    if (lane_port(r) == PORT && lane_group(r) == GROUP && wired_wanted[r] &&
                        wired_reach[REACH_BITS * r +: REACH_BITS] == PLACE[REACH_BITS-1:0])
                        ram_address[m * ADDR_BITS +: ADDR_BITS] =
                            ram_address[m * ADDR_BITS +: ADDR_BITS] | wired_address[ADDR_BITS * r +: ADDR_BITS];
            end
        end
    endgenerate

    // The incoming value's BRAM, address and half.
    wire [ADDR_BITS-1:0] write_address = column[SHIFT +: ADDR_BITS];
    wire [DATA-1:0] ram_data [0:LINE_READS*RAMS-1];  // each BRAM port's value, port by port
    genvar p;
    generate
        for (m = 0; m < RAMS; m = m + 1) begin : rams
            localparam integer SLOT = m / LINE_BANKS, BANK = m % LINE_BANKS;
            wire [LINE_READS*DATA-1:0] q;
            line_ram #(.WORDS(BANK_WORDS), .ADDR_BITS(ADDR_BITS), .PAIRS(LINE_PAIRS), .READS(LINE_READS)) ram (
                .clk(clk), .clk2x(clk2x),
                .we(write && write_slot == SLOT[SLOT_BITS-1:0] && (LINE_BANKS == 1 || column[0] == BANK[0])),
                .waddr(write_address), .whalf(column[0]), .wdata(in_value),
                .raddr(ram_address[m * LINE_READS * ADDR_BITS +: LINE_READS * ADDR_BITS]), .q(q));
            for (p = 0; p < LINE_READS; p = p + 1) begin : ports
                assign ram_data[p * RAMS + m] = q[p * DATA +: DATA];
            end
        end
    endgenerate

    // Next cycle, each wired read takes its value from its port of its BRAM (and half): a
    // multiplexer over its group's BRAMs. Then the buses turn back.
    reg [REQUESTS-1:0]            took, took_half;
    reg [REQUESTS*REACH_BITS-1:0] took_from;  // the BRAM, in the lane's group
    reg [2:0]                     took_turn;
    always @(posedge clk) begin
        took <= wired_wanted;
        took_half <= wired_half;
        took_from <= wired_reach;
        took_turn <= turn;
    end
    wire [REQUESTS*32-1:0] wired_data;
    generate
        for (m = 0; m < REQUESTS; m = m + 1) begin : values
            localparam integer GROUP = lane_group(m);
            wire [DATA-1:0] reach [0:REACH-1];  // its port of each BRAM of its group
            for (p = 0; p < REACH; p = p + 1) begin : reachable
                localparam integer RAM = ((p / LINE_BANKS) * LINE_GROUPS + GROUP) * LINE_BANKS + p % LINE_BANKS;
                assign reach[p] = ram_data[lane_port(m) * RAMS + RAM];
            end
            wire [DATA-1:0] value = reach[took_from[REACH_BITS * m +: REACH_BITS]];
            assign wired_data[32 * m +: 32] = !took[m] ? 32'd0 : took_half[m] ? value[DATA-1 -: 32] : value[31:0];
        end
        for (m = 0; m < REQUESTS; m = m + 1) begin : unturn
            // Read m went out on the wired lane of its bus plus the turn.
            reg [31:0] v;
            integer t;
            always @* begin
                v = 32'd0;
                for (t = 0; t < LINE_GROUPS; t = t + 1)
                    if (took_turn == t[2:0])
                        v = wired_data[32 * (((m / LANES + t) % READ_BUSES) * LANES + m % LANES) +: 32];
            end
            assign bus_data[32 * m +: 32] = v;
        end
    endgenerate
endmodule
