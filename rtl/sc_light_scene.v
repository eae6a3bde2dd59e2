// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_light_scene.v
// Purpose  : the scene term of one colour channel, e + a·A (GL: the material's emission plus its ambient
//            times the global ambient), min(e + ⌊a·A / 2^F⌋, 2^F); combinational, bit for bit
//            LightCore::eval()'s t.scene (saturated: every term after it is >= 0, so the core's saturating
//            sum is unchanged). One source for the register-only scene term of rtl/sc_light_regfile.v and
//            the per-fragment one of rtl/sc_light.v (colour material, docs/lighting.md §3.8).
// Parameters: FRAC (F); MREG 0/1 (rtl/sc_light.v's pipelining parameter: the product a·A registered between
//             its tree and its final adder, rtl/sc_mul_stage.v: scene_o one enabled edge after the inputs).
// Ports     : clk_i, en_i (MREG = 1); em_i, am_i, ga_i (colour codes, F+1 bits); scene_o (F+1 bits, <= 2^F).
// ============================================================================================
`default_nettype none

module sc_light_scene #(
    parameter integer FRAC = 16,
    parameter integer MREG = 0
) (
    input  wire          clk_i,
    input  wire          en_i,
    input  wire [FRAC:0] em_i,
    input  wire [FRAC:0] am_i,
    input  wire [FRAC:0] ga_i,
    output wire [FRAC:0] scene_o
);

  localparam integer CL = FRAC + 1;
  localparam [CL-1:0] ONE = {1'b1, {FRAC{1'b0}}};

  wire [2*CL-1:0] ag;
  wire [CL-1:0]   em;   // em_i beside the product
  sc_mul_stage #(.AW(CL), .BW(CL), .PW(2 * CL), .MREG(MREG), .SW(CL)) u_ag (
      .clk_i(clk_i), .en_i(en_i), .a_i(am_i), .b_i(ga_i), .c_i(1'b0), .side_i(em_i), .p_o(ag), .side_o(em));
  wire [CL+1:0]   sc = {2'b00, em} + {1'b0, ag[2*CL-1:FRAC]};
  wire unused_ag = &{1'b0, ag[FRAC-1:0]};
  assign scene_o = (sc > {2'b00, ONE}) ? ONE : sc[CL-1:0];

endmodule

`default_nettype wire
