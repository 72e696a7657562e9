// round(value / 2^SHIFT), half up (add half, arithmetic shift right), saturated to OUT bits:
// HessianCore's step_shift and clamp_to (models/fhg/hessian_core.cpp) at exact widths.
// OUT = IN + 1 never saturates (a rounding alone).
module round_saturate #(
    parameter IN = 48,
    parameter SHIFT = 16,
    parameter OUT = 18
) (
    input  wire signed [IN-1:0]  value,
    output wire signed [OUT-1:0] result
);
    wire signed [IN:0] widened = {value[IN-1], value};
    wire signed [IN:0] rounded;
    generate
        if (SHIFT == 0) begin : exact
            assign rounded = widened;
        end else begin : half_up
            wire signed [IN:0] half = $signed({{IN{1'b0}}, 1'b1} << (SHIFT - 1));
            wire signed [IN:0] sum = widened + half;
            assign rounded = sum >>> SHIFT;
        end
    endgenerate
    // In range when every bit from OUT - 1 up is a copy of the sign.
    wire [IN-OUT+1:0] top = rounded[IN:OUT-1];
    assign result = (&top || ~|top) ? rounded[OUT-1:0] : {rounded[IN], {(OUT - 1){~rounded[IN]}}};
endmodule
