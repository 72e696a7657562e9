// One TripleMAC (paper III-C): the three responses Dxx, Dyy, Dxy of one determinant of the
// block, each an integer sum of integral-image values times 1, -1, 3 or -3, in ACC_BITS
// two's complement that wraps like HessianCore's accumulators (models/fhg/hessian_core.h).
//
// Paper III-C: to save resources a TripleMAC adds three times instead of multiplying by 3 or
// -3, and it does not tell the MasterController it is busy. With X3_CYCLES = 3 a x3
// value is added in this cycle and the next two, and the TripleMAC is busy meanwhile; it
// reports no busy signal, so the sequence never hands it a value then (check_sequence holds
// every generated sequence to that). With X3_CYCLES = 1 the x3 is one addition of 3v.
//
// The end-of-sequence signal (`last`; III-C: it makes the TripleMACs load their results into
// output buffers and reset their accumulators) makes it latch its three sums into its output buffer,
// once its last addition is done, and start the next block from zero (the results go to
// output buffers that HessianCalc reads while the next block accumulates).
module triple_mac #(
    parameter ACC_BITS = 24,
    parameter X3_CYCLES = 3
) (
    input  wire                clk,
    input  wire                rst,
    input  wire                take,         // a value for this TripleMAC this cycle
    input  wire [ACC_BITS-1:0] value,        // the integral value's low ACC_BITS (the sum wraps)
    input  wire [1:0]          coefficient,  // bit 0: negative; bit 1: x3
    input  wire [1:0]          response,     // 0 Dxx, 1 Dyy, 2 Dxy
    input  wire                last,         // the sequence's final word is this cycle
    output reg  [ACC_BITS-1:0] out_xx,
    output reg  [ACC_BITS-1:0] out_yy,
    output reg  [ACC_BITS-1:0] out_xy,
    output reg                 out_valid     // one cycle: the output buffer took a block's sums
);
    reg [ACC_BITS-1:0] acc_xx, acc_yy, acc_xy;
    reg [ACC_BITS-1:0] repeat_value;  // a x3 value still to be added
    reg [1:0]          repeat_response;
    reg [1:0]          repeats;       // additions of it still to come
    reg                pending;       // `last` came; latch once the additions are done

    // This cycle's addend: a new value, or the next addition of a x3 in progress.
    wire [ACC_BITS-1:0] signed_value = coefficient[0] ? -value : value;
    wire [ACC_BITS-1:0] addend = take ? ((coefficient[1] && X3_CYCLES == 1) ? 3 * signed_value : signed_value)
                                      : (repeats != 0 ? repeat_value : {ACC_BITS{1'b0}});
    wire [1:0] target = take ? response : repeat_response;
    wire [1:0] repeats_next = take ? ((coefficient[1] && X3_CYCLES == 3) ? 2'd2 : 2'd0)
                                   : (repeats != 0 ? repeats - 2'd1 : 2'd0);
    wire [ACC_BITS-1:0] xx_next = acc_xx + (target == 2'd0 ? addend : {ACC_BITS{1'b0}});
    wire [ACC_BITS-1:0] yy_next = acc_yy + (target == 2'd1 ? addend : {ACC_BITS{1'b0}});
    wire [ACC_BITS-1:0] xy_next = acc_xy + (target == 2'd2 ? addend : {ACC_BITS{1'b0}});
    wire latch = (pending || last) && repeats_next == 2'd0;

    always @(posedge clk) begin
        if (rst) begin
            acc_xx <= 0; acc_yy <= 0; acc_xy <= 0;
            repeats <= 0; repeat_value <= 0; repeat_response <= 0;
            pending <= 0; out_valid <= 0;
            out_xx <= 0; out_yy <= 0; out_xy <= 0;
        end else begin
            repeats <= repeats_next;
            if (take) begin
                repeat_value <= signed_value;
                repeat_response <= response;
            end
            out_valid <= latch;
            if (latch) begin
                out_xx <= xx_next; out_yy <= yy_next; out_xy <= xy_next;
                acc_xx <= 0; acc_yy <= 0; acc_xy <= 0;
                pending <= 0;
            end else begin
                acc_xx <= xx_next; acc_yy <= yy_next; acc_xy <= xy_next;
                pending <= pending || last;
            end
        end
    end
endmodule
