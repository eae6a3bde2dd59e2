// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : formal/sc_formal_env.vh
// Purpose  : the one copy of the formal harnesses' environment (docs/formal.md): rst_ni is assumed
//            low in cycle 0 of the base case; f_first marks that cycle, f_past every later one.
//            Included INSIDE a harness module that has clk_i and rst_ni (`include "sc_formal_env.vh",
//            found beside the harness), so there is no include guard. Files that include it:
//            formal/sc_formal_unit.v, formal/sc_formal_light.v.
// ============================================================================================
  reg f_first = 1'b1;   // cycle 0 of the base case
  reg f_past  = 1'b0;   // cycle >= 1
  always @(posedge clk_i) begin
    f_first <= 1'b0;
    f_past  <= 1'b1;
  end
  always @* begin
    if (f_first) assume (!rst_ni);
  end
