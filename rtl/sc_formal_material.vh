// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_formal_material.vh
// Purpose  : the one copy of the material rule's properties of the units with a material
//            register mat_n_q (docs/spec.md §4, proved with the unit: docs/formal.md): mat_n_q
//            loads exactly at an edge with mat_we_i high (in reset too) and holds otherwise, and
//            a fragment accepted at an edge captures n as it was before that edge (the old one
//            at a write). Included INSIDE a unit's `ifdef FORMAL block, after the unit has named
//            the edge at which a fragment captures the material and the n it captured:
//              wire        f_capture    = <enable of the capturing register>;
//              wire [10:0] f_captured_n = <that register>;
//            Files that include it: rtl/sc_schlick_div.v, rtl/sc_schlick_nr.v,
//            rtl/sc_schlick_iter.v. No include guard (module-scoped).
// ============================================================================================
  reg f_init = 1'b0;
  always @(posedge clk_i) f_init <= 1'b1;
  always @(posedge clk_i) begin
    if (f_init) begin
      mat_load_n: assert (mat_n_q == ($past(mat_we_i) ? $past(mat_n_i) : $past(mat_n_q)));
      if ($past(f_capture)) begin
        mat_old_n: assert (f_captured_n == $past(mat_n_q));
      end
    end
  end
