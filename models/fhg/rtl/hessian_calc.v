// HessianCalc (paper III-C): the TripleMACs' output buffers share one three-state bus, over
// which it reads them after the end of a block's sequence, and it forms each determinant from
// its three sums, one TripleMAC a cycle, while the next block accumulates. Inside an FPGA a three-state bus is a multiplexer; this is one.
//
// Per determinant of size L (HessianCore::finish, models/fhg/hessian_core.h), rounding half
// up (add half, arithmetic shift right) and saturating:
//   r   = sat(round(D x K_L / 2^RECIP_SHIFT), RESPONSE_BITS)          for Dxx, Dyy, Dxy
//   det = sat(round((rxx ryy - round(W rxy^2 / 2^WEIGHT_FRAC_BITS)) / 2^DET_SHIFT), DET_BITS)
// and 0 where the filter does not lie inside the image. Four pipeline stages; the record
// position k leaves with its determinant.
module hessian_calc (clk, rst, start, block_x, block_y, width, height, sums, reading, det_valid, det_index,
                     det_value, det_block_x, det_block_y);
`include "fhg_params.vh"
    input  wire                              clk;
    input  wire                              rst;
    input  wire                              start;    // every TripleMAC has latched a block
    input  wire [15:0]                       block_x;  // the block's pixel (0, 0), taken at start
    input  wire [15:0]                       block_y;
    input  wire [15:0]                       width;    // the image
    input  wire [15:0]                       height;
    input  wire [TRIPLE_MACS*3*ACC_BITS-1:0] sums;     // TripleMAC t: {xy, yy, xx} from bit 3 t ACC_BITS
    output reg                               reading;  // the output buffers are being read
    output reg                               det_valid;
    output reg  [4:0]                        det_index;
    output reg  [DET_BITS-1:0]               det_value;
    output reg  [15:0]                       det_block_x;  // the block being read
    output reg  [15:0]                       det_block_y;

    // Exact widths, so that synthesis sizes the multipliers as the arithmetic needs: a sum
    // (ACC_BITS, signed) times K_L (K_BITS, unsigned); the responses (RESPONSE_BITS); their
    // product; W (W_BITS, unsigned) times rxy^2; the determinant before its last rounding.
    localparam P_BITS = ACC_BITS + K_BITS + 1;
    localparam SQ_BITS = 2 * RESPONSE_BITS;
    localparam WSQ_BITS = W_BITS + 1 + SQ_BITS;
    localparam D_BITS = (WSQ_BITS + 1 > SQ_BITS ? WSQ_BITS + 1 : SQ_BITS) + 1;

    // Stage 0: the TripleMAC the bus carries, and whether its filter lies inside the image.
    // The output buffers as an array indexed by k: an 18-way multiplexer of 3 ACC_BITS. (A part
    // select at 3 k ACC_BITS would be a barrel shifter over all 18 buffers, 20 times the LUTs.)
    reg [4:0]  k;
    wire [3*ACC_BITS-1:0] buffers [0:TRIPLE_MACS-1];
    genvar t;
    generate
        for (t = 0; t < TRIPLE_MACS; t = t + 1) begin : bus
            assign buffers[t] = sums[3 * t * ACC_BITS +: 3 * ACC_BITS];
        end
    endgenerate
    wire [3*ACC_BITS-1:0] carried = k < TRIPLE_MACS ? buffers[k] : {3 * ACC_BITS{1'b0}};
    wire [ACC_BITS-1:0] sxx = carried[0 +: ACC_BITS];
    wire [ACC_BITS-1:0] syy = carried[ACC_BITS +: ACC_BITS];
    wire [ACC_BITS-1:0] sxy = carried[2 * ACC_BITS +: ACC_BITS];
    wire signed [K_BITS:0] reciprocal = $signed({1'b0, det_reciprocal(k)});
    wire [15:0] x = det_block_x + det_px(k), y = det_block_y + det_py(k), b = (det_size(k) - 16'd1) >> 1;
    wire in_image = x >= b && y >= b && x + b < width && y + b < height;

    // Stage 1: the sums times K_L. Stage 2: the responses.
    reg v1, v2, v3, in1, in2, in3;
    reg [4:0] k1, k2, k3;
    reg signed [P_BITS-1:0] pxx, pyy, pxy;
    reg signed [RESPONSE_BITS-1:0] rxx, ryy, rxy;
    wire signed [RESPONSE_BITS-1:0] nxx, nyy, nxy;
    round_saturate #(.IN(P_BITS), .SHIFT(RECIP_SHIFT), .OUT(RESPONSE_BITS)) norm_xx (.value(pxx), .result(nxx));
    round_saturate #(.IN(P_BITS), .SHIFT(RECIP_SHIFT), .OUT(RESPONSE_BITS)) norm_yy (.value(pyy), .result(nyy));
    round_saturate #(.IN(P_BITS), .SHIFT(RECIP_SHIFT), .OUT(RESPONSE_BITS)) norm_xy (.value(pxy), .result(nxy));
    // Stage 3: det = rxx ryy - round(W rxy^2 / 2^WEIGHT_FRAC_BITS), 2 RESPONSE_FRAC_BITS fraction bits.
    wire signed [SQ_BITS-1:0] xy_square = rxy * rxy;
    wire signed [WSQ_BITS-1:0] weighted = $signed({1'b0, WEIGHT[W_BITS-1:0]}) * xy_square;
    wire signed [WSQ_BITS:0] weighted_rounded;
    round_saturate #(.IN(WSQ_BITS), .SHIFT(WEIGHT_FRAC_BITS), .OUT(WSQ_BITS + 1)) weigh (
        .value(weighted), .result(weighted_rounded));
    reg signed [D_BITS-1:0] det;
    // Stage 4: rounded to DET_FRAC_BITS and saturated to DET_BITS.
    wire signed [DET_BITS-1:0] finished;
    round_saturate #(.IN(D_BITS), .SHIFT(DET_SHIFT), .OUT(DET_BITS)) finish (.value(det), .result(finished));

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
            v1 <= reading; k1 <= k; in1 <= in_image;
            pxx <= $signed(sxx) * reciprocal;
            pyy <= $signed(syy) * reciprocal;
            pxy <= $signed(sxy) * reciprocal;
            v2 <= v1; k2 <= k1; in2 <= in1;
            rxx <= nxx; ryy <= nyy; rxy <= nxy;
            v3 <= v2; k3 <= k2; in3 <= in2;
            det <= rxx * ryy - weighted_rounded;
            det_valid <= v3; det_index <= k3;
            det_value <= in3 ? finished : {DET_BITS{1'b0}};
        end
    end
endmodule
