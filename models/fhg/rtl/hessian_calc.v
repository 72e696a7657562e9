// HessianCalc (paper III-C): the TripleMACs' output buffers share one three-state bus, over
// which it reads them after the end of a block's sequence, and it forms each determinant from
// its three sums, one TripleMAC a cycle, while the next
// block accumulates. Inside an FPGA a three-state bus is a multiplexer; this is one.
//
// Per determinant of size L (HessianCore::finish, models/fhg/hessian_core.h), rounding half
// up (add half, arithmetic shift right) and saturating:
//   r   = sat(round(D x K_L / 2^RECIP_SHIFT), RESPONSE_BITS)          for Dxx, Dyy, Dxy
//   det = sat(round((rxx ryy - round(W rxy^2 / 2^WEIGHT_FRAC_BITS)) / 2^DET_SHIFT), DET_BITS)
// and 0 where the filter does not lie in_image the image. Four pipeline stages; the record
// position k leaves with its determinant.
module hessian_calc (clk, rst, start, block_x, block_y, width, height, sums, det_valid, det_index, det_value,
                     det_block_x, det_block_y);
`include "fhg_params.vh"
    input  wire                              clk;
    input  wire                              rst;
    input  wire                              start;    // every TripleMAC has latched a block
    input  wire [15:0]                       block_x;  // the block's pixel (0, 0), taken at start
    input  wire [15:0]                       block_y;
    input  wire [15:0]                       width;    // the image
    input  wire [15:0]                       height;
    input  wire [TRIPLE_MACS*3*ACC_BITS-1:0] sums;     // TripleMAC t: {xy, yy, xx} from bit 3 t ACC_BITS
    output reg                               det_valid;
    output reg  [4:0]                        det_index;
    output reg  [DET_BITS-1:0]               det_value;
    output reg  [15:0]                       det_block_x;  // the block being read
    output reg  [15:0]                       det_block_y;

    function signed [63:0] round_shift(input signed [63:0] v, input integer s);
        round_shift = s == 0 ? v : (v + (64'sd1 <<< (s - 1))) >>> s;
    endfunction
    function signed [63:0] saturate(input signed [63:0] v, input integer bits);
        reg signed [63:0] top;
        begin
            top = (64'sd1 <<< (bits - 1)) - 1;
            saturate = v > top ? top : (v < -top - 1 ? -top - 1 : v);
        end
    endfunction
    function signed [63:0] widen(input [ACC_BITS-1:0] s);  // an accumulator's two's complement
        widen = $signed({{(64 - ACC_BITS){s[ACC_BITS-1]}}, s});
    endfunction

    // Stage 0: which TripleMAC the bus carries.
    reg        reading;
    reg [4:0]  k;
    reg        v1, v2, v3;
    reg [4:0]  k1, k2, k3;
    reg        in1, in2, in3;
    reg signed [63:0] pxx, pyy, pxy, rxx, ryy, rxy, det;

    wire [ACC_BITS-1:0] sxx = sums[(3 * k + 0) * ACC_BITS +: ACC_BITS];
    wire [ACC_BITS-1:0] syy = sums[(3 * k + 1) * ACC_BITS +: ACC_BITS];
    wire [ACC_BITS-1:0] sxy = sums[(3 * k + 2) * ACC_BITS +: ACC_BITS];
    wire [15:0] x = det_block_x + det_px(k), y = det_block_y + det_py(k), b = (det_size(k) - 16'd1) >> 1;
    wire signed [63:0] reciprocal = $signed({32'd0, det_reciprocal(k)});
    wire in_image = x >= b && y >= b && x + b < width && y + b < height;
    /* verilator lint_off UNUSEDSIGNAL */  // saturated to DET_BITS: the bits above are its sign
    wire signed [63:0] finished = saturate(round_shift(det, DET_SHIFT), DET_BITS);
    /* verilator lint_on UNUSEDSIGNAL */

    always @(posedge clk) begin
        if (rst) begin
            reading <= 0; k <= 0; v1 <= 0; v2 <= 0; v3 <= 0; det_valid <= 0;
        end else begin
            if (start) begin
                reading <= 1; k <= 0;
                det_block_x <= block_x; det_block_y <= block_y;
            end else if (reading) begin
                reading <= k != TRIPLE_MACS - 1;
                k <= k + 1;
            end
            // Stage 1: the sums times K_L.
            v1 <= reading; k1 <= k; in1 <= in_image;
            pxx <= widen(sxx) * reciprocal;
            pyy <= widen(syy) * reciprocal;
            pxy <= widen(sxy) * reciprocal;
            // Stage 2: the responses.
            v2 <= v1; k2 <= k1; in2 <= in1;
            rxx <= saturate(round_shift(pxx, RECIP_SHIFT), RESPONSE_BITS);
            ryy <= saturate(round_shift(pyy, RECIP_SHIFT), RESPONSE_BITS);
            rxy <= saturate(round_shift(pxy, RECIP_SHIFT), RESPONSE_BITS);
            // Stage 3: the determinant at 2 RESPONSE_FRAC_BITS fraction bits.
            v3 <= v2; k3 <= k2; in3 <= in2;
            det <= rxx * ryy - round_shift(WEIGHT * rxy * rxy, WEIGHT_FRAC_BITS);
            // Stage 4: rounded to DET_FRAC_BITS and saturated.
            det_valid <= v3; det_index <= k3;
            det_value <= in3 ? finished[DET_BITS-1:0] : {DET_BITS{1'b0}};
        end
    end
endmodule
