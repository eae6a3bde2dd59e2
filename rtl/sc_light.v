// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_light.v
// Purpose  : lighting core — OpenGL 1.x fixed-function lighting per fragment, division-free, bit
//            for bit as the C model LightCore::eval() (cmodel/include/shadecore/light.hpp, which is
//            the specification; signal names as LightTrace):
//
//   colour_c = min(1, e_c + a_c·A_c + Σ_j att_j·(a_c·Ia_jc + max(N̂·L_j, 0)·d_c·Id_jc + f_j·s_c·Is_jc·spec(x_j, n)))
//
//            Every feature is an elaboration-time parameter; a feature that is off instantiates no
//            hardware (no sc_normalize for directional lights or without GL_NORMALIZE, no sc_recip
//            without point_att, no specular units without SPECULAR, no V̂ normaliser without
//            LOCAL_VIEWER, no registers or datapath for channels 1..2 with CHANNELS = 1, ...).
//
// Parameters (exactly FeatureSet::verilog_params(), cmodel/include/shadecore/features.hpp; illegal
// values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC          F, fraction bits of every code (1.0 = 2^F)                8 <= F <= 16 (default 16)
//   GUARD         G of the cs16 unit (checked there: 4..8)                               (default 5)
//   LIGHTS        number of lights, 1..8 (MAX_LIGHTS of sc_light_regs.vh)               (default 1)
//   LIGHT_KINDS   2 bits per light, light j at [2j+1:2j]: 0 directional, 1 point, 2 point_att
//                 (KIND_* of sc_light_regs.vh; bits of lights >= LIGHTS are ignored)  (default 0)
//   AMBIENT       0/1: emission + global ambient + per-light ambient terms            (default 1)
//   DIFFUSE       0/1: max(N̂·L, 0)·d·Id                                               (default 1)
//   SPECULAR      0/1: one rtl/sc_specular.v per light                                 (default 1)
//   VARIANT       the unit (config/configs.json "variants", sc_variants.vh)           (default 0 = cs16)
//   CUTOFF        cs16 cut-off form, 0 theta_cr / 1 sign_clamp                         (default 0)
//   NORM          0/1: sc_norm after the unit (coefficient register mat_coef); needs SPECULAR (default 0)
//   BLINN         1: x = N̂·Ĥ, Ĥ = normalise(L̂ + V̂) (Blinn-Phong); 0: x = R·V̂, R = 2(N̂·L̂)N̂ − L̂ (Phong)
//                                                                                      (default 1)
//   LOCAL_VIEWER  1: V̂ = normalise(−P); 0: V = (0, 0, 1) (only with SPECULAR)          (default 0)
//   NORMALIZE     1: N̂ = normalise(N) (GL_NORMALIZE); 0: N is used as given           (default 1)
//   CHANNELS      1 (mono: channel 0 only, out_g_o = out_b_o = 0) or 3 (RGB)           (default 3)
//   TAGW          width of the opaque fragment tag, >= 1                               (default 8)
//   At least one of AMBIENT, DIFFUSE, SPECULAR must be 1.
//
// Ports (docs/spec.md §4 convention: all flops on the rising edge of clk_i; rst_ni synchronous,
// active-low; AXI-Stream style valid/ready):
//   clk_i, rst_ni                                     clock, reset (clears every valid bit: fragments
//                                                     in flight are dropped; registers keep values)
//   reg_we_i, reg_addr_i[7:0], reg_data_i[31:0]       register write (map: config/configs.json "light",
//   reg_ready_o                                       sc_light_regs.vh); see "Registers" below
//   in_valid_i, in_ready_o                            fragment handshake
//   in_nx_i, in_ny_i, in_nz_i [F+1:0]                 normal N, signed, 1.0 = 2^F (any length)
//   in_px_i, in_py_i, in_pz_i [F+7:0]                 eye-space position P, signed, [−128, 128)
//   in_tag_i[TAGW-1:0]                                returned with the colour
//   out_valid_o, out_ready_i                          colour handshake; a held colour keeps data and tag
//   out_r_o, out_g_o, out_b_o [F:0]                   colour, unsigned, saturated to [0, 2^F]
//   out_tag_o[TAGW-1:0]
//   Unused inputs (position without point lights or local viewer, normal without diffuse and
//   specular) are marked unused.
//
// Registers : a write happens at a rising edge with reg_we_i && reg_ready_o (LightRegs::write):
//             the register takes the low bits of its width (colours F+1, kc/kl/kq F+8, position
//             F+8 two's complement, mat_n 11, mat_thr F+1, mat_coef F+8); other addresses and the
//             registers of absent features / lights are ignored. reg_ready_o = rst_ni && no fragment
//             in flight anywhere (front, units, back, output stage: a counter of accepted minus taken
//             fragments), and in_ready_o is low while reg_we_i is high (writes have priority, the
//             core drains first). So a fragment is shaded with exactly the registers written before
//             its acceptance, and the datapath reads the registers directly. Registers are not reset.
//             Register-only products (the scene term e + a·A, per light a·Ia) are recomputed into
//             registers at every edge: one edge behind a write, before any later fragment needs them.
//             The units' material ports get mat_n / mat_thr / mat_coef with mat_we_i at the write edge.
//
// Latency   : LATENCY advancing edges from the accepting edge to the edge that takes the colour, with
//             out_ready_i high throughout exactly LATENCY cycles (accepted in cycle t → out_valid_o in
//             t+LATENCY) — LightCore::latency() computes the same formula:
//               NL = 10 (sc_normalize), RL = 7 (sc_recip), NEED_N = DIFFUSE | SPECULAR,
//               LV = SPECULAR & LOCAL_VIEWER, ANY_ATT = some point_att light,
//               ANY_PL = ANY_ATT | (NEED_N & some point light)
//               T_NN = (NEED_N & NORMALIZE) ? NL : 0      N̂
//               T_V  = LV ? NL : 0                         V̂
//               T_L  = ANY_PL ? NL : 0                     L̂ of the point lights
//               T_A  = max(T_NN, T_L)                      N̂·L → diff, f at T_A+1
//               T_H  = max(T_L, T_V);  T_RV = max(T_A+2, T_V)
//               T_X  = BLINN ? T_H+NL+1 : (LV ? T_RV+1 : T_A+2)     unit input x_j
//               T_F  = max(1, NEED_N ? T_A+1 : 0, SPECULAR ? T_X : 0, ANY_ATT ? NL+3+RL : 0)
//               NB   = 3 + ANY_ATT
//               LATENCY = T_F + (SPECULAR ? L_unit : 0) + NB,  L_unit = Unit::latency(): cs16 7,
//                         cs16 forms (FORM = 1) 5, schlick_nr 10, schlick_div / schlick_iter F+4; +2 with NORM
//             Named sets (config/configs.json): full 21+9+4 = 34, diffuse 1+3 = 4,
//             gl_default 11+7+3 = 21, phong_point 20+10+4 = 34, mono_spec 12+14+3 = 29.
//             Under backpressure: without SPECULAR the core is one global-enable pipeline (exactly
//             LATENCY advancing edges). With SPECULAR the front, the units and the back are elastic
//             segments (as sc_specular with NORM = 1): while the output is held a fragment can move
//             up to the units' output stage, so it takes LATENCY_MIN = NB+1 .. LATENCY advancing
//             edges (LightCore::latency_min()); every advancing edge advances every segment, so never
//             more than LATENCY.
// Throughput: one fragment per clock (all lights in parallel) while out_ready_i is high, except
//             VARIANT = schlick_iter: one per F+4 clocks — after an acceptance in_ready_o stays low for
//             F+3 front-advancing edges, so a fragment reaches the unit exactly when it is free.
// Handshake : in_ready_o = rst_ni && !reg_we_i && front enable (&& issue interval with schlick_iter);
//             the path out_ready_i → in_ready_o is combinational (as in sc_cs16).
//
// Architecture (every box a register stage):
//   front (enable adv_f = !valid(T_F) || units' in_ready; without SPECULAR adv_f = adv_b):
//     N̂        sc_normalize(N)                                   (NORMALIZE)
//     V̂        sc_normalize(−P), −P F+9 bits                       (LV)
//     per light j:
//       L̂_j    directional: the position register (a unit direction code, F+8 bits);
//               point: sc_normalize(P_j − P), P_j − P F+9 bits (also passed through, for d)
//       att_j   A1 d = max(⌊(P_j−P)·L̂ / 2^F⌋, 0) (F+9 bits); A2 dd = ⌊d²/2^F⌋, ⌊kl·d/2^F⌋;
//               A3 q = kc + ⌊kl·d/2^F⌋ + ⌊kq·dd/2^F⌋ (F+27 bits); sc_recip(q) (F+8 bits) (point_att)
//       ndl_j   ⌊N̂·L̂ / 2^F⌋ → diff_j = clamp(ndl, 0, 2^F), f_j = ndl > 0
//       x_j     Blinn: Ĥ = sc_normalize(L̂ + V̂), x = ⌊N̂·Ĥ / 2^F⌋; Phong: R = ⌊ndl·N̂ / 2^(F−1)⌋ − L̂,
//               x = ⌊R·V̂ / 2^F⌋ (= R_z without local viewer); saturated to the unit's F+2-bit word
//     everything is delayed (sc_delay) to T_F
//   units: one sc_specular per light (VARIANT, FRAC, GUARD, CUTOFF, NORM; COEFW = F+8), in
//     lock-step (same in_valid, same out_ready: identical handshake state; unit 0's is used); the
//     sideband {att_j, diff_j, f_j, fragment tag (light 0)} travels in the unit's tag
//   back (enable adv_b = !out_valid_o || out_ready_i), per light j and channel c:
//     B1  ⌊diff·d_c / 2^F⌋, ⌊spec·s_c / 2^F⌋ (spec = 0 unless f_j)
//     B2  sum = ⌊a_c·Ia_jc / 2^F⌋ + ⌊·Id_jc / 2^F⌋ + ⌊·Is_jc / 2^F⌋
//     B3  term = ⌊att·sum / 2^F⌋ (point_att; the stage exists only with some point_att light)
//     B4  colour = min(scene + Σ_j term, 2^F)
//   Each term and the scene term are saturated to 2^F before the sum: all are >= 0 and the total is
//   clamped to 2^F, so the result is the C model's min(Σ, 2^F) exactly, with narrower adders.
// ============================================================================================
`default_nettype none

module sc_light #(
    parameter integer FRAC         = 16,
    parameter integer GUARD        = 5,
    parameter integer LIGHTS       = 1,
    parameter integer LIGHT_KINDS  = 0,
    parameter integer AMBIENT      = 1,
    parameter integer DIFFUSE      = 1,
    parameter integer SPECULAR     = 1,
    parameter integer VARIANT      = 0,
    parameter integer CUTOFF       = 0,
    parameter integer NORM         = 0,
    parameter integer BLINN        = 1,
    parameter integer LOCAL_VIEWER = 0,
    parameter integer NORMALIZE    = 1,
    parameter integer CHANNELS     = 3,
    parameter integer TAGW         = 8
) (
    input  wire              clk_i,
    input  wire              rst_ni,
    // register write port
    input  wire              reg_we_i,
    input  wire [7:0]        reg_addr_i,
    input  wire [31:0]       reg_data_i,
    output wire              reg_ready_o,
    // fragment in
    input  wire              in_valid_i,
    output wire              in_ready_o,
    input  wire [FRAC+1:0]   in_nx_i,
    input  wire [FRAC+1:0]   in_ny_i,
    input  wire [FRAC+1:0]   in_nz_i,
    input  wire [FRAC+7:0]   in_px_i,
    input  wire [FRAC+7:0]   in_py_i,
    input  wire [FRAC+7:0]   in_pz_i,
    input  wire [TAGW-1:0]   in_tag_i,
    // colour out
    output wire              out_valid_o,
    input  wire              out_ready_i,
    output wire [FRAC:0]     out_r_o,
    output wire [FRAC:0]     out_g_o,
    output wire [FRAC:0]     out_b_o,
    output wire [TAGW-1:0]   out_tag_o
);

`include "sc_light_regs.vh"
`include "sc_variants.vh"

  // ---------------------------------------------------------------------------- constant functions
  function integer clog2(input integer x);
    integer v;
    begin
      clog2 = 0;
      v = 1;
      while (v < x) begin
        v = v * 2;
        clog2 = clog2 + 1;
      end
      if (clog2 == 0) clog2 = 1;
    end
  endfunction

  function integer imax(input integer a, input integer b);
    imax = (a > b) ? a : b;
  endfunction

  // integer address of a register (8-bit map address + offset)
  function integer reg_at(input [7:0] base, input integer off);
    reg_at = {24'd0, base} + off;
  endfunction

  // kind of light j: LIGHT_KINDS bits [2j+1:2j]
  function integer kind_of(input integer j);
    kind_of = (LIGHT_KINDS >> (2 * j)) & 3;
  endfunction

  // ---------------------------------------------------------------------------- derived parameters
  localparam integer F   = FRAC;
  localparam integer NW  = FRAC + 2;   // normal component, normalised vectors, unit input x
  localparam integer PW  = FRAC + 8;   // position component (and directional L), kc/kl/kq, coef
  localparam integer CL  = FRAC + 1;   // colour
  localparam integer NL  = 10;         // latency of rtl/sc_normalize.v
  localparam integer RL  = 7;          // latency of rtl/sc_recip.v
  // structure sizes, clamped so that an illegal LIGHTS / CHANNELS reaches its own error message
  localparam integer NLT = (LIGHTS < 1) ? 1 : ((LIGHTS > MAX_LIGHTS) ? MAX_LIGHTS : LIGHTS);
  localparam integer NCH = (CHANNELS == 1) ? 1 : 3;

  function integer count_kind(input integer k);
    integer j;
    begin
      count_kind = 0;
      for (j = 0; j < NLT; j = j + 1) begin
        if (kind_of(j) == k) count_kind = count_kind + 1;
      end
    end
  endfunction

  localparam integer NEED_N  = (DIFFUSE != 0 || SPECULAR != 0) ? 1 : 0;   // N̂·L is needed
  localparam integer LV      = (SPECULAR != 0 && LOCAL_VIEWER != 0) ? 1 : 0;
  localparam integer ANY_ATT = (count_kind(KIND_POINT_ATT) > 0) ? 1 : 0;
  // a point light whose L = normalise(P_j − P) is needed (point_att always: its distance)
  localparam integer ANY_PL  = (ANY_ATT != 0 || (NEED_N != 0 && count_kind(KIND_POINT) > 0)) ? 1 : 0;
  // front pipeline: the time (enabled edges after acceptance) at which each value is registered
  localparam integer T_NN  = (NEED_N != 0 && NORMALIZE != 0) ? NL : 0;   // N̂ (0: the input N)
  localparam integer T_V   = (LV != 0) ? NL : 0;                          // V̂ (0: constant)
  localparam integer T_L   = (ANY_PL != 0) ? NL : 0;                      // L̂ of point lights
  localparam integer T_A   = imax(T_NN, T_L);                             // N̂·L operands
  localparam integer T_H   = imax(T_L, T_V);                              // H = L + V (Blinn)
  localparam integer T_RV  = imax(T_A + 2, T_V);                          // R·V operands (Phong, local viewer)
  localparam integer T_X   = (BLINN != 0) ? T_H + NL + 1 : ((LV != 0) ? T_RV + 1 : T_A + 2);
  localparam integer T_NX  = (BLINN != 0) ? T_H + NL : T_A + 1;           // N̂ for x
  localparam integer T_ATT = NL + 3 + RL;                                 // att (point_att)
  localparam integer T_F   = imax(imax(1, (NEED_N != 0) ? T_A + 1 : 0),
                                  imax((SPECULAR != 0) ? T_X : 0, (ANY_ATT != 0) ? T_ATT : 0));
  localparam integer NB    = (ANY_ATT != 0) ? 4 : 3;                      // back pipeline stages
  localparam integer SPW   = (NORM != 0) ? FRAC + 8 : FRAC + 1;           // unit output width
  localparam integer SUMW  = imax(SPW + 2, FRAC + 3) + 2;                // per-light sum
  localparam integer TOTW  = FRAC + 5;                                    // <= 9 terms of <= 2^F
  localparam integer LAT_UNIT = ((VARIANT == VARIANT_CS16) ? 7 : (cs16_sq_param(VARIANT, 0) == 1) ? 5 :
                                 (VARIANT == VARIANT_SCHLICK_NR) ? 10 :
                                 (VARIANT == VARIANT_SCHLICK_DIV || VARIANT == VARIANT_SCHLICK_ITER) ? FRAC + 4 : 0)
                                + ((NORM != 0) ? 2 : 0);
  localparam integer LATENCY = T_F + ((SPECULAR != 0) ? LAT_UNIT : 0) + NB;
  localparam integer CNTW    = clog2(LATENCY + 2);                          // fragments in flight <= LATENCY
  localparam integer ITER    = (SPECULAR != 0 && VARIANT == VARIANT_SCHLICK_ITER) ? 1 : 0;
  localparam integer GAP     = FRAC + 3;                                    // schlick_iter: interval F+4, minus 1

  localparam [CL-1:0]     ONE     = {1'b1, {FRAC{1'b0}}};                 // 2^F
  localparam [NW-1:0]     X_MAX   = {2'b01, {FRAC{1'b1}}};                // 2^(F+1) − 1
  localparam [NW-1:0]     X_MIN   = {2'b10, {FRAC{1'b0}}};                // −2^(F+1)

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  // (VARIANT, CUTOFF and GUARD are checked by rtl/sc_specular.v and its unit when SPECULAR = 1.)
  genvar j, c, i;
  generate
    if (FRAC < 8 || FRAC > 16) begin : g_check_frac
      sc_light_error_illegal_FRAC_legal_range_is_8_to_16 u_error ();
    end
    if (LIGHTS < 1 || LIGHTS > MAX_LIGHTS) begin : g_check_lights
      sc_light_error_illegal_LIGHTS_legal_range_is_1_to_8 u_error ();
    end
    for (j = 0; j < NLT; j = j + 1) begin : g_check_kind
      if (kind_of(j) != KIND_DIRECTIONAL && kind_of(j) != KIND_POINT && kind_of(j) != KIND_POINT_ATT) begin : g_bad
        sc_light_error_illegal_LIGHT_KINDS_each_used_kind_is_0_1_or_2 u_error ();
      end
    end
    if (CHANNELS != 1 && CHANNELS != 3) begin : g_check_channels
      sc_light_error_illegal_CHANNELS_must_be_1_or_3 u_error ();
    end
    if (AMBIENT != 0 && AMBIENT != 1) begin : g_check_ambient
      sc_light_error_illegal_AMBIENT_must_be_0_or_1 u_error ();
    end
    if (DIFFUSE != 0 && DIFFUSE != 1) begin : g_check_diffuse
      sc_light_error_illegal_DIFFUSE_must_be_0_or_1 u_error ();
    end
    if (SPECULAR != 0 && SPECULAR != 1) begin : g_check_specular
      sc_light_error_illegal_SPECULAR_must_be_0_or_1 u_error ();
    end
    if (NORM != 0 && NORM != 1) begin : g_check_norm
      sc_light_error_illegal_NORM_must_be_0_or_1 u_error ();
    end
    if (BLINN != 0 && BLINN != 1) begin : g_check_blinn
      sc_light_error_illegal_BLINN_must_be_0_or_1 u_error ();
    end
    if (LOCAL_VIEWER != 0 && LOCAL_VIEWER != 1) begin : g_check_local_viewer
      sc_light_error_illegal_LOCAL_VIEWER_must_be_0_or_1 u_error ();
    end
    if (NORMALIZE != 0 && NORMALIZE != 1) begin : g_check_normalize
      sc_light_error_illegal_NORMALIZE_must_be_0_or_1 u_error ();
    end
    // The table units (docs/spec.md §9) need their table RAM loaded through sc_specular's tab_*_i
    // port, which the lighting core's register file does not have.
    // (sc_variants.vh's table sizes are named here so that lint does not flag them unused in this module.)
    if (SPECULAR != 0 && (VARIANT == VARIANT_TABLE256 || VARIANT == VARIANT_TABLE1024) &&
        VARIANT_TABLE256_ENTRIES + VARIANT_TABLE1024_ENTRIES > 0) begin : g_check_table
      sc_light_error_table_VARIANT_not_supported_no_table_load_port u_error ();
    end
    if (NORM != 0 && SPECULAR == 0) begin : g_check_norm_spec
      sc_light_error_illegal_NORM_needs_SPECULAR u_error ();
    end
    if (AMBIENT == 0 && DIFFUSE == 0 && SPECULAR == 0) begin : g_check_terms
      sc_light_error_illegal_no_term_enabled_AMBIENT_DIFFUSE_SPECULAR_all_0 u_error ();
    end
    if (TAGW < 1) begin : g_check_tagw
      sc_light_error_illegal_TAGW_must_be_at_least_1 u_error ();
    end
  endgenerate

  // ---------------------------------------------------------------------------- handshake
  // front: T_F stages, enable adv_f; back: NB stages, enable adv_b (the core's advancing condition)
  wire adv_f, adv_b;
  wire u_in_ready, u_out_valid;   // unit 0's handshake (the units run in lock-step)
  wire b_in_valid;                // what the back's first stage takes
  wire gap_ok;                    // schlick_iter: the issue interval has passed
  reg  [T_F-1:0] vf_q;            // front valid bits, stage k at bit k-1
  reg  [NB-1:0]  vb_q;            // back valid bits
  wire vf_last = vf_q[T_F-1];

  assign adv_b       = !vb_q[NB-1] || out_ready_i;
  assign out_valid_o = vb_q[NB-1];
  assign in_ready_o  = rst_ni && adv_f && !reg_we_i && gap_ok;
  wire   accept      = in_valid_i && in_ready_o;
  wire   take        = out_valid_o && out_ready_i;

  generate
    if (SPECULAR != 0) begin : g_hs_units
      // the front hands x_j and the sideband to the units; they hand results to the back
      assign adv_f      = !vf_last || u_in_ready;
      assign b_in_valid = u_out_valid;
    end else begin : g_hs_direct
      // no units: front and back are one global-enable pipeline
      assign adv_f      = adv_b;
      assign b_in_valid = vf_last;
      wire unused_u_hs = &{1'b0, u_in_ready, u_out_valid};
      // GUARD and CUTOFF configure the cs16 unit only; referenced so that lint of a wrapper that fixes
      // them (a handoff bundle, where sc_specular.v is absent) does not flag them as unused.
      wire unused_unit_cfg = (GUARD == 0) || (CUTOFF == 0);
    end
    if (T_F == 1) begin : g_vf_one
      always @(posedge clk_i) begin
        if (!rst_ni) vf_q <= 1'b0;
        else if (adv_f) vf_q <= accept;
      end
    end else begin : g_vf_line
      always @(posedge clk_i) begin
        if (!rst_ni) vf_q <= {T_F{1'b0}};
        else if (adv_f) vf_q <= {vf_q[T_F-2:0], accept};
      end
    end
    if (ITER != 0) begin : g_gap
      // schlick_iter takes one fragment per F+4 clocks: after an acceptance the input stays
      // closed for F+3 front-advancing edges, so fragments reach the unit exactly when it is free
      // (never blocked by it while the core advances: the latency stays fixed).
      localparam [4:0] GAP5 = GAP[4:0];
      reg [4:0] gap_q;
      always @(posedge clk_i) begin
        if (!rst_ni) gap_q <= 5'd0;
        else if (accept) gap_q <= GAP5;
        else if (adv_f && gap_q != 5'd0) gap_q <= gap_q - 5'd1;
      end
      assign gap_ok = (gap_q == 5'd0);
    end else begin : g_no_gap
      assign gap_ok = 1'b1;
    end
  endgenerate

  always @(posedge clk_i) begin
    if (!rst_ni) vb_q <= {NB{1'b0}};
    else if (adv_b) vb_q <= {vb_q[NB-2:0], b_in_valid};
  end

  // Fragments in flight (front, units, back, output stage). reg_ready_o: none, so a register
  // write cannot affect a fragment; in_ready_o is low while reg_we_i is high (the core drains).
  reg [CNTW-1:0] cnt_q;
  always @(posedge clk_i) begin
    if (!rst_ni) cnt_q <= {CNTW{1'b0}};
    else cnt_q <= cnt_q + {{(CNTW-1){1'b0}}, accept} - {{(CNTW-1){1'b0}}, take};
  end
  assign reg_ready_o = rst_ni && (cnt_q == {CNTW{1'b0}});
  wire wr = reg_we_i && reg_ready_o;

  // ---------------------------------------------------------------------------- material registers
  // (LightRegs::write: each register takes the low bits of its width; other addresses are ignored.
  // Registers of features that are off do not exist: their writes are ignored.)
  wire unused_reg_data = &{1'b0, reg_data_i};   // which bits are read depends on the features
  wire [NCH*CL-1:0] mamb_w, mdif_w, mspec_w;
  wire [NCH*CL-1:0] scene_w;   // min(e + a·A >> F, 2^F): registered from the registers above
  generate
    for (c = 0; c < NCH; c = c + 1) begin : g_mat
      localparam integer A_GA = reg_at(REG_GLOBAL_AMBIENT, c);
      localparam integer A_EM = reg_at(REG_MAT_EMISSION, c);
      localparam integer A_MA = reg_at(REG_MAT_AMBIENT, c);
      localparam integer A_MD = reg_at(REG_MAT_DIFFUSE, c);
      localparam integer A_MS = reg_at(REG_MAT_SPECULAR, c);
      if (AMBIENT != 0) begin : g_amb
        reg [CL-1:0] ga_q, em_q, mamb_q, scene_q;
        always @(posedge clk_i) begin
          if (wr && reg_addr_i == A_GA[7:0]) ga_q   <= reg_data_i[CL-1:0];
          if (wr && reg_addr_i == A_EM[7:0]) em_q   <= reg_data_i[CL-1:0];
          if (wr && reg_addr_i == A_MA[7:0]) mamb_q <= reg_data_i[CL-1:0];
        end
        // The scene term depends on registers only. It is recomputed into scene_q at every edge:
        // one edge behind a write, long before the first fragment accepted after it needs it.
        wire [2*CL-1:0] ag = {{CL{1'b0}}, mamb_q} * {{CL{1'b0}}, ga_q};
        wire [CL+1:0]   sc = {2'b00, em_q} + {1'b0, ag[2*CL-1:F]};
        wire unused_ag = &{1'b0, ag[F-1:0]};
        always @(posedge clk_i) begin
          scene_q <= (sc > {2'b00, ONE}) ? ONE : sc[CL-1:0];
        end
        assign mamb_w[c*CL +: CL]  = mamb_q;
        assign scene_w[c*CL +: CL] = scene_q;
      end else begin : g_no_amb
        assign mamb_w[c*CL +: CL]  = {CL{1'b0}};
        assign scene_w[c*CL +: CL] = {CL{1'b0}};
      end
      if (DIFFUSE != 0) begin : g_dif
        reg [CL-1:0] mdif_q;
        always @(posedge clk_i) begin
          if (wr && reg_addr_i == A_MD[7:0]) mdif_q <= reg_data_i[CL-1:0];
        end
        assign mdif_w[c*CL +: CL] = mdif_q;
      end else begin : g_no_dif
        assign mdif_w[c*CL +: CL] = {CL{1'b0}};
      end
      if (SPECULAR != 0) begin : g_spec
        reg [CL-1:0] mspec_q;
        always @(posedge clk_i) begin
          if (wr && reg_addr_i == A_MS[7:0]) mspec_q <= reg_data_i[CL-1:0];
        end
        assign mspec_w[c*CL +: CL] = mspec_q;
      end else begin : g_no_spec
        assign mspec_w[c*CL +: CL] = {CL{1'b0}};
      end
    end
  endgenerate
  generate
    if (AMBIENT == 0) begin : g_mamb_unused
      wire unused_mamb = &{1'b0, mamb_w};
    end
    if (DIFFUSE == 0) begin : g_mdif_unused
      wire unused_mdif = &{1'b0, mdif_w};
    end
    if (SPECULAR == 0) begin : g_mspec_unused
      wire unused_mspec = &{1'b0, mspec_w};
    end
  endgenerate

  // Unit material (n, thr, coef): the core's registers, and the units' own copies loaded at the
  // same edge with the same values (mat_we_i with the next register values; legal at any write,
  // since a write only happens with the core empty).
  wire              mat_we_u;
  wire [10:0]       mat_n_u;
  wire [FRAC:0]     mat_thr_u;
  wire [FRAC+7:0]   mat_coef_u;
  generate
    if (SPECULAR != 0) begin : g_unit_mat
      wire hit_n = wr && (reg_addr_i == REG_MAT_N);
      wire hit_t = wr && (reg_addr_i == REG_MAT_THR);
      reg [10:0]   mat_n_q;
      reg [FRAC:0] mat_thr_q;
      assign mat_n_u   = hit_n ? reg_data_i[10:0] : mat_n_q;
      assign mat_thr_u = hit_t ? reg_data_i[FRAC:0] : mat_thr_q;
      always @(posedge clk_i) begin
        mat_n_q   <= mat_n_u;
        mat_thr_q <= mat_thr_u;
      end
      if (NORM != 0) begin : g_coef
        wire hit_c = wr && (reg_addr_i == REG_MAT_COEF);
        reg [FRAC+7:0] mat_coef_q;
        assign mat_coef_u = hit_c ? reg_data_i[FRAC+7:0] : mat_coef_q;
        always @(posedge clk_i) begin
          mat_coef_q <= mat_coef_u;
        end
        assign mat_we_u = hit_n || hit_t || hit_c;
      end else begin : g_no_coef
        assign mat_coef_u = {(FRAC+8){1'b0}};
        assign mat_we_u   = hit_n || hit_t;
      end
    end else begin : g_no_unit_mat
      assign mat_we_u   = 1'b0;
      assign mat_n_u    = 11'd0;
      assign mat_thr_u  = {(FRAC+1){1'b0}};
      assign mat_coef_u = {(FRAC+8){1'b0}};
      wire unused_unit_mat = &{1'b0, mat_we_u, mat_n_u, mat_thr_u, mat_coef_u};
    end
  endgenerate

  // ---------------------------------------------------------------------------- front: shared operands
  wire [3*NW-1:0] n_in = {in_nz_i, in_ny_i, in_nx_i};
  wire [3*PW-1:0] p_in = {in_pz_i, in_py_i, in_px_i};

  // fragment tag through the front
  wire [TAGW-1:0] tag_f;
  sc_delay #(.W(TAGW), .DEPTH(T_F)) u_dly_tag (
      .clk_i(clk_i), .en_i(adv_f), .d_i(in_tag_i), .q_o(tag_f));

  // N̂ (GL_NORMALIZE) or N, at T_A (for N̂·L) and at T_NX (for x)
  wire [3*NW-1:0] nn_a, nn_x;
  generate
    if (NEED_N != 0) begin : g_nn
      wire [3*NW-1:0] nn0;
      if (NORMALIZE != 0) begin : g_norm_n
        wire [3*NW-1:0] n_pass_unused;
        sc_normalize #(.FRAC(FRAC), .VW(NW)) u_norm_n (
            .clk_i(clk_i), .en_i(adv_f), .v_i(n_in), .u_o(nn0), .v_o(n_pass_unused));
      end else begin : g_raw_n
        assign nn0 = n_in;
      end
      sc_delay #(.W(3*NW), .DEPTH(T_A - T_NN)) u_dly_nn_a (
          .clk_i(clk_i), .en_i(adv_f), .d_i(nn0), .q_o(nn_a));
      if (SPECULAR != 0) begin : g_nn_x
        sc_delay #(.W(3*NW), .DEPTH(T_NX - T_A)) u_dly_nn_x (
            .clk_i(clk_i), .en_i(adv_f), .d_i(nn_a), .q_o(nn_x));
      end else begin : g_no_nn_x
        assign nn_x = {3*NW{1'b0}};
        wire unused_nn_x = &{1'b0, nn_x};
      end
    end else begin : g_no_nn
      assign nn_a = {3*NW{1'b0}};
      assign nn_x = {3*NW{1'b0}};
      wire unused_n = &{1'b0, n_in, nn_a, nn_x};
    end
  endgenerate

  // V̂ = normalise(−P) (local viewer) at T_H (Blinn) or T_RV (Phong); else V = (0, 0, 1)
  wire [3*NW-1:0] v_h, v_p;
  generate
    if (LV != 0) begin : g_view
      wire [3*(PW+1)-1:0] mp;   // −P, F+9 bits per component (−(−2^(F+7)) = 2^(F+7))
      for (i = 0; i < 3; i = i + 1) begin : g_neg
        wire [PW-1:0] pc = p_in[i*PW +: PW];
        assign mp[i*(PW+1) +: PW+1] = {(PW+1){1'b0}} - {pc[PW-1], pc};
      end
      wire [3*NW-1:0]     v0;
      wire [3*(PW+1)-1:0] mp_pass_unused;
      sc_normalize #(.FRAC(FRAC), .VW(PW+1)) u_norm_v (
          .clk_i(clk_i), .en_i(adv_f), .v_i(mp), .u_o(v0), .v_o(mp_pass_unused));
      if (BLINN != 0) begin : g_v_blinn
        sc_delay #(.W(3*NW), .DEPTH(T_H - T_V)) u_dly_v (
            .clk_i(clk_i), .en_i(adv_f), .d_i(v0), .q_o(v_h));
        assign v_p = {3*NW{1'b0}};
        wire unused_v_p = &{1'b0, v_p};
      end else begin : g_v_phong
        sc_delay #(.W(3*NW), .DEPTH(T_RV - T_V)) u_dly_v (
            .clk_i(clk_i), .en_i(adv_f), .d_i(v0), .q_o(v_p));
        assign v_h = {3*NW{1'b0}};
        wire unused_v_h = &{1'b0, v_h};
      end
    end else begin : g_no_view
      assign v_h = {3*NW{1'b0}};
      assign v_p = {3*NW{1'b0}};
      wire unused_v = &{1'b0, v_h, v_p};
    end
    if (ANY_PL == 0 && LV == 0) begin : g_no_pos
      wire unused_p = &{1'b0, p_in};
    end
  endgenerate

  // ---------------------------------------------------------------------------- per light
  wire [NCH*NLT*CL-1:0] term_all;   // light j's saturated term of channel c at (c*NLT + j)*CL
  wire [NLT-1:0]        u_in_ready_all, u_out_valid_all;
  wire [TAGW-1:0]       bk_tag;     // the fragment tag as the back takes it

  generate
    for (j = 0; j < NLT; j = j + 1) begin : g_light
      localparam integer KIND   = kind_of(j);
      localparam integer IS_DIR = (KIND == KIND_DIRECTIONAL) ? 1 : 0;
      localparam integer IS_ATT = (KIND == KIND_POINT_ATT) ? 1 : 0;
      localparam integer NEED_L = (IS_DIR != 0) ? NEED_N : ((NEED_N != 0 || IS_ATT != 0) ? 1 : 0);
      localparam integer LW     = (IS_DIR != 0) ? PW : NW;     // component width of L
      localparam integer HVW    = LW + 1;                      // of H = L + V
      localparam integer NDW    = LW + 4;                      // of ⌊N̂·L / 2^F⌋
      localparam integer RVW    = NDW + 4;                     // of R = 2(N̂·L)N̂ − L
      localparam integer ABASE  = LIGHT_STRIDE * j;
      localparam integer A_POS  = reg_at(REG_LIGHT_POSITION, ABASE);
      localparam integer A_KC   = reg_at(REG_LIGHT_KC, ABASE);
      localparam integer A_KL   = reg_at(REG_LIGHT_KL, ABASE);
      localparam integer A_KQ   = reg_at(REG_LIGHT_KQ, ABASE);

      // ---------------------------------------------------------------- light registers
      wire [3*PW-1:0]    pos;
      wire [NCH*CL-1:0]  lamb_w, ldif_w, lspec_w;
      wire [NCH*(CL+1)-1:0] amb_w;   // (mat ambient · light ambient) >> F, registered like scene_w
      if (NEED_L != 0) begin : g_pos
        for (i = 0; i < 3; i = i + 1) begin : g_c
          localparam integer A = A_POS + i;
          reg [PW-1:0] pos_q;
          always @(posedge clk_i) begin
            if (wr && reg_addr_i == A[7:0]) pos_q <= reg_data_i[PW-1:0];
          end
          assign pos[i*PW +: PW] = pos_q;
        end
      end else begin : g_no_pos
        assign pos = {3*PW{1'b0}};
        wire unused_pos = &{1'b0, pos};
      end
      for (c = 0; c < NCH; c = c + 1) begin : g_col
        localparam integer A_LA = reg_at(REG_LIGHT_AMBIENT, ABASE + c);
        localparam integer A_LD = reg_at(REG_LIGHT_DIFFUSE, ABASE + c);
        localparam integer A_LS = reg_at(REG_LIGHT_SPECULAR, ABASE + c);
        if (AMBIENT != 0) begin : g_amb
          reg [CL-1:0] lamb_q;
          reg [CL:0]   amb_q;
          always @(posedge clk_i) begin
            if (wr && reg_addr_i == A_LA[7:0]) lamb_q <= reg_data_i[CL-1:0];
          end
          wire [2*CL-1:0] aa = {{CL{1'b0}}, mamb_w[c*CL +: CL]} * {{CL{1'b0}}, lamb_q};
          wire unused_aa = &{1'b0, aa[F-1:0]};
          always @(posedge clk_i) begin
            amb_q <= aa[2*CL-1:F];
          end
          assign lamb_w[c*CL +: CL]      = lamb_q;
          assign amb_w[c*(CL+1) +: CL+1] = amb_q;
        end else begin : g_no_amb
          assign lamb_w[c*CL +: CL]      = {CL{1'b0}};
          assign amb_w[c*(CL+1) +: CL+1] = {(CL+1){1'b0}};
        end
        if (DIFFUSE != 0) begin : g_dif
          reg [CL-1:0] ldif_q;
          always @(posedge clk_i) begin
            if (wr && reg_addr_i == A_LD[7:0]) ldif_q <= reg_data_i[CL-1:0];
          end
          assign ldif_w[c*CL +: CL] = ldif_q;
        end else begin : g_no_dif
          assign ldif_w[c*CL +: CL] = {CL{1'b0}};
        end
        if (SPECULAR != 0) begin : g_spec
          reg [CL-1:0] lspec_q;
          always @(posedge clk_i) begin
            if (wr && reg_addr_i == A_LS[7:0]) lspec_q <= reg_data_i[CL-1:0];
          end
          assign lspec_w[c*CL +: CL] = lspec_q;
        end else begin : g_no_spec
          assign lspec_w[c*CL +: CL] = {CL{1'b0}};
        end
      end
      wire unused_lamb = &{1'b0, lamb_w};   // read only through amb_w
      if (DIFFUSE == 0) begin : g_ldif_unused
        wire unused_ldif = &{1'b0, ldif_w};
      end
      if (SPECULAR == 0) begin : g_lspec_unused
        wire unused_lspec = &{1'b0, lspec_w};
      end

      // ---------------------------------------------------------------- L (and the distance)
      wire [3*LW-1:0]     l;      // unit direction to the light (point: at T_L; directional: the register)
      wire [3*(PW+1)-1:0] dv_d;   // P_j − P at T_L (point lights)
      if (IS_DIR != 0) begin : g_l_dir
        assign l    = pos;
        assign dv_d = {3*(PW+1){1'b0}};
        wire unused_dv = &{1'b0, dv_d};
      end else if (NEED_L != 0) begin : g_l_point
        wire [3*(PW+1)-1:0] dv;
        for (i = 0; i < 3; i = i + 1) begin : g_dv
          wire [PW-1:0] pj = pos[i*PW +: PW];
          wire [PW-1:0] pf = p_in[i*PW +: PW];
          assign dv[i*(PW+1) +: PW+1] = {pj[PW-1], pj} - {pf[PW-1], pf};
        end
        sc_normalize #(.FRAC(FRAC), .VW(PW+1)) u_norm_l (
            .clk_i(clk_i), .en_i(adv_f), .v_i(dv), .u_o(l), .v_o(dv_d));
      end else begin : g_l_none
        assign l    = {3*LW{1'b0}};
        assign dv_d = {3*(PW+1){1'b0}};
        wire unused_l = &{1'b0, l, dv_d};
      end

      // ---------------------------------------------------------------- attenuation (point_att)
      wire [FRAC+7:0] att_f;   // att at T_F
      if (IS_ATT != 0) begin : g_att
        localparam integer DW = FRAC + 9;    // distance d < 2^(F+9) (|P_j − P| < √3·2^(F+8))
        localparam integer QW = FRAC + 27;   // q = kc + kl·d + kq·d² < 2^(F+27)
        reg [PW-1:0] kc_q, kl_q, kq_q;
        always @(posedge clk_i) begin
          if (wr && reg_addr_i == A_KC[7:0]) kc_q <= reg_data_i[PW-1:0];
          if (wr && reg_addr_i == A_KL[7:0]) kl_q <= reg_data_i[PW-1:0];
          if (wr && reg_addr_i == A_KQ[7:0]) kq_q <= reg_data_i[PW-1:0];
        end
        // A1 (T_L+1): dl = ⌊(P_j − P)·L̂ / 2^F⌋, d = max(dl, 0)
        wire signed [PW+NW:0] dp0 = $signed(dv_d[0 +: PW+1]) * $signed(l[0 +: NW]);
        wire signed [PW+NW:0] dp1 = $signed(dv_d[PW+1 +: PW+1]) * $signed(l[NW +: NW]);
        wire signed [PW+NW:0] dp2 = $signed(dv_d[2*(PW+1) +: PW+1]) * $signed(l[2*NW +: NW]);
        wire [PW+NW+2:0] dsum = {{2{dp0[PW+NW]}}, dp0} + {{2{dp1[PW+NW]}}, dp1} + {{2{dp2[PW+NW]}}, dp2};
        wire [DW-1:0] d_d = dsum[PW+NW+2] ? {DW{1'b0}} : dsum[F+DW-1:F];
        wire unused_dsum = &{1'b0, dsum[PW+NW+1:F+DW], dsum[F-1:0]};
        reg [DW-1:0] a1_d_q;
        always @(posedge clk_i) begin
          if (adv_f) a1_d_q <= d_d;
        end
        // A2: dd = ⌊d² / 2^F⌋, kld = ⌊kl·d / 2^F⌋
        wire [2*DW-1:0]    dd_p  = {{DW{1'b0}}, a1_d_q} * {{DW{1'b0}}, a1_d_q};
        wire [PW+DW-1:0]   kld_p = {{DW{1'b0}}, kl_q} * {{PW{1'b0}}, a1_d_q};
        wire unused_a2 = &{1'b0, dd_p[F-1:0], kld_p[F-1:0]};
        reg [2*DW-F-1:0]   a2_dd_q;
        reg [PW+DW-F-1:0]  a2_kld_q;
        always @(posedge clk_i) begin
          if (adv_f) begin
            a2_dd_q  <= dd_p[2*DW-1:F];
            a2_kld_q <= kld_p[PW+DW-1:F];
          end
        end
        // A3: q = kc + kld + ⌊kq·dd / 2^F⌋
        localparam integer DDW = 2 * DW - F;
        wire [PW+DDW-1:0] kqdd_p = {{DDW{1'b0}}, kq_q} * {{PW{1'b0}}, a2_dd_q};
        wire unused_a3 = &{1'b0, kqdd_p[F-1:0]};
        wire [QW-1:0] q_d = {{(QW-PW){1'b0}}, kc_q} + {{(QW-(PW+DW-F)){1'b0}}, a2_kld_q}
                          + {{(QW-(PW+DDW-F)){1'b0}}, kqdd_p[PW+DDW-1:F]};
        reg [QW-1:0] a3_q_q;
        always @(posedge clk_i) begin
          if (adv_f) a3_q_q <= q_d;
        end
        // att = 1/q (T_ATT), then to T_F
        wire [FRAC+7:0] att_r;
        sc_recip #(.FRAC(FRAC), .QW(QW)) u_recip (
            .clk_i(clk_i), .en_i(adv_f), .q_i(a3_q_q), .att_o(att_r));
        sc_delay #(.W(FRAC+8), .DEPTH(T_F - T_ATT)) u_dly_att (
            .clk_i(clk_i), .en_i(adv_f), .d_i(att_r), .q_o(att_f));
      end else begin : g_no_att
        assign att_f = {(FRAC+8){1'b0}};
        wire unused_att = &{1'b0, att_f};
        if (IS_DIR == 0 && NEED_L != 0) begin : g_dv_unused
          wire unused_dv = &{1'b0, dv_d};
        end
      end

      // ---------------------------------------------------------------- N̂·L, diffuse factor, front-facing
      wire [LW+3:0]  ndl;      // ⌊N̂·L / 2^F⌋ at T_A+1
      wire [FRAC:0]  diff_f;   // clamp(ndl, 0, 2^F) at T_F
      wire           f_f;      // ndl > 0 at T_F
      if (NEED_N != 0) begin : g_ndl
        wire signed [NW+LW-1:0] np0 = $signed(nn_a[0 +: NW]) * $signed(l[0 +: LW]);
        wire signed [NW+LW-1:0] np1 = $signed(nn_a[NW +: NW]) * $signed(l[LW +: LW]);
        wire signed [NW+LW-1:0] np2 = $signed(nn_a[2*NW +: NW]) * $signed(l[2*LW +: LW]);
        wire [NW+LW+1:0] nsum = {{2{np0[NW+LW-1]}}, np0} + {{2{np1[NW+LW-1]}}, np1}
                              + {{2{np2[NW+LW-1]}}, np2};
        wire unused_nsum = &{1'b0, nsum[F-1:0]};
        reg [NDW-1:0] ndl_q;
        always @(posedge clk_i) begin
          if (adv_f) ndl_q <= nsum[NW+LW+1:F];
        end
        assign ndl = ndl_q;
        wire          neg   = ndl_q[NDW-1];
        wire          big   = !neg && (ndl_q > {{(NDW-CL){1'b0}}, ONE});
        wire [CL-1:0] diff1 = neg ? {CL{1'b0}} : (big ? ONE : ndl_q[CL-1:0]);
        wire          f1    = !neg && (ndl_q != {NDW{1'b0}});
        if (DIFFUSE != 0) begin : g_diff
          sc_delay #(.W(CL), .DEPTH(T_F - T_A - 1)) u_dly_diff (
              .clk_i(clk_i), .en_i(adv_f), .d_i(diff1), .q_o(diff_f));
        end else begin : g_no_diff
          assign diff_f = {CL{1'b0}};
          wire unused_diff = &{1'b0, diff1, diff_f};
        end
        if (SPECULAR != 0) begin : g_f
          sc_delay #(.W(1), .DEPTH(T_F - T_A - 1)) u_dly_f (
              .clk_i(clk_i), .en_i(adv_f), .d_i(f1), .q_o(f_f));
        end else begin : g_no_f
          assign f_f = 1'b0;
          wire unused_f = &{1'b0, f1, f_f, ndl};
        end
      end else begin : g_no_ndl
        assign ndl    = {NDW{1'b0}};
        assign diff_f = {CL{1'b0}};
        assign f_f    = 1'b0;
        wire unused_ndl = &{1'b0, ndl, diff_f, f_f, l};
      end

      // ---------------------------------------------------------------- x_j: the unit's input
      wire [NW-1:0] x_f;   // clamp(x, −2^(F+1), 2^(F+1) − 1) at T_F
      if (SPECULAR != 0 && BLINN != 0) begin : g_blinn
        // H = L + V at T_H (V = (0, 0, 2^F) without local viewer), Ĥ at T_H+NL
        wire [3*HVW-1:0] h;
        for (i = 0; i < 3; i = i + 1) begin : g_h
          wire [LW-1:0] lc = l[i*LW +: LW];
          wire [NW-1:0] vc;
          if (LV != 0) begin : g_lv
            assign vc = v_h[i*NW +: NW];
          end else if (i == 2) begin : g_vz
            assign vc = {1'b0, ONE};
          end else begin : g_v0
            assign vc = {NW{1'b0}};
          end
          assign h[i*HVW +: HVW] = {lc[LW-1], lc} + {{(HVW-NW){vc[NW-1]}}, vc};
        end
        wire [3*NW-1:0]  hn;
        wire [3*HVW-1:0] h_pass_unused;
        wire unused_ndl_b = &{1'b0, ndl};   // Blinn needs only diff and f of N̂·L
        sc_normalize #(.FRAC(FRAC), .VW(HVW)) u_norm_h (
            .clk_i(clk_i), .en_i(adv_f), .v_i(h), .u_o(hn), .v_o(h_pass_unused));
        // x = ⌊N̂·Ĥ / 2^F⌋ (T_X = T_H+NL+1)
        wire signed [2*NW-1:0] xp0 = $signed(nn_x[0 +: NW]) * $signed(hn[0 +: NW]);
        wire signed [2*NW-1:0] xp1 = $signed(nn_x[NW +: NW]) * $signed(hn[NW +: NW]);
        wire signed [2*NW-1:0] xp2 = $signed(nn_x[2*NW +: NW]) * $signed(hn[2*NW +: NW]);
        wire [2*NW+1:0] xsum = {{2{xp0[2*NW-1]}}, xp0} + {{2{xp1[2*NW-1]}}, xp1}
                             + {{2{xp2[2*NW-1]}}, xp2};
        localparam integer XFW = 2 * NW + 2 - FRAC;
        wire [XFW-1:0] xs = xsum[2*NW+1:F];
        wire unused_xsum = &{1'b0, xsum[F-1:0]};
        wire in_rng = (xs[XFW-1:NW-1] == {(XFW-NW+1){1'b0}}) || (xs[XFW-1:NW-1] == {(XFW-NW+1){1'b1}});
        reg [NW-1:0] x_q;
        always @(posedge clk_i) begin
          if (adv_f) x_q <= in_rng ? xs[NW-1:0] : (xs[XFW-1] ? X_MIN : X_MAX);
        end
        sc_delay #(.W(NW), .DEPTH(T_F - T_X)) u_dly_x (
            .clk_i(clk_i), .en_i(adv_f), .d_i(x_q), .q_o(x_f));
      end else if (SPECULAR != 0) begin : g_phong
        // R = ((ndl·N̂) >> (F−1)) − L at T_A+2 (L of a point light delayed to T_A+1)
        wire [3*LW-1:0] l1;
        if (IS_DIR != 0) begin : g_l1_dir
          assign l1 = l;
        end else begin : g_l1_point
          sc_delay #(.W(3*LW), .DEPTH(T_A + 1 - T_L)) u_dly_l (
              .clk_i(clk_i), .en_i(adv_f), .d_i(l), .q_o(l1));
        end
        wire [3*RVW-1:0] rv;
        for (i = 0; i < 3; i = i + 1) begin : g_r
          wire signed [NDW+NW-1:0] rp = $signed(ndl) * $signed(nn_x[i*NW +: NW]);
          wire [NDW+2:0] rs = rp[NDW+NW-1:F-1];
          wire unused_rp = &{1'b0, rp[F-2:0]};
          wire [LW-1:0] lc = l1[i*LW +: LW];
          assign rv[i*RVW +: RVW] = {{(RVW-NDW-3){rs[NDW+2]}}, rs} - {{(RVW-LW){lc[LW-1]}}, lc};
        end
        if (LV != 0) begin : g_lv
          // x = ⌊R·V̂ / 2^F⌋ at T_RV+1
          reg [3*RVW-1:0] rv_q;
          always @(posedge clk_i) begin
            if (adv_f) rv_q <= rv;
          end
          wire [3*RVW-1:0] rv_d;
          sc_delay #(.W(3*RVW), .DEPTH(T_RV - T_A - 2)) u_dly_rv (
              .clk_i(clk_i), .en_i(adv_f), .d_i(rv_q), .q_o(rv_d));
          wire signed [RVW+NW-1:0] xp0 = $signed(rv_d[0 +: RVW]) * $signed(v_p[0 +: NW]);
          wire signed [RVW+NW-1:0] xp1 = $signed(rv_d[RVW +: RVW]) * $signed(v_p[NW +: NW]);
          wire signed [RVW+NW-1:0] xp2 = $signed(rv_d[2*RVW +: RVW]) * $signed(v_p[2*NW +: NW]);
          wire [RVW+NW+1:0] xsum = {{2{xp0[RVW+NW-1]}}, xp0} + {{2{xp1[RVW+NW-1]}}, xp1}
                                 + {{2{xp2[RVW+NW-1]}}, xp2};
          localparam integer XFW = RVW + NW + 2 - FRAC;
          wire [XFW-1:0] xs = xsum[RVW+NW+1:F];
          wire unused_xsum = &{1'b0, xsum[F-1:0]};
          wire in_rng = (xs[XFW-1:NW-1] == {(XFW-NW+1){1'b0}}) || (xs[XFW-1:NW-1] == {(XFW-NW+1){1'b1}});
          reg [NW-1:0] x_q;
          always @(posedge clk_i) begin
            if (adv_f) x_q <= in_rng ? xs[NW-1:0] : (xs[XFW-1] ? X_MIN : X_MAX);
          end
          sc_delay #(.W(NW), .DEPTH(T_F - T_X)) u_dly_x (
              .clk_i(clk_i), .en_i(adv_f), .d_i(x_q), .q_o(x_f));
        end else begin : g_inf
          // V = (0, 0, 1): x = R_z exactly (T_A+2)
          wire [RVW-1:0] xs = rv[2*RVW +: RVW];
          wire unused_rxy = &{1'b0, rv[2*RVW-1:0]};
          wire in_rng = (xs[RVW-1:NW-1] == {(RVW-NW+1){1'b0}}) || (xs[RVW-1:NW-1] == {(RVW-NW+1){1'b1}});
          reg [NW-1:0] x_q;
          always @(posedge clk_i) begin
            if (adv_f) x_q <= in_rng ? xs[NW-1:0] : (xs[RVW-1] ? X_MIN : X_MAX);
          end
          sc_delay #(.W(NW), .DEPTH(T_F - T_X)) u_dly_x (
              .clk_i(clk_i), .en_i(adv_f), .d_i(x_q), .q_o(x_f));
        end
      end else begin : g_no_x
        assign x_f = {NW{1'b0}};
        wire unused_x = &{1'b0, x_f};
      end

      // ---------------------------------------------------------------- specular unit
      // Sideband in the unit's tag: {att (point_att), diff (DIFFUSE), f, fragment tag (light 0)}
      localparam integer OFF_F = (j == 0) ? TAGW : 0;
      localparam integer OFF_D = OFF_F + 1;
      localparam integer OFF_A = OFF_D + ((DIFFUSE != 0) ? CL : 0);
      localparam integer UTW   = OFF_A + ((IS_ATT != 0) ? FRAC + 8 : 0);
      wire [SPW-1:0]   bk_spec;   // what the back takes: spec (unit output), f, diff, att
      wire             bk_f;
      wire [CL-1:0]    bk_diff;
      wire [FRAC+7:0]  bk_att;
      if (SPECULAR != 0) begin : g_unit
        wire [UTW-1:0] ut_in, ut_out;
        assign ut_in[OFF_F] = f_f;
        if (j == 0) begin : g_tag_in
          assign ut_in[TAGW-1:0] = tag_f;
        end
        if (DIFFUSE != 0) begin : g_diff_in
          assign ut_in[OFF_D +: CL] = diff_f;
          assign bk_diff = ut_out[OFF_D +: CL];
        end else begin : g_no_diff_in
          assign bk_diff = {CL{1'b0}};
        end
        if (IS_ATT != 0) begin : g_att_in
          assign ut_in[OFF_A +: FRAC+8] = att_f;
          assign bk_att = ut_out[OFF_A +: FRAC+8];
        end else begin : g_no_att_in
          assign bk_att = {(FRAC+8){1'b0}};
        end
        assign bk_f = ut_out[OFF_F];
        if (j == 0) begin : g_tag_out
          assign bk_tag = ut_out[TAGW-1:0];
        end
        sc_specular #(
            .VARIANT(VARIANT),
            .FRAC   (FRAC),
            .GUARD  (GUARD),
            .CUTOFF (CUTOFF),
            .TAGW   (UTW),
            .NORM   (NORM)
        ) u_unit (
            .clk_i      (clk_i),
            .rst_ni     (rst_ni),
            .mat_we_i   (mat_we_u),
            .mat_n_i    (mat_n_u),
            .mat_thr_i  (mat_thr_u),
            .mat_coef_i (mat_coef_u),
            .tab_we_i   (1'b0),
            .tab_addr_i (10'd0),
            .tab_value_i({(FRAC+1){1'b0}}),
            .tab_delta_i({(FRAC+1){1'b0}}),
            .in_valid_i (vf_last),
            .in_ready_o (u_in_ready_all[j]),
            .in_cos_i   (x_f),
            .in_tag_i   (ut_in),
            .out_valid_o(u_out_valid_all[j]),
            .out_ready_i(adv_b),
            .out_spec_o (bk_spec),
            .out_tag_o  (ut_out)
        );
      end else begin : g_no_unit
        assign bk_spec = {SPW{1'b0}};
        assign bk_f    = 1'b0;
        assign bk_diff = diff_f;
        assign bk_att  = att_f;
        assign u_in_ready_all[j]  = 1'b0;
        assign u_out_valid_all[j] = 1'b0;
        if (j == 0) begin : g_tag_direct
          assign bk_tag = tag_f;
        end
        wire unused_front = &{1'b0, x_f, f_f, bk_spec, bk_f};
      end

      // ---------------------------------------------------------------- back: B1, B2, (B3)
      // spec only counts when N̂·L > 0
      wire [SPW-1:0] spec_e = bk_f ? bk_spec : {SPW{1'b0}};
      if (SPECULAR == 0) begin : g_spec_e_unused
        wire unused_spec_e = &{1'b0, spec_e};
      end
      if (DIFFUSE == 0) begin : g_bk_diff_unused
        wire unused_bk_diff = &{1'b0, bk_diff};
      end
      wire [FRAC+7:0] b2_att;   // att at B2 (point_att)
      if (IS_ATT != 0) begin : g_b_att
        reg [FRAC+7:0] b1_att_q, b2_att_q;
        always @(posedge clk_i) begin
          if (adv_b) begin
            b1_att_q <= bk_att;
            b2_att_q <= b1_att_q;
          end
        end
        assign b2_att = b2_att_q;
      end else begin : g_no_b_att
        assign b2_att = {(FRAC+8){1'b0}};
        wire unused_b_att = &{1'b0, bk_att, b2_att};
      end
      for (c = 0; c < NCH; c = c + 1) begin : g_bk
        // B1: pd = ⌊diff·d_c / 2^F⌋, ps = ⌊spec·s_c / 2^F⌋
        wire [CL+1:0]   td;    // ⌊pd·Id_c / 2^F⌋ (B2 input)
        wire [SPW+1:0]  ts;    // ⌊ps·Is_c / 2^F⌋
        if (DIFFUSE != 0) begin : g_d
          wire [2*CL-1:0] pd_p = {{CL{1'b0}}, bk_diff} * {{CL{1'b0}}, mdif_w[c*CL +: CL]};
          wire unused_pd = &{1'b0, pd_p[F-1:0]};
          reg  [CL:0] b1_pd_q;
          always @(posedge clk_i) begin
            if (adv_b) b1_pd_q <= pd_p[2*CL-1:F];
          end
          wire [2*CL:0] td_p = {{CL{1'b0}}, b1_pd_q} * {{(CL+1){1'b0}}, ldif_w[c*CL +: CL]};
          wire unused_td = &{1'b0, td_p[F-1:0]};
          assign td = td_p[2*CL:F];
        end else begin : g_no_d
          assign td = {(CL+2){1'b0}};
        end
        if (SPECULAR != 0) begin : g_s
          wire [SPW+CL-1:0] ps_p = {{CL{1'b0}}, spec_e} * {{SPW{1'b0}}, mspec_w[c*CL +: CL]};
          wire unused_ps = &{1'b0, ps_p[F-1:0]};
          reg  [SPW:0] b1_ps_q;
          always @(posedge clk_i) begin
            if (adv_b) b1_ps_q <= ps_p[SPW+CL-1:F];
          end
          wire [SPW+CL:0] ts_p = {{CL{1'b0}}, b1_ps_q} * {{(SPW+1){1'b0}}, lspec_w[c*CL +: CL]};
          wire unused_ts = &{1'b0, ts_p[F-1:0]};
          assign ts = ts_p[SPW+CL:F];
        end else begin : g_no_s
          assign ts = {(SPW+2){1'b0}};
        end
        // B2: sum = amb + td + ts
        wire [SUMW-1:0] sum_d = {{(SUMW-CL-1){1'b0}}, amb_w[c*(CL+1) +: CL+1]}
                              + {{(SUMW-CL-2){1'b0}}, td} + {{(SUMW-SPW-2){1'b0}}, ts};
        reg  [SUMW-1:0] b2_sum_q;
        always @(posedge clk_i) begin
          if (adv_b) b2_sum_q <= sum_d;
        end
        // term = point_att ? ⌊att·sum / 2^F⌋ : sum, saturated to 2^F (exact: every term is >= 0 and
        // the total is clamped to 2^F)
        wire [CL-1:0] term;
        if (ANY_ATT != 0) begin : g_b3
          wire [SUMW+7:0] t_d;
          if (IS_ATT != 0) begin : g_mul
            wire [SUMW+FRAC+7:0] at_p = {{SUMW{1'b0}}, b2_att} * {{(FRAC+8){1'b0}}, b2_sum_q};
            wire unused_at = &{1'b0, at_p[F-1:0]};
            assign t_d = at_p[SUMW+FRAC+7:F];
          end else begin : g_pass
            assign t_d = {8'd0, b2_sum_q};
          end
          reg [CL-1:0] b3_term_q;
          always @(posedge clk_i) begin
            if (adv_b) b3_term_q <= (t_d > {{(SUMW+7-F){1'b0}}, ONE}) ? ONE : t_d[CL-1:0];
          end
          assign term = b3_term_q;
        end else begin : g_sat
          assign term = (b2_sum_q > {{(SUMW-CL){1'b0}}, ONE}) ? ONE : b2_sum_q[CL-1:0];
        end
        assign term_all[(c*NLT + j)*CL +: CL] = term;
      end
    end
  endgenerate
  wire unused_units = &{1'b0, u_in_ready_all, u_out_valid_all};
  assign u_in_ready  = u_in_ready_all[0];
  assign u_out_valid = u_out_valid_all[0];

  // ---------------------------------------------------------------------------- back: total, clamp
  sc_delay #(.W(TAGW), .DEPTH(NB)) u_dly_btag (
      .clk_i(clk_i), .en_i(adv_b), .d_i(bk_tag), .q_o(out_tag_o));

  wire [NCH*CL-1:0] out_w;
  generate
    for (c = 0; c < NCH; c = c + 1) begin : g_total
      reg [CL-1:0]   out_q;
      reg [TOTW-1:0] tot;
      integer        k;
      always @* begin
        tot = {{(TOTW-CL){1'b0}}, scene_w[c*CL +: CL]};
        for (k = 0; k < NLT; k = k + 1) begin
          tot = tot + {{(TOTW-CL){1'b0}}, term_all[(c*NLT + k)*CL +: CL]};
        end
      end
      always @(posedge clk_i) begin
        if (adv_b) out_q <= (tot > {{(TOTW-CL){1'b0}}, ONE}) ? ONE : tot[CL-1:0];
      end
      assign out_w[c*CL +: CL] = out_q;
    end
  endgenerate

  assign out_r_o = out_w[CL-1:0];
  generate
    if (NCH == 3) begin : g_rgb
      assign out_g_o = out_w[2*CL-1:CL];
      assign out_b_o = out_w[3*CL-1:2*CL];
    end else begin : g_mono
      assign out_g_o = {CL{1'b0}};
      assign out_b_o = {CL{1'b0}};
    end
  endgenerate

endmodule

`default_nettype wire
