// One line of the line FIFO, or one column bank of it, as the block RAM fhg.line_fifo names
// (models/fhg/sequence_generator.h, LineFifo; Virtex-5 UG190 for the RAMB36's ports):
// WORDS words of 32 bits, or of 64 (PAIRS: an aligned pair of columns, the 72-bit simple
// dual-port mode), written one 32-bit value at a time, with READS reads each FHG cycle:
//
// - READS 1 or 2 (`sdp72`; `tdp`, `banked`): the RAM's ports at the FHG clock. Port A writes
//   while the line fills and reads otherwise; a line is never read while written (the
//   window's lines are all written, line_fifo.v), so both ports serve the buses.
// - READS 4 (`tdp_x2`): the same two ports at twice the FHG clock (clk2x, edges aligned with
//   clk's), each reading twice a cycle: reads 0 and 1 at the edge in the middle of the cycle,
//   reads 2 and 3 (or the write) at the edge that ends it. Hold registers take reads 0 and 1
//   at that edge and reads 2 and 3 at the next middle edge, so all four are `q` at the end of
//   the next cycle, where the TripleMACs take them. Two paths get half a cycle: a word to the
//   address of reads 0 and 1, and held reads 2 and 3 to the TripleMACs.
//
// A read's address is sampled at the end of the cycle that names it (mid-cycle for reads 0
// and 1 of READS 4), and its value is `q` at the end of the next cycle, as one read at the FHG
// clock would give it and the sequence expects (line_fifo.v).
module line_ram #(
    parameter WORDS = 1024,
    parameter ADDR_BITS = 10,
    parameter PAIRS = 0,
    parameter READS = 2
) (
    input  wire                           clk,
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire                           clk2x,  // READS 4 only
    input  wire                           whalf,  // PAIRS: the pair's upper column
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire                           we,     // write wdata (the FHG cycle's, at its end)
    input  wire [ADDR_BITS-1:0]           waddr,
    input  wire [31:0]                    wdata,
    input  wire [READS*ADDR_BITS-1:0]     raddr,  // read r's address at bits r ADDR_BITS
    output wire [READS*(PAIRS+1)*32-1:0]  q       // read r's word at bits r DATA: last cycle's reads
);
    localparam DATA = (PAIRS + 1) * 32;
    reg [DATA-1:0] memory [0:WORDS-1];

    // Port A's write: a whole word, or the half of a pair the column selects.
    task write;
        input [ADDR_BITS-1:0] at;
        begin
            if (PAIRS == 0 || !whalf) memory[at][31:0] <= wdata;
            else memory[at][DATA-1:DATA-32] <= wdata;
        end
    endtask

    // A port that writes reads from the address it writes (one address a port, as the RAMB36's
    // true dual-port mode has it); what it reads then is not used.
    generate
        if (READS == 4) begin : double_clock
            // The edge in the middle of the cycle: clk toggled `toggle` at the cycle's start, and
            // clk2x has not seen it yet.
            reg toggle = 1'b0, seen = 1'b0;
            always @(posedge clk) toggle <= ~toggle;
            wire middle = seen != toggle;
            wire [ADDR_BITS-1:0] a = middle ? raddr[0 +: ADDR_BITS] : we ? waddr : raddr[2 * ADDR_BITS +: ADDR_BITS];
            wire [ADDR_BITS-1:0] b = middle ? raddr[ADDR_BITS +: ADDR_BITS] : raddr[3 * ADDR_BITS +: ADDR_BITS];
            reg [DATA-1:0] qa, qb, held0, held1, held2, held3;
            always @(posedge clk2x) begin
                seen <= toggle;
                if (!middle && we) write(a);
                qa <= memory[a];
                qb <= memory[b];
                // The values read at the previous edge: reads 2 and 3 of the cycle before at the
                // middle edge, reads 0 and 1 of this cycle at its end.
                if (middle) begin
                    held2 <= qa;
                    held3 <= qb;
                end else begin
                    held0 <= qa;
                    held1 <= qb;
                end
            end
            assign q = {held3, held2, held1, held0};
        end else if (READS == 2) begin : two_ports
            wire [ADDR_BITS-1:0] a = we ? waddr : raddr[0 +: ADDR_BITS];
            reg [DATA-1:0] qa, qb;
            always @(posedge clk) begin
                if (we) write(a);
                qa <= memory[a];
            end
            always @(posedge clk) qb <= memory[raddr[ADDR_BITS +: ADDR_BITS]];
            assign q = {qb, qa};
        end else begin : write_and_read_port  // simple dual-port: a write port and a read port
            reg [DATA-1:0] qa;
            always @(posedge clk) begin
                if (we) write(waddr);
                qa <= memory[raddr];
            end
            assign q = qa;
        end
    endgenerate
endmodule
