// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_square.v
// Purpose  : folded (and optionally truncated) squarer, combinational (or registered inside: REG = 1):
//              sq_o = (S + C) >> SHIFT,  OW bits,
//            S = the sum of the kept partial-product bits of x_i·x_i, C a constant (below).
//            Bit-accurate C model: cmodel/include/shadecore/units/square.hpp (square_trunc()); used by
//            rtl/sc_cs16.v (FORM = 1), docs/spec.md §3.4.
//
// Folding: x² = Σ_i x_i·2^(2i) + Σ_{i<j} x_i·x_j·2^(i+j+1). Each off-diagonal product x_i·x_j is
// formed once (doubled by its position) and the diagonal x_i·x_i = x_i needs no gate, so row i is
//   x_i ? {x[N-1:i+1], 1'b0, 1'b1} << 2i : 0        (N rows, N(N+1)/2 bits instead of N²)
// and the rows are summed by one multi-operand addition (Yosys maps it to a carry-save tree and
// one carry-propagate adder). With DROP = 0 and C = 0, S + C = x·x exactly.
//
// Truncation: every partial-product bit in a column < DROP is dropped (never formed). The
// constant C (elaboration time) is
//     RND   ? 2^(SHIFT-1) : 0                           (round half up instead of floor)
//   + ECOMP ? round(E[dropped sum]) : 0                 (expected value of the dropped bits for
//                                                        independent uniform x_i: ½ per diagonal
//                                                        bit, ¼ per off-diagonal bit)
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   N      input width                                  1 <= N <= 40
//   OW     output width (the caller guarantees (S + C) >> SHIFT < 2^OW)   1 <= OW
//   SHIFT  result shift                                 0 <= SHIFT, SHIFT + OW <= 2N + 1
//   DROP   columns dropped                              0 <= DROP <= SHIFT
//   RND    0/1, ECOMP 0/1 (above; RND needs SHIFT >= 1)
//   REG    0: combinational (clk_i, en_i unused); 1: the sum S + C is registered inside (rtl/sc_sum_reg.v:
//          the cell flow puts the register between the carry-save tree and the final adder), so sq_o is the
//          result for x_i as it was one enabled edge ago (the cs16 forms' MREG = 1, rtl/sc_cs16.v)  (default 0)
// ============================================================================================
`default_nettype none

module sc_square #(
    parameter integer N     = 16,
    parameter integer OW    = 16,
    parameter integer SHIFT = 16,
    parameter integer DROP  = 0,
    parameter integer RND   = 0,
    parameter integer ECOMP = 0,
    parameter integer REG   = 0
) (
    input  wire          clk_i,   // REG = 1: the register's clock
    input  wire          en_i,    // REG = 1: its enable (the pipeline's global enable)
    input  wire [N-1:0]  x_i,
    output wire [OW-1:0] sq_o
);

  localparam integer PW = 2 * N + 1;  // S + C < 2^(2N) + 2^SHIFT <= 2^(2N+1)

  generate
    if (N < 1 || N > 40) begin : g_check_n
      sc_square_error_illegal_N_legal_range_is_1_to_40 u_error ();
    end
    if (OW < 1 || SHIFT < 0 || SHIFT + OW > PW) begin : g_check_ow
      sc_square_error_illegal_OW_or_SHIFT_need_SHIFT_plus_OW_at_most_2N_plus_1 u_error ();
    end
    if (DROP < 0 || DROP > SHIFT) begin : g_check_drop
      sc_square_error_illegal_DROP_legal_range_is_0_to_SHIFT u_error ();
    end
    if ((RND != 0 && RND != 1) || (ECOMP != 0 && ECOMP != 1) || (RND == 1 && SHIFT < 1)) begin : g_check_c
      sc_square_error_illegal_RND_or_ECOMP_must_be_0_or_1_RND_needs_SHIFT_at_least_1 u_error ();
    end
    if (REG != 0 && REG != 1) begin : g_check_reg
      sc_square_error_illegal_REG_must_be_0_or_1 u_error ();
    end
  endgenerate

  // 4·E[dropped sum] = Σ_{2i < DROP} 2·2^(2i) + Σ_{i<j, i+j+1 < DROP} 2^(i+j+1); C as above.
  function [PW-1:0] comp_const(input integer dummy);
    reg [PW+1:0] e4;
    reg [PW+1:0] c;
    reg [PW+1:0] one;
    integer i, j;
    begin
      e4  = 0;
      one = 1;
      for (i = 0; i < N; i = i + 1) begin
        if (2 * i < DROP) e4 = e4 + (one << (2 * i + 1));
        for (j = i + 1; j < N; j = j + 1) begin
          if (i + j + 1 < DROP) e4 = e4 + (one << (i + j + 1));
        end
      end
      c = 0;
      if (ECOMP == 1) c = (e4 + 2) >> 2;  // round(E), ties up
      if (RND == 1) c = c + (one << (SHIFT - 1));
      if (dummy != 0) c = 0;
      comp_const = c[PW-1:0];
    end
  endfunction
  localparam [PW-1:0] C = comp_const(0);

  // Rows of the folded matrix, bit by bit at elaboration: column c of row i is x_i (c = 2i, the diagonal), x_i·x_j
  // (c = i + j + 1, j > i) or a constant 0 (every other column, and every column below DROP), so each structural
  // zero is a constant in the netlist, not a masked gate. Then one multi-operand sum.
  wire [N*PW-1:0] rows;
  genvar i, c;
  generate
    for (i = 0; i < N; i = i + 1) begin : g_row
      for (c = 0; c < PW; c = c + 1) begin : g_col
        if (c >= DROP && c == 2 * i) begin : g_diag
          assign rows[i*PW + c] = x_i[i];
        end else if (c >= DROP && c >= 2 * i + 2 && c - i - 1 < N) begin : g_pair
          assign rows[i*PW + c] = x_i[i] & x_i[c-i-1];
        end else begin : g_zero
          assign rows[i*PW + c] = 1'b0;
        end
      end
    end
  endgenerate
  wire unused_x = &{1'b0, x_i};   // bits whose every column is dropped (DROP) are not read
  wire [PW-1:0] sum;
  generate
    if (REG != 0) begin : g_reg
      // the rows and the constant as N + 1 operands of one registered sum (the constant's bits fold into one row)
      sc_sum_reg #(.N(N + 1), .W(PW)) u_sum (.clk_i(clk_i), .en_i(en_i), .x_i({rows, C}), .s_o(sum));
    end else begin : g_comb
      reg [PW-1:0] s;
      integer k;
      always @* begin
        s = C;
        for (k = 0; k < N; k = k + 1) s = s + rows[k*PW +: PW];
      end
      assign sum = s;
      wire unused_clk = &{1'b0, clk_i, en_i};
    end
  endgenerate

  assign sq_o = sum[SHIFT+OW-1:SHIFT];
  generate
    if (SHIFT > 0) begin : g_unused_lo
      wire unused_lo = &{1'b0, sum[SHIFT-1:0]};
    end
    if (SHIFT + OW < PW) begin : g_unused_hi
      wire unused_hi = &{1'b0, sum[PW-1:SHIFT+OW]};
    end
  endgenerate

endmodule

`default_nettype wire
