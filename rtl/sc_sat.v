// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_sat.v
// Purpose  : signed saturation of a two's complement word to a narrower one (combinational): the
//            lighting lane's specular input x (Blinn, Phong with and without local viewer) and a
//            directional light's unit-direction code. C model: std::clamp in LightCore::eval
//            (cmodel/include/shadecore/light.hpp).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   IW  input width, >= 2                                                   (default 8)
//   OW  output width, 2 <= OW < IW                                          (default 4)
//
// Ports : d_i[IW-1:0]  signed input
//         q_o[OW-1:0]  d_i if it lies in [−2^(OW−1), 2^(OW−1) − 1], else the end of that range on
//                      d_i's side
// ============================================================================================
`default_nettype none

module sc_sat #(
    parameter integer IW = 8,
    parameter integer OW = 4
) (
    input  wire [IW-1:0] d_i,
    output wire [OW-1:0] q_o
);

  generate
    if (OW < 2 || OW >= IW) begin : g_check_w
      sc_sat_error_illegal_OW_legal_range_is_2_to_IW_minus_1 u_error ();
    end
  endgenerate

  // in range iff the bits above the output's sign bit all equal it
  wire in_rng = (d_i[IW-1:OW-1] == {(IW-OW+1){1'b0}}) || (d_i[IW-1:OW-1] == {(IW-OW+1){1'b1}});
  assign q_o = in_rng ? d_i[OW-1:0] : {d_i[IW-1], {(OW-1){!d_i[IW-1]}}};

endmodule

`default_nettype wire
