// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_schlick_front.vh
// Purpose  : the one copy of the Schlick units' front end (docs/spec.md §3.1, §4): the material
//            register mat_n_q (n only: the Schlick forms have no per-material threshold, so
//            mat_thr_i is unused) and the input clamp c_d = clamp(in_cos_i, 0, 2^F). Included
//            INSIDE the module body after localparams F and ONE = 2^F; no include guard. Files
//            that include it: rtl/sc_schlick_div.v, rtl/sc_schlick_nr.v, rtl/sc_schlick_iter.v.
// ============================================================================================
  wire unused_thr = &{1'b0, mat_thr_i};

  // ---------------------------------------------------------------------------- material register
  reg [10:0] mat_n_q;
  always @(posedge clk_i) begin
    if (mat_we_i) begin
      mat_n_q <= mat_n_i;
    end
  end

  // ---------------------------------------------------------------------------- input clamp
  wire        cos_neg  = in_cos_i[F+1];
  wire        cos_over = !cos_neg && (in_cos_i[F:0] > ONE);
  wire [F:0]  c_d      = cos_neg ? {(F+1){1'b0}} : (cos_over ? ONE : in_cos_i[F:0]);
