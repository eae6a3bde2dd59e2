// SPDX-License-Identifier: Apache-2.0
// Negative fixture for scripts/yosys_check.sh: a combinational loop (a -> b -> a).
// The ctest `rtl.yosys_check_rejects_loop` passes only if the check REJECTS this file.
`default_nettype none
module loop_fixture (
    input  wire i_i,
    output wire o_o
);
  wire a, b;
  assign a = b ^ i_i;
  assign b = ~a;
  assign o_o = b;
endmodule
`default_nettype wire
