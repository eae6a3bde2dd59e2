// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_delay.v
// Purpose  : delay line with a clock enable, for aligning operands inside a global-enable
//            pipeline (rtl/sc_light.v): q_o is d_i as it was DEPTH enabled edges ago.
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   W      data width, >= 1                                                 (default 1)
//   DEPTH  number of register stages, >= 0; 0 is a wire (q_o = d_i, clk_i and en_i unused)
//                                                                           (default 1)
//
// Ports : clk_i     clock, all flops on the rising edge
//         en_i      enable: every stage loads its predecessor at a rising edge with en_i high
//                   (the pipeline's global enable)
//         d_i[W-1:0]  data in;  q_o[W-1:0]  data out
//
// Latency : DEPTH enabled edges. No reset: the data registers are qualified by the valid bits
//           of the pipeline that instantiates the line.
// ============================================================================================
`default_nettype none

module sc_delay #(
    parameter integer W     = 1,
    parameter integer DEPTH = 1
) (
    input  wire         clk_i,
    input  wire         en_i,
    input  wire [W-1:0] d_i,
    output wire [W-1:0] q_o
);

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (W < 1) begin : g_check_w
      sc_delay_error_illegal_W_must_be_at_least_1 u_error ();
    end
    if (DEPTH < 0) begin : g_check_depth
      sc_delay_error_illegal_DEPTH_must_be_at_least_0 u_error ();
    end
  endgenerate

  generate
    if (DEPTH == 0) begin : g_wire
      assign q_o = d_i;
      wire unused_ctl = &{1'b0, clk_i, en_i};
    end else if (DEPTH == 1) begin : g_one
      reg [W-1:0] q_q;
      always @(posedge clk_i) begin
        if (en_i) q_q <= d_i;
      end
      assign q_o = q_q;
    end else begin : g_line
      // stage k at bits [k*W +: W]; stage 0 loads d_i, stage DEPTH-1 is the output
      reg [W*DEPTH-1:0] line_q;
      always @(posedge clk_i) begin
        if (en_i) line_q <= {line_q[W*(DEPTH-1)-1:0], d_i};
      end
      assign q_o = line_q[W*DEPTH-1:W*(DEPTH-1)];
    end
  endgenerate

endmodule

`default_nettype wire
