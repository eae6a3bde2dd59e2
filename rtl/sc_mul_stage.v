// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_mul_stage.v
// Purpose  : a product that a pipelining parameter may cut: with MREG = 0 p_o = (a_i·b_i + c_i) mod 2^PW
//            combinationally; with MREG = 1 the product goes through rtl/sc_mul_reg.v (its register between the
//            partial-product tree and the final adder in the cell flow) and p_o is that of the operands one
//            enabled edge ago. A sideband (the values a pipeline stage carries beside its product) is delayed by
//            the same MREG edges, so side_o stays aligned with p_o. The lighting core's normaliser (rtl/sc_normalize.v)
//            is written once with it for both values of its MREG.
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   AW, BW, PW, SIGNED, ADD, CW   as rtl/sc_mul_reg.v; ADD = 1 needs MREG = 1 (defaults 8, 8, 16, 0, 0, 1)
//   MREG    0: combinational; 1: registered (latency 1)                     (default 0)
//   SW      sideband width, >= 1 (tie unused bits to constants)             (default 1)
//
// Ports : clk_i, en_i        clock and the pipeline's global enable (unused with MREG = 0)
//         a_i, b_i, c_i      operands and addend (c_i with ADD = 1; tie to 0 otherwise)
//         side_i[SW-1:0]     the sideband
//         p_o[PW-1:0]        the product (+ addend), modulo 2^PW
//         side_o[SW-1:0]     side_i delayed by MREG enabled edges
//
// Latency : MREG enabled edges. No reset: the pipeline's valid bits qualify the registers.
// ============================================================================================
`default_nettype none

module sc_mul_stage #(
    parameter integer AW     = 8,
    parameter integer BW     = 8,
    parameter integer PW     = 16,
    parameter integer SIGNED = 0,
    parameter integer ADD    = 0,
    parameter integer CW     = 1,
    parameter integer MREG   = 0,
    parameter integer SW     = 1
) (
    input  wire          clk_i,
    input  wire          en_i,
    input  wire [AW-1:0] a_i,
    input  wire [BW-1:0] b_i,
    input  wire [CW-1:0] c_i,
    input  wire [SW-1:0] side_i,
    output wire [PW-1:0] p_o,
    output wire [SW-1:0] side_o
);

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (MREG != 0 && MREG != 1) begin : g_check_mreg
      sc_mul_stage_error_illegal_MREG_must_be_0_or_1 u_error ();
    end
    if (SW < 1) begin : g_check_sw
      sc_mul_stage_error_illegal_SW_must_be_at_least_1 u_error ();
    end
    if (ADD != 0 && MREG == 0) begin : g_check_add
      sc_mul_stage_error_illegal_ADD_needs_MREG_1 u_error ();
    end
  endgenerate

  generate
    if (MREG != 0) begin : g_reg
      sc_mul_reg #(.AW(AW), .BW(BW), .PW(PW), .SIGNED(SIGNED), .ADD(ADD), .CW(CW)) u_mul (
          .clk_i(clk_i), .en_i(en_i), .a_i(a_i), .b_i(b_i), .c_i(c_i), .p_o(p_o));
      reg [SW-1:0] side_q;
      always @(posedge clk_i) begin
        if (en_i) side_q <= side_i;
      end
      assign side_o = side_q;
    end else begin : g_comb
      // the product alone (modulo 2^PW), as rtl/sc_mul_reg.v without its register
      if (SIGNED != 0) begin : g_signed
        assign p_o = $signed(a_i) * $signed(b_i);
      end else begin : g_unsigned
        assign p_o = a_i * b_i;
      end
      assign side_o = side_i;
      wire unused_comb = &{1'b0, clk_i, en_i, c_i};
    end
  endgenerate

endmodule

`default_nettype wire
