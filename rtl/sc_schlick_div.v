// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_schlick_div.v
// Purpose  : Schlick-divide specular unit, pipelined restoring divider —
//              out = 2^F · c / Dc  rounded half up,   Dc = n·(2^F − c) + c  (exact),
//            i.e. Schlick's S(t, n) = t / (n − (n−1)·t) with t = c/2^F, correctly rounded to F
//            fraction bits (docs/spec.md §6; bit-accurate C model: schlick_div_eval() in
//            cmodel/include/shadecore/units/schlick.hpp, same stage names as SchlickTrace).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC   F, fraction bits of cos θ and of the output     8 <= F <= 24   (default 16)
//   TAGW   width of the opaque tag that travels with each fragment, >= 1  (default 8)
//   MREG   0 or 1, the pipelining parameter: 1 forms n·d in rtl/sc_mul_reg.v, whose register M1 sits
//          between S0 and S1 (LATENCY F + 5), the same outputs                     (default 0)
//   (no GUARD: the divider is exact up to its final rounding; mat_thr_i is not used)
//
// Ports : docs/spec.md §4 (clk_i, rst_ni synchronous active-low, AXI-Stream style valid/ready).
//
// Latency   : LATENCY = F + 4 clock cycles (20 at F = 16): S0, S1 and the F+2 quotient stages
//             Q0..Q(F+1); F + 5 with MREG = 1 (M1). A fragment accepted at a rising edge is on out_* (out_valid_o = 1)
//             after the (F+4)th advancing edge from it; an edge advances the pipeline iff
//             (!out_valid_o || out_ready_i) before it (one global enable, as rtl/sc_cs16.v).
// Throughput: one fragment per clock while out_ready_i is high.
// Handshake : in_ready_o = rst_ni && (!out_valid_o || out_ready_i) (ready -> ready path is
//             combinational, no valid depends on a ready). While stalled, out_* hold.
// Reset     : synchronous, active-low; clears every valid bit (fragments in flight dropped);
//             in_ready_o is low during reset. Data and material registers are not reset.
// Material  : mat_we_i loads mat_n_i at a rising edge; a fragment accepted at that same edge uses
//             the old n. n travels with the fragment to S1 (where Dc is formed); Dc travels on.
//             mat_n_i must be in [16, 1024]; mat_thr_i is ignored.
//
// Datapath (DB = F+11 = width of Dc; every box is a register stage on the global enable):
//
//   in_cos_i[F+1:0] signed
//      │  clamp to [0, 2^F]; d = 2^F − c
//   ┌──▼───────────────────────┐
//   │ S0  c[F:0] d[F:0] n[10:0] │
//   └──┬───────────────────────┘
//      │  Dc = n·d + c                      (DB bits, exact; 2^F <= Dc <= n·2^F, Dc >= c)
//   ┌──▼──────────────┐
//   │ S1  Dc  c        │
//   └──┬──────────────┘
//      │  q0 = (c >= Dc)  (only c = Dc = 2^F);  r = c − q0·Dc
//   ┌──▼──────────────┐
//   │ Q0  r  Dc  q     │
//   └──┬──────────────┘
//      │  r2 = 2r;  b = (r2 >= Dc);  r = b ? r2 − Dc : r2;  q = {q, b}     (DB+1-bit subtract)
//   ┌──▼──────────────┐
//   │ Qk  r  Dc  q     │   k = 1 .. F, one quotient bit per stage
//   └──┬──────────────┘
//      │  the same step for bit F+1, then out = (q + 1) >> 1   (q = ⌊c·2^(F+1)/Dc⌋, F+2 bits)
//   ┌──▼──────────────┐
//   │ Q(F+1)  out      │──► out_spec_o[F:0] (<= 2^F), out_tag_o, out_valid_o
//   └─────────────────┘
// ============================================================================================
`default_nettype none

module sc_schlick_div #(
    parameter integer FRAC = 16,
    parameter integer TAGW = 8,
    parameter integer MREG = 0
) (
    // clk_i, rst_ni; mat_we_i, mat_n_i[10:0], mat_thr_i[FRAC:0]; in_valid_i, in_ready_o,
    // in_cos_i[FRAC+1:0], in_tag_i; out_valid_o, out_ready_i, out_spec_o[FRAC:0], out_tag_o
`include "sc_unit_ports.vh"
);

  localparam integer F  = FRAC;
  localparam integer DB = FRAC + 11;   // Dc <= n*2^F <= 2^(F+10)
  localparam integer NQ = FRAC + 2;    // quotient bits = division stages Q0..Q(F+1)
  localparam integer HB = (DB + 1) / 2;   // the remainder select's halves: bits [DB:HB] by b, [HB-1:0] by b2
  localparam integer NS = FRAC + 4 + MREG;  // register stages S0, (M1,) S1, Q0..Q(F+1) = latency

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (FRAC < 8 || FRAC > 24) begin : g_check_frac
      sc_schlick_div_error_illegal_FRAC_legal_range_is_8_to_24 u_error ();
    end
    if (TAGW < 1) begin : g_check_tagw
      sc_schlick_div_error_illegal_TAGW_must_be_at_least_1 u_error ();
    end
    if (MREG != 0 && MREG != 1) begin : g_check_mreg
      sc_schlick_div_error_illegal_MREG_must_be_0_or_1 u_error ();
    end
  endgenerate

  localparam [F:0] ONE = {1'b1, {F{1'b0}}};   // 2^F, cos θ = 1.0

  // ---------------------------------------------------------------------------- handshake
  wire          adv;                        // global enable (rtl/sc_pipe_ctrl.v)
  wire [NS-1:0] v_stage;                    // valid bit of each stage (unused: adv qualifies the data)
  sc_pipe_ctrl #(.DEPTH(NS)) u_ctrl (
      .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
      .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .en_o(adv), .valid_o(v_stage));
  wire unused_v_stage = &{1'b0, v_stage};

  // mat_n_q, the input clamp c_d (rtl/sc_schlick_front.vh)
`include "sc_schlick_front.vh"

  // ---------------------------------------------------------------------------- S0: clamp

  reg [F:0]      s0_c_q, s0_d_q;
  reg [10:0]     s0_n_q;
  reg [TAGW-1:0] s0_tag_q;
  always @(posedge clk_i) begin
    if (adv) begin
      s0_c_q   <= c_d;
      s0_d_q   <= ONE - c_d;
      s0_n_q   <= mat_n_q;
      s0_tag_q <= in_tag_i;
    end
  end

  // ---------------------------------------------------------------------------- S1: denominator
  // MREG = 1: Dc = (−n)·(c − 2^F) + c, where c − 2^F (in [−2^F, 0]) is c with bit F inverted read as a signed
  // F+1-bit word (no subtractor in front of the multiplier; S0's d is unused) and −n is formed in S0 from the
  // material register; one signed rtl/sc_mul_reg.v with c as its addend (inside the tree), its register M1
  // between S0 and S1, c and the tag beside it.
  wire [DB-1:0]   den_d;
  wire [F:0]      s0_c_m;
  wire [TAGW-1:0] s0_tag_m;
  generate
    if (MREG != 0) begin : g_den_m
      reg  [11:0] s0_nn_q;   // −n, two's complement
      always @(posedge clk_i) begin
        if (adv) s0_nn_q <= 12'd0 - {1'b0, mat_n_q};
      end
      wire [DB:0] dc;        // (−n)·(c − 2^F) + c = n·d + c = Dc <= 2^(F+10): bit DB is 0
      sc_mul_reg #(.AW(12), .BW(F+1), .PW(DB+1), .SIGNED(1), .ADD(1), .CW(F+1)) u_nd (
          .clk_i(clk_i), .en_i(adv), .a_i(s0_nn_q), .b_i({~s0_c_q[F], s0_c_q[F-1:0]}), .c_i(s0_c_q), .p_o(dc));
      sc_delay #(.W(TAGW + F + 1), .DEPTH(1)) u_dly_m1 (
          .clk_i(clk_i), .en_i(adv), .d_i({s0_tag_q, s0_c_q}), .q_o({s0_tag_m, s0_c_m}));
      assign den_d = dc[DB-1:0];
      wire unused_den = &{1'b0, dc[DB], s0_d_q, s0_n_q};
    end else begin : g_den
      assign den_d = ({{(DB-11){1'b0}}, s0_n_q} * {{(DB-F-1){1'b0}}, s0_d_q}) + {{(DB-F-1){1'b0}}, s0_c_q};
      assign s0_c_m = s0_c_q;
      assign s0_tag_m = s0_tag_q;
    end
  endgenerate

  reg [DB-1:0]   s1_den_q;
  reg [F:0]      s1_c_q;
  reg [TAGW-1:0] s1_tag_q;
  always @(posedge clk_i) begin
    if (adv) begin
      s1_den_q <= den_d;
      s1_c_q   <= s0_c_m;
      s1_tag_q <= s0_tag_m;
    end
  end

  // ---------------------------------------------------------------------------- Q0: integer bit
  // Stage k of Q0..Q(F) keeps its remainder, divisor, quotient and tag in slice k of these vectors.
  reg [DB*(NQ-1)-1:0]   r_q;
  reg [DB*(NQ-1)-1:0]   den_q;
  reg [NQ*(NQ-1)-1:0]   quo_q;
  reg [TAGW*(NQ-1)-1:0] tag_q;

  wire [DB-1:0] c_ext  = {{(DB-F-1){1'b0}}, s1_c_q};
  wire          q0_b   = (c_ext >= s1_den_q);
  always @(posedge clk_i) begin
    if (adv) begin
      r_q[0 +: DB]     <= q0_b ? (c_ext - s1_den_q) : c_ext;
      den_q[0 +: DB]   <= s1_den_q;
      quo_q[0 +: NQ]   <= {{(NQ-1){1'b0}}, q0_b};
      tag_q[0 +: TAGW] <= s1_tag_q;
    end
  end

  // ---------------------------------------------------------------------------- Q1..Q(F+1): one bit each
  reg [F:0]      out_q;
  reg [TAGW-1:0] out_tag_q;

  genvar k;
  generate
    for (k = 1; k < NQ; k = k + 1) begin : g_q
      wire [DB-1:0] r_in   = r_q[(k-1)*DB +: DB];
      wire [DB-1:0] den_in = den_q[(k-1)*DB +: DB];
      wire [NQ-1:0] quo_in = quo_q[(k-1)*NQ +: NQ];
      wire [DB:0]   r2     = {r_in, 1'b0};                       // 2r < 2·Dc
      wire [DB+1:0] diff   = {1'b0, r2} - {2'b0, den_in};        // sign bit = borrow
      wire          b      = !diff[DB+1];                        // r2 >= Dc
      // The same bit from a compare of its own, 2r + 1 > Dc, on other operands so that synthesis keeps it apart
      // from the subtraction's sign: b selects the remainder's upper half, b2 its lower half and the output
      // (each sign half the fanout; rtl/sc_schlick_iter.v does the same)
      wire          b2     = ({1'b0, r_in, 1'b1} > {2'b0, den_in});
      wire [DB:0]   r_nx   = {b ? diff[DB:HB] : r2[DB:HB], b2 ? diff[HB-1:0] : r2[HB-1:0]};   // < Dc: top bit 0
      wire [NQ-1:0] quo_nx = {quo_in[NQ-2:0], b};
      wire unused_step = &{1'b0, r_nx[DB], quo_in[NQ-1]};
      if (k < NQ - 1) begin : g_mid
        always @(posedge clk_i) begin
          if (adv) begin
            r_q[k*DB +: DB]       <= r_nx[DB-1:0];
            den_q[k*DB +: DB]     <= den_in;
            quo_q[k*NQ +: NQ]     <= quo_nx;
            tag_q[k*TAGW +: TAGW] <= tag_q[(k-1)*TAGW +: TAGW];
          end
        end
      end else begin : g_last
        // q = ⌊c·2^(F+1)/Dc⌋ <= 2^(F+1); out = (q + 1) >> 1 <= 2^F (round half up) = Q + b with Q the
        // bits before the last: Q + 1 is formed beside the step's subtraction, and b2 selects
        wire [NQ-2:0] q_inc = quo_in[NQ-2:0] + {{(NQ-2){1'b0}}, 1'b1};
        wire unused_last = &{1'b0, quo_nx, r_nx};
        always @(posedge clk_i) begin
          if (adv) begin
            out_q     <= b2 ? q_inc : quo_in[NQ-2:0];
            out_tag_q <= tag_q[(k-1)*TAGW +: TAGW];
          end
        end
      end
    end
  endgenerate

  assign out_spec_o = out_q;
  assign out_tag_o  = out_tag_q;

`ifdef FORMAL
  // Material rule of docs/spec.md §4 (rtl/sc_formal_material.vh): a fragment captures n at an advancing edge.
  wire        f_capture    = adv;
  wire [10:0] f_captured_n = s0_n_q;
`include "sc_formal_material.vh"
`endif

endmodule

`default_nettype wire
