// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_cs16.v
// Purpose  : cs16 specular unit — out = ((n/16)(cos θ − 1) + 1)^16, cut to 0 past the cut-off,
//            in fixed point exactly as docs/spec.md §3 (bit-accurate C model:
//            cmodel/include/shadecore/units/cs16.hpp, cs16_eval(); same stage names as Cs16Trace).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC   F, fraction bits of cos θ and of the output     8 <= F <= 24        (default 16)
//   GUARD  G, extra fraction bits through the squarings    4 <= G <= 8, F+G <= 31 (default 5)
//   CUTOFF 0 = theta_cr (cut when clamped code c < thr(n), thr from mat_thr_i)
//          1 = sign_clamp (cut when the base <= 0; mat_thr_i ignored)          (default 0)
//   TAGW   width of the opaque tag that travels with each fragment, >= 1       (default 8)
//   FORM   0 = reference datapath (below); 1 = folded truncated squarers (rtl/sc_square.v) with
//          the stage widths SQ_A1..SQ_A4 (relative to F, or F+G with SQ_REL_G = 1), kept columns
//          SQ_K1..SQ_K4 and compensation SQ_COMP (docs/spec.md §3.4). FORM = 1 has no S0 and no S6:
//          clamp, n·d and the cut feed S1 combinationally, S5 is the output register (latency 5).
//   SHARE  1..4 (FORM = 0; the lighting core's `share`): the four squarings share ⌈4/SHARE⌉ squarers
//          (rtl/sc_mul_pool.v, squaring k at stage k; each squarer takes the one valid stage of its
//          group) and a fragment is accepted only SHARE stages behind the one ahead (rtl/sc_pipe_ctrl.v
//          GAP): one fragment per SHARE clocks, the same outputs and latency.           (default 1)
//   MREG   0 or 1: the pipelining parameter. 1 puts a register inside each of the five
//          products (n·d and the four squarings: rtl/sc_mul_reg.v, a DSP block's M register, in the
//          reference form; rtl/sc_square.v REG = 1, rtl/sc_sum_reg.v, in FORM = 1; the standard-cell flow
//          places it between the carry-save tree and the final adder), so each product spans two clocks;
//          FORM = 1 also gains an input register S0 (the port's code, the cut tests and the material, so no
//          logic sits between the input ports and a product): LATENCY = 12 (reference) or 11 (FORM = 1),
//          the same outputs. With SHARE > 1 (reference form) the four squarings go through one
//          rtl/sc_mul_pool.v with LAT = 1 (its registers are M2..M5): squarings two stages apart share a
//          squarer when 2·|k − k'| < SHARE, so share 4 has two squarers, share 2 four.    (default 0)
//
// Ports : docs/spec.md §4 (clk_i, rst_ni synchronous active-low, AXI-Stream style valid/ready).
//
// Latency   : LATENCY = 7 clock cycles (FORM = 0; 12 with MREG = 1; FORM = 1: 5, 11 with MREG = 1, below). A fragment presented in
//             cycle t and accepted at the rising edge that ends cycle t is presented on out_*
//             (out_valid_o = 1) in cycle t+LATENCY, when out_ready_i is high throughout. In general
//             the result appears after the LATENCY-th *advancing* edge counted from the accepting
//             edge, where an edge advances the pipeline iff (!out_valid_o || out_ready_i) before it
//             (one global enable).
// Throughput: one fragment per clock while out_ready_i is high.
// Handshake : in_ready_o = rst_ni && (!out_valid_o || out_ready_i). The path out_ready_i ->
//             in_ready_o is combinational (allowed by AXI-Stream: ready may depend on ready;
//             no valid depends on a ready). While out_ready_i is low and out_valid_o is high
//             the whole pipeline holds; out_spec_o/out_tag_o stay stable until taken.
// Reset     : synchronous, active-low; clears every valid bit, so fragments in flight are
//             dropped. in_ready_o is low while rst_ni is low (nothing is accepted during reset).
//             The material registers and the data registers are not reset (no need: valid bits
//             qualify them); load a material with mat_we_i before the first fragment.
// Material  : mat_we_i loads mat_n_i / mat_thr_i at a rising edge. A fragment accepted at that
//             same edge uses the old material; n and thr travel with the fragment through S0,
//             so fragments in flight are never affected by a material write.
//             mat_n_i must be in [16, 1024] and mat_thr_i must be thr(n) of docs/spec.md §3.1
//             (as cs16_setup() computes it); then |base| <= 2^(F+4) for every shaded fragment.
//
// Datapath (W = F+G; every box is a register stage clocked by the global enable):
//
//   in_cos_i[F+1:0] signed
//      │  clamp to [0, 2^F]; d = 2^F − c
//   ┌──▼───────────────────────────────┐
//   │ S0  c[F:0] d[F:0] n[10:0] thr[F:0] tag │
//   └──┬───────────────────────────────┘
//      │  base = 2^(F+4) − n·d   (signed, F+13 bits, exact)
//      │  cut  = CUTOFF==0 ? (c < thr) : (base <= 0)
//      │  x0   = cut ? 0 : |base| << (G−4)          (W+1 bits, <= 2^W)
//   ┌──▼──────────┐
//   │ S1  x0  tag │
//   └──┬──────────┘
//      │  x1 = (x0·x0) >> W   (2W+2-bit product, truncate)
//   ┌──▼──────────┐
//   │ S2  x1  tag │   S3 x2, S4 x3, S5 x4: the same squaring, four in all (x^16)
//   └──┬──────────┘
//      ⋮
//   ┌──▼──────────┐
//   │ S5  x4  tag │
//   └──┬──────────┘
//      │  out = (x4 + 2^(G−1)) >> G                (round half up, F+1 bits, <= 2^F)
//   ┌──▼───────────┐
//   │ S6  out  tag │──► out_spec_o[F:0], out_tag_o, out_valid_o
//   └──────────────┘
// ============================================================================================
`default_nettype none

module sc_cs16 #(
    parameter integer FRAC   = 16,
    parameter integer GUARD  = 5,
    parameter integer CUTOFF = 0,
    parameter integer TAGW   = 8,
    // squaring form (docs/spec.md §3.4); the SQ_* parameters apply to FORM = 1 only
    parameter integer FORM     = 0,
    parameter integer SQ_REL_G = 1,
    parameter integer SQ_A1    = 0,
    parameter integer SQ_A2    = 0,
    parameter integer SQ_A3    = 0,
    parameter integer SQ_A4    = 0,
    parameter integer SQ_K1    = 99,
    parameter integer SQ_K2    = 99,
    parameter integer SQ_K3    = 99,
    parameter integer SQ_K4    = 99,
    parameter integer SQ_COMP  = 0,
    parameter integer SHARE    = 1,
    parameter integer MREG     = 0
) (
    // clk_i, rst_ni; mat_we_i, mat_n_i[10:0], mat_thr_i[FRAC:0]; in_valid_i, in_ready_o,
    // in_cos_i[FRAC+1:0], in_tag_i; out_valid_o, out_ready_i, out_spec_o[FRAC:0], out_tag_o
`include "sc_unit_ports.vh"
);

  localparam integer F = FRAC;
  localparam integer G = GUARD;
  localparam integer W = FRAC + GUARD;   // working fraction width of the squaring chain
  localparam integer BW = FRAC + 13;     // signed width of base = 2^(F+4) - n*d (|n*d| < 2^(F+11))

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (FRAC < 8 || FRAC > 24) begin : g_check_frac
      sc_cs16_error_illegal_FRAC_legal_range_is_8_to_24 u_error ();
    end
    if (GUARD < 4 || GUARD > 8) begin : g_check_guard
      sc_cs16_error_illegal_GUARD_legal_range_is_4_to_8 u_error ();
    end
    if (FRAC + GUARD > 31) begin : g_check_work
      sc_cs16_error_illegal_FRAC_plus_GUARD_must_be_at_most_31 u_error ();
    end
    if (CUTOFF != 0 && CUTOFF != 1) begin : g_check_cutoff
      sc_cs16_error_illegal_CUTOFF_0_is_theta_cr_1_is_sign_clamp u_error ();
    end
    if (TAGW < 1) begin : g_check_tagw
      sc_cs16_error_illegal_TAGW_must_be_at_least_1 u_error ();
    end
    if (SHARE < 1 || SHARE > 4) begin : g_check_share
      sc_cs16_error_illegal_SHARE_legal_range_is_1_to_4 u_error ();
    end
    if (MREG != 0 && MREG != 1) begin : g_check_mreg
      sc_cs16_error_illegal_MREG_must_be_0_or_1 u_error ();
    end
  endgenerate

  localparam [F:0]    ONE      = {1'b1, {F{1'b0}}};           // 2^F, cos θ = 1.0
  localparam [BW-1:0] BASE_ONE = {{(BW-F-5){1'b0}}, 1'b1, {(F+4){1'b0}}};  // 2^(F+4)
  localparam [W+1:0]  HALF_G   = {{(W+2-G){1'b0}}, 1'b1, {(G-1){1'b0}}};   // 2^(G-1)

  // ---------------------------------------------------------------------------- handshake
  // One global enable: every stage moves when the output stage is empty or being taken.
  // LATENCY register stages: S0..S6 in the reference form (and with MREG = 1 the five product
  // registers M1..M5), S1..S5 in FORM = 1 (no S0, no S6; with MREG = 1 S0 and M1..M5 too).
  localparam integer LATENCY = (FORM == 0) ? 7 + 5 * MREG : 5 + 6 * MREG;
  wire               adv;                  // global enable (rtl/sc_pipe_ctrl.v)
  wire [LATENCY-1:0] v_stage;              // valid bit of each stage (the shared squarers' selection)
  sc_pipe_ctrl #(.DEPTH(LATENCY), .GAP((FORM == 0) ? SHARE : 1)) u_ctrl (
      .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
      .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .en_o(adv), .valid_o(v_stage));
  wire unused_v_stage = &{1'b0, v_stage};

  // ---------------------------------------------------------------------------- material registers
  reg [10:0] mat_n_q;
  reg [F:0]  mat_thr_q;
  always @(posedge clk_i) begin
    if (mat_we_i) begin
      mat_n_q   <= mat_n_i;
      mat_thr_q <= mat_thr_i;
    end
  end

  `include "sc_util.vh"   // sc_clog2 (ceil(log2 v), sc_clog2(1) = 0), sc_bits, sc_max, sc_min
  // Columns a FORM = 1 squaring drops (docs/spec.md §3.4): those more than T = clog2(N) + keep
  // (keep = SQ_Kk of squaring k) below the stage's truncation point 2·Win - Wout, clamped to [0, shift].
  function integer drop_cols(input integer shift, input integer win, input integer wout, input integer keep);
    integer d;
    begin
      d = 2 * win - wout - (sc_clog2(win) + keep);
      if (d < 0) d = 0;
      if (d > shift) d = shift;
      drop_cols = d;
    end
  endfunction

  genvar k;

  // ---------------------------------------------------------------------------- S0: clamp
  wire        cos_neg  = in_cos_i[F+1];
  wire        cos_over = !cos_neg && (in_cos_i[F:0] > ONE);
  wire [F:0]  c_d      = cos_neg ? {(F+1){1'b0}} : (cos_over ? ONE : in_cos_i[F:0]);

  generate
    if (FORM == 0) begin : g_ref
      // Reference form: full products x·x, one truncation per squaring (the docs/spec.md §3.2 datapath).
      wire unused_form = &{1'b0, SQ_REL_G[0], SQ_A1[0], SQ_A2[0], SQ_A3[0], SQ_A4[0], SQ_K1[0], SQ_K2[0], SQ_K3[0],
                                  SQ_K4[0], SQ_COMP[0]};
      reg [F:0]      s0_c_q, s0_d_q, s0_thr_q;
      reg [10:0]     s0_n_q;
      reg [TAGW-1:0] s0_tag_q;
      always @(posedge clk_i) begin
        if (adv) begin
          s0_c_q   <= c_d;
          s0_d_q   <= ONE - c_d;
          s0_n_q   <= mat_n_q;
          s0_thr_q <= mat_thr_q;
          s0_tag_q <= in_tag_i;
        end
      end

      // ---------------------------------------------------------------------------- S1: scale, offset, cut
      // base = 2^(F+4) − n·d (signed, exact). MREG = 1: the same integer as 2^(F+4) + n·(c − 2^F), where
      // c − 2^F (in [−2^F, 0]) is c with bit F inverted read as a signed F+1-bit word: no subtractor between
      // the input and S0 (S0's d is unused) nor in front of the multiplier. n·(c − 2^F) + 2^(F+4) is a signed
      // rtl/sc_mul_reg.v with the constant as its addend (inside the tree), its register M1 between S0 and S1;
      // the cut test and the tag wait beside it.
      wire [BW-1:0]   base;                                  // two's complement, exact
      wire            base_le0;                              // base <= 0
      wire [BW-1:0]   mag;                                   // |base|
      wire [TAGW-1:0] s0_tag_m;                              // the tag beside the product
      wire            cthr_m;                                // c < thr beside the product
      if (MREG != 0) begin : g_nd_m
        wire [BW-1:0] ncd;                                   // 2^(F+4) + n·(c − 2^F) (the addend in the tree)
        sc_mul_reg #(.AW(12), .BW(F+1), .PW(BW), .SIGNED(1), .ADD(1), .CW(F+5)) u_nd (
            .clk_i(clk_i), .en_i(adv), .a_i({1'b0, s0_n_q}), .b_i({~s0_c_q[F], s0_c_q[F-1:0]}),
            .c_i(BASE_ONE[F+4:0]), .p_o(ncd));
        sc_delay #(.W(TAGW + 1), .DEPTH(1)) u_dly_m1 (
            .clk_i(clk_i), .en_i(adv), .d_i({s0_tag_q, s0_c_q < s0_thr_q}), .q_o({s0_tag_m, cthr_m}));
        assign base     = ncd;
        assign base_le0 = base[BW-1] || (base == {BW{1'b0}});
        assign mag      = base;   // S1 holds base itself, signed (below): no |base| needed
        wire unused_d = &{1'b0, s0_d_q};
      end else begin : g_nd
        wire [BW-1:0] nd = {{(BW-11){1'b0}}, s0_n_q} * {{(BW-F-1){1'b0}}, s0_d_q};  // < 2^(F+11)
        assign base     = BASE_ONE - nd;
        assign base_le0 = (nd >= BASE_ONE);
        assign mag      = base_le0 ? (nd - BASE_ONE) : base;
        assign s0_tag_m = s0_tag_q;
        assign cthr_m   = s0_c_q < s0_thr_q;
      end
      wire          cut;
      // cut decision (one test per CUTOFF form)
      if (CUTOFF == 0) begin : g_cut_theta_cr
        assign cut = cthr_m;
        wire unused_le0 = &{1'b0, base_le0};               // the sign test is the other form's cut
      end else begin : g_cut_sign_clamp
        assign cut = base_le0;
        wire unused_thr = &{1'b0, cthr_m};                 // thr and c are not needed by this form
      end
      // |base| <= 2^(F+4) for every shaded fragment (spec §3.2), so F+5 bits carry it exactly. MREG = 1:
      // S1 holds base itself, signed in F+6 bits (X1W = W+2), and the first squaring squares it
      // (base² = |base|²): no negation after the multiplier.
      localparam integer X1W = (MREG != 0) ? W + 2 : W + 1;
      wire [X1W-1:0] x0_d;
      if (MREG != 0) begin : g_x0_signed
        assign x0_d = cut ? {X1W{1'b0}} : {mag[F+5:0], {(G-4){1'b0}}};
        wire unused_mag = &{1'b0, mag[BW-1:F+6]};
      end else begin : g_x0
        assign x0_d = cut ? {X1W{1'b0}} : {mag[F+4:0], {(G-4){1'b0}}};
        wire unused_mag = &{1'b0, mag[BW-1:F+5]};
      end

      reg [X1W-1:0]  s1_x_q;
      reg [TAGW-1:0] s1_tag_q;
      always @(posedge clk_i) begin
        if (adv) begin
          s1_x_q   <= x0_d;
          s1_tag_q <= s0_tag_m;
        end
      end

      // ---------------------------------------------------------------------------- S2..S5: x <- floor(x^2 / 2^W)
      // squaring k (0..3) reads stage S(k+1); with SHARE > 1 those of SHARE consecutive stages share one
      // squarer, which takes the stage whose valid bit is set (rtl/sc_mul_pool.v); with MREG = 1 each
      // squaring is an rtl/sc_mul_reg.v whose register M(k+2) sits between S(k+1) and S(k+2), the tag beside it
      localparam integer XW = W + 1;
      localparam [63:0]  SQ_W = {32'd0, XW[7:0], XW[7:0], XW[7:0], XW[7:0]};
      reg  [W:0]      s2_x_q, s3_x_q, s4_x_q, s5_x_q;
      reg  [TAGW-1:0] s2_tag_q, s3_tag_q, s4_tag_q, s5_tag_q;
      wire [4*XW-1:0] sq_in = {s4_x_q, s3_x_q, s2_x_q, s1_x_q[W:0]};
      wire [4*2*XW-1:0] sq;   // squaring k's x·x at [2k·XW +: 2XW]
      wire [4*TAGW-1:0] tag_m;  // the tag of S(k+1) beside squaring k's product at [k·TAGW +: TAGW]
      if (MREG != 0 && SHARE > 1) begin : g_sq_ms
        // MREG at SHARE > 1: the four squarings through one rtl/sc_mul_pool.v with LAT = 1 (each instance's register
        // is M(k+2)), signed (S1's signed x, the others with a 0 on top). Squaring k reads S(k+1), pipeline stage
        // 2k+2, so squarings are two stages apart and two of them may share a squarer only when 2·|k − k'| < SHARE
        // (GAP keeps fragments SHARE stages apart, not a multiple of it): the pool is given the squarings' own index
        // k as its stage and ⌈SHARE/2⌉ as its SH, so each instance holds consecutive k within that window.
        localparam integer SHM  = (SHARE + 1) / 2;
        localparam integer XS   = XW + 1;
        localparam [63:0]  SQ_S = {32'd0, XS[7:0], XS[7:0], XS[7:0], XS[7:0]};
        wire [4*2*XS-1:0] sqs;
        sc_mul_pool #(
            .NOP(4), .SH(SHM), .ON(15), .ST({32'd0, 8'd3, 8'd2, 8'd1, 8'd0}), .AW(SQ_S), .BW(SQ_S),
            .AMX(XS), .BMX(XS), .SIGNED(1), .LAT(1)
        ) u_sq (
            .clk_i(clk_i), .en_i(adv),
            .a_i({1'b0, s4_x_q, 1'b0, s3_x_q, 1'b0, s2_x_q, s1_x_q}),
            .b_i({1'b0, s4_x_q, 1'b0, s3_x_q, 1'b0, s2_x_q, s1_x_q}),
            .sel_i({v_stage[8], v_stage[6], v_stage[4], v_stage[2]}), .p_o(sqs));
        for (k = 0; k < 4; k = k + 1) begin : g_k
          assign sq[k*2*XW +: 2*XW] = sqs[k*2*XS +: 2*XW];
        end
        wire unused_sqs = &{1'b0, sqs, sq_in, v_stage};   // the pool reads the stage registers directly
        sc_delay #(.W(4 * TAGW), .DEPTH(1)) u_dly_tag (
            .clk_i(clk_i), .en_i(adv), .d_i({s4_tag_q, s3_tag_q, s2_tag_q, s1_tag_q}), .q_o(tag_m));
      end else if (MREG != 0) begin : g_sq_m
        // squaring 0 of the signed S1 (W+2 bits; the square <= 2^(2W) fits the same 2W+2 bits), 1..3 unsigned
        sc_mul_reg #(.AW(XW + 1), .BW(XW + 1), .PW(2 * XW), .SIGNED(1)) u_sq0 (
            .clk_i(clk_i), .en_i(adv), .a_i(s1_x_q), .b_i(s1_x_q), .c_i(1'b0), .p_o(sq[0 +: 2*XW]));
        for (k = 1; k < 4; k = k + 1) begin : g_k
          sc_mul_reg #(.AW(XW), .BW(XW), .PW(2 * XW), .SIGNED(0)) u_sq (
              .clk_i(clk_i), .en_i(adv), .a_i(sq_in[k*XW +: XW]), .b_i(sq_in[k*XW +: XW]), .c_i(1'b0),
              .p_o(sq[k*2*XW +: 2*XW]));
        end
        wire unused_sq_in = &{1'b0, sq_in[XW-1:0]};   // squaring 0 reads the signed s1_x_q
        sc_delay #(.W(4 * TAGW), .DEPTH(1)) u_dly_tag (
            .clk_i(clk_i), .en_i(adv), .d_i({s4_tag_q, s3_tag_q, s2_tag_q, s1_tag_q}), .q_o(tag_m));
      end else begin : g_sq
        wire unused_s1 = &{1'b0, s1_x_q};   // (read through sq_in; X1W = W+1 here)
        sc_mul_pool #(
            .NOP(4), .SH(SHARE), .ON(15), .ST({32'd0, 8'd4, 8'd3, 8'd2, 8'd1}), .AW(SQ_W), .BW(SQ_W),
            .AMX(XW), .BMX(XW), .SIGNED(0)
        ) u_sq (
            .clk_i(clk_i), .en_i(adv), .a_i(sq_in), .b_i(sq_in), .sel_i(v_stage[4:1]), .p_o(sq));
        assign tag_m = {s4_tag_q, s3_tag_q, s2_tag_q, s1_tag_q};
      end
      wire [2*W+1:0] sq1 = sq[0*2*XW +: 2*XW];
      wire [2*W+1:0] sq2 = sq[1*2*XW +: 2*XW];
      wire [2*W+1:0] sq3 = sq[2*2*XW +: 2*XW];
      wire [2*W+1:0] sq4 = sq[3*2*XW +: 2*XW];
      // x <= 2^W, so x^2 <= 2^(2W): bit 2W+1 is always 0 and bits W-1..0 are truncated.
      wire unused_sq = &{1'b0, sq1[2*W+1], sq1[W-1:0], sq2[2*W+1], sq2[W-1:0],
                         sq3[2*W+1], sq3[W-1:0], sq4[2*W+1], sq4[W-1:0]};
      always @(posedge clk_i) begin
        if (adv) begin
          s2_x_q   <= sq1[2*W:W];
          s2_tag_q <= tag_m[0*TAGW +: TAGW];
          s3_x_q   <= sq2[2*W:W];
          s3_tag_q <= tag_m[1*TAGW +: TAGW];
          s4_x_q   <= sq3[2*W:W];
          s4_tag_q <= tag_m[2*TAGW +: TAGW];
          s5_x_q   <= sq4[2*W:W];
          s5_tag_q <= tag_m[3*TAGW +: TAGW];
        end
      end

      // ---------------------------------------------------------------------------- S6: round half up
      wire [W+1:0] rnd = {1'b0, s5_x_q} + HALF_G;          // <= 2^W + 2^(G-1)
      wire unused_rnd = &{1'b0, rnd[W+1], rnd[G-1:0]};     // result <= 2^F: bit W+1 is 0
      reg  [F:0]      s6_out_q;
      reg  [TAGW-1:0] s6_tag_q;
      always @(posedge clk_i) begin
        if (adv) begin
          s6_out_q <= rnd[W:G];
          s6_tag_q <= s5_tag_q;
        end
      end

      assign out_spec_o = s6_out_q;
      assign out_tag_o  = s6_tag_q;
    end else begin : g_form
      // FORM = 1: folded, truncated squarers (rtl/sc_square.v) with per-stage widths (docs/spec.md §3.4).
      // x_k has W_k fraction bits plus the integer bit; x_k = 1.0 only when x0 = 1.0 (c = 2^F), so each
      // squarer takes the W_(k-1) fraction bits and the integer bit is passed on (1.0^2 = 1.0).
      localparam integer WB = F + (SQ_REL_G != 0 ? G : 0);
      localparam integer W0 = F + 4;        // x0 = base, exact (F+4 fraction bits)
      localparam integer W1 = WB + SQ_A1;
      localparam integer W2 = WB + SQ_A2;
      localparam integer W3 = WB + SQ_A3;
      localparam integer W4 = WB + SQ_A4;   // stage 4 rounds to F; W4 only places its truncation
      localparam integer S1 = 2 * W0 - W1, S2 = 2 * W1 - W2, S3 = 2 * W2 - W3, S4 = 2 * W3 - F;
      localparam integer D1 = drop_cols(S1, W0, W1, SQ_K1);
      localparam integer D2 = drop_cols(S2, W1, W2, SQ_K2);
      localparam integer D3 = drop_cols(S3, W2, W3, SQ_K3);
      localparam integer D4 = drop_cols(S4, W3, W4, SQ_K4);
      if (SQ_REL_G != 0 && SQ_REL_G != 1) begin : g_check_rel
        sc_cs16_error_illegal_SQ_REL_G_must_be_0_or_1 u_error ();
      end
      if (SQ_COMP != 0 && SQ_COMP != 1) begin : g_check_comp
        sc_cs16_error_illegal_SQ_COMP_must_be_0_or_1 u_error ();
      end
      if (W1 < F || W2 < F || W3 < F || W4 < F || W1 > 40 || W2 > 40 || W3 > 40) begin : g_check_w
        sc_cs16_error_illegal_SQ_A_stage_widths_must_be_F_to_40 u_error ();
      end
      if (SQ_K1 < -8 || SQ_K1 > 99 || SQ_K2 < -8 || SQ_K2 > 99 ||
          SQ_K3 < -8 || SQ_K3 > 99 || SQ_K4 < -8 || SQ_K4 > 99) begin : g_check_keep
        sc_cs16_error_illegal_SQ_K1_to_SQ_K4_legal_range_is_minus_8_to_99 u_error ();
      end

      // Input stage. MREG = 0: no S0 register, everything from the input port and the material registers
      // straight into S1. mat_n_q/mat_thr_q are read before the accepting edge, so a fragment accepted at a
      // material-write edge uses the old material, as in the reference form. MREG = 1: S0 registers what the
      // port and the material give (the code's classes, its low F bits, the cut test against thr, n), so the
      // fragment keeps its material as well; the product n·c + k runs from S0 through M1 (rtl/sc_mul_reg.v).
      // No clamp or d = 2^F - c sits in front of the multiplier (docs/spec.md §3.4): with c < 2^F the raw
      // code's low F bits are c and
      //   base = 2^(F+4) - n·(2^F - c) = n·c + (16 - n)·2^F,
      // one product plus a per-material constant (one adder tree, no subtractor after it); a negative code
      // (c = 0: base = (16 - n)·2^F <= 0) is cut and a code >= 2^F (c = 2^F) gives x0 = 1.0 exactly.
      wire          i_neg  = in_cos_i[F+1];
      wire          i_ge1  = !i_neg && in_cos_i[F];                 // code >= 2^F: c = 2^F
      wire          i_thr_gt1 = mat_thr_q[F] && (|mat_thr_q[F-1:0]);  // thr > 2^F (not a legal thr(n))
      wire          i_cthr_lo = (CUTOFF == 0) && ({1'b0, in_cos_i[F-1:0]} < mat_thr_q);
      wire          c_neg, c_ge1, thr_gt1, cthr_lo;                 // the same, as the product's stage sees them
      wire [F-1:0]  c_lo;                                           // c when !c_neg && !c_ge1
      wire [10:0]   n_x;                                            // n of the fragment
      wire [TAGW-1:0] tag_x;                                        // its tag
      if (MREG != 0) begin : g_s0
        reg           s0_neg_q, s0_ge1_q, s0_thr_gt1_q, s0_cthr_q;
        reg [F-1:0]   s0_c_q;
        reg [10:0]    s0_n_q;
        reg [TAGW-1:0] s0_tag_q;
        always @(posedge clk_i) begin
          if (adv) begin
            s0_neg_q     <= i_neg;
            s0_ge1_q     <= i_ge1;
            s0_thr_gt1_q <= i_thr_gt1;
            s0_cthr_q    <= i_cthr_lo;
            s0_c_q       <= in_cos_i[F-1:0];
            s0_n_q       <= mat_n_q;
            s0_tag_q     <= in_tag_i;
          end
        end
        assign c_lo = s0_c_q;
        assign n_x  = s0_n_q;
        // the flags and the tag wait beside the product's register M1
        sc_delay #(.W(TAGW + 4), .DEPTH(1)) u_dly_m1 (
            .clk_i(clk_i), .en_i(adv), .d_i({s0_tag_q, s0_neg_q, s0_ge1_q, s0_thr_gt1_q, s0_cthr_q}),
            .q_o({tag_x, c_neg, c_ge1, thr_gt1, cthr_lo}));
      end else begin : g_no_s0
        assign c_neg   = i_neg;
        assign c_ge1   = i_ge1;
        assign thr_gt1 = i_thr_gt1;
        assign cthr_lo = i_cthr_lo;
        assign c_lo    = in_cos_i[F-1:0];
        assign n_x     = mat_n_q;
        assign tag_x   = in_tag_i;
      end
      wire          base_pos;                                       // base >= 0 (c < 2^F)
      wire [F+4:0]  b_lo;                                           // base mod 2^(F+5)
      if (CUTOFF == 0) begin : g_nd_mod
        // theta_cr: a shaded fragment has c >= thr(n) >= cos(6/sqrt(n))·2^F, so n·d <= 18·2^F and
        // -2^(F+1) <= base < 2^(F+4): base mod 2^(F+5) (only the low F+5 columns; of (16 - n)·2^F only
        // (16 - n) mod 32 matters) decides base > 0 exactly; a code below thr is cut whatever it gives.
        wire [4:0]   k_hi = 5'd16 - n_x[4:0];
        wire [F+4:0] bm;
        if (MREG != 0) begin : g_m
          sc_mul_reg #(.AW(11), .BW(F), .PW(F+5), .SIGNED(0), .ADD(1), .CW(F+5)) u_nd (
              .clk_i(clk_i), .en_i(adv), .a_i(n_x), .b_i(c_lo), .c_i({k_hi, {F{1'b0}}}), .p_o(bm));
        end else begin : g_c
          assign bm = n_x * c_lo + {k_hi, {F{1'b0}}};
        end
        assign base_pos = ~bm[F+4];  // base = 0 passes bm = 0 = x0 of a cut: no zero test needed
        assign b_lo     = bm;
        wire unused_n = &{1'b0, n_x[10:5]};
      end else begin : g_nd_full
        // sign_clamp: the whole signed base (|base| < 2^(F+11)).
        wire [12:0]   kh = 13'd16 - {2'b00, n_x};                    // 16 - n, two's complement
        wire [BW-1:0] kf = {kh, {F{1'b0}}};                             // BW = F + 13
        wire [BW-1:0] bf;
        if (MREG != 0) begin : g_m
          sc_mul_reg #(.AW(11), .BW(F), .PW(BW), .SIGNED(0), .ADD(1), .CW(BW)) u_nd (
              .clk_i(clk_i), .en_i(adv), .a_i(n_x), .b_i(c_lo), .c_i(kf), .p_o(bf));
        end else begin : g_c
          assign bf = {{(BW-11){1'b0}}, n_x} * {{(BW-F){1'b0}}, c_lo} + kf;
        end
        assign base_pos = ~bf[BW-1];  // base = 0: b_lo = 0, as a cut
        assign b_lo     = bf[F+4:0];
      end
      wire [F+4:0]  x0_d = c_neg ? {(F+5){1'b0}} :
                           c_ge1 ? ((CUTOFF == 0 && thr_gt1) ? {(F+5){1'b0}} : BASE_ONE[F+4:0]) :
                           ((base_pos && !cthr_lo) ? b_lo : {(F+5){1'b0}});
      wire unused_nd = &{1'b0, BASE_ONE, HALF_G, c_d};
      reg [W0:0]     s1_x_q;
      reg [TAGW-1:0] s1_tag_q;
      always @(posedge clk_i) begin
        if (adv) begin
          s1_x_q   <= x0_d;
          s1_tag_q <= tag_x;
        end
      end
      // S2..S4: x_k = x_(k-1)^2 truncated to W_k fraction bits; S5: x3^2 rounded to F bits (= output).
      // MREG = 1: each squarer holds its register inside (rtl/sc_square.v REG = 1, M2..M5), the integer bit
      // and the tag of its stage wait beside it.
      wire [W1:0] sq1;
      wire [W2:0] sq2;
      wire [W3:0] sq3;
      wire [F:0]  sq4;
      reg  [W1:0] s2_x_q;
      reg  [W2:0] s3_x_q;
      reg  [W3:0] s4_x_q;
      reg  [F:0]  s5_x_q;
      reg  [TAGW-1:0] s2_tag_q, s3_tag_q, s4_tag_q, s5_tag_q;
      sc_square #(.N(W0), .OW(W1 + 1), .SHIFT(S1), .DROP(D1), .RND(SQ_COMP), .ECOMP(SQ_COMP), .REG(MREG))
          u_sq1 (.clk_i(clk_i), .en_i(adv), .x_i(s1_x_q[W0-1:0]), .sq_o(sq1));
      sc_square #(.N(W1), .OW(W2 + 1), .SHIFT(S2), .DROP(D2), .RND(SQ_COMP), .ECOMP(SQ_COMP), .REG(MREG))
          u_sq2 (.clk_i(clk_i), .en_i(adv), .x_i(s2_x_q[W1-1:0]), .sq_o(sq2));
      sc_square #(.N(W2), .OW(W3 + 1), .SHIFT(S3), .DROP(D3), .RND(SQ_COMP), .ECOMP(SQ_COMP), .REG(MREG))
          u_sq3 (.clk_i(clk_i), .en_i(adv), .x_i(s3_x_q[W2-1:0]), .sq_o(sq3));
      sc_square #(.N(W3), .OW(F + 1), .SHIFT(S4), .DROP(D4), .RND(1), .ECOMP(SQ_COMP), .REG(MREG))
          u_sq4 (.clk_i(clk_i), .en_i(adv), .x_i(s4_x_q[W3-1:0]), .sq_o(sq4));
      wire [3:0]        ib_m;    // the integer bit of S1..S4 beside squaring 1..4
      wire [4*TAGW-1:0] tag_m;   // the tag of S1..S4 beside squaring 1..4
      sc_delay #(.W(4 * TAGW + 4), .DEPTH(MREG)) u_dly_sq (
          .clk_i(clk_i), .en_i(adv),
          .d_i({s4_tag_q, s3_tag_q, s2_tag_q, s1_tag_q, s4_x_q[W3], s3_x_q[W2], s2_x_q[W1], s1_x_q[W0]}),
          .q_o({tag_m, ib_m}));
      always @(posedge clk_i) begin
        if (adv) begin
          s2_x_q   <= {ib_m[0], {W1{1'b0}}} | sq1;
          s2_tag_q <= tag_m[0*TAGW +: TAGW];
          s3_x_q   <= {ib_m[1], {W2{1'b0}}} | sq2;
          s3_tag_q <= tag_m[1*TAGW +: TAGW];
          s4_x_q   <= {ib_m[2], {W3{1'b0}}} | sq3;
          s4_tag_q <= tag_m[2*TAGW +: TAGW];
          s5_x_q   <= {ib_m[3], {F{1'b0}}} | sq4;
          s5_tag_q <= tag_m[3*TAGW +: TAGW];
        end
      end
      // S5 is the output register (latency 5; 11 with MREG = 1).
      assign out_spec_o = s5_x_q;
      assign out_tag_o  = s5_tag_q;
    end
  endgenerate

`ifdef FORMAL
  // Material rule of docs/spec.md §4 (proved with the unit, docs/formal.md): a material register
  // loads exactly at an edge with mat_we_i high (in reset too) and holds otherwise, and a fragment
  // accepted at an edge captures the material as it was before that edge (the old one at a write).
  reg f_init = 1'b0;
  always @(posedge clk_i) f_init <= 1'b1;
  always @(posedge clk_i) begin
    if (f_init) begin
      mat_load_n:   assert (mat_n_q == ($past(mat_we_i) ? $past(mat_n_i) : $past(mat_n_q)));
      mat_load_thr: assert (mat_thr_q == ($past(mat_we_i) ? $past(mat_thr_i) : $past(mat_thr_q)));
    end
  end
  generate
    if (FORM == 0) begin : g_f_ref
      always @(posedge clk_i) begin
        if (f_init && $past(adv)) begin
          mat_old_n:   assert (g_ref.s0_n_q == $past(mat_n_q));
          mat_old_thr: assert (g_ref.s0_thr_q == $past(mat_thr_q));
        end
      end
    end
  endgenerate
`endif

endmodule

`default_nettype wire
