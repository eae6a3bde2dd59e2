// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_schlick_iter.v
// Purpose  : Schlick-divide specular unit, iterative (small) form — the same restoring division
//            as rtl/sc_schlick_div.v, one quotient bit per clock in ONE subtract/compare stage:
//              out = 2^F · c / Dc  rounded half up,   Dc = n·(2^F − c) + c  (exact).
//            Bit-identical to sc_schlick_div (C model: schlick_iter_eval() == schlick_div_eval()
//            in cmodel/include/shadecore/units/schlick.hpp).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC   F, fraction bits of cos θ and of the output     8 <= F <= 24   (default 16)
//   TAGW   width of the opaque tag that travels with each fragment, >= 1  (default 8)
//
// Ports : docs/spec.md §4 (clk_i, rst_ni synchronous active-low, AXI-Stream style valid/ready).
//
// Latency   : LATENCY = F + 4 clock cycles (20 at F = 16) from the accepting edge to the edge at
//             which the result can first be taken: 1 (clamp) + 1 (Dc) + F+2 quotient bits, the
//             last of which also rounds into the output register.
// Throughput: one fragment every F + 4 clocks (initiation interval F + 4 with out_ready_i high):
//             a new fragment is accepted at the same edge at which the previous result is taken.
// Handshake : in_ready_o = rst_ni && !busy && (!out_valid_o || out_ready_i): LOW while a division
//             is in progress (busy) and while an untaken result waits in the output register.
//             out_* hold until taken.
// Reset     : synchronous, active-low; clears busy and out_valid_o (a fragment in progress is
//             dropped); in_ready_o low during reset. Data and material registers are not reset.
// Material  : mat_we_i loads mat_n_i at a rising edge; a fragment accepted at that same edge uses
//             the old n (it is copied into the working register at acceptance). mat_thr_i unused.
//
// Datapath (DB = F+11):
//
//   accept:  c, n, 1 − n, tag ──► working registers               busy = 1, phase = DEN
//   DEN   :  Dc = (1 − n)·c + n·2^F into a registered product (its tree);
//            quotient bit 0 without Dc: b0 = (n == 0 || c == 2^F) (c >= Dc iff n·(2^F − c) = 0),
//            r = b0 ? 0 : c, q = b0                                  phase = DIV, k = 0
//   DIV 0 :  den = Dc (the product's final adder); r, q hold
//   DIV k :  2r;  b = (2r >= Dc);  r = b ? 2r − Dc : 2r;  q = {q, b}
//            k = 1 .. F+1 (one bit per clock; k == 0 is the register first_q); at k = F+1:
//            out = (q + 1) >> 1 = Q + b (Q the bits before the last, Q + 1 formed beside the last
//            subtraction), out_valid = 1, busy = 0
// ============================================================================================
`default_nettype none

module sc_schlick_iter #(
    parameter integer FRAC = 16,
    parameter integer TAGW = 8
) (
    // clk_i, rst_ni; mat_we_i, mat_n_i[10:0], mat_thr_i[FRAC:0]; in_valid_i, in_ready_o,
    // in_cos_i[FRAC+1:0], in_tag_i; out_valid_o, out_ready_i, out_spec_o[FRAC:0], out_tag_o
`include "sc_unit_ports.vh"
);

  localparam integer F  = FRAC;
  localparam integer DB = FRAC + 11;   // width of Dc
  localparam integer NQ = FRAC + 2;    // quotient bits

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (FRAC < 8 || FRAC > 24) begin : g_check_frac
      sc_schlick_iter_error_illegal_FRAC_legal_range_is_8_to_24 u_error ();
    end
    if (TAGW < 1) begin : g_check_tagw
      sc_schlick_iter_error_illegal_TAGW_must_be_at_least_1 u_error ();
    end
  endgenerate

  localparam [F:0] ONE     = {1'b1, {F{1'b0}}};
  localparam integer LASTK = NQ - 1;   // F+1 <= 25
  localparam [4:0]   LAST_K = LASTK[4:0];

  // ---------------------------------------------------------------------------- control
  reg        busy_q;       // a fragment is in DEN or DIV
  reg        div_q;        // phase: 0 = DEN, 1 = DIV (meaningful while busy_q)
  reg  [4:0] k_q;          // quotient bit being produced
  reg        first_q;      // k_q == 0 in DIV (den_q loads; no step), as a register of its own
  reg        out_valid_q;

  wire take   = out_valid_q && out_ready_i;
  wire accept = in_valid_i && in_ready_o;
  wire last   = busy_q && div_q && (k_q == LAST_K);

  assign in_ready_o  = rst_ni && !busy_q && (!out_valid_q || out_ready_i);
  assign out_valid_o = out_valid_q;

  always @(posedge clk_i) begin
    if (!rst_ni) begin
      busy_q      <= 1'b0;
      div_q       <= 1'b0;
      k_q         <= 5'd0;
      first_q     <= 1'b0;
      out_valid_q <= 1'b0;
    end else begin
      if (accept) begin
        busy_q <= 1'b1;
        div_q  <= 1'b0;
      end else if (busy_q && !div_q) begin
        div_q   <= 1'b1;
        k_q     <= 5'd0;
        first_q <= 1'b1;
      end else if (last) begin
        busy_q  <= 1'b0;
        first_q <= 1'b0;
      end else if (busy_q) begin
        k_q     <= k_q + 5'd1;
        first_q <= 1'b0;
      end
      // last never coincides with take of an older result: in_ready (hence a new fragment) needs
      // an empty or departing output register, and a result is only produced by the fragment
      // accepted then.
      if (last) begin
        out_valid_q <= 1'b1;
      end else if (take) begin
        out_valid_q <= 1'b0;
      end
    end
  end

  // mat_n_q, the input clamp c_d (rtl/sc_schlick_front.vh)
`include "sc_schlick_front.vh"

  // ---------------------------------------------------------------------------- datapath

  reg [F:0]      c_q;
  reg [10:0]     n_q;
  reg [11:0]     omn_q;      // 1 − n, two's complement, from the material register
  reg [TAGW-1:0] tag_q;
  reg [DB-1:0]   den_q, r_q;
  reg [NQ-1:0]   quo_q;
  reg [F:0]      out_q;
  reg [TAGW-1:0] out_tag_q;

  // Dc = n·(2^F − c) + c = (1 − n)·c + n·2^F: one signed product with n·2^F as its addend (no subtractor behind
  // the input ports), an rtl/sc_mul_reg.v loaded in DEN; den_q takes it at k = 0 (the cell flow cuts it between
  // its carry-save tree, in DEN, and its final adder, at k = 0).
  wire den_en = busy_q && !div_q;
  wire [DB-1:0] den_p;
  sc_mul_reg #(.AW(F + 2), .BW(12), .PW(DB), .SIGNED(1), .ADD(1), .CW(DB)) u_den (
      .clk_i(clk_i), .en_i(den_en), .a_i({1'b0, c_q}), .b_i(omn_q), .c_i({n_q, {F{1'b0}}}), .p_o(den_p));
  // Quotient bit 0 needs no Dc: c >= Dc iff n·(2^F − c) = 0, i.e. n = 0 or c = 2^F, and then c − Dc = 0. DEN
  // produces it; k = 0 loads den_q; k = 1..F+1 each shift the remainder and subtract Dc.
  wire          b0     = (n_q == 11'd0) || (c_q == ONE);

  wire [DB:0]   r2     = {r_q, 1'b0};                                  // 2r < 2·Dc
  wire [DB+1:0] diff   = {1'b0, r2} - {2'b0, den_q};
  wire          b      = !diff[DB+1];                                  // r2 >= Dc
  wire [DB:0]   r_nx   = b ? diff[DB:0] : r2;                          // < Dc
  wire [NQ-1:0] quo_nx = {quo_q[NQ-2:0], b};
  // round half up: out = (q + 1) >> 1 with q = {Q, b}, Q = quo_q[NQ-2:0], is Q + b (<= 2^F); Q + 1 is formed
  // beside the step's subtraction, so only a select follows b
  // The select takes its own compare, 2r + 1 > Dc (= b, for integers), written on other operands so that synthesis
  // keeps it apart from the subtraction's sign: b then drives the remainder's select alone, this one the output's.
  wire [NQ-2:0] q_inc  = quo_q[NQ-2:0] + {{(NQ-2){1'b0}}, 1'b1};
  wire          b_out  = ({1'b0, r_q, 1'b1} > {2'b0, den_q});
  wire [F:0]    rnd    = b_out ? q_inc : quo_q[NQ-2:0];
  wire unused_dp = &{1'b0, r_nx[DB], quo_q[NQ-1]};

  always @(posedge clk_i) begin
    if (accept) begin
      c_q   <= c_d;
      n_q   <= mat_n_q;
      omn_q <= 12'd1 - {1'b0, mat_n_q};
      tag_q <= in_tag_i;
    end
    if (den_en) begin
      r_q   <= b0 ? {DB{1'b0}} : {{(DB-F-1){1'b0}}, c_q};
      quo_q <= {{(NQ-1){1'b0}}, b0};
    end else if (busy_q && first_q) begin
      den_q <= den_p;
    end else if (busy_q) begin
      r_q   <= r_nx[DB-1:0];
      quo_q <= quo_nx;
    end
    if (last) begin
      out_q     <= rnd;
      out_tag_q <= tag_q;
    end
  end

  assign out_spec_o = out_q;
  assign out_tag_o  = out_tag_q;

`ifdef FORMAL
  // Material rule of docs/spec.md §4 (rtl/sc_formal_material.vh): a fragment captures n when it is accepted.
  wire        f_capture    = accept;
  wire [10:0] f_captured_n = n_q;
`include "sc_formal_material.vh"

  // Handshake properties, the same as rtl/sc_pipe_ctrl.v's (this unit has its own multi-cycle
  // control): at most one fragment in flight (in the divider or in the output register).
  reg       f_past = 1'b0;                 // cycle >= 1 (the harness resets in cycle 0)
  reg [1:0] f_cnt  = 2'd0;                 // accepted - taken since the last reset
  reg       f_acc  = 1'b0;
  always @(posedge clk_i) begin
    f_past <= 1'b1;
    if (!rst_ni) begin
      f_cnt  <= 2'd0;
      f_acc  <= 1'b0;
    end else begin
      f_cnt <= f_cnt + {1'b0, accept} - {1'b0, take};
      if (accept) f_acc <= 1'b1;
    end
  end
  always @* begin
    it_ready_reset: assert (rst_ni || !in_ready_o);
    if (f_past) begin
      it_count:       assert (f_cnt == {1'b0, busy_q} + {1'b0, out_valid_q});
      it_count_bound: assert (f_cnt <= 2'd1);
      it_no_spurious: assert (f_acc || !out_valid_o);
      it_acc:         assert (f_acc || f_cnt == 2'd0);
    end
  end
  always @(posedge clk_i) begin
    if (f_past && $past(f_past) && $past(rst_ni) && $past(out_valid_o) && !$past(out_ready_i)) begin
      it_hold: assert (out_valid_o);
    end
  end
`endif

endmodule

`default_nettype wire
