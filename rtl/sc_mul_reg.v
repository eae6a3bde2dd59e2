// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_mul_reg.v
// Purpose  : a product with its own pipeline register (a DSP block's M register): p_o is
//            (a_i · b_i + c_i) mod 2^PW of the operands as they were one enabled edge ago (with N > 1 the
//            sum of N products a_k · b_k, a dot product: one tree, one register, one adder; the addend
//            c_i with ADD = 1, a DSP block's C port; the cell flow adds it inside the product's tree). The units'
//            pipelining parameter MREG (rtl/sc_cs16.v) puts one behind each product, so that a
//            product's delay is cut across two clock cycles.
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   AW, BW  operand widths, >= 1                                           (default 8, 8)
//   PW      product width, >= 1; the product is taken modulo 2^PW            (default 16)
//   SIGNED  0: unsigned operands; 1: both two's complement                   (default 0)
//   ADD     0: no addend (c_i unused); 1: p = a·b + c_i, c_i unsigned          (default 0)
//   CW      width of c_i, >= 1                                               (default 1)
//   N       products summed, >= 1: operand k at a_i[k*AW +: AW], b_i[k*BW +: BW] (default 1)
//   LAT     1 or 2 (default 1): enabled edges to p_o. 2: the cell flow registers each product's two carry-save
//           rows, then reduces all of them and adds (the second register holds the sum): a deep tree (a dot
//           product) over two cycles, p_o straight from a register
//
// Ports : clk_i    clock, the register loads on the rising edge
//         en_i     enable (the pipeline's global enable)
//         a_i[N*AW-1:0], b_i[N*BW-1:0]  operands (a square: the same bits on both)
//         c_i[CW-1:0]               the addend (ADD = 1; tie to 0 otherwise)
//         p_o[PW-1:0]               the registered product
//
// Latency : LAT enabled edges. No reset: the pipeline's valid bits qualify the registers.
//
// Implementation: behavioural (`*` then a register), so FPGA flows put the register into the DSP
// block. The standard-cell flow (signoff/signoff.py) reads this module as a black box and maps each
// instance with signoff/fastmul.py to the partial-product tree, the register on its two carry-save
// rows, and the final Kogge-Stone adder after the register: the register cuts the product between
// the tree and the adder. The gate-level simulation shows the mapped netlist computes the same bits.
// ============================================================================================
`default_nettype none

module sc_mul_reg #(
    parameter integer AW     = 8,
    parameter integer BW     = 8,
    parameter integer PW     = 16,
    parameter integer SIGNED = 0,
    parameter integer ADD    = 0,
    parameter integer CW     = 1,
    parameter integer N      = 1,
    parameter integer LAT    = 1
) (
    input  wire            clk_i,
    input  wire            en_i,
    input  wire [N*AW-1:0] a_i,
    input  wire [N*BW-1:0] b_i,
    input  wire [CW-1:0] c_i,
    output wire [PW-1:0] p_o
);

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (AW < 1 || BW < 1 || PW < 1 || CW < 1 || N < 1) begin : g_check_w
      sc_mul_reg_error_illegal_AW_BW_PW_CW_N_must_be_at_least_1 u_error ();
    end
    if (ADD != 0 && ADD != 1) begin : g_check_add
      sc_mul_reg_error_illegal_ADD_must_be_0_or_1 u_error ();
    end
    if (LAT != 1 && LAT != 2) begin : g_check_lat
      sc_mul_reg_error_illegal_LAT_must_be_1_or_2 u_error ();
    end
    if (SIGNED != 0 && SIGNED != 1) begin : g_check_signed
      sc_mul_reg_error_illegal_SIGNED_must_be_0_or_1 u_error ();
    end
  endgenerate

  wire [PW-1:0] p, c;
  generate
    if (ADD != 0) begin : g_add
      if (CW >= PW) begin : g_c_trunc
        assign c = c_i[PW-1:0];
        if (CW > PW) begin : g_c_unused
          wire unused_c = &{1'b0, c_i[CW-1:PW]};
        end
      end else begin : g_c_ext
        assign c = {{(PW-CW){1'b0}}, c_i};
      end
    end else begin : g_no_add
      assign c = {PW{1'b0}};
      wire unused_c = &{1'b0, c_i};
    end
  endgenerate
  // the products, each modulo 2^PW, and their sum with the addend
  wire [N*PW-1:0] ab;
  genvar k;
  generate
    for (k = 0; k < N; k = k + 1) begin : g_prod
      wire [AW-1:0] ak = a_i[k*AW +: AW];
      wire [BW-1:0] bk = b_i[k*BW +: BW];
      if (SIGNED != 0) begin : g_signed
        assign ab[k*PW +: PW] = $signed(ak) * $signed(bk);
      end else begin : g_unsigned
        assign ab[k*PW +: PW] = ak * bk;
      end
    end
  endgenerate
  reg [PW-1:0] sum;
  integer      i;
  always @* begin
    sum = c;
    for (i = 0; i < N; i = i + 1) sum = sum + ab[i*PW +: PW];
  end
  assign p = sum;

  reg [PW-1:0] m_q;
  always @(posedge clk_i) begin
    if (en_i) m_q <= p;
  end
  generate
    if (LAT == 2) begin : g_lat2
      reg [PW-1:0] m2_q;
      always @(posedge clk_i) begin
        if (en_i) m2_q <= m_q;
      end
      assign p_o = m2_q;
    end else begin : g_lat1
      assign p_o = m_q;
    end
  endgenerate

endmodule

`default_nettype wire
