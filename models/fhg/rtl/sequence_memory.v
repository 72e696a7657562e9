// The MasterController's sequence memory (paper III-C: the control and addressing sequence is
// "stored in block RAM"): the image `surfvp export-sequence` writes (docs/sequence-memory.md),
// one word per cycle of a block's interval, read synchronously as a block RAM reads: `word` is
// the word at the address of the edge before. Up to 512 words deep, one RAMB36 at its widest
// (512 x 72), a RAMB36 per 72 bits of the word.
module sequence_memory (clk, address, word);
`include "fhg_params.vh"
    localparam DEPTH_MAX = 512;
    input  wire                 clk;
    input  wire [8:0]           address;
    output reg  [SEQ_WIDTH-1:0] word;

    reg [SEQ_WIDTH-1:0] memory [0:DEPTH_MAX-1];
`ifdef SYNTHESIS
    // Synthesis takes no plusargs: the block RAM's contents are the file in the working folder.
    initial $readmemh("fhg_sequence.mem", memory);
`else
    // Simulation: the file given by +sequence=FILE, else the same default.
    reg [1023:0] file;
    initial begin
        if (!$value$plusargs("sequence=%s", file)) file = "fhg_sequence.mem";
        $readmemh(file, memory);
    end
`endif
    always @(posedge clk) word <= memory[address];
endmodule
