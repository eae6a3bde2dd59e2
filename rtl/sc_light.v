// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_light.v
// Purpose  : lighting core — OpenGL 1.x fixed-function lighting per fragment, division-free,
//            programmable and time-multiplexed, bit for bit as the C model LightCore::eval()
//            (cmodel/include/shadecore/light.hpp, which is the specification):
//
//   colour_c = min(1, e_c + a_c·A_c + Σ_{j on} att_j·(a_c·Ia_jc + max(N̂·L_j, 0)·d_c·Id_jc + f_j·s_c·Is_jc·spec(x_j, n)))
//
//            Capabilities are elaboration-time parameters (what hardware exists; an absent one
//            instantiates nothing); the register file chooses among them at run time: per light
//            enable and kind, local viewer, reflection, normalize, the material's unit.
//            Parts: rtl/sc_light_regfile.v (registers, mode decode), rtl/sc_light_lane.v (a lane's
//            front: L̂, attenuation, N̂·L, x), the specular units (rtl/sc_specular.v, one per unit
//            and lane), rtl/sc_light_shade.v (a lane's colour products); this file: handshake, the
//            pass scheduler, N̂ and V̂ (shared by the lanes) and the accumulator.
//
// Parameters (exactly FeatureSet::verilog_params(), cmodel/include/shadecore/features.hpp; illegal
// values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC          F, fraction bits of every code (1.0 = 2^F)                8 <= F <= 16 (default 16)
//   GUARD         G of the cs16 unit (checked there: 4..8)                               (default 5)
//   SGUARD        extra fraction bits of the specular path: N̂, V̂, L̂, Ĥ, N̂·L, R, x and the
//                 units run at VF = F + SGUARD (mat_thr, mat_coef in the units' format), 0..8,
//                 F + SGUARD <= 24 (feature-set key spec_guard)                          (default 0)
//   LIGHTS        light slots, 1..8 (MAX_LIGHTS of sc_light_regs.vh)                    (default 1)
//   SLOT_KINDS    3 bits per slot, slot j at [3j+2:3j]: bit k = the slot can take kind k
//                 (KIND_* of sc_light_regs.vh: 0 directional, 1 point, 2 point_att)   (default 1)
//   SLOT_SPOT     bit j = slot j can be spot (KIND_SPOT = 3: point_att times GL's spot factor,
//                 the spot registers and the lane's spot path exist)                   (default 0)
//   LANES         per-light datapaths, 1..LIGHTS: k enabled lights take ⌈k/LANES⌉ passes (default 1)
//   SHARE         clocks per pass, 1..4 (feature-set key share): passes issue only every SHARE-th
//                 front-advancing edge (a phase counter), and the vector normalisations of a pass
//                 (N̂, V̂, L̂, Ĥ, those that exist) share ⌈ops/SHARE⌉ sc_normalize instances, op k
//                 entering instance ⌊k/SHARE⌋ at a stage ≡ k (mod SHARE). SHARE > 1 needs LANES = 1
//                 (default 1)
//   AMBIENT       0/1: emission + global ambient + per-light ambient terms            (default 1)
//   DIFFUSE       0/1: max(N̂·L, 0)·d·Id                                               (default 1)
//   UNITS         bit v = the specular unit with variant id v (config/configs.json "variants",
//                 sc_variants.vh); 0 = no specular term. The table units are not supported;
//                 schlick_iter only alone                                                (default 1)
//   CUTOFF        cs16 cut-off form, 0 theta_cr / 1 sign_clamp                         (default 0)
//   ENERGY        0/1: sc_energy after each unit (coefficient register mat_coef)       (default 0)
//   BLINN, PHONG  0/1 each, at least one with a unit: x = N̂·Ĥ, Ĥ = normalise(L̂ + V̂) / x = R·V̂,
//                 R = 2(N̂·L̂)N̂ − L̂ exist                                              (default 1, 0)
//   LOCAL_VIEWER  0/1: V̂ = normalise(−P) exists (V = (0, 0, 1) always does)          (default 0)
//   NORMALIZE     0/1: N̂ = normalise(N) exists (GL_NORMALIZE; N as given always does) (default 1)
//   LOW_N         0/1: a shininess register value below 2^LOW_N_BITS (= 16, the units' smallest n;
//                 GL's 0..15) selects x^n from an exact chain (rtl/sc_powi.v) in each lane instead of
//                 the unit's value, unnormalised (feature-set key low_shininess); needs UNITS     (default 0)
//   TWO_SIDE      0/1: GL_LIGHT_MODEL_TWO_SIDE exists (feature-set key two_side): with light_model bit 3
//                 a fragment with in_back_i is lit with −N (each component negated, −(−2^(F+1))
//                 saturating to 2^(F+1)−1) and the back colour bank back_mat_* (emission, ambient,
//                 diffuse, specular; the unit material n/thr/coef/unit is shared with the front) (default 0)
//   SEP_SPEC      0/1: GL_SEPARATE_SPECULAR_COLOR exists (feature-set key separate_specular; needs UNITS):
//                 with light_model bit 4 set each lane attenuates the ambient + diffuse and the specular
//                 sums apart and the back accumulates them apart: out_* = the primary sum, out_s* = the
//                 specular sum (each saturated); clear: as without SEP_SPEC (bit for bit), out_s* = 0
//                                                                                         (default 0)
//   COL_MAT       0/1: GL_COLOR_MATERIAL exists (feature-set key colour_material): with the colour_material
//                 register's bit 0 the fragment's colour in_cr_i/in_cg_i/in_cb_i replaces the material
//                 colour(s) its mode names (emission, ambient, diffuse, specular, ambient and diffuse) of
//                 the bank the fragment is lit with; the colour travels with the fragment (the internal
//                 tag widens by 3·(F+1) bits) and the scene term is formed per fragment    (default 0)
//   CHANNELS      1 (mono: channel 0 only, out_g_o = out_b_o = 0) or 3 (RGB)           (default 3)
//   TAGW          width of the opaque fragment tag, >= 1                               (default 8)
//   MREG          0/1, the pipelining parameter (feature-set key mreg; every SHARE): 1 cuts every
//                 product of the vector normalisers with a register (rtl/sc_normalize.v, NL 10 -> 18), each
//                 dot product of the lanes over D = MREG_DOT cycles (rtl/sc_mul_reg.v LAT), each product stage
//                 of the back over DB = MREG_BACK more (rtl/sc_light_shade.v), registers the lanes' N (N̂ or N,
//                 MREG_N stages after the normalize-mode choice) and diff (before its clamp's output, not after),
//                 P_j − P and −P before the L and V normalisers (MREG_P), cuts the attenuation's q over MREG_ATT
//                 and sc_recip's products over MREG_RECIP more (rtl/sc_light_lane.v, rtl/sc_recip.v),
//                 cuts each stage of the spot and low-shininess power chains over MREG_POWI more
//                 (rtl/sc_powi.v), and passes MREG to the specular
//                 units (their mreg_stages); the same outputs, more latency (config/configs.json light.latency;
//                 docs/signoff.md "Fifth round"). With SHARE > 1: cs16's squarings in a pool of registered
//                 squarers (rtl/sc_mul_pool.v LAT), schlick_nr's, sc_recip's and q's products unshared with
//                 their registers, the dot products unshared (as at SHARE = 1); V and L enter the shared
//                 normalisers at E_V, E_L (below)                                        (default 0)
//   At least one of AMBIENT, DIFFUSE, UNITS must be non-zero.
//
// Ports (docs/spec.md §4 convention: all flops on the rising edge of clk_i; rst_ni synchronous,
// active-low; AXI-Stream style valid/ready):
//   clk_i, rst_ni                                     clock, reset (clears every valid bit: fragments
//                                                     in flight are dropped; registers keep values)
//   reg_we_i, reg_addr_i[8:0], reg_data_i[31:0]       register write (map: config/configs.json "light",
//   reg_ready_o                                       sc_light_regs.vh); see "Registers" below
//   in_valid_i, in_ready_o                            fragment handshake
//   in_nx_i, in_ny_i, in_nz_i [F+1:0]                 normal N, signed, 1.0 = 2^F (any length)
//   in_px_i, in_py_i, in_pz_i [F+7:0]                 eye-space position P, signed, [−128, 128)
//   in_tag_i[TAGW-1:0]                                returned with the colour
//   in_back_i                                         the fragment's polygon faces away (window-space winding,
//                                                     glFrontFace CCW); used only by TWO_SIDE's two-sided mode
//   in_cr_i, in_cg_i, in_cb_i [F:0]                   the fragment's colour, a material colour code (1.0 =
//                                                     2^F, [0, 2)); used only by COL_MAT's colour material
//   out_valid_o, out_ready_i                          colour handshake; a held colour keeps data and tag
//   out_r_o, out_g_o, out_b_o [F:0]                   colour, unsigned, saturated to [0, 2^F]
//   out_sr_o, out_sg_o, out_sb_o [F:0]                secondary colour (SEP_SPEC, separate mode: the specular
//                                                     sum, saturated; else 0); GL's colour sum is
//                                                     min(2^F, out + out_s), formed by the renderer
//   out_tag_o[TAGW-1:0]
//
// Registers : a write happens at a rising edge with reg_we_i && reg_ready_o (LightRegs::write):
//             the register takes the low bits of its width; other addresses, reserved ones and the
//             registers of absent capabilities are ignored. reg_ready_o = rst_ni && no fragment in
//             flight anywhere (a counter of accepted minus taken fragments), and in_ready_o is low
//             while reg_we_i is high (writes have priority, the core drains first). So a fragment is
//             shaded with exactly the registers written before its acceptance, and the datapath
//             reads the registers directly. Registers are not reset (rtl/sc_light_regfile.v).
//
// Passes    : the enabled lights (mode enable, a kind the slot can take) are dealt to the lanes in
//             slot order, LANES per pass: ⌈k/LANES⌉ passes for k lights, one pass (the scene term)
//             for none; with LANES = LIGHTS lane j always serves slot j. The fragment is accepted
//             with its first pass; while further passes issue (one per front-advancing edge,
//             schlick_iter: one per VF+4) in_ready_o is low. Per pass each lane adds its light's term;
//             the accumulator adds every pass's terms to the scene term and saturates: all terms are
//             >= 0, so this equals the exact sum saturated once to 2^F (the only rounding is each
//             product's truncation, docs/spec.md §10.4).
//
// Latency   : per pass LATENCY_P advancing edges from its issue to the colour (out_ready_i high):
//               NL = 10 + 8·MREG (sc_normalize), RL = 7 (sc_recip; 11 with MREG) (config/configs.json light.latency, through
//               sc_light_regs.vh), NEED_N = DIFFUSE | UNITS,
//               LV = UNITS & LOCAL_VIEWER, ANY_ATT = some slot can be point_att or spot,
//               ANY_SPOT = some slot can be spot,
//               ANY_PL = ANY_ATT | (NEED_N & some slot can be point)
//               the normalisations N (NEED_N & NORMALIZE), V (LV), L (ANY_PL), H (UNITS & BLINN) that
//               exist are numbered k = 0, 1, ... in that order: K_V, K_L, K_H; S = SHARE
//               T_NN = ((NEED_N & NORMALIZE) ? NL : 0) + MREG_N·MREG   N̂ or N (registered after the choice with MREG)
//               E(k) = k mod S + (k mod S < MRP ? S : 0), MRP = MREG_P·MREG   the entry stage of normalisation k
//                      (MREG: −P and P_j − P registered first; S = 1: MRP)
//               T_V  = LV ? E(K_V) + NL : 0                  V̂
//               T_L  = ANY_PL ? E(K_L) + NL : 0              L̂ of point lights
//               D    = MREG_DOT·MREG (2 with MREG): registers inside each of the lanes' dot products
//               T_A  = max(T_NN, T_L)                      N̂·L → diff, f at T_A+1+D
//               T_H  = the first t >= max(T_L, T_V, T_NN − NL) with t ≡ K_H (mod S);  T_RV = max(T_A+2+2D, T_V)
//               T_XB = T_H+NL+1+D (BLINN), T_XP = LV ? T_RV+1+D : T_A+2+2D (PHONG)   unit input x
//               T_ATT = T_L+3+D+RL (+1 with SHARE > 1 and MREG = 0)   att (point_att)
//                       + (MREG_ATT + MREG_RECIP)·MREG     (q's and sc_recip's products over two edges each)
//               T_SP = T_L+2+D+SPOT_EXP_BITS·PS            the spot factor (sc_powi, PS = 1 + MREG_POWI·MREG
//                                                          stages per exponent bit; SPOT_EXP_BITS = 8, sc_light_regs.vh)
//               T_X  = max(T_XB, T_XP) of the reflections that exist
//               T_F  = max(1, NEED_N ? T_A+1+D : 0, UNITS ? T_X : 0, ANY_ATT ? T_ATT : 0,
//                          ANY_SPOT ? max(T_ATT, T_SP)+1 : 0, LOW_N ? T_X+LOW_N_BITS·PS : 0)
//               (with S = 1 every op enters at stage 0: T_V = T_L = NL, T_H = max(T_L, T_V))
//               NB   = 3 + ANY_ATT + DB·(2 + ANY_ATT), DB = MREG_BACK·MREG (each product stage of the back)
//               LATENCY_P = T_F + (UNITS ? L_unit : 0) + NB, L_unit = the material's unit's
//                           Unit::latency(): cs16 7, cs16 forms 5, schlick_nr 10, schlick_div /
//                           schlick_iter VF+4; +2 with ENERGY; + the unit's mreg_stages with MREG
//             and the last pass issues (passes − 1)·interval edges after the acceptance (interval = S,
//             schlick_iter: VF+4 rounded up to a multiple of S):
//             LightCore::latency(regs) = LATENCY_P + (passes − 1)·interval. Under backpressure the
//             front, the units and the back are elastic segments (as sc_specular with ENERGY = 1): a
//             fragment takes LightCore::latency_min() = NB+1 .. latency(regs) advancing edges;
//             without units the core is one global-enable pipeline (exactly latency(regs)).
// Throughput: one pass per SHARE clocks while out_ready_i is high: one fragment per SHARE·⌈k/LANES⌉
//             clocks with k enabled lights (per interval clocks per pass with schlick_iter).
// Handshake : in_ready_o = rst_ni && !reg_we_i && front enable && no pass pending (&& issue
//             interval with schlick_iter, && phase 0 with SHARE > 1); the path out_ready_i → in_ready_o is
//             combinational.
// ============================================================================================
`default_nettype none

module sc_light #(
    parameter integer FRAC         = 16,
    parameter integer GUARD        = 5,
    parameter integer SGUARD       = 0,
    parameter integer LIGHTS       = 1,
    parameter integer SLOT_KINDS   = 1,
    parameter integer SLOT_SPOT    = 0,
    parameter integer LANES        = 1,
    parameter integer SHARE        = 1,
    parameter integer AMBIENT      = 1,
    parameter integer DIFFUSE      = 1,
    parameter integer UNITS        = 1,
    parameter integer CUTOFF       = 0,
    parameter integer ENERGY       = 0,
    parameter integer BLINN        = 1,
    parameter integer PHONG        = 0,
    parameter integer LOCAL_VIEWER = 0,
    parameter integer NORMALIZE    = 1,
    parameter integer LOW_N        = 0,
    parameter integer SEP_SPEC     = 0,
    parameter integer TWO_SIDE     = 0,
    parameter integer COL_MAT      = 0,
    parameter integer CHANNELS     = 3,
    parameter integer TAGW         = 8,
    parameter integer MREG         = 0
) (
    input  wire              clk_i,
    input  wire              rst_ni,
    // register write port
    input  wire              reg_we_i,
    input  wire [8:0]        reg_addr_i,
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
    input  wire              in_back_i,
    input  wire [FRAC:0]     in_cr_i,
    input  wire [FRAC:0]     in_cg_i,
    input  wire [FRAC:0]     in_cb_i,
    // colour out
    output wire              out_valid_o,
    input  wire              out_ready_i,
    output wire [FRAC:0]     out_r_o,
    output wire [FRAC:0]     out_g_o,
    output wire [FRAC:0]     out_b_o,
    output wire [FRAC:0]     out_sr_o,
    output wire [FRAC:0]     out_sg_o,
    output wire [FRAC:0]     out_sb_o,
    output wire [TAGW-1:0]   out_tag_o
);

`include "sc_light_regs.vh"
`include "sc_variants.vh"
`include "sc_util.vh"

  // ---------------------------------------------------------------------------- constant functions
  // OR of the kinds the slots can take
  function integer all_kinds(input integer n);
    integer j;
    begin
      all_kinds = 0;
      for (j = 0; j < n; j = j + 1) all_kinds = all_kinds | ((SLOT_KINDS >> (3 * j)) & 7);
    end
  endfunction
  // the longest unit latency among UNITS (for the in-flight counter's width)
  function integer unit_latency(input integer v);
    unit_latency = ((v == VARIANT_CS16) ? 7 : (cs16_sq_param(v, 0) == 1) ? 5 :
                    (v == VARIANT_SCHLICK_NR) ? 10 :
                    (v == VARIANT_SCHLICK_DIV || v == VARIANT_SCHLICK_ITER) ? FRAC + SGUARD + 4 : 0) +
                   ((ENERGY != 0) ? 2 : 0) + variant_mreg_stages(v) * MREG;   // (sc_variants.vh)
  endfunction
  function integer max_unit_latency(input integer dummy);
    integer v;
    begin
      max_unit_latency = dummy;
      for (v = 0; v < 8; v = v + 1) begin
        if (((UNITS >> v) & 1) != 0) max_unit_latency = sc_max(max_unit_latency, unit_latency(v));
      end
    end
  endfunction
  // passes a unit (with its sc_energy) can hold: cs16 and schlick_nr at SHARE > 1 keep them SHARE stages apart
  // (rtl/sc_pipe_ctrl.v GAP); the others, and sc_energy, one per stage
  function integer unit_in_flight(input integer v);
    integer e, l;
    begin
      e = (ENERGY != 0) ? 2 : 0;
      l = unit_latency(v) - e;   // the unit's own stages
      if (SH > 1 && (v == VARIANT_CS16 || v == VARIANT_SCHLICK_NR)) l = (l + SH - 1) / SH;
      unit_in_flight = l + e;
    end
  endfunction
  function integer max_in_flight(input integer dummy);
    integer v;
    begin
      max_in_flight = dummy;
      for (v = 0; v < 8; v = v + 1) begin
        if (((UNITS >> v) & 1) != 0) max_in_flight = sc_max(max_in_flight, unit_in_flight(v));
      end
    end
  endfunction
  // number of set bits of the low 8 bits of m
  function integer popcount8(input integer m);
    integer b;
    begin
      popcount8 = 0;
      for (b = 0; b < 8; b = b + 1) popcount8 = popcount8 + ((m >> b) & 1);
    end
  endfunction
  // index of the lowest set bit of m (0 for m = 0)
  function [2:0] lowest(input [7:0] m);
    integer b;
    begin
      lowest = 3'd0;
      for (b = 7; b >= 0; b = b - 1) begin
        if (m[b]) lowest = b[2:0];
      end
    end
  endfunction

  // ---------------------------------------------------------------------------- derived parameters
  localparam integer NW  = FRAC + 2;   // normal component (the input N)
  localparam integer VF  = FRAC + SGUARD;   // fraction bits of the specular path
  localparam integer NV  = VF + 2;     // normalised vectors N̂, V̂ (and the lanes' L̂, Ĥ, x)
  localparam integer PW  = FRAC + 8;   // position component (and directional L), kc/kl/kq, coef
  localparam integer CL  = FRAC + 1;   // colour
  localparam integer AW  = REG_ADDR_BITS;
  localparam integer NL  = NORMALIZE_LATENCY + MREG_NORMALIZE * MREG;   // latency of rtl/sc_normalize.v
  localparam integer RL  = RECIP_LATENCY;                               // latency of rtl/sc_recip.v
  localparam integer D   = MREG_DOT * MREG;    // the lanes' dot products' (and R's products') extra stages
  localparam integer DB  = MREG_BACK * MREG;   // each product stage of the back: its extra stages
  // structure sizes, clamped so that an illegal LIGHTS / LANES / CHANNELS reaches its own error message
  localparam integer NLT = (LIGHTS < 1) ? 1 : ((LIGHTS > MAX_LIGHTS) ? MAX_LIGHTS : LIGHTS);
  localparam integer NLN = (LANES < 1) ? 1 : ((LANES > NLT) ? NLT : LANES);
  localparam integer NCH = (CHANNELS == 1) ? 1 : 3;
  localparam integer SPECULAR = (UNITS != 0) ? 1 : 0;
  localparam integer KINDS   = all_kinds(NLT);
  localparam integer CAN_DIR = KINDS & 1;
  localparam integer ANY_SPOT = ((SLOT_SPOT & ((1 << NLT) - 1)) != 0) ? 1 : 0;
  localparam integer CAN_PT  = (((KINDS >> 1) & 3) != 0 || ANY_SPOT != 0) ? 1 : 0;   // point, point_att or spot
  localparam integer ANY_ATT = (((KINDS >> 2) & 1) != 0 || ANY_SPOT != 0) ? 1 : 0;   // point_att or spot

  localparam integer NEED_N  = (DIFFUSE != 0 || SPECULAR != 0) ? 1 : 0;   // N̂·L is needed
  localparam integer LV      = (SPECULAR != 0 && LOCAL_VIEWER != 0) ? 1 : 0;
  localparam integer HAS_B   = (SPECULAR != 0 && BLINN != 0) ? 1 : 0;
  localparam integer HAS_P   = (SPECULAR != 0 && PHONG != 0) ? 1 : 0;
  localparam integer ANY_PL  = (ANY_ATT != 0 || (NEED_N != 0 && ((KINDS >> 1) & 1) != 0)) ? 1 : 0;
  // the normalisations of a pass (N̂, V̂, L̂, Ĥ: those that exist), numbered k in that order; with
  // SHARE > 1, op k enters shared instance ⌊k/SHARE⌋ at a stage ≡ k (mod SHARE) (LightCore's light_pipe)
  localparam integer SH    = (SHARE < 1) ? 1 : ((SHARE > 4) ? 4 : SHARE);
  localparam integer OP_N  = (NEED_N != 0 && NORMALIZE != 0) ? 1 : 0;
  localparam integer OP_V  = LV;
  localparam integer OP_L  = ANY_PL;
  localparam integer OP_H  = HAS_B;
  localparam integer K_V   = OP_N;
  localparam integer K_L   = OP_N + OP_V;
  localparam integer K_H   = OP_N + OP_V + OP_L;
  localparam integer NOPS  = K_H + OP_H;
  localparam integer NPOOL = (NOPS + SH - 1) / SH;                        // shared sc_normalize instances
  // front pipeline: the time (enabled edges after the issue) at which each value is registered
  localparam integer T_N0  = (OP_N != 0) ? NL : 0;                        // N̂ (0: the input N) chosen
  localparam integer T_NN  = T_N0 + ((NEED_N != 0) ? MREG_N * MREG : 0);  // ... and registered (MREG)
  localparam integer MRP   = MREG_P * MREG;                               // −P, P_j − P registered (MREG)
  // V and L enter their normaliser at E_V, E_L: K mod SH, or SH edges later when that is below MRP (−P and P_j − P
  // registered first, every op keeping its phase); with SH = 1, MRP
  localparam integer E_V   = (K_V % SH) + (((K_V % SH) < MRP) ? SH : 0);
  localparam integer E_L   = (K_L % SH) + (((K_L % SH) < MRP) ? SH : 0);
  localparam integer T_V   = (LV != 0) ? E_V + NL : 0;                    // V̂ (0: constant)
  localparam integer T_L   = (ANY_PL != 0) ? E_L + NL : 0;                // L̂ of point lights
  localparam integer T_A   = sc_max(T_NN, T_L);                             // N̂·L operands
  localparam integer T_H0  = sc_max(sc_max(T_L, T_V), T_NN - NL);     // (N̂ registered after the choice: Ĥ not before it)
  localparam integer T_H   = T_H0 + (((K_H % SH) - (T_H0 % SH)) + SH) % SH;   // H = L + V (Blinn)
  localparam integer T_RV  = sc_max(T_A + 2 + 2 * D, T_V);                  // R·V operands (Phong, local viewer)
  localparam integer T_XB  = T_H + NL + 1 + D;                            // x, Blinn
  localparam integer T_XP  = (LV != 0) ? T_RV + 1 + D : T_A + 2 + 2 * D;  // x, Phong
  localparam integer T_X   = sc_max((HAS_B != 0) ? T_XB : 0, (HAS_P != 0) ? T_XP : 0);
  // att (point_att; T_L = NL with SHARE 1); with SHARE > 1 (without MREG) q takes one stage more, its three
  // products at three stages sharing one multiplier (rtl/sc_light_lane.v); MREG cuts q and sc_recip instead
  localparam integer T_ATT = T_L + 3 + D + RL + ((SH > 1 && MREG == 0) ? 1 : 0) + (MREG_ATT + MREG_RECIP) * MREG;
  localparam integer SPEB  = SPOT_EXP_BITS;                                // spot exponent bits (sc_powi stages)
  localparam integer MPW   = MREG_POWI * MREG;                             // each sc_powi stage's extra edge
  localparam integer T_SP  = T_L + 2 + D + SPEB * (1 + MPW);               // the spot factor
  localparam integer LNB   = LOW_N_BITS;                                 // the low-shininess chain's stages
  localparam integer HAS_LO = (SPECULAR != 0 && LOW_N != 0) ? 1 : 0;      // x^n for n < 2^LNB (low_shininess)
  localparam integer HAS_SEP = (SPECULAR != 0 && SEP_SPEC != 0) ? 1 : 0;   // the secondary colour (separate_specular)
  localparam integer T_F   = sc_max(sc_max(sc_max(sc_max(1, (NEED_N != 0) ? T_A + 1 + D : 0),
                                  sc_max((SPECULAR != 0) ? T_X : 0, (ANY_ATT != 0) ? T_ATT : 0)),
                                  (ANY_SPOT != 0) ? sc_max(T_ATT, T_SP) + 1 : 0),
                                  (HAS_LO != 0) ? T_X + LNB * (1 + MPW) : 0);
  localparam integer NB    = (ANY_ATT != 0) ? 4 + 3 * DB : 3 + 2 * DB;    // back pipeline stages
  // channel-serial back (SHARE >= 4, RGB, units): a pass enters the back as three items, channels 0, 1, 2 on
  // consecutive back-advancing edges, through one set of colour multipliers (rtl/sc_light_shade.v CSER):
  // its colour is out two edges later (LightCore: back = NB + 2). SHARE >= 4 keeps the back (3 edges per
  // pass) faster than the issue (one pass per SHARE edges), so passes a stall has bunched in the units
  // drain and no fragment waits beyond LightCore::latency (at SHARE = 3 the co-simulation showed
  // fragments 2..3 edges late after stalls: the backlog never drained).
  localparam integer CSER  = (SH >= 4 && NCH == 3 && SPECULAR != 0) ? 1 : 0;
  localparam integer SPW   = (ENERGY != 0) ? VF + 8 : VF + 1;               // unit output width
  // with ENERGY and more than one unit, one sc_energy per lane after the unit selection instead of one per
  // unit (only the selected unit has passes; its coefficient register cannot change while one is in flight)
  localparam integer SNORM = (ENERGY != 0 && popcount8(UNITS) > 1) ? 1 : 0;
  localparam integer UOW   = (ENERGY != 0 && SNORM == 0) ? VF + 8 : VF + 1;   // each unit's own output width
  localparam integer CNTW  = sc_bits(T_F + max_unit_latency(0) + NB + 3);   // fragments in flight
  localparam integer ITER  = (UNITS == (1 << VARIANT_SCHLICK_ITER)) ? 1 : 0;
  localparam integer GAP   = VF + 3;                                      // schlick_iter: interval VF+4, minus 1
  localparam integer IDENT = (NLN == NLT) ? 1 : 0;                        // lane j serves slot j
  // per-lane sideband through the units: {x^n of the low chain (LOW_N), att (point_att), diff (DIFFUSE), f, slot,
  // lane valid}
  localparam integer OFF_V = 0;
  localparam integer OFF_I = 1;
  localparam integer OFF_F = 4;
  localparam integer OFF_D = 5;
  localparam integer OFF_A = OFF_D + ((DIFFUSE != 0) ? CL : 0);
  localparam integer OFF_LO = OFF_A + ((ANY_ATT != 0) ? FRAC + 8 : 0);
  localparam integer SBW   = OFF_LO + ((HAS_LO != 0) ? VF + 1 : 0);
  localparam integer HAS_TWO = (TWO_SIDE != 0) ? 1 : 0;                   // two-sided lighting
  localparam integer HAS_CM  = (COL_MAT != 0) ? 1 : 0;                    // colour material
  localparam integer CMW   = (HAS_CM != 0) ? NCH * CL : 0;                // the fragment colour in the tag
  localparam integer FTW   = CMW + TAGW + 3;                              // {colour, fragment tag, back, first, last}

  localparam [CL-1:0] ONE = {1'b1, {FRAC{1'b0}}};                         // 2^F

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  // (CUTOFF and GUARD are checked by rtl/sc_specular.v and its unit when cs16 is among UNITS.)
  genvar j, c, gi, u;
  generate
    if (FRAC < 8 || FRAC > 16) begin : g_check_frac
      sc_light_error_illegal_FRAC_legal_range_is_8_to_16 u_error ();
    end
    if (SGUARD < 0 || SGUARD > 8 || FRAC + SGUARD > 24) begin : g_check_sguard
      sc_light_error_illegal_SGUARD_legal_range_is_0_to_8_and_FRAC_plus_SGUARD_at_most_24 u_error ();
    end
    if (LIGHTS < 1 || LIGHTS > MAX_LIGHTS) begin : g_check_lights
      sc_light_error_illegal_LIGHTS_legal_range_is_1_to_8 u_error ();
    end
    if (LANES < 1 || LANES > LIGHTS) begin : g_check_lanes
      sc_light_error_illegal_LANES_legal_range_is_1_to_LIGHTS u_error ();
    end
    if ((MREG != 0 && MREG != 1) || MREG_DOT < 1 || MREG_DOT > 2) begin : g_check_mreg
      sc_light_error_illegal_MREG_must_be_0_or_1_and_MREG_DOT_1_or_2 u_error ();
    end
    if (SHARE < 1 || SHARE > 4) begin : g_check_share
      sc_light_error_illegal_SHARE_legal_range_is_1_to_4 u_error ();
    end
    if (SHARE > 1 && LANES != 1) begin : g_check_share_lanes
      sc_light_error_illegal_SHARE_above_1_needs_LANES_1 u_error ();
    end
    for (j = 0; j < NLT; j = j + 1) begin : g_check_kind
      if (((SLOT_KINDS >> (3 * j)) & 7) == 0 && ((SLOT_SPOT >> j) & 1) == 0) begin : g_bad
        sc_light_error_illegal_SLOT_KINDS_each_slot_needs_a_kind u_error ();
      end
    end
    if (SLOT_KINDS < 0 || (SLOT_KINDS >> (3 * NLT)) != 0) begin : g_check_kinds_range
      sc_light_error_illegal_SLOT_KINDS_bits_beyond_LIGHTS_slots u_error ();
    end
    if (SLOT_SPOT < 0 || (SLOT_SPOT >> NLT) != 0) begin : g_check_spot_range
      sc_light_error_illegal_SLOT_SPOT_bits_beyond_LIGHTS_slots u_error ();
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
    if (UNITS < 0 || UNITS > 255) begin : g_check_units
      sc_light_error_illegal_UNITS_is_a_mask_of_variant_ids_0_to_7 u_error ();
    end
    // The table units (docs/spec.md §9) need their table RAM loaded through sc_specular's tab_*_i
    // port, which the lighting core's register file does not have.
    // (sc_variants.vh's table sizes are named here so that lint does not flag them unused in this module.)
    if ((((UNITS >> VARIANT_TABLE256) & 1) != 0 || ((UNITS >> VARIANT_TABLE1024) & 1) != 0) &&
        VARIANT_TABLE256_ENTRIES + VARIANT_TABLE1024_ENTRIES > 0) begin : g_check_table
      sc_light_error_table_VARIANT_not_supported_no_table_load_port u_error ();
    end
    if (((UNITS >> VARIANT_SCHLICK_ITER) & 1) != 0 && ITER == 0) begin : g_check_iter
      sc_light_error_schlick_iter_cannot_share_the_core_with_other_UNITS u_error ();
    end
    if (ENERGY != 0 && ENERGY != 1) begin : g_check_energy
      sc_light_error_illegal_ENERGY_must_be_0_or_1 u_error ();
    end
    if (BLINN != 0 && BLINN != 1) begin : g_check_blinn
      sc_light_error_illegal_BLINN_must_be_0_or_1 u_error ();
    end
    if (PHONG != 0 && PHONG != 1) begin : g_check_phong
      sc_light_error_illegal_PHONG_must_be_0_or_1 u_error ();
    end
    if (SPECULAR != 0 && BLINN == 0 && PHONG == 0) begin : g_check_reflection
      sc_light_error_illegal_UNITS_need_BLINN_or_PHONG u_error ();
    end
    if (LOCAL_VIEWER != 0 && LOCAL_VIEWER != 1) begin : g_check_local_viewer
      sc_light_error_illegal_LOCAL_VIEWER_must_be_0_or_1 u_error ();
    end
    if (NORMALIZE != 0 && NORMALIZE != 1) begin : g_check_normalize
      sc_light_error_illegal_NORMALIZE_must_be_0_or_1 u_error ();
    end
    if (LOW_N != 0 && LOW_N != 1) begin : g_check_low_n
      sc_light_error_illegal_LOW_N_must_be_0_or_1 u_error ();
    end
    if (LOW_N != 0 && SPECULAR == 0) begin : g_check_low_n_spec
      sc_light_error_illegal_LOW_N_needs_UNITS u_error ();
    end
    if (SEP_SPEC != 0 && SEP_SPEC != 1) begin : g_check_sep
      sc_light_error_illegal_SEP_SPEC_must_be_0_or_1 u_error ();
    end
    if (TWO_SIDE != 0 && TWO_SIDE != 1) begin : g_check_two
      sc_light_error_illegal_TWO_SIDE_must_be_0_or_1 u_error ();
    end
    if (COL_MAT != 0 && COL_MAT != 1) begin : g_check_cm
      sc_light_error_illegal_COL_MAT_must_be_0_or_1 u_error ();
    end
    if (SEP_SPEC != 0 && SPECULAR == 0) begin : g_check_sep_spec
      sc_light_error_illegal_SEP_SPEC_needs_UNITS u_error ();
    end
    if (ENERGY != 0 && SPECULAR == 0) begin : g_check_energy_spec
      sc_light_error_illegal_ENERGY_needs_SPECULAR u_error ();
    end
    if (AMBIENT == 0 && DIFFUSE == 0 && SPECULAR == 0) begin : g_check_terms
      sc_light_error_illegal_no_term_enabled_AMBIENT_DIFFUSE_SPECULAR_all_0 u_error ();
    end
    if (AW != 9) begin : g_check_addr_bits
      sc_light_error_reg_addr_i_is_9_bits_update_the_port_with_config_light_addr_bits u_error ();
    end
    if (TAGW < 1) begin : g_check_tagw
      sc_light_error_illegal_TAGW_must_be_at_least_1 u_error ();
    end
  endgenerate

  // ---------------------------------------------------------------------------- register file
  wire                   wr;
  wire [NLT*3*PW-1:0]    pos_all, katt_all;
  wire [NLT*2-1:0]       kind_all;
  wire [NLT*3*(FRAC+2)-1:0] sdir_all;
  wire [NLT*(VF+2)-1:0]  scos_all;
  wire [NLT*SPEB-1:0]    sexp_all;
  wire [NLT-1:0]         on_all;
  wire [NLT*NCH*CL-1:0]  lamb_all;
  wire [NCH*CL-1:0]      mamb_w;
  wire [NLT*NCH*CL-1:0]  ldif_all, lspec_all;
  wire [NCH*CL-1:0]      scene_w, mdif_w, mspec_w;
  wire                   mat_we_u;
  wire [10:0]            mat_n_u;
  wire [VF:0]            mat_thr_u;
  wire [VF+7:0]          mat_coef_u;
  wire [7:0]             unit_sel;
  wire                   unit_kill, lv_mode, phong_mode, norm_mode, sep_mode, two_mode;
  wire [NCH*CL-1:0]      bamb_w, bscene_w, bdif_w, bspec_w;   // TWO_SIDE: the back colour bank
  wire [NCH*CL-1:0]      em_w, bem_w, ga_w;                   // the scene term's operands (COL_MAT)
  wire [3:0]             cm_w;   // COL_MAT: {specular, diffuse, ambient, emission} take the fragment's colour
  sc_light_regfile #(
      .FRAC(FRAC), .UFRAC(VF), .SLOT_KINDS(SLOT_KINDS), .SLOT_SPOT(SLOT_SPOT), .SEB(SPEB), .AMBIENT(AMBIENT), .DIFFUSE(DIFFUSE),
      .UNITS(UNITS), .ENERGY(ENERGY), .BLINN(BLINN), .PHONG(PHONG), .LOCAL_VIEWER(LOCAL_VIEWER),
      .NORMALIZE(NORMALIZE), .SEP(HAS_SEP), .TWO_SIDE(HAS_TWO), .COL_MAT(HAS_CM), .NLT(NLT), .NCH(NCH), .AW(AW),
      .MREG(DB)
  ) u_regs (
      .clk_i(clk_i), .wr_i(wr), .addr_i(reg_addr_i[AW-1:0]), .data_i(reg_data_i),
      .pos_o(pos_all), .katt_o(katt_all), .kind_o(kind_all), .on_o(on_all),
      .sdir_o(sdir_all), .scos_o(scos_all), .sexp_o(sexp_all),
      .lamb_o(lamb_all), .mamb_o(mamb_w), .ldif_o(ldif_all), .lspec_o(lspec_all),
      .scene_o(scene_w), .mdif_o(mdif_w), .mspec_o(mspec_w),
      .mat_we_o(mat_we_u), .mat_n_o(mat_n_u), .mat_thr_o(mat_thr_u), .mat_coef_o(mat_coef_u),
      .unit_sel_o(unit_sel), .unit_kill_o(unit_kill),
      .lv_o(lv_mode), .phong_o(phong_mode), .normalize_o(norm_mode), .sep_o(sep_mode), .two_o(two_mode),
      .bamb_o(bamb_w), .bscene_o(bscene_w), .bdif_o(bdif_w), .bspec_o(bspec_w),
      .em_o(em_w), .bem_o(bem_w), .ga_o(ga_w), .cm_o(cm_w));

  // ---------------------------------------------------------------------------- handshake, pass issue
  // front: T_F stages, enable adv_f; back: NB stages, enable adv_b (the core's advancing condition)
  wire adv_f, adv_b;
  wire u_in_ready, u_out_valid;   // the selected unit's handshake (lane 0; the lanes run in lock-step)
  wire u_out_ready;               // the back takes the units' output (CSER: not while it feeds channels 1, 2)
  wire [1:0] ser;                 // CSER: 0 the back takes from the units, 1 / 2 it feeds the held pass's channel
  wire b_in_valid;                // what the back's first stage takes
  wire gap_ok;                    // schlick_iter: the issue interval has passed
  reg  [T_F-1:0] vf_q;            // front valid bits, stage k at bit k-1
  reg  [NB-1:0]  vb_q;            // back valid bits
  wire vf_last = vf_q[T_F-1];
  wire out_last;                  // the pass in the output stage is its fragment's last

  // a fragment with passes still to issue (its data held; reset drops it)
  reg              hold_q;
  reg  [NLT-1:0]   rem_q;
  reg  [3*NW-1:0]  hold_n_q;
  reg  [3*PW-1:0]  hold_p_q;
  reg  [TAGW-1:0]  hold_tag_q;
  reg              hold_back_q;
  reg  [3*CL-1:0]  hold_col_q;

  assign out_valid_o = vb_q[NB-1] && out_last;
  assign adv_b       = !out_valid_o || out_ready_i;   // a pass that is not its fragment's last leaves at once
  wire   ph_ok;                    // SHARE > 1: the phase at which a pass may issue
  wire [1:0] ph;                   // the phase: front-advancing edges since the last issue slot, mod SHARE
  assign in_ready_o  = rst_ni && adv_f && !reg_we_i && gap_ok && ph_ok && !hold_q;
  wire   accept      = in_valid_i && in_ready_o;
  wire   issue       = accept || (rst_ni && hold_q && adv_f && gap_ok && ph_ok);
  wire   take        = out_valid_o && out_ready_i;

  // the pass's lanes: the lowest NLN lights of what remains (identity with NLN = NLT)
  wire [NLT-1:0]   rem_cur = hold_q ? rem_q : on_all;
  reg  [NLT-1:0]   rem_next;
  reg  [3*NLN-1:0] lane_idx;
  reg  [NLN-1:0]   lane_v;
  integer l;
  always @* begin : p_deal
    reg [7:0] m;
    m = {{(8-NLT){1'b0}}, rem_cur};
    for (l = 0; l < NLN; l = l + 1) begin
      if (IDENT != 0) begin
        lane_v[l] = rem_cur[l];
        lane_idx[3*l +: 3] = l[2:0];
      end else begin
        lane_v[l] = (m != 8'd0);
        lane_idx[3*l +: 3] = lowest(m);
        m = m & (m - 8'd1);
      end
    end
    rem_next = (IDENT != 0) ? {NLT{1'b0}} : m[NLT-1:0];
  end
  wire pass_first = !hold_q;
  wire pass_last  = (rem_next == {NLT{1'b0}});

  always @(posedge clk_i) begin
    if (!rst_ni) hold_q <= 1'b0;
    else if (issue) hold_q <= !pass_last;
    if (issue) rem_q <= rem_next;
    if (accept) begin
      hold_n_q   <= {in_nz_i, in_ny_i, in_nx_i};
      hold_p_q   <= {in_pz_i, in_py_i, in_px_i};
      hold_tag_q <= in_tag_i;
      hold_back_q <= in_back_i;
      hold_col_q <= {in_cb_i, in_cg_i, in_cr_i};
    end
  end

  generate
    if (SPECULAR != 0) begin : g_hs_units
      // the front hands x and the sideband to the units; they hand results to the back
      assign adv_f      = !vf_last || u_in_ready;
      assign b_in_valid = u_out_valid || (ser != 2'd0);
    end else begin : g_hs_direct
      // no units: front and back are one global-enable pipeline
      assign adv_f      = adv_b;
      assign b_in_valid = vf_last;
      wire unused_u_hs = &{1'b0, u_in_ready, u_out_valid, u_out_ready};
      // GUARD and CUTOFF configure the cs16 unit only; referenced so that lint of a wrapper that fixes
      // them (a handoff bundle, where sc_specular.v is absent) does not flag them as unused.
      wire unused_unit_cfg = (GUARD == 0) || (CUTOFF == 0);
    end
    if (T_F == 1) begin : g_vf_one
      always @(posedge clk_i) begin
        if (!rst_ni) vf_q <= 1'b0;
        else if (adv_f) vf_q <= issue;
      end
    end else begin : g_vf_line
      always @(posedge clk_i) begin
        if (!rst_ni) vf_q <= {T_F{1'b0}};
        else if (adv_f) vf_q <= {vf_q[T_F-2:0], issue};
      end
    end
    if (ITER != 0) begin : g_gap
      // schlick_iter takes one pass per F+4 clocks: after an issue the front stays closed for F+3
      // front-advancing edges, so passes reach the unit exactly when it is free.
      localparam [4:0] GAP5 = GAP[4:0];
      reg [4:0] gap_q;
      always @(posedge clk_i) begin
        if (!rst_ni) gap_q <= 5'd0;
        else if (issue) gap_q <= GAP5;
        else if (adv_f && gap_q != 5'd0) gap_q <= gap_q - 5'd1;
      end
      assign gap_ok = (gap_q == 5'd0);
    end else begin : g_no_gap
      assign gap_ok = 1'b1;
    end
    if (SH > 1) begin : g_phase
      // a pass at front stage s is there when ph ≡ s (mod SHARE): the shared normalisers' inputs are
      // chosen by ph, and their outputs reach each consumer at its own stage without a selection
      localparam integer PH_LASTI = SH - 1;
      localparam [1:0] PH_LAST = PH_LASTI[1:0];
      reg [1:0] ph_q;
      always @(posedge clk_i) begin
        if (!rst_ni) ph_q <= 2'd0;
        else if (adv_f) ph_q <= (ph_q == PH_LAST) ? 2'd0 : ph_q + 2'd1;
      end
      assign ph    = ph_q;
      assign ph_ok = (ph_q == 2'd0);
    end else begin : g_no_phase
      assign ph    = 2'd0;
      assign ph_ok = 1'b1;
    end
  endgenerate

  always @(posedge clk_i) begin
    if (!rst_ni) vb_q <= {NB{1'b0}};
    else if (adv_b) vb_q <= {vb_q[NB-2:0], b_in_valid};
  end
  generate
    if (CSER != 0) begin : g_ser
      reg [1:0] ser_q;
      always @(posedge clk_i) begin
        if (!rst_ni) ser_q <= 2'd0;
        else if (adv_b) ser_q <= (ser_q == 2'd0) ? {1'b0, u_out_valid} : ((ser_q == 2'd2) ? 2'd0 : 2'd2);
      end
      assign ser = ser_q;
    end else begin : g_no_ser
      assign ser = 2'd0;
    end
  endgenerate
  assign u_out_ready = adv_b && (ser == 2'd0);

  // Fragments in flight (front, units, back, output stage). reg_ready_o: none, so a register
  // write cannot affect a fragment; in_ready_o is low while reg_we_i is high (the core drains).
  reg [CNTW-1:0] cnt_q;
  always @(posedge clk_i) begin
    if (!rst_ni) cnt_q <= {CNTW{1'b0}};
    else cnt_q <= cnt_q + {{(CNTW-1){1'b0}}, accept} - {{(CNTW-1){1'b0}}, take};
  end
  assign reg_ready_o = rst_ni && (cnt_q == {CNTW{1'b0}});
  assign wr = reg_we_i && reg_ready_o;
  wire unused_addr = &{1'b0, reg_addr_i};

  // ---------------------------------------------------------------------------- front: the pass's operands
  // the shared normalisers' results (SHARE > 1; see "shared normalisers" below)
  wire [3*NV-1:0] pool_nhat, pool_vhat, pool_lhat, pool_hhat;
  wire [3*NW-1:0] n_pick = hold_q ? hold_n_q : {in_nz_i, in_ny_i, in_nx_i};
  // the two-sided mode lights a back-facing fragment with −N, each component saturated (−(−2^(F+1)) is 2^(F+1)−1)
  wire            bk_in  = (HAS_TWO != 0) && two_mode && (hold_q ? hold_back_q : in_back_i);
  wire [3*NW-1:0] n_in;
  generate
    for (gi = 0; gi < 3; gi = gi + 1) begin : g_nneg
      wire [NW-1:0] e   = n_pick[gi*NW +: NW];
      wire [NW-1:0] neg = (e == {1'b1, {(NW-1){1'b0}}}) ? {1'b0, {(NW-1){1'b1}}} : ({NW{1'b0}} - e);
      assign n_in[gi*NW +: NW] = bk_in ? neg : e;
    end
  endgenerate
  wire [3*PW-1:0] p_in   = hold_q ? hold_p_q : {in_pz_i, in_py_i, in_px_i};
  wire [TAGW-1:0] tag_in = hold_q ? hold_tag_q : in_tag_i;

  // fragment tag, first and last (and with COL_MAT the fragment's colour) through the front
  wire [FTW-1:0] ftag_in;
  wire [3*CL-1:0] col_in = hold_q ? hold_col_q : {in_cb_i, in_cg_i, in_cr_i};
  generate
    if (HAS_CM != 0) begin : g_ftag_col
      assign ftag_in = {col_in[NCH*CL-1:0], tag_in, bk_in, pass_first, pass_last};
      if (NCH < 3) begin : g_col_mono
        wire unused_col_gb = &{1'b0, col_in[3*CL-1:NCH*CL]};
      end
    end else begin : g_ftag
      assign ftag_in = {tag_in, bk_in, pass_first, pass_last};
      wire unused_col = &{1'b0, col_in};
    end
  endgenerate
  wire [FTW-1:0] ftag_f;
  sc_delay #(.W(FTW), .DEPTH(T_F)) u_dly_tag (
      .clk_i(clk_i), .en_i(adv_f), .d_i(ftag_in), .q_o(ftag_f));
  // lane valid bits through the front
  wire [NLN-1:0] lv_f;
  sc_delay #(.W(NLN), .DEPTH(T_F)) u_dly_lv (
      .clk_i(clk_i), .en_i(adv_f), .d_i(lane_v), .q_o(lv_f));

  // N̂ (the normalize mode) or N·2^SGUARD at T_NN, then at T_A (N̂·L), T_H+NL (Blinn's x), T_A+1
  // (Phong's R); VF fraction bits
  wire [3*NV-1:0] nn_a, nn_b, nn_p;
  generate
    if (NEED_N != 0) begin : g_nn
      wire [3*NV-1:0] nn_c, nn0;
      wire [3*NW-1:0] n_raw;     // N as given (through the normaliser's delay line with NORMALIZE)
      wire [3*NV-1:0] n_raw_v;   // N·2^SGUARD
      for (gi = 0; gi < 3; gi = gi + 1) begin : g_nv
        if (SGUARD > 0) begin : g_sh
          assign n_raw_v[gi*NV +: NV] = {n_raw[gi*NW +: NW], {SGUARD{1'b0}}};
        end else begin : g_id
          assign n_raw_v[gi*NV +: NV] = n_raw[gi*NW +: NW];
        end
      end
      if (NORMALIZE != 0 && SH > 1) begin : g_pool_n
        // N̂ from the shared normalisers (op 0), N as given delayed beside it
        sc_delay #(.W(3*NW), .DEPTH(T_N0)) u_dly_nraw (
            .clk_i(clk_i), .en_i(adv_f), .d_i(n_in), .q_o(n_raw));
        assign nn_c = norm_mode ? pool_nhat : n_raw_v;
      end else if (NORMALIZE != 0) begin : g_norm_n
        wire [3*NV-1:0] n_norm;
        sc_normalize #(.FRAC(VF), .VW(NW), .MREG(MREG)) u_norm_n (
            .clk_i(clk_i), .en_i(adv_f), .v_i(n_in), .u_o(n_norm), .v_o(n_raw));
        assign nn_c = norm_mode ? n_norm : n_raw_v;
        wire unused_pool_n = &{1'b0, pool_nhat};
      end else begin : g_raw_n
        assign n_raw = n_in;
        assign nn_c = n_raw_v;
        wire unused_norm_mode = &{1'b0, norm_mode, pool_nhat};
      end
      // MREG: the choice registered (T_NN − T_N0 = MREG_N stages) before the lanes' dot products, so that
      // their trees start at flip-flops: not behind the normalize-mode select (a 3·NV fan-out) nor, with no
      // normaliser, behind the input N's own arrival (docs/signoff.md "Ninth round")
      sc_delay #(.W(3*NV), .DEPTH(T_NN - T_N0)) u_dly_nn0 (
          .clk_i(clk_i), .en_i(adv_f), .d_i(nn_c), .q_o(nn0));
      sc_delay #(.W(3*NV), .DEPTH(T_A - T_NN)) u_dly_nn_a (
          .clk_i(clk_i), .en_i(adv_f), .d_i(nn0), .q_o(nn_a));
      if (HAS_B != 0) begin : g_nn_b
        sc_delay #(.W(3*NV), .DEPTH(T_H + NL - T_A)) u_dly_nn_b (
            .clk_i(clk_i), .en_i(adv_f), .d_i(nn_a), .q_o(nn_b));
      end else begin : g_no_nn_b
        assign nn_b = {3*NV{1'b0}};
      end
      if (HAS_P != 0) begin : g_nn_p
        sc_delay #(.W(3*NV), .DEPTH(1 + D)) u_dly_nn_p (
            .clk_i(clk_i), .en_i(adv_f), .d_i(nn_a), .q_o(nn_p));
      end else begin : g_no_nn_p
        assign nn_p = {3*NV{1'b0}};
      end
    end else begin : g_no_nn
      assign nn_a = {3*NV{1'b0}};
      assign nn_b = {3*NV{1'b0}};
      assign nn_p = {3*NV{1'b0}};
      wire unused_n = &{1'b0, n_in, norm_mode, pool_nhat};
    end
  endgenerate

  // V̂ = normalise(−P) (local-viewer mode) or (0, 0, 1), at T_H (Blinn) and T_RV (Phong)
  wire [3*NV-1:0] v_h, v_p;
  wire [3*(PW+1)-1:0] mp_w;   // −P (the shared normalisers' V input with SHARE > 1)
  localparam [3*NV-1:0] V_INF = {{2'b01, {VF{1'b0}}}, {NV{1'b0}}, {NV{1'b0}}};
  generate
    if (LV != 0) begin : g_view
      wire [3*(PW+1)-1:0] mp;   // −P, F+9 bits per component (−(−2^(F+7)) = 2^(F+7))
      for (gi = 0; gi < 3; gi = gi + 1) begin : g_neg
        wire [PW-1:0] pc = p_in[gi*PW +: PW];
        assign mp[gi*(PW+1) +: PW+1] = {(PW+1){1'b0}} - {pc[PW-1], pc};
      end
      wire [3*NV-1:0]     v_norm;
      assign mp_w = mp;
      if (SH > 1) begin : g_pool_v
        assign v_norm = pool_vhat;
      end else begin : g_own_v
        wire [3*(PW+1)-1:0] mp_pass_unused;
        wire [3*(PW+1)-1:0] mp_q;   // −P, registered with MREG (an input's subtraction and S1's squares in one stage miss 4.0 ns)
        sc_delay #(.W(3*(PW+1)), .DEPTH(MRP)) u_dly_mp (.clk_i(clk_i), .en_i(adv_f), .d_i(mp), .q_o(mp_q));
        sc_normalize #(.FRAC(VF), .VW(PW+1), .MREG(MREG)) u_norm_v (
            .clk_i(clk_i), .en_i(adv_f), .v_i(mp_q), .u_o(v_norm), .v_o(mp_pass_unused));
        wire unused_pool_v = &{1'b0, pool_vhat};
      end
      wire [3*NV-1:0] v0 = lv_mode ? v_norm : V_INF;
      if (HAS_B != 0) begin : g_v_blinn
        sc_delay #(.W(3*NV), .DEPTH(T_H - T_V)) u_dly_vh (
            .clk_i(clk_i), .en_i(adv_f), .d_i(v0), .q_o(v_h));
      end else begin : g_no_v_blinn
        assign v_h = V_INF;
      end
      if (HAS_P != 0) begin : g_v_phong
        sc_delay #(.W(3*NV), .DEPTH(T_RV - T_V)) u_dly_vp (
            .clk_i(clk_i), .en_i(adv_f), .d_i(v0), .q_o(v_p));
      end else begin : g_no_v_phong
        assign v_p = V_INF;
      end
    end else begin : g_no_view
      assign v_h = V_INF;
      assign v_p = V_INF;
      assign mp_w = {3*(PW+1){1'b0}};
      wire unused_lv = &{1'b0, lv_mode, pool_vhat};
    end
    if (ANY_PL == 0 && LV == 0) begin : g_no_pos
      wire unused_p = &{1'b0, p_in};
    end
  endgenerate

  // ---------------------------------------------------------------------------- lanes
  localparam integer HVW_T = NV + 1;   // H = L + V (sc_light_lane's HVW)
  wire [NLN*3*(PW+1)-1:0] lv_all;    // lane j's P_j − P at stage 0 (SHARE > 1)
  wire [NLN*3*HVW_T-1:0]  hv_all;    // lane j's H at T_H (SHARE > 1)
  wire [NLN*NCH*CL-1:0] term_all;    // lane l's saturated term of channel c at (l*NCH + c)*CL
  wire [NLN*NCH*CL-1:0] sterm_all;   // SEP_SPEC: lane l's saturated specular term, likewise
  wire [NLN*8-1:0]      u_in_ready_all, u_out_valid_all;   // per lane and variant id
  wire [NLN-1:0]        lane_out_valid;                    // per lane: what its back takes is valid
  wire [FTW-1:0]        bk_ftag;     // {colour, fragment tag, back, first, last} as the back takes it
  // COL_MAT: the fragment's colour at B0 (as the back takes it) and at B1 (one back-advancing edge later)
  wire [NCH*CL-1:0]     col_b0, col_b1;
  generate
    if (HAS_CM != 0) begin : g_col_b
      // (B1 is 1 + D edges after B0: rtl/sc_light_shade.v)
      assign col_b0 = bk_ftag[FTW-1:TAGW+3];
      sc_delay #(.W(NCH*CL), .DEPTH(1 + DB)) u_dly_col_b1 (
          .clk_i(clk_i), .en_i(adv_b), .d_i(col_b0), .q_o(col_b1));
    end else begin : g_no_col_b
      assign col_b0 = {(NCH*CL){1'b0}};
      assign col_b1 = {(NCH*CL){1'b0}};
    end
  endgenerate
  wire                  u_kill = unit_kill;
  // LOW_N: the shininess register holds n < 2^LNB (constant while a fragment is in flight)
  wire                  lo_mode = (HAS_LO != 0) && (mat_n_u[10:LNB] == {(11-LNB){1'b0}});

  generate
    for (j = 0; j < NLN; j = j + 1) begin : g_lane
      wire [NV-1:0]   x_f;
      wire [CL-1:0]   diff_f;
      wire            f_f;
      wire [PW-1:0]   att_f;
      wire [2:0]      idx_f;
      wire [VF:0]     lo_f;
      sc_light_lane #(
          .FRAC(FRAC), .SG(SGUARD), .NLT(NLT), .CAN_DIR(CAN_DIR), .CAN_PT(CAN_PT), .CAN_ATT(ANY_ATT),
          .CAN_SPOT(ANY_SPOT), .T_SP(T_SP), .SEB(SPEB), .LOW_N(HAS_LO), .LNB(LNB),
          .NEED_N(NEED_N), .SPECULAR(SPECULAR), .DIFFUSE(DIFFUSE), .BLINN(BLINN), .PHONG(PHONG),
          .LV(LV), .T_L(T_L), .T_A(T_A), .T_H(T_H), .T_RV(T_RV), .T_XB(T_XB), .T_XP(T_XP),
          .T_ATT(T_ATT), .T_F(T_F), .EXT_NORM((SH > 1) ? 1 : 0), .SH(SH), .MREG(MREG)
      ) u_lane (
          .clk_i(clk_i), .en_i(adv_f), .idx_i(lane_idx[3*j +: 3]), .p_i(p_in),
          .nn_a_i(nn_a), .nn_b_i(nn_b), .nn_p_i(nn_p), .v_h_i(v_h), .v_p_i(v_p), .phong_i(phong_mode),
          .pos_i(pos_all), .katt_i(katt_all), .kind_i(kind_all),
          .sdir_i(sdir_all), .scos_i(scos_all), .sexp_i(sexp_all), .lo_e_i(mat_n_u[LNB-1:0]),
          .x_o(x_f), .lo_o(lo_f), .diff_o(diff_f), .f_o(f_f), .att_o(att_f), .idx_o(idx_f),
          .lv_o(lv_all[j*3*(PW+1) +: 3*(PW+1)]), .hv_o(hv_all[j*3*HVW_T +: 3*HVW_T]),
          .lhat_i(pool_lhat), .hhat_i(pool_hhat), .ph_i(ph));

      // sideband through the units
      wire [SBW-1:0] sb_f;
      assign sb_f[OFF_V] = lv_f[j];
      assign sb_f[OFF_I +: 3] = idx_f;
      assign sb_f[OFF_F] = f_f && !u_kill;
      if (DIFFUSE != 0) begin : g_sb_d
        assign sb_f[OFF_D +: CL] = diff_f;
      end else begin : g_sb_no_d
        wire unused_diff_f = &{1'b0, diff_f};
      end
      if (ANY_ATT != 0) begin : g_sb_a
        assign sb_f[OFF_A +: PW] = att_f;
      end else begin : g_sb_no_a
        wire unused_att_f = &{1'b0, att_f};
      end
      if (HAS_LO != 0) begin : g_sb_lo
        assign sb_f[OFF_LO +: VF+1] = lo_f;
      end else begin : g_sb_no_lo
        wire unused_lo_f = &{1'b0, lo_f};
      end
      localparam integer UTW = SBW + ((j == 0) ? FTW : 0);
      wire [UTW-1:0] ut_in;
      assign ut_in[SBW-1:0] = sb_f;
      if (j == 0) begin : g_ftag_in
        assign ut_in[UTW-1:SBW] = ftag_f;
      end

      wire [UTW-1:0] ut_b;     // what the back takes
      wire [SPW-1:0] spec_b;
      if (SPECULAR != 0) begin : g_units
        // one sc_specular per unit of UNITS; only the selected one gets passes (mat_unit cannot
        // change while one is in flight), its handshake and results are the lane's
        // the units' tag: the sideband (UTW bits) at SHARE 1, one constant bit beside the queue at SHARE > 1
        localparam integer UTAG = (SH > 1) ? 1 : UTW;
        wire [8*UTAG-1:0] ut_out_all;
        wire [8*UOW-1:0] spec_all;
        wire [UTAG-1:0]  ut_u_in, ut_u_out;   // the tag the units (and sc_energy) carry and hand out
        wire             n_in_ready;   // SNORM: the shared sc_energy takes the selected unit's result
        for (u = 0; u < 8; u = u + 1) begin : g_u
          if (((UNITS >> u) & 1) != 0) begin : g_on
            sc_specular #(
                .VARIANT(u),
                .FRAC   (VF),
                .GUARD  (GUARD),
                .CUTOFF (CUTOFF),
                .TAGW   (UTAG),
                .ENERGY ((SNORM != 0) ? 0 : ENERGY),
                .SHARE  (SH),
                .MREG   (MREG)
            ) u_unit (
                .clk_i      (clk_i),
                .rst_ni     (rst_ni),
                .mat_we_i   (mat_we_u),
                .mat_n_i    (mat_n_u),
                .mat_thr_i  (mat_thr_u),
                .mat_coef_i (mat_coef_u),
                .tab_we_i   (1'b0),
                .tab_addr_i (10'd0),
                .tab_value_i({(VF+1){1'b0}}),
                .tab_delta_i({(VF+1){1'b0}}),
                .in_valid_i (vf_last && unit_sel[u]),
                .in_ready_o (u_in_ready_all[8*j + u]),
                .in_cos_i   (x_f),
                .in_tag_i   (ut_u_in),
                .out_valid_o(u_out_valid_all[8*j + u]),
                .out_ready_i((SNORM != 0) ? n_in_ready : u_out_ready),
                .out_spec_o (spec_all[u*UOW +: UOW]),
                .out_tag_o  (ut_out_all[u*UTAG +: UTAG])
            );
          end else begin : g_off
            assign u_in_ready_all[8*j + u]  = 1'b0;
            assign u_out_valid_all[8*j + u] = 1'b0;
            assign spec_all[u*UOW +: UOW]   = {UOW{1'b0}};
            assign ut_out_all[u*UTAG +: UTAG] = {UTAG{1'b0}};
          end
        end
        // the selected unit's outputs (AND-OR over the one-hot selection)
        reg [UTAG-1:0] ut_sel;
        reg [UOW-1:0] spec_sel;
        integer v;
        always @* begin
          ut_sel = {UTAG{1'b0}};
          spec_sel = {UOW{1'b0}};
          for (v = 0; v < 8; v = v + 1) begin
            ut_sel   = ut_sel | (ut_out_all[v*UTAG +: UTAG] & {UTAG{unit_sel[v]}});
            spec_sel = spec_sel | (spec_all[v*UOW +: UOW] & {UOW{unit_sel[v]}});
          end
        end
        wire sel_valid = |(u_out_valid_all[8*j +: 8] & unit_sel);
        if (SNORM != 0) begin : g_snorm
          sc_energy #(
              .FRAC(VF), .COEFW(VF + 8), .COEF_SRC(0), .TAGW(UTAG), .MREG(MREG)
          ) u_norm (
              .clk_i(clk_i), .rst_ni(rst_ni), .mat_we_i(mat_we_u), .mat_coef_i(mat_coef_u),
              .in_valid_i(sel_valid), .in_ready_o(n_in_ready), .in_spec_i(spec_sel),
              .in_coef_i({(VF+8){1'b0}}), .in_tag_i(ut_sel),
              .out_valid_o(lane_out_valid[j]), .out_ready_i(u_out_ready), .out_norm_o(spec_b),
              .out_tag_o(ut_u_out));
        end else begin : g_unorm
          assign n_in_ready = 1'b0;
          assign lane_out_valid[j] = sel_valid;
          assign ut_u_out = ut_sel;
          assign spec_b = spec_sel;
          wire unused_n_in_ready = &{1'b0, n_in_ready};
        end
        if (SH > 1) begin : g_sbq
          // SHARE > 1: the sideband waits in a queue beside the units instead of travelling through their
          // stages (passes there are SHARE apart: a few entries instead of a tag register per stage of every
          // unit); pushed when the selected unit takes a pass, popped when the back takes its result, in
          // order. The units' own tag lines carry zeros (synthesis removes them). Cleared by reset, which
          // also drops every pass in the units.
          localparam integer QD  = max_in_flight(0);
          localparam integer QAW = sc_bits(QD);
          localparam integer QL = QD - 1;
          wire [QAW-1:0] q_last = QL[QAW-1:0];
          reg [UTW-1:0] q_mem [0:QD-1];
          reg [QAW-1:0] q_wr, q_rd;
          wire q_push = vf_last && |(u_in_ready_all[8*j +: 8] & unit_sel);
          wire q_pop  = lane_out_valid[j] && u_out_ready;
          always @(posedge clk_i) begin
            if (!rst_ni) begin
              q_wr <= {QAW{1'b0}};
              q_rd <= {QAW{1'b0}};
            end else begin
              if (q_push) q_wr <= (q_wr == q_last) ? {QAW{1'b0}} : q_wr + 1'b1;
              if (q_pop)  q_rd <= (q_rd == q_last) ? {QAW{1'b0}} : q_rd + 1'b1;
            end
          end
          always @(posedge clk_i) begin
            if (q_push) q_mem[q_wr] <= ut_in;
          end
          assign ut_u_in = 1'b0;
          assign ut_b    = q_mem[q_rd];
          wire unused_u_out = &{1'b0, ut_u_out};
        end else begin : g_sbt
          assign ut_u_in = ut_in;
          assign ut_b    = ut_u_out;
        end
      end else begin : g_no_units
        assign ut_b   = ut_in;
        assign spec_b = {SPW{1'b0}};
        assign u_in_ready_all[8*j +: 8]  = 8'd0;
        assign u_out_valid_all[8*j +: 8] = 8'd0;
        assign lane_out_valid[j] = 1'b0;
        wire unused_x = &{1'b0, x_f, spec_b, mat_we_u, mat_n_u, mat_thr_u, mat_coef_u};
      end
      // what the back's first stage takes: the units' output, or with CSER the held pass for channels 1, 2
      wire [UTW-1:0] ut_x;
      wire [SPW-1:0] spec_x;
      if (CSER != 0) begin : g_hold_b
        reg [UTW-1:0] ut_h_q;
        reg [SPW-1:0] spec_h_q;
        always @(posedge clk_i) begin
          if (u_out_ready) begin
            ut_h_q   <= ut_b;
            spec_h_q <= spec_b;
          end
        end
        assign ut_x   = (ser == 2'd0) ? ut_b : ut_h_q;
        assign spec_x = (ser == 2'd0) ? spec_b : spec_h_q;
      end else begin : g_direct_b
        assign ut_x   = ut_b;
        assign spec_x = spec_b;
      end
      if (j == 0) begin : g_ftag_out
        assign bk_ftag = ut_x[UTW-1:SBW];
      end

      wire [CL-1:0] bk_diff;
      wire [PW-1:0] bk_att;
      if (DIFFUSE != 0) begin : g_bk_d
        assign bk_diff = ut_x[OFF_D +: CL];
      end else begin : g_bk_no_d
        assign bk_diff = {CL{1'b0}};
      end
      if (ANY_ATT != 0) begin : g_bk_a
        assign bk_att = ut_x[OFF_A +: PW];
      end else begin : g_bk_no_a
        assign bk_att = {PW{1'b0}};
      end
      // the specular value: the unit's, or with a shininess below 2^LNB the low chain's (unnormalised)
      wire [SPW-1:0] spec_s;
      if (HAS_LO != 0) begin : g_bk_lo
        assign spec_s = lo_mode ? {{(SPW-VF-1){1'b0}}, ut_x[OFF_LO +: VF+1]} : spec_x;
      end else begin : g_bk_no_lo
        assign spec_s = spec_x;
        wire unused_lo_mode = &{1'b0, lo_mode};
      end
      sc_light_shade #(
          .FRAC(FRAC), .NLT(NLT), .NCH(NCH), .SPW(SPW), .SG(SGUARD), .AMBIENT(AMBIENT), .DIFFUSE(DIFFUSE),
          .SPECULAR(SPECULAR), .CAN_ATT(ANY_ATT), .CSER(CSER), .SEP(HAS_SEP), .TWO(HAS_TWO), .COL(HAS_CM), .D(DB)
      ) u_shade (
          .clk_i(clk_i), .en_i(adv_b), .spec_i(spec_s), .f_i(ut_x[OFF_F]), .sep_i(sep_mode),
          .back_i(bk_ftag[2]), .bamb_i(bamb_w), .bdif_i(bdif_w), .bspec_i(bspec_w), .diff_i(bk_diff),
          .cm_i(cm_w[3:1]), .col0_i(col_b0), .col1_i(col_b1),
          .att_i(bk_att), .idx_i(ut_x[OFF_I +: 3]), .v_i(ut_x[OFF_V]), .ch_i(ser),
          .mamb_i(mamb_w), .mdif_i(mdif_w), .mspec_i(mspec_w), .lamb_i(lamb_all), .ldif_i(ldif_all),
          .lspec_i(lspec_all), .term_o(term_all[j*NCH*CL +: NCH*CL]),
          .sterm_o(sterm_all[j*NCH*CL +: NCH*CL]));
    end
  endgenerate
  // lane 0's selected unit gives the handshake (the lanes run in lock-step)
  assign u_in_ready  = |(u_in_ready_all[7:0] & unit_sel);
  assign u_out_valid = lane_out_valid[0];
  wire unused_units = &{1'b0, u_in_ready_all, u_out_valid_all, unit_sel, lane_out_valid};

  // ---------------------------------------------------------------------------- shared normalisers
  // SHARE > 1 (LANES = 1): op k of {N, V, L, H} (those that exist, in that order) enters instance
  // ⌊k/SHARE⌋ at front stage E_k ≡ k (mod SHARE) — N at 0, V at K_V mod SHARE, L at K_L mod SHARE, H at
  // T_H — so at phase ph each instance takes the op with k ≡ ph and no two ops of one pass, nor of two
  // passes (issued SHARE edges apart), meet in an instance. Each result is read at its own stage.
  // Inputs are sign-extended to the instance's widest op: the normaliser's result does not depend on
  // the input width (rtl/sc_normalize.v), so outputs are bit-identical to SHARE = 1.
  localparam integer VWX = sc_max(sc_max(NW, PW + 1), HVW_T);
  function integer op_vw(input integer k);
    op_vw = (k < K_V) ? NW : ((k < K_H) ? PW + 1 : HVW_T);
  endfunction
  function integer pool_vw(input integer i);
    integer k;
    begin
      pool_vw = 2;
      for (k = i * SH; k < (i + 1) * SH; k = k + 1) begin
        if (k < NOPS) pool_vw = sc_max(pool_vw, op_vw(k));
      end
    end
  endfunction
  generate
    if (SH > 1) begin : g_pool
      wire [4*3*VWX-1:0] ops;   // op k's vector at its entry stage, components sign-extended to VWX
      wire [3*(PW+1)-1:0] mp_e;  // −P at V's entry stage
      if (OP_V != 0) begin : g_op_v
        sc_delay #(.W(3*(PW+1)), .DEPTH(E_V)) u_dly_mp (
            .clk_i(clk_i), .en_i(adv_f), .d_i(mp_w), .q_o(mp_e));
      end else begin : g_no_op_v
        assign mp_e = {3*(PW+1){1'b0}};
        wire unused_mp = &{1'b0, mp_e, mp_w};
      end
      for (gi = 0; gi < 3; gi = gi + 1) begin : g_ops
        if (OP_N != 0) begin : g_op_n
          wire [NW-1:0] e = n_in[gi*NW +: NW];
          assign ops[gi*VWX +: VWX] = {{(VWX-NW){e[NW-1]}}, e};
        end
        if (OP_V != 0) begin : g_op_v
          wire [PW:0] e = mp_e[gi*(PW+1) +: PW+1];
          assign ops[(3*K_V + gi)*VWX +: VWX] = {{(VWX-PW-1){e[PW]}}, e};
        end
      end
      wire [3*(PW+1)-1:0] lv_e;   // P_j − P at its entry stage
      if (OP_L != 0) begin : g_op_l
        sc_delay #(.W(3*(PW+1)), .DEPTH(E_L)) u_dly_lv (
            .clk_i(clk_i), .en_i(adv_f), .d_i(lv_all[3*(PW+1)-1:0]), .q_o(lv_e));
        for (gi = 0; gi < 3; gi = gi + 1) begin : g_c
          wire [PW:0] e = lv_e[gi*(PW+1) +: PW+1];
          assign ops[(3*K_L + gi)*VWX +: VWX] = {{(VWX-PW-1){e[PW]}}, e};
        end
      end else begin : g_no_op_l
        assign lv_e = {3*(PW+1){1'b0}};
        wire unused_lv_e = &{1'b0, lv_e, lv_all};
      end
      if (OP_H != 0) begin : g_op_h
        for (gi = 0; gi < 3; gi = gi + 1) begin : g_c
          wire [HVW_T-1:0] e = hv_all[gi*HVW_T +: HVW_T];
          assign ops[(3*K_H + gi)*VWX +: VWX] = {{(VWX-HVW_T){e[HVW_T-1]}}, e};
        end
      end else begin : g_no_op_h
        wire unused_hv = &{1'b0, hv_all};
      end
      if (NOPS < 4) begin : g_ops_pad
        assign ops[4*3*VWX-1:NOPS*3*VWX] = {((4-NOPS)*3*VWX){1'b0}};
      end
      wire [4*3*NV-1:0] pu;   // instance i's result at [3*NV*i +: 3*NV]
      for (u = 0; u < NPOOL; u = u + 1) begin : g_inst
        localparam integer PVW = pool_vw(u);
        reg [3*PVW-1:0] pin;
        integer k, cc;
        always @* begin
          pin = {3*PVW{1'b0}};
          for (k = u * SH; k < (u + 1) * SH; k = k + 1) begin
            if (k < NOPS && {30'd0, ph} == k % SH) begin
              for (cc = 0; cc < 3; cc = cc + 1) pin[cc*PVW +: PVW] = ops[(3*k + cc)*VWX +: PVW];
            end
          end
        end
        wire [3*PVW-1:0] pass_unused;
        sc_normalize #(.FRAC(VF), .VW(PVW), .MREG(MREG)) u_norm (
            .clk_i(clk_i), .en_i(adv_f), .v_i(pin), .u_o(pu[u*3*NV +: 3*NV]), .v_o(pass_unused));
      end
      if (NPOOL < 4) begin : g_pu_pad
        assign pu[4*3*NV-1:NPOOL*3*NV] = {((4-NPOOL)*3*NV){1'b0}};
      end
      assign pool_nhat = pu[(0 / SH)*3*NV +: 3*NV];
      assign pool_vhat = pu[(K_V / SH)*3*NV +: 3*NV];
      assign pool_lhat = pu[(K_L / SH)*3*NV +: 3*NV];
      assign pool_hhat = pu[(K_H / SH)*3*NV +: 3*NV];
      wire unused_ops = &{1'b0, ops, pu};
    end else begin : g_no_pool
      assign pool_nhat = {3*NV{1'b0}};
      assign pool_vhat = {3*NV{1'b0}};
      assign pool_lhat = {3*NV{1'b0}};
      assign pool_hhat = {3*NV{1'b0}};
      wire unused_pool = &{1'b0, lv_all, hv_all, mp_w};
    end
  endgenerate

  // ---------------------------------------------------------------------------- back: accumulate, clamp
  // {tag, last} to the output stage (NB), first (and with CSER the item's channel) to its input (NB-1);
  // with CSER an item is its fragment's last only as the last pass's channel 2
  wire [TAGW:0] tl_out;
  wire item_last = bk_ftag[0] && (CSER == 0 || ser == 2'd2);
  sc_delay #(.W(TAGW+1), .DEPTH(NB)) u_dly_btag (
      .clk_i(clk_i), .en_i(adv_b), .d_i({bk_ftag[TAGW+2:3], item_last}), .q_o(tl_out));
  assign out_tag_o = tl_out[TAGW:1];
  assign out_last  = tl_out[0];
  wire first_acc;
  wire [1:0] ch_acc;   // CSER: the channel the accumulator adds this edge
  wire back_acc;       // TWO_SIDE: the item's fragment is lit as a back face (the back scene term)
  sc_delay #(.W(4), .DEPTH(NB-1)) u_dly_bfirst (
      .clk_i(clk_i), .en_i(adv_b), .d_i({ser, bk_ftag[2:1]}), .q_o({ch_acc, back_acc, first_acc}));
  wire acc_en = adv_b && vb_q[NB-2];

  // COL_MAT: the fragment's scene term e + a·A, formed at B0 from its bank's registers with the fragment's colour
  // in place of e (emission) or a (ambient, ambient and diffuse), and delayed to the accumulator beside
  // first_acc; without colour material it is the register-only term of its bank, bit for bit
  wire [NCH*CL-1:0] scene_acc;
  generate
    if (HAS_CM != 0 && AMBIENT != 0) begin : g_scene_cm
      wire [NCH*CL-1:0] sc0;
      wire [NCH*CL-1:0] em_bk0 = (HAS_TWO != 0 && bk_ftag[2]) ? bem_w : em_w;
      wire [NCH*CL-1:0] am_bk0 = (HAS_TWO != 0 && bk_ftag[2]) ? bamb_w : mamb_w;
      for (c = 0; c < NCH; c = c + 1) begin : g_sc
        sc_light_scene #(.FRAC(FRAC), .MREG(DB)) u_scene (
            .clk_i(clk_i), .en_i(adv_b),
            .em_i(cm_w[0] ? col_b0[c*CL +: CL] : em_bk0[c*CL +: CL]),
            .am_i(cm_w[1] ? col_b0[c*CL +: CL] : am_bk0[c*CL +: CL]),
            .ga_i(ga_w[c*CL +: CL]), .scene_o(sc0[c*CL +: CL]));
      end
      sc_delay #(.W(NCH*CL), .DEPTH(NB-1-DB)) u_dly_scene (
          .clk_i(clk_i), .en_i(adv_b), .d_i(sc0), .q_o(scene_acc));
    end else begin : g_no_scene_cm
      assign scene_acc = {(NCH*CL){1'b0}};
      wire unused_scene_cm = &{1'b0, em_w, bem_w, ga_w, cm_w[0]};
    end
  endgenerate

  wire [NCH*CL-1:0] out_w, outs_w;
  generate
    for (c = 0; c < NCH; c = c + 1) begin : g_acc
      localparam integer TOTW = CL + 4;   // <= 9 addends of <= 2^F
      localparam integer TC = (CSER != 0) ? 0 : c;   // where a lane's term of this channel is
      localparam integer CI = c;
      wire ch_on = (CSER == 0) || (ch_acc == CI[1:0]);
      // the primary sum (from the scene term) and, with SEP_SPEC, the specular sum (from 0), each saturated
      localparam integer NSUM = (HAS_SEP != 0) ? 2 : 1;
      wire [NSUM*CL-1:0] acc_w;
      for (gi = 0; gi < NSUM; gi = gi + 1) begin : g_sum
        reg [CL-1:0]   acc_q;
        reg [TOTW-1:0] tot;
        integer        k;
        wire [NLN*NCH*CL-1:0] terms = (gi == 0) ? term_all : sterm_all;
        wire [CL-1:0] start = (gi != 0) ? {CL{1'b0}} :
                              (HAS_CM != 0) ? scene_acc[c*CL +: CL] :
                              ((HAS_TWO != 0 && back_acc) ? bscene_w[c*CL +: CL] : scene_w[c*CL +: CL]);
        always @* begin
          tot = {{(TOTW-CL){1'b0}}, first_acc ? start : acc_q};
          for (k = 0; k < NLN; k = k + 1) begin
            tot = tot + {{(TOTW-CL){1'b0}}, terms[(k*NCH + TC)*CL +: CL]};
          end
        end
        always @(posedge clk_i) begin
          if (acc_en && ch_on) acc_q <= (tot > {{(TOTW-CL){1'b0}}, ONE}) ? ONE : tot[CL-1:0];
        end
        assign acc_w[gi*CL +: CL] = acc_q;
      end
      // the separate mode: the primary and the specular sum apart (the single mode's specular sum is 0)
      if (HAS_SEP != 0) begin : g_sep_out
        assign out_w[c*CL +: CL]  = acc_w[CL-1:0];
        assign outs_w[c*CL +: CL] = acc_w[NSUM*CL-1:CL];
      end else begin : g_one_out
        assign out_w[c*CL +: CL]  = acc_w[CL-1:0];
        assign outs_w[c*CL +: CL] = {CL{1'b0}};
      end
    end
    if (HAS_SEP == 0) begin : g_no_sep
      wire unused_sep = &{1'b0, sterm_all};
    end
    if (HAS_TWO == 0) begin : g_no_two
      wire unused_two = &{1'b0, two_mode, bamb_w, bscene_w, bdif_w, bspec_w, back_acc, in_back_i, hold_back_q};
    end
  endgenerate

  assign out_r_o  = out_w[CL-1:0];
  assign out_sr_o = outs_w[CL-1:0];
  generate
    if (NCH == 3) begin : g_rgb
      assign out_g_o  = out_w[2*CL-1:CL];
      assign out_b_o  = out_w[3*CL-1:2*CL];
      assign out_sg_o = outs_w[2*CL-1:CL];
      assign out_sb_o = outs_w[3*CL-1:2*CL];
    end else begin : g_mono
      assign out_g_o  = {CL{1'b0}};
      assign out_b_o  = {CL{1'b0}};
      assign out_sg_o = {CL{1'b0}};
      assign out_sb_o = {CL{1'b0}};
    end
  endgenerate

endmodule

`default_nettype wire
