// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_light_scene.v
// Purpose  : the scene term of one colour channel, e + a·A (GL: the material's emission plus its ambient
//            times the global ambient), min(e + ⌊a·A / 2^F⌋, 2^F); combinational, bit for bit
//            LightCore::eval()'s t.scene (saturated: every term after it is >= 0, so the core's saturating
//            sum is unchanged). One source for the register-only scene term of rtl/sc_light_regfile.v and
//            the per-fragment one of rtl/sc_light.v (colour material, docs/lighting.md §3.8).
// Parameters: FRAC (F).
// Ports     : em_i, am_i, ga_i (colour codes, F+1 bits); scene_o (F+1 bits, <= 2^F).
// ============================================================================================
`default_nettype none

module sc_light_scene #(
    parameter integer FRAC = 16
) (
    input  wire [FRAC:0] em_i,
    input  wire [FRAC:0] am_i,
    input  wire [FRAC:0] ga_i,
    output wire [FRAC:0] scene_o
);

  localparam integer CL = FRAC + 1;
  localparam [CL-1:0] ONE = {1'b1, {FRAC{1'b0}}};

  wire [2*CL-1:0] ag = {{CL{1'b0}}, am_i} * {{CL{1'b0}}, ga_i};
  wire [CL+1:0]   sc = {2'b00, em_i} + {1'b0, ag[2*CL-1:FRAC]};
  wire unused_ag = &{1'b0, ag[FRAC-1:0]};
  assign scene_o = (sc > {2'b00, ONE}) ? ONE : sc[CL-1:0];

endmodule

`default_nettype wire
