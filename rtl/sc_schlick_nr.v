// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_schlick_nr.v
// Purpose  : Schlick-divide specular unit, reciprocal form —
//              out ≈ 2^F · c / Dc,   Dc = n·(2^F − c) + c  (exact),
//            via a leading-zero normalisation of Dc, a 64-entry reciprocal table, two
//            Newton–Raphson iterations, one multiply and a rounding shift. Faithful: the output
//            is within 1 ulp of the exact quotient (bound 0.5 + 2^F·(ε1² + 3·2^−R) ulp,
//            0.547 at F = 16; docs/spec.md §6.4). Bit-accurate C model: schlick_nr_eval() in
//            cmodel/include/shadecore/units/schlick.hpp (same stage names as SchlickTrace).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC   F, fraction bits of cos θ and of the output     8 <= F <= 24   (default 16)
//   TAGW   width of the opaque tag that travels with each fragment, >= 1  (default 8)
//   SHARE  1..4 (the lighting core's `share`): the six products (n·d, the four Newton–Raphson products,
//          c·y2) share multipliers over SHARE consecutive stages (rtl/sc_mul_pool.v: at 4, two: one for
//          e1, y2, c·y2 and y1, one for e0 and n·d), each taking the one valid stage of its group, and a
//          fragment is accepted only SHARE stages behind the one ahead (rtl/sc_pipe_ctrl.v GAP): one
//          fragment per SHARE clocks, the same outputs and latency                  (default 1)
//   MREG   0 or 1: the pipelining parameter. 1 makes each of the six products an rtl/sc_mul_reg.v
//          (a DSP block's M register; the standard-cell flow places it between the carry-save tree and the
//          final adder), M1..M6 after S0, S3..S7, the other stage data beside it: LATENCY = 16, the same
//          outputs. Forms that leave each stage after a register its adder alone: Dc = (1 − n)·c + n·2^F
//          (1 − n from the material register; no subtractor behind the input ports), each Newton step's
//          g = 2 − e as K + (−mt)·y (K = 2^(R+1+s) + 2^s − 1 the addend, −mt carried from S3), and S9's rounding
//          "+ 1" as the last product's addend 2^(R−1+10−s) (S9 a shift only:
//          ⌊(p + 2^k) / 2^(k+1)⌋ = ((p >> k) + 1) >> 1). With SHARE > 1 the six products are not shared
//          (their addends and signs have no form in the pool; SHARE still spaces the fragments, GAP)  (default 0)
//   (no GUARD: the reciprocal carries R = F + 6 fraction bits; mat_thr_i is not used)
//
// Ports : docs/spec.md §4 (clk_i, rst_ni synchronous active-low, AXI-Stream style valid/ready).
//
// Latency   : LATENCY = 10 clock cycles for every F (stages S0..S9; 16 with MREG = 1), counted in advancing edges
//             as in rtl/sc_cs16.v (an edge advances iff !out_valid_o || out_ready_i before it).
// Throughput: one fragment per clock while out_ready_i is high.
// Handshake : in_ready_o = rst_ni && (!out_valid_o || out_ready_i); out_* hold while stalled.
// Reset     : synchronous, active-low; clears every valid bit; in_ready_o low during reset.
// Material  : mat_we_i loads mat_n_i at a rising edge; a fragment accepted at that same edge uses
//             the old n; n travels with the fragment to S1. mat_thr_i is ignored.
//
// Datapath (DB = F+11, R = F+6, P = 6 index bits, T = 10 table fraction bits):
//
//   in_cos_i ─ clamp ─► S0  c[F:0] d = 2^F − c  n
//                       │  Dc = n·d + c                                   DB bits, exact
//                       S1  Dc  c
//                       │  s = lzc(Dc) in 0..10 (Dc >= 2^F); mn = Dc << s  (leading one at DB−1)
//                       │  mt = mn[DB−1 : DB−1−R]                          R+1 bits, [1, 2), truncated
//                       S2  mt  s  c
//                       │  y0 = TABLE[mt[R−1 : R−6]]                       10 bits, T fraction bits
//                       S3  y0  mt  s  c
//                       │  e = ⌊mt·y0 / 2^T⌋;  g = 2^(R+1) − e             R+2 bits
//                       S4  g  y0  mt  s  c
//                       │  y1 = ⌊y0·g / 2^T⌋                               R+1 bits (<= 2^R + 1)
//                       S5  y1  mt  s  c
//                       │  e = ⌊mt·y1 / 2^R⌋;  g = 2^(R+1) − e             R+2 bits
//                       S6  g  y1  s  c
//                       │  y2 = ⌊y1·g / 2^R⌋                               R+1 bits
//                       S7  y2  s  c
//                       │  p = c·y2                                        2F+8 bits
//                       S8  p  s
//                       │  out = ((p >> (R+9−s)) + 1) >> 1   = round half up of p / 2^(R+10−s)
//                       S9  out ──► out_spec_o[F:0] (<= 2^F), out_tag_o, out_valid_o
//
// TABLE[i] = round(2^17 / (2^7 + 2i + 1)) (the reciprocal of the interval midpoint, T = 10
// fraction bits), 1016 .. 514; the same rule is schlick_nr_table() in the C model.
// ============================================================================================
`default_nettype none

module sc_schlick_nr #(
    parameter integer FRAC = 16,
    parameter integer TAGW = 8,
    parameter integer SHARE = 1,
    parameter integer MREG = 0
) (
    // clk_i, rst_ni; mat_we_i, mat_n_i[10:0], mat_thr_i[FRAC:0]; in_valid_i, in_ready_o,
    // in_cos_i[FRAC+1:0], in_tag_i; out_valid_o, out_ready_i, out_spec_o[FRAC:0], out_tag_o
`include "sc_unit_ports.vh"
);

  localparam integer F  = FRAC;
  localparam integer DB = FRAC + 11;   // width of Dc
  localparam integer R  = FRAC + 6;    // fraction bits of the reciprocal
  localparam integer T  = 10;          // fraction bits of the table entries
  localparam integer PW = 2 * FRAC + 8;  // width of p = c * y2
  localparam integer NS = 10 + 6 * MREG;  // register stages S0..S9 (and M1..M6) = latency
  localparam integer MTW = R + 1 + MREG;  // the mantissa word carried S3..S5: mt, or −mt (signed) with MREG = 1

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (FRAC < 8 || FRAC > 24) begin : g_check_frac
      sc_schlick_nr_error_illegal_FRAC_legal_range_is_8_to_24 u_error ();
    end
    if (TAGW < 1) begin : g_check_tagw
      sc_schlick_nr_error_illegal_TAGW_must_be_at_least_1 u_error ();
    end
    if (SHARE < 1 || SHARE > 4) begin : g_check_share
      sc_schlick_nr_error_illegal_SHARE_legal_range_is_1_to_4 u_error ();
    end
    if (MREG != 0 && MREG != 1) begin : g_check_mreg
      sc_schlick_nr_error_illegal_MREG_must_be_0_or_1 u_error ();
    end
  endgenerate

  localparam [F:0]   ONE   = {1'b1, {F{1'b0}}};          // 2^F, cos θ = 1.0
  localparam [R+1:0] TWO_R = {1'b1, {(R+1){1'b0}}};      // 2^(R+1) = 2.0 with R fraction bits

  // ---------------------------------------------------------------------------- handshake
  wire          adv;                        // global enable (rtl/sc_pipe_ctrl.v)
  wire [NS-1:0] v_stage;                    // valid bit of each stage (the shared multipliers' selection)
  sc_pipe_ctrl #(.DEPTH(NS), .GAP(SHARE)) u_ctrl (
      .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
      .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .en_o(adv), .valid_o(v_stage));
  wire unused_v_stage = &{1'b0, v_stage};

  // The tag and c travel along the pipeline.
  reg [TAGW*NS-1:0] tag_q;
  always @(posedge clk_i) begin
    if (adv) begin
      tag_q <= {tag_q[TAGW*(NS-1)-1:0], in_tag_i};
    end
  end

  // mat_n_q, the input clamp c_d (rtl/sc_schlick_front.vh)
`include "sc_schlick_front.vh"

  // ---------------------------------------------------------------------------- S0: clamp

  // MREG = 1 forms Dc = n·2^F + (1 − n)·c instead (1 − n from the material register), so no subtractor
  // follows the input ports: S0 holds the clamp only
  reg [F:0]  s0_c_q, s0_d_q;
  reg [10:0] s0_n_q;
  reg [11:0] s0_omn_q;   // 1 − n, two's complement (MREG = 1)
  always @(posedge clk_i) begin
    if (adv) begin
      s0_c_q   <= c_d;
      s0_d_q   <= ONE - c_d;
      s0_n_q   <= mat_n_q;
      s0_omn_q <= 12'd1 - {1'b0, mat_n_q};
    end
  end

  // ---------------------------------------------------------------------------- the products
  // op: 0 e1 = mt·y1 (S5), 1 y2 = g·y1 (S6), 2 p = y2·c (S7), 3 y1 = g·y0 (S4), 4 e0 = mt·y0 (S3),
  // 5 n·d (S0); each read at its stage, its product in the low bits of its slot (rtl/sc_mul_pool.v)
  localparam integer MA = R + 2;   // widest a (g)
  localparam integer MB = R + 1;   // widest b (y1)
  localparam integer MP = MA + MB;
  localparam integer R1 = R + 1, R2 = R + 2, F1 = F + 1, TT = T, NN = 11;
  wire [R:0]   s3_mt_w, s5_mt_w, s5_y1_w, s6_y1_w, s7_y2_w;   // the stage registers below
  wire [MTW-1:0] s3_mtc_w, s5_mtc_w;                         // the carried mantissa word (−mt with MREG = 1)
  wire [R+1:0] s4_g_w, s6_g_w;
  wire [T-1:0] s3_y0_w, s4_y0t_w;
  wire [F:0]   s0_d_w, s7_c_w;
  wire [10:0]  s0_n_w;
  wire [6*MA-1:0] pa;
  wire [6*MB-1:0] pb;
  wire [6*MP-1:0] pp;
  assign pa = {{(MA-F1){1'b0}}, s0_d_w, {(MA-R1){1'b0}}, s3_mt_w, s4_g_w, {(MA-R1){1'b0}}, s7_y2_w, s6_g_w,
               {(MA-R1){1'b0}}, s5_mt_w};
  assign pb = {{(MB-NN){1'b0}}, s0_n_w, {(MB-TT){1'b0}}, s3_y0_w, {(MB-TT){1'b0}}, s4_y0t_w, {(MB-F1){1'b0}}, s7_c_w,
               s6_y1_w, s5_y1_w};
  wire [R+9:0] s7_rnd_w;   // MREG = 1: 2^(R−1+10−s) (<= 2^(R+9)), S9's rounding, as the last product's addend
  generate
    if (MREG != 0) begin : g_mreg
      // One rtl/sc_mul_reg.v per op, its product in the low bits of the op's slot (as the pool's).
      // The Newton steps' g = 2^(R+1) − ⌊mt·y / 2^s⌋ (s = T, then R) is ⌊(K − mt·y) / 2^s⌋ with
      // K = 2^(R+1+s) + 2^s − 1, exactly and modulo 2^(R+2): formed as K + (−mt)·y inside the product's
      // tree (−mt carried from S3, K the addend), so the stage after the register is its adder alone;
      // slots 4 and 0 hold g·2^s + (low bits) instead of e.
      localparam integer P5 = DB, P4 = R + T + 2, P3 = R + T + 2, P0 = 2 * R + 2, P1 = 2 * R + 3;
      localparam [P4-1:0] K0 = {1'b1, {(R+1){1'b0}}, {T{1'b1}}};   // 2^(R+1+T) + 2^T − 1
      localparam [P0-1:0] K1 = {1'b1, {(R+1){1'b0}}, {R{1'b1}}};   // 2^(2R+1) + 2^R − 1
      localparam integer F2 = F + 2, T1 = T + 1;
      wire [P5-1:0] m5;
      wire [P4-1:0] m4;
      wire [P3-1:0] m3;
      wire [P0-1:0] m0;
      wire [P1-1:0] m1;
      wire [PW-1:0] m2;
      sc_mul_reg #(.AW(F2), .BW(12), .PW(P5), .SIGNED(1), .ADD(1), .CW(DB)) u_m1 (   // (1 − n)·c + n·2^F
          .clk_i(clk_i), .en_i(adv), .a_i({1'b0, s0_c_q}), .b_i(s0_omn_q),
          .c_i({s0_n_w, {F{1'b0}}}), .p_o(m5));   // DB = F + 11 bits
      sc_mul_reg #(.AW(MTW), .BW(T1), .PW(P4), .SIGNED(1), .ADD(1), .CW(P4)) u_m2 (   // K0 − mt·y0
          .clk_i(clk_i), .en_i(adv), .a_i(s3_mtc_w), .b_i({1'b0, s3_y0_w}), .c_i(K0), .p_o(m4));
      sc_mul_reg #(.AW(R2), .BW(TT), .PW(P3)) u_m3 (                        // y0·g
          .clk_i(clk_i), .en_i(adv), .a_i(s4_g_w), .b_i(s4_y0t_w), .c_i(1'b0), .p_o(m3));
      sc_mul_reg #(.AW(MTW), .BW(R2), .PW(P0), .SIGNED(1), .ADD(1), .CW(P0)) u_m4 (   // K1 − mt·y1
          .clk_i(clk_i), .en_i(adv), .a_i(s5_mtc_w), .b_i({1'b0, s5_y1_w}), .c_i(K1), .p_o(m0));
      sc_mul_reg #(.AW(R2), .BW(R1), .PW(P1)) u_m5 (                        // y1·g
          .clk_i(clk_i), .en_i(adv), .a_i(s6_g_w), .b_i(s6_y1_w), .c_i(1'b0), .p_o(m1));
      sc_mul_reg #(.AW(R1), .BW(F1), .PW(PW), .ADD(1), .CW(R + 10)) u_m6 (   // c·y2 + 2^(R−1+10−s)
          .clk_i(clk_i), .en_i(adv), .a_i(s7_y2_w), .b_i(s7_c_w), .c_i(s7_rnd_w), .p_o(m2));
      assign pp = {{(MP-P5){1'b0}}, m5, {(MP-P4){1'b0}}, m4, {(MP-P3){1'b0}}, m3, {(MP-PW){1'b0}}, m2,
                   {(MP-P1){1'b0}}, m1, {(MP-P0){1'b0}}, m0};
      wire unused_pool = &{1'b0, pa, pb, v_stage, s0_d_w};
    end else begin : g_pool
      sc_mul_pool #(
          .NOP(6), .SH(SHARE), .ON(63),
          .ST({16'd0, 8'd0, 8'd3, 8'd4, 8'd7, 8'd6, 8'd5}),
          .AW({16'd0, F1[7:0], R1[7:0], R2[7:0], R1[7:0], R2[7:0], R1[7:0]}),
          .BW({16'd0, NN[7:0], TT[7:0], TT[7:0], F1[7:0], R1[7:0], R1[7:0]}),
          .AMX(MA), .BMX(MB), .SIGNED(0)
      ) u_mul (
          .clk_i(clk_i), .en_i(adv), .a_i(pa), .b_i(pb),
          .sel_i({v_stage[0], v_stage[3], v_stage[4], v_stage[7], v_stage[6], v_stage[5]}), .p_o(pp));
      wire unused_v_rest = &{1'b0, v_stage[9:8], v_stage[2:1], s7_rnd_w, s0_omn_q, s3_mtc_w, s5_mtc_w};
    end
  endgenerate
  wire unused_pp = &{1'b0, pp};   // each op reads the low bits of its slot

  // ---------------------------------------------------------------------------- S1: denominator
  // (MREG = 1: c is the product's addend, and c waits beside M1)
  wire [DB-1:0] den_d = (MREG != 0) ? pp[5*MP +: DB]
                                    : pp[5*MP +: DB] + {{(DB-F-1){1'b0}}, s0_c_q};   // n·d + c < 2^(F+11)
  wire [F:0]    s0_c_x;
  sc_delay #(.W(F + 1), .DEPTH(MREG)) u_dly_m1 (.clk_i(clk_i), .en_i(adv), .d_i(s0_c_q), .q_o(s0_c_x));
  reg [DB-1:0] s1_den_q;
  reg [F:0]    s1_c_q;
  always @(posedge clk_i) begin
    if (adv) begin
      s1_den_q <= den_d;
      s1_c_q   <= s0_c_x;
    end
  end

  // ---------------------------------------------------------------------------- S2: normalise
  // Dc >= 2^F, so its leading one is in bits F..F+10 and s = 10 - (its position - F).
  reg [3:0] lzc_d;
  integer   i;
  always @* begin
    lzc_d = 4'd10;
    for (i = 0; i <= 10; i = i + 1) begin
      if (s1_den_q[F+i]) lzc_d = 4'd10 - i[3:0];
    end
  end
  wire [DB-1:0] mn_d = s1_den_q << lzc_d;
  wire unused_mn = &{1'b0, mn_d[DB-R-2:0], s1_den_q[F-1:0]};  // truncated to R fraction bits

  reg [R:0]  s2_mt_q;
  reg [3:0]  s2_s_q;
  reg [F:0]  s2_c_q;
  always @(posedge clk_i) begin
    if (adv) begin
      s2_mt_q <= mn_d[DB-1:DB-1-R];
      s2_s_q  <= lzc_d;
      s2_c_q  <= s1_c_q;
    end
  end

  // ---------------------------------------------------------------------------- S3: table
  reg [T-1:0] y0_d;
  always @* begin
    case (s2_mt_q[R-1:R-6])
      6'd0 : y0_d = 10'd1016;
      6'd1 : y0_d = 10'd1001;
      6'd2 : y0_d = 10'd986;
      6'd3 : y0_d = 10'd971;
      6'd4 : y0_d = 10'd957;
      6'd5 : y0_d = 10'd943;
      6'd6 : y0_d = 10'd930;
      6'd7 : y0_d = 10'd917;
      6'd8 : y0_d = 10'd904;
      6'd9 : y0_d = 10'd892;
      6'd10: y0_d = 10'd880;
      6'd11: y0_d = 10'd868;
      6'd12: y0_d = 10'd857;
      6'd13: y0_d = 10'd846;
      6'd14: y0_d = 10'd835;
      6'd15: y0_d = 10'd824;
      6'd16: y0_d = 10'd814;
      6'd17: y0_d = 10'd804;
      6'd18: y0_d = 10'd794;
      6'd19: y0_d = 10'd785;
      6'd20: y0_d = 10'd776;
      6'd21: y0_d = 10'd767;
      6'd22: y0_d = 10'd758;
      6'd23: y0_d = 10'd749;
      6'd24: y0_d = 10'd741;
      6'd25: y0_d = 10'd732;
      6'd26: y0_d = 10'd724;
      6'd27: y0_d = 10'd716;
      6'd28: y0_d = 10'd708;
      6'd29: y0_d = 10'd701;
      6'd30: y0_d = 10'd694;
      6'd31: y0_d = 10'd686;
      6'd32: y0_d = 10'd679;
      6'd33: y0_d = 10'd672;
      6'd34: y0_d = 10'd665;
      6'd35: y0_d = 10'd659;
      6'd36: y0_d = 10'd652;
      6'd37: y0_d = 10'd646;
      6'd38: y0_d = 10'd639;
      6'd39: y0_d = 10'd633;
      6'd40: y0_d = 10'd627;
      6'd41: y0_d = 10'd621;
      6'd42: y0_d = 10'd615;
      6'd43: y0_d = 10'd610;
      6'd44: y0_d = 10'd604;
      6'd45: y0_d = 10'd599;
      6'd46: y0_d = 10'd593;
      6'd47: y0_d = 10'd588;
      6'd48: y0_d = 10'd583;
      6'd49: y0_d = 10'd577;
      6'd50: y0_d = 10'd572;
      6'd51: y0_d = 10'd567;
      6'd52: y0_d = 10'd563;
      6'd53: y0_d = 10'd558;
      6'd54: y0_d = 10'd553;
      6'd55: y0_d = 10'd548;
      6'd56: y0_d = 10'd544;
      6'd57: y0_d = 10'd539;
      6'd58: y0_d = 10'd535;
      6'd59: y0_d = 10'd531;
      6'd60: y0_d = 10'd526;
      6'd61: y0_d = 10'd522;
      6'd62: y0_d = 10'd518;
      6'd63: y0_d = 10'd514;
      default: y0_d = 10'd0;
    endcase
  end
  wire [MTW-1:0] mtc_d;   // mt, or −mt with MREG = 1 (R+2 bits, signed: −2^(R+1) < −mt <= −2^R)
  generate
    if (MREG != 0) begin : g_neg_mt
      assign mtc_d = ~{1'b0, s2_mt_q} + 1'b1;
    end else begin : g_mt
      assign mtc_d = s2_mt_q;
    end
  endgenerate
  reg [T-1:0]   s3_y0_q;
  reg [MTW-1:0] s3_mt_q;
  reg [3:0]     s3_s_q;
  reg [F:0]     s3_c_q;
  always @(posedge clk_i) begin
    if (adv) begin
      s3_y0_q <= y0_d;
      s3_mt_q <= mtc_d;
      s3_s_q  <= s2_s_q;
      s3_c_q  <= s2_c_q;
    end
  end

  // ---------------------------------------------------------------------------- S4/S5: first iteration
  wire [R+T+1:0] e0_p = pp[4*MP +: R+T+2];              // mt·y0 < 2^(R+1+T) (MREG = 1: (K0 − mt·y0))
  wire [R+1:0]   g0_d = (MREG != 0) ? e0_p[R+T+1:T]       // 2 − e, e < 2
                                    : TWO_R - {1'b0, e0_p[R+T:T]};
  wire unused_e0 = &{1'b0, e0_p[T-1:0]};
  reg  [R+1:0]   s4_g_q;
  reg  [T-1:0]   s4_y0_q;
  reg  [MTW-1:0] s4_mt_q;
  reg  [3:0]     s4_s_q;
  reg  [F:0]     s4_c_q;
  wire [T-1:0]   s3_y0_x;   // S3's data beside M2 (MREG = 1), or S3's own
  wire [MTW-1:0] s3_mt_x;
  wire [3:0]     s3_s_x;
  wire [F:0]     s3_c_x;
  sc_delay #(.W(T + MTW + 4 + F + 1), .DEPTH(MREG)) u_dly_m2 (.clk_i(clk_i), .en_i(adv),
      .d_i({s3_y0_q, s3_mt_q, s3_s_q, s3_c_q}), .q_o({s3_y0_x, s3_mt_x, s3_s_x, s3_c_x}));
  always @(posedge clk_i) begin
    if (adv) begin
      s4_g_q  <= g0_d;
      s4_y0_q <= s3_y0_x;
      s4_mt_q <= s3_mt_x;
      s4_s_q  <= s3_s_x;
      s4_c_q  <= s3_c_x;
    end
  end

  wire [R+T+1:0] y1_p = pp[3*MP +: R+T+2];              // y0·g; y1 = ⌊y0·g / 2^T⌋ <= 2^R + 1
  wire unused_y1 = &{1'b0, y1_p[R+T+1], y1_p[T-1:0]};
  reg  [R:0]     s5_y1_q;
  reg  [MTW-1:0] s5_mt_q;
  reg  [3:0]     s5_s_q;
  reg  [F:0]     s5_c_q;
  wire [MTW-1:0] s4_mt_x;   // S4's data beside M3
  wire [3:0]     s4_s_x;
  wire [F:0]     s4_c_x;
  sc_delay #(.W(MTW + 4 + F + 1), .DEPTH(MREG)) u_dly_m3 (.clk_i(clk_i), .en_i(adv),
      .d_i({s4_mt_q, s4_s_q, s4_c_q}), .q_o({s4_mt_x, s4_s_x, s4_c_x}));
  always @(posedge clk_i) begin
    if (adv) begin
      s5_y1_q <= y1_p[R+T:T];
      s5_mt_q <= s4_mt_x;
      s5_s_q  <= s4_s_x;
      s5_c_q  <= s4_c_x;
    end
  end

  // ---------------------------------------------------------------------------- S6/S7: second iteration
  wire [2*R+1:0] e1_p = pp[0*MP +: 2*R+2];              // mt·y1 < 2^(2R+2)
  wire [R+1:0]   g1_d = (MREG != 0) ? e1_p[2*R+1:R] : TWO_R - e1_p[2*R+1:R];   // MREG = 1: (K1 − mt·y1)
  wire unused_e1 = &{1'b0, e1_p[R-1:0]};
  reg  [R+1:0]   s6_g_q;
  reg  [R:0]     s6_y1_q;
  reg  [3:0]     s6_s_q;
  reg  [F:0]     s6_c_q;
  wire [R:0]     s5_y1_x;   // S5's data beside M4
  wire [3:0]     s5_s_x;
  wire [F:0]     s5_c_x;
  sc_delay #(.W(R + 1 + 4 + F + 1), .DEPTH(MREG)) u_dly_m4 (.clk_i(clk_i), .en_i(adv),
      .d_i({s5_y1_q, s5_s_q, s5_c_q}), .q_o({s5_y1_x, s5_s_x, s5_c_x}));
  always @(posedge clk_i) begin
    if (adv) begin
      s6_g_q  <= g1_d;
      s6_y1_q <= s5_y1_x;
      s6_s_q  <= s5_s_x;
      s6_c_q  <= s5_c_x;
    end
  end

  wire [2*R+2:0] y2_p = pp[1*MP +: 2*R+3];              // y1·g; y2 = ⌊y1·g / 2^R⌋ <= 2^R + 1
  wire unused_y2 = &{1'b0, y2_p[2*R+2:2*R+1], y2_p[R-1:0]};
  reg  [R:0]     s7_y2_q;
  reg  [3:0]     s7_s_q;
  reg  [F:0]     s7_c_q;
  wire [3:0]     s6_s_x;   // S6's data beside M5
  wire [F:0]     s6_c_x;
  sc_delay #(.W(4 + F + 1), .DEPTH(MREG)) u_dly_m5 (.clk_i(clk_i), .en_i(adv),
      .d_i({s6_s_q, s6_c_q}), .q_o({s6_s_x, s6_c_x}));
  always @(posedge clk_i) begin
    if (adv) begin
      s7_y2_q <= y2_p[2*R:R];
      s7_s_q  <= s6_s_x;
      s7_c_q  <= s6_c_x;
    end
  end
  // MREG = 1: S9's rounding bit, 2^(R−1+rsh) with rsh = 10 − s, added inside the last product
  wire [3:0] s7_rsh = 4'd10 - s7_s_q;   // 0..10
  assign s7_rnd_w = {{(R+9){1'b0}}, 1'b1} << ((R - 1) + {28'd0, s7_rsh});

  // ---------------------------------------------------------------------------- S8: multiply
  reg [PW-1:0] s8_p_q;
  reg [3:0]    s8_s_q;
  wire [3:0]   s7_s_x;   // S7's s beside M6
  sc_delay #(.W(4), .DEPTH(MREG)) u_dly_m6 (.clk_i(clk_i), .en_i(adv), .d_i(s7_s_q), .q_o(s7_s_x));
  always @(posedge clk_i) begin
    if (adv) begin
      s8_p_q <= pp[2*MP +: PW];   // c·y2 (MREG = 1: + 2^(R−1+rsh))
      s8_s_q <= s7_s_x;
    end
  end

  // ---------------------------------------------------------------------------- S9: round half up
  // p / 2^(R+10−s): keep one bit more (shift by R+9−s = (R−1) + (10−s)), add 1, drop it.
  wire [PW-R:0]  p_hi  = s8_p_q[PW-1:R-1];
  wire [3:0]     rsh   = 4'd10 - s8_s_q;                 // 0..10
  wire [PW-R:0]  p_sh  = p_hi >> rsh;
  wire [PW-R+1:0] rnd  = {1'b0, p_sh} + {{(PW-R+1){1'b0}}, (MREG != 0) ? 1'b0 : 1'b1};   // rounded already
  wire unused_rnd = &{1'b0, s8_p_q[R-2:0], rnd[PW-R+1:F+2], rnd[0]};  // result <= 2^F
  reg  [F:0]     s9_out_q;
  always @(posedge clk_i) begin
    if (adv) begin
      s9_out_q <= rnd[F+1:1];
    end
  end

  // the pool's operands (declared before the registers they read)
  assign s0_d_w   = s0_d_q;
  assign s0_n_w   = s0_n_q;
  assign s3_mtc_w = s3_mt_q;
  assign s3_mt_w  = s3_mt_q[R:0];
  assign s3_y0_w  = s3_y0_q;
  assign s4_g_w   = s4_g_q;
  assign s4_y0t_w = s4_y0_q;
  assign s5_mtc_w = s5_mt_q;
  assign s5_mt_w  = s5_mt_q[R:0];
  assign s5_y1_w  = s5_y1_q;
  assign s6_g_w   = s6_g_q;
  assign s6_y1_w  = s6_y1_q;
  assign s7_y2_w  = s7_y2_q;
  assign s7_c_w   = s7_c_q;

  assign out_spec_o = s9_out_q;
  assign out_tag_o  = tag_q[TAGW*NS-1:TAGW*(NS-1)];

`ifdef FORMAL
  // Material rule of docs/spec.md §4 (rtl/sc_formal_material.vh): a fragment captures n at an advancing edge.
  wire        f_capture    = adv;
  wire [10:0] f_captured_n = s0_n_q;
`include "sc_formal_material.vh"
`endif

endmodule

`default_nettype wire
