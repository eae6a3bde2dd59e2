// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_sum_reg.v
// Purpose  : a multi-operand sum with its own pipeline register: s_o is (x_0 + x_1 + ... + x_(N-1)) mod 2^W of
//            the operands as they were one enabled edge ago. The sibling of rtl/sc_mul_reg.v for a bit heap that
//            is not one product: rtl/sc_square.v (REG = 1) sums its folded, truncated rows and its constant here,
//            so that the pipelining parameter MREG of the cs16 forms (rtl/sc_cs16.v FORM = 1) cuts each squaring
//            across two clocks.
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   N   number of operands, >= 1                                                (default 2)
//   W   operand and sum width, >= 1; the sum is taken modulo 2^W                 (default 8)
//
// Ports : clk_i            clock, the register loads on the rising edge
//         en_i             enable (the pipeline's global enable)
//         x_i[N*W-1:0]     operand k at [k*W +: W] (constant bits welcome: they cost nothing, below)
//         s_o[W-1:0]       the registered sum
//
// Latency : 1 enabled edge. No reset: the pipeline's valid bits qualify the register.
//
// Implementation: behavioural (a sum, then a register), so FPGA flows may retime the register into the adder
// tree. The standard-cell flow (signoff/signoff.py) reads this module as a black box and maps each instance with
// signoff/fastmul.py: the operands' non-constant bits form a bit heap (their constant bits fold into one
// constant row), a Dadda tree reduces it to two carry-save rows, the register holds those two rows, and a
// Kogge-Stone adder after the register adds them: the register cuts the sum between the tree and the final
// adder. The gate-level simulation shows the mapped netlist computes the same bits.
// ============================================================================================
`default_nettype none

module sc_sum_reg #(
    parameter integer N = 2,
    parameter integer W = 8
) (
    input  wire           clk_i,
    input  wire           en_i,
    input  wire [N*W-1:0] x_i,
    output wire [W-1:0]   s_o
);

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (N < 1 || W < 1) begin : g_check_nw
      sc_sum_reg_error_illegal_N_and_W_must_be_at_least_1 u_error ();
    end
  endgenerate

  reg [W-1:0] sum;
  integer k;
  always @* begin
    sum = {W{1'b0}};
    for (k = 0; k < N; k = k + 1) sum = sum + x_i[k*W +: W];
  end

  reg [W-1:0] s_q;
  always @(posedge clk_i) begin
    if (en_i) s_q <= sum;
  end
  assign s_o = s_q;

endmodule

`default_nettype wire
