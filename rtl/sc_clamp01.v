// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_clamp01.v
// Purpose  : a signed fixed-point value clamped to [0, 1] (combinational): the lighting lane's
//            diffuse factor clamp(⌊ndl / 2^SG⌋, 0, 2^F) and the spot chain's input
//            clamp(sdl, 0, 2^VF). C model: std::clamp(…, 0, 2^FRAC) in LightCore::eval
//            (cmodel/include/shadecore/light.hpp).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   IW    input width, >= FRAC + 2 (a sign bit above 1.0)                   (default 18)
//   FRAC  fraction bits of input and output (1.0 = 2^FRAC), >= 1           (default 16)
//
// Ports : d_i[IW-1:0]    signed input
//         q_o[FRAC:0]    unsigned: 0 if d_i < 0, 2^FRAC if d_i > 2^FRAC, else d_i
// ============================================================================================
`default_nettype none

module sc_clamp01 #(
    parameter integer IW   = 18,
    parameter integer FRAC = 16
) (
    input  wire [IW-1:0] d_i,
    output wire [FRAC:0] q_o
);

  generate
    if (FRAC < 1 || IW < FRAC + 2) begin : g_check_w
      sc_clamp01_error_illegal_IW_must_be_at_least_FRAC_plus_2 u_error ();
    end
  endgenerate

  localparam [FRAC:0] ONE = {1'b1, {FRAC{1'b0}}};
  wire neg = d_i[IW-1];
  wire big = !neg && (d_i[IW-2:0] > {{(IW-FRAC-2){1'b0}}, ONE});
  assign q_o = neg ? {(FRAC+1){1'b0}} : (big ? ONE : d_i[FRAC:0]);

endmodule

`default_nettype wire
