// SPDX-License-Identifier: Apache-2.0
// Negative fixture for scripts/yosys_check.sh: an incomplete combinational assignment infers a
// latch. The ctest `rtl.yosys_check_rejects_latch` passes only if the check REJECTS this file.
`default_nettype none
module latchy_fixture (
    input  wire       en_i,
    input  wire [3:0] d_i,
    output reg  [3:0] q_o
);
  always @* begin
    if (en_i) q_o = d_i;  // no else: q_o holds its value -> latch
  end
endmodule
`default_nettype wire
