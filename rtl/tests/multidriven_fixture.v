// SPDX-License-Identifier: Apache-2.0
// Negative fixture for scripts/yosys_check.sh: one net driven by two continuous assignments.
// The ctest `rtl.yosys_check_rejects_multidriven` passes only if the check REJECTS this file.
`default_nettype none
module multidriven_fixture (
    input  wire a_i,
    input  wire b_i,
    output wire o_o
);
  assign o_o = a_i;
  assign o_o = b_i;
endmodule
`default_nettype wire
