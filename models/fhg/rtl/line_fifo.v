// The MasterController's line FIFO (paper III-C: 56 integral-image lines, reached through 4
// independent buses, because a block reads its 52 x 52 window many times and out of order):
// FIFO_LINES lines of up to LINE_WORDS integral values, written
// row by row as the PixelBus delivers them and read by the buses, one word each per cycle.
//
// - Writing: a line's slot is its row modulo FIFO_LINES. Row r waits (in_ready low) until the
//   row FIFO_LINES before it has left the window of the block row in flight (rows
//   block_y - 26 .. block_y + 25), so no value a block still needs is overwritten.
// - Reading: each bus names a word of the block's window; its lanes are read at the next clock
//   edge, as a block RAM reads. A value left of column 0 or above row 0 is 0 (the integral
//   image's I(-1, .) = I(., -1) = 0); a value right of or below the image is never needed.
// - `rows_written` tells the sequence when a block row's window is complete.
//
// Storage is one array with a read port per bus lane. How a real design splits it into block
// RAMs with their port limits (fhg.line_fifo) is what the sequence already respects
// (check_sequence); mapping it onto RAMB36 is left to synthesis.
module line_fifo (clk, rst, start, width, height, in_valid, in_value, in_ready, rows_written, block_x, block_y,
                  bus_valid, bus_line, bus_column, bus_data);
`include "fhg_params.vh"
    input  wire                             clk;
    input  wire                             rst;
    input  wire                             start;
    input  wire [15:0]                      width;
    input  wire [15:0]                      height;
    input  wire                             in_valid;
    input  wire [31:0]                      in_value;
    output wire                             in_ready;
    output reg  [15:0]                      rows_written;
    input  wire [15:0]                      block_x;  // the block in flight, pixel (0, 0)
    input  wire [15:0]                      block_y;
    input  wire [READ_BUSES-1:0]            bus_valid;
    input  wire [READ_BUSES*COORD_BITS-1:0] bus_line;
    input  wire [READ_BUSES*COORD_BITS-1:0] bus_column;
    output reg  [READ_BUSES*LANES*32-1:0]   bus_data;  // the words named last cycle

    reg [31:0] memory [0:FIFO_LINES*LINE_WORDS-1];
    reg [15:0] column;  // the next value's place in row rows_written
    reg        busy_frame;

    // The row FIFO_LINES before the one being written is free once it is above the window.
    wire [16:0] window_top = {1'b0, block_y} - WINDOW_BEFORE;  // may be "negative": bit 16 set
    wire free = rows_written < FIFO_LINES ||
                (!window_top[16] && {1'b0, rows_written} - FIFO_LINES < window_top);
    assign in_ready = busy_frame && rows_written < height && free;

    always @(posedge clk) begin
        if (rst) begin
            rows_written <= 0; column <= 0; busy_frame <= 0;
        end else if (start) begin
            rows_written <= 0; column <= 0; busy_frame <= 1;
        end else if (in_valid && in_ready) begin
            memory[({16'd0, rows_written} % FIFO_LINES) * LINE_WORDS + {16'd0, column}] <= in_value;
            if (column == width - 1) begin
                column <= 0;
                rows_written <= rows_written + 1;
            end else begin
                column <= column + 1;
            end
        end
    end

    genvar b, l;
    generate
        for (b = 0; b < READ_BUSES; b = b + 1) begin : buses
            for (l = 0; l < LANES; l = l + 1) begin : lanes
                // The lane's offset in the word: quad (dx, dy) = (l % 2, l / 2), pair dx = l.
                localparam DX = LANES == 1 ? 0 : l % 2, DY = LANES == 4 ? l / 2 : 0;
                wire signed [17:0] y = $signed({2'b0, block_y}) + $signed({12'b0, bus_line[b * COORD_BITS +: COORD_BITS]})
                                       + DY - WINDOW_BEFORE;
                wire signed [17:0] x = $signed({2'b0, block_x}) + $signed({12'b0, bus_column[b * COORD_BITS +: COORD_BITS]})
                                       + DX - WINDOW_BEFORE;
                always @(posedge clk)
                    bus_data[32 * (LANES * b + l) +: 32] <=
                        (!bus_valid[b] || y < 0 || x < 0 || x >= $signed({2'b0, width})) ? 32'd0
                        : memory[({16'd0, y[15:0]} % FIFO_LINES) * LINE_WORDS + {16'd0, x[15:0]}];
            end
        end
    endgenerate
endmodule
