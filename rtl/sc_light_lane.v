// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_light_lane.v
// Purpose  : one lane of the lighting core's front (rtl/sc_light.v): for the light slot a pass gives
//            it, the unit direction L̂, the attenuation 1/q, N̂·L and the specular unit's input x,
//            bit for bit as LightCore::eval() (cmodel/include/shadecore/light.hpp). One global
//            enable (en_i, the core's front-advancing condition); every box a register stage.
//            Vectors, N̂·L, R and x carry VF = F + SG fraction bits (SG = SGUARD of rtl/sc_light.v,
//            the specular path's extra bits); the distance, diff and att have F.
//
//   Slot registers are read through the slot index that travels with the pass (idx_i at stage 0,
//   delayed here to every stage that reads a register; they cannot change while a pass is in flight).
//   L̂     directional: the position register (a unit direction code, F+8 bits) saturated to the
//          signed F+2 bits of [−2, 2), · 2^SG (L, H, N̂·L and R are VF+2 / VF+3 bits wide, not F+8+SG);
//          point: sc_normalize(P_j − P) at VF (P_j − P F+9 bits, also passed through for the distance)
//   att    A1 d = max(⌊(P_j−P)·L̂ / 2^VF⌋, 0); A2 dd = ⌊d²/2^F⌋, ⌊kl·d/2^F⌋; A3 q = kc + ⌊kl·d/2^F⌋ +
//          ⌊kq·dd/2^F⌋; sc_recip(q) — for point_att; 2^F for every other kind
//   spot   (CAN_SPOT, kind spot) S1 (T_L+1) sdl = ⌊−(L̂·ŝ) / 2^VF⌋, ŝ the spot direction register
//          (F+2 bits) · 2^SG; S2 (T_L+2) in = sdl >= the spot cos register, x = clamp(sdl, 0,
//          2^VF); rtl/sc_powi.v x^e at VF over 8 stages (0 outside the
//          cone; with MREG two edges per stage) → T_SP = T_L+2+D+8·(1+MREG_POWI·MREG); att · spot registered at max(T_ATT, T_SP)+1 (⌊att·spot / 2^VF⌋ for spot)
//   ndl    ⌊N̂·L / 2^VF⌋ → diff = clamp(⌊ndl / 2^SG⌋, 0, 2^F), f = ndl > 0
//   x      Blinn: Ĥ = sc_normalize(L̂ + V̂), x = ⌊N̂·Ĥ / 2^VF⌋; Phong: R = ⌊ndl·N̂ / 2^(VF−1)⌋ − L̂,
//          x = ⌊R·V̂ / 2^VF⌋ (= R_z when only V = (0, 0, 1) exists); saturated to the unit's VF+2-bit
//          word, at T_X = max(T_XB, T_XP) of the reflections that exist (phong_i chooses when both do),
//          then delayed to T_F
//   low    (LOW_N, rtl/sc_light.v's low_shininess) rtl/sc_powi.v x_lo = clamp(x, 0, 2^VF)^n at VF over LNB
//          stages from T_X (two edges each with MREG; lo_e_i = the low bits of the shininess register; exact chain,
//          x^0 = 1), to T_F
// Parameters: FRAC, SG, NLT (slots), capabilities CAN_DIR / CAN_PT (point, point_att or spot) / CAN_ATT
//             (point_att or spot) / CAN_SPOT, NEED_N,
//             SPECULAR, DIFFUSE, BLINN, PHONG, LV, and the stage times of rtl/sc_light.v's header
//             (T_L, T_A, T_H, T_RV, T_XB, T_XP, T_ATT, T_SP = T_L+2+D+SEB·(1+MREG_POWI·MREG), T_F); SEB (spot exponent bits,
//             SPOT_EXP_BITS); LOW_N, LNB (LOW_N_BITS: the low-shininess chain's stages, T_F >= T_X+LNB·(1+MREG_POWI·MREG));
//             SH (SHARE of rtl/sc_light.v: the lane's
//             dot-product multipliers are shared by ops whose stages differ mod SH, chosen by the
//             phase ph_i; "dot-product multipliers" below); EXT_NORM = 1 (rtl/sc_light.v's SHARE > 1):
//             L̂ and Ĥ are normalised outside the lane by the core's shared normalisers — the lane
//             hands out P_j − P (stage 0, lv_o) and H (stage T_H, hv_o) and takes L̂ (T_L, lhat_i) and
//             Ĥ (T_H+NL, hhat_i); with EXT_NORM = 0 these ports are unused and the lane has its own.
//             MREG: rtl/sc_light.v's pipelining parameter, passed to the lane's own normalisers.
// Ports     : clk_i, en_i; idx_i (slot, stage 0); p_i (fragment position, stage 0); nn_a_i (N̂ at
//             T_A), nn_b_i (N̂ at T_H+NL), nn_p_i (N̂ at T_A+1), v_h_i (V̂ at T_H), v_p_i (V̂ at T_RV);
//             phong_i (mode); pos_i, katt_i, kind_i, sdir_i, scos_i, sexp_i (every slot's registers,
//             packed as sc_light_regfile.v); lo_e_i (LOW_N: the shininess's low LNB bits); outputs at
//             T_F: x_o, diff_o, f_o, att_o, idx_o, lo_o (LOW_N: x^n of the chain, else 0); EXT_NORM's
//             lv_o, hv_o, lhat_i, hhat_i (above).
// ============================================================================================
`default_nettype none

module sc_light_lane #(
    parameter integer FRAC     = 16,
    parameter integer SG       = 0,
    parameter integer NLT      = 1,
    parameter integer CAN_DIR  = 1,
    parameter integer CAN_PT   = 0,
    parameter integer CAN_ATT  = 0,
    parameter integer CAN_SPOT = 0,
    parameter integer NEED_N   = 1,
    parameter integer SPECULAR = 1,
    parameter integer DIFFUSE  = 1,
    parameter integer BLINN    = 1,
    parameter integer PHONG    = 0,
    parameter integer LV       = 0,
    parameter integer T_L      = 0,
    parameter integer T_A      = 0,
    parameter integer T_H      = 0,
    parameter integer T_RV     = 0,
    parameter integer T_XB     = 0,
    parameter integer T_XP     = 0,
    parameter integer T_ATT    = 0,
    parameter integer T_SP     = 0,
    parameter integer SEB      = 8,
    parameter integer LOW_N    = 0,
    parameter integer LNB      = 4,
    parameter integer T_F      = 1,
    parameter integer EXT_NORM = 0,
    parameter integer SH       = 1,
    parameter integer MREG     = 0
) (
    input  wire                      clk_i,
    input  wire                      en_i,
    input  wire [2:0]                idx_i,
    input  wire [3*(FRAC+8)-1:0]     p_i,
    input  wire [3*(FRAC+SG+2)-1:0]  nn_a_i,
    input  wire [3*(FRAC+SG+2)-1:0]  nn_b_i,
    input  wire [3*(FRAC+SG+2)-1:0]  nn_p_i,
    input  wire [3*(FRAC+SG+2)-1:0]  v_h_i,
    input  wire [3*(FRAC+SG+2)-1:0]  v_p_i,
    input  wire                      phong_i,
    input  wire [NLT*3*(FRAC+8)-1:0] pos_i,
    input  wire [NLT*3*(FRAC+8)-1:0] katt_i,
    input  wire [NLT*2-1:0]          kind_i,
    input  wire [NLT*3*(FRAC+2)-1:0] sdir_i,
    input  wire [NLT*(FRAC+SG+2)-1:0] scos_i,
    input  wire [NLT*SEB-1:0]        sexp_i,
    input  wire [LNB-1:0]            lo_e_i,
    output wire [FRAC+SG+1:0]        x_o,
    output wire [FRAC+SG:0]          lo_o,
    output wire [FRAC:0]             diff_o,
    output wire                      f_o,
    output wire [FRAC+7:0]           att_o,
    output wire [2:0]                idx_o,
    output wire [3*(FRAC+9)-1:0]     lv_o,
    output wire [3*(FRAC+SG+3)-1:0]  hv_o,
    input  wire [3*(FRAC+SG+2)-1:0]  lhat_i,
    input  wire [3*(FRAC+SG+2)-1:0]  hhat_i,
    input  wire [1:0]                ph_i
);

`include "sc_light_regs.vh"
  localparam integer MPW = MREG_POWI * MREG;   // each power-chain stage's extra edge (rtl/sc_powi.v MREG)
  localparam integer D = MREG_DOT * MREG;   // the dot products' (and R's products') extra stages (rtl/sc_light.v)
  localparam integer DL = (D > 0) ? D : 1;  // their sc_mul_reg's latency (LAT)

  localparam integer F   = FRAC;
  localparam integer VF  = FRAC + SG;                        // fraction bits of the specular path
  localparam integer NW  = VF + 2;                           // normalised vectors, x
  localparam integer PW  = FRAC + 8;
  localparam integer CL  = FRAC + 1;
  localparam integer LW  = NW;   // component width of L: L̂, or a directional light's unit direction (saturated)
  localparam integer HVW = LW + 1;                           // of H = L + V
  localparam integer NDF = NW + LW + 2 - VF;                 // of ⌊N̂·L / 2^VF⌋, exact
  localparam integer NDW = NW + 2;                           // of ndl: ⌊N̂·L / 2^VF⌋ saturated to [−8, 8)
  localparam integer RVF = NDW + 4;                          // of R = 2·ndl·N̂ − L, exact
  localparam integer RVW = NW + 2;                           // of R saturated to [−8, 8) per component
  localparam integer NEED_L = (NEED_N != 0 || CAN_ATT != 0) ? 1 : 0;
  localparam integer POINT_L = (CAN_PT != 0 && NEED_L != 0) ? 1 : 0;   // an L̂ = normalise(P_j − P)
  localparam [PW-1:0] ATT_ONE = {{7{1'b0}}, 1'b1, {FRAC{1'b0}}};

  genvar gi, k;

  // ---------------------------------------------------------------------------- dot-product multipliers
  // Six triplets of signed products, op: the NW-bit side × the other side, at a stage:
  //   0 A1  L̂ · (P_j − P)   at T_L      (point_att)     1 NL  N̂ · L        at T_A   (N̂·L)
  //   2 R   N̂ · ndl         at T_A+1    (Phong)         3 RV  V̂ · R        at T_RV  (Phong, local viewer)
  //   4 NH  N̂ · Ĥ           at T_XB−1   (Blinn)         5 S1  ŝ · L̂        at T_L+1 (spot)
  // One rtl/sc_mul_pool.v per component: each op k that exists joins the first multiplier instance
  // with no op at a stage ≡ its stage (mod SH): with SH = 1 every op has its own three multipliers
  // (the products as written out before); with SHARE > 1 an instance multiplies, at phase ph_i, the
  // operands of its op whose stage ≡ ph_i — the pass at that stage is exactly there — and every op
  // reads its product combinationally at its own stage.
  localparam integer NOP = 6;
  localparam integer BMX = (PW + 1 > RVW) ? PW + 1 : RVW;   // the widest other side (RVW = NDW >= LW, NW)
  localparam integer PMX = NW + BMX;
  localparam integer SMX = PMX + 2;             // a dot product: the sum of an op's three products
  function integer op_on(input integer o);
    op_on = (o == 0) ? CAN_ATT : (o == 1) ? NEED_N : (o == 2) ? ((SPECULAR != 0 && PHONG != 0) ? 1 : 0) :
            (o == 3) ? ((SPECULAR != 0 && PHONG != 0 && LV != 0) ? 1 : 0) :
            (o == 4) ? ((SPECULAR != 0 && BLINN != 0) ? 1 : 0) : CAN_SPOT;
  endfunction
  function integer op_stage(input integer o);
    op_stage = (o == 0) ? T_L : (o == 1) ? T_A : (o == 2) ? T_A + 1 + D : (o == 3) ? T_RV : (o == 4) ? T_XB - 1 - D :
               T_L + 1;
  endfunction
  function integer op_bw(input integer o);
    op_bw = (o == 0) ? PW + 1 : (o == 1) ? LW : (o == 2) ? NDW : (o == 3) ? RVW : (o == 4) ? NW : LW;
  endfunction
  // the packed parameters of rtl/sc_mul_pool.v: op o's field f (0 on, 1 stage, 2 b width) at [8o +: 8]
  function [63:0] op_pack(input integer f);
    integer o, v;
    begin
      op_pack = 64'd0;
      for (o = 0; o < NOP; o = o + 1) begin
        v = (f == 0) ? op_on(o) : (f == 1) ? op_stage(o) : op_bw(o);
        op_pack = op_pack | ({32'd0, v} << (8 * o));   // every v < 256
      end
    end
  endfunction
  function integer op_mask(input integer dummy);
    integer o;
    begin
      op_mask = dummy;
      for (o = 0; o < NOP; o = o + 1) op_mask = op_mask | (op_on(o) << o);
    end
  endfunction
  localparam [63:0] OP_ST = op_pack(1);
  localparam [63:0] OP_BW = op_pack(2);
  localparam [63:0] OP_AW = {16'd0, {6{NW[7:0]}}};
  localparam integer OP_ON = op_mask(0);
  wire [NOP*3*NW-1:0]  opa;    // op o, component c at [(3o+c)*NW +: NW]
  wire [NOP*3*BMX-1:0] opb;    // sign-extended to BMX
  wire [NOP*3*PMX-1:0] prod;   // its product, sign-extended to PMX
  wire [NOP*SMX-1:0]   dsum;   // op o's dot product at [o*SMX +: SMX] (exact; consumers read its low bits)
  wire unused_dsum = &{1'b0, dsum};   // each consumer reads the low bits its op needs
  wire [NOP-1:0] op_sel;       // op o's pass is at its stage (the phase)
  generate
    for (k = 0; k < NOP; k = k + 1) begin : g_op_sel
      localparam integer RI = op_stage(k) % SH;
      assign op_sel[k] = (SH == 1) || (ph_i == RI[1:0]);
    end
    if (D != 0) begin : g_dot_reg
      // MREG (SHARE = 1): each op's products through rtl/sc_mul_reg.v, D stages later (LAT = D = 2: each product's
      // tree to two carry-save rows | register | the rows reduced and added | register): a dot product as one sum
      // of three products (N = 3), R's three products (op 2) each on its own
      for (k = 0; k < NOP; k = k + 1) begin : g_k
        localparam integer BK = op_bw(k);
        wire [3*NW-1:0] ak;
        wire [3*BK-1:0] bk;
        for (gi = 0; gi < 3; gi = gi + 1) begin : g_ab
          assign ak[gi*NW +: NW] = opa[(3*k + gi)*NW +: NW];
          assign bk[gi*BK +: BK] = opb[(3*k + gi)*BMX +: BK];   // the low bits of the sign-extended operand
        end
        if (op_on(k) == 0) begin : g_off
          assign prod[3*k*PMX +: 3*PMX] = {3*PMX{1'b0}};
          wire unused_ab = &{1'b0, ak, bk};
        end else if (k == 2) begin : g_each
          for (gi = 0; gi < 3; gi = gi + 1) begin : g_p
            sc_mul_reg #(.AW(NW), .BW(BK), .PW(PMX), .SIGNED(1), .LAT(DL)) u_p (
                .clk_i(clk_i), .en_i(en_i), .a_i(ak[gi*NW +: NW]), .b_i(bk[gi*BK +: BK]), .c_i(1'b0),
                .p_o(prod[(3*k + gi)*PMX +: PMX]));
          end
        end else begin : g_dot
          assign prod[3*k*PMX +: 3*PMX] = {3*PMX{1'b0}};
          sc_mul_reg #(.AW(NW), .BW(BK), .PW(SMX), .SIGNED(1), .N(3), .LAT(DL)) u_dot (
              .clk_i(clk_i), .en_i(en_i), .a_i(ak), .b_i(bk), .c_i(1'b0), .p_o(dsum[k*SMX +: SMX]));
        end
        if (BMX > BK) begin : g_bhi
          wire unused_bhi = &{1'b0, opb[3*k*BMX +: 3*BMX]};
        end
      end
      wire unused_sel = &{1'b0, op_sel};
    end else begin : g_pool
    // one pool per component: op o's component c is at [o*NW +: NW] / [o*BMX +: BMX] of pool c
    for (gi = 0; gi < 3; gi = gi + 1) begin : g_c
      wire [NOP*NW-1:0]  a_c;
      wire [NOP*BMX-1:0] b_c;
      wire [NOP*PMX-1:0] p_c;
      for (k = 0; k < NOP; k = k + 1) begin : g_k
        assign a_c[k*NW +: NW]   = opa[(3*k + gi)*NW +: NW];
        assign b_c[k*BMX +: BMX] = opb[(3*k + gi)*BMX +: BMX];
        assign prod[(3*k + gi)*PMX +: PMX] = p_c[k*PMX +: PMX];
      end
      sc_mul_pool #(
          .NOP(NOP), .SH(SH), .ON(OP_ON), .ST(OP_ST), .AW(OP_AW), .BW(OP_BW), .AMX(NW), .BMX(BMX), .SIGNED(1)
      ) u_mul (
          .clk_i(clk_i), .en_i(en_i), .a_i(a_c), .b_i(b_c), .sel_i(op_sel), .p_o(p_c));
    end
    end
    for (k = 0; k < NOP; k = k + 1) begin : g_op_off
      if (op_on(k) == 0) begin : g_off
        assign opa[k*3*NW +: 3*NW]   = {3*NW{1'b0}};
        assign opb[k*3*BMX +: 3*BMX] = {3*BMX{1'b0}};
        assign dsum[k*SMX +: SMX] = {SMX{1'b0}};
      end else if (D != 0 && k == 2) begin : g_prod_only
        assign dsum[k*SMX +: SMX] = {SMX{1'b0}};   // R's products are used one by one
      end else if (D == 0) begin : g_on
        wire [PMX-1:0] p0 = prod[(3*k + 0)*PMX +: PMX];
        wire [PMX-1:0] p1 = prod[(3*k + 1)*PMX +: PMX];
        wire [PMX-1:0] p2 = prod[(3*k + 2)*PMX +: PMX];
        assign dsum[k*SMX +: SMX] = {{2{p0[PMX-1]}}, p0} + {{2{p1[PMX-1]}}, p1} + {{2{p2[PMX-1]}}, p2};
      end
    end
  endgenerate
  wire unused_prod = &{1'b0, prod, opa, opb};

  // ---------------------------------------------------------------------------- slot index per stage
  wire [3*(T_F+1)-1:0] idx_s;   // the slot index at stage k at [3k +: 3]
  assign idx_s[2:0] = idx_i;
  generate
    for (k = 1; k <= T_F; k = k + 1) begin : g_idx
      reg [2:0] idx_q;
      always @(posedge clk_i) begin
        if (en_i) idx_q <= idx_s[3*(k-1) +: 3];
      end
      assign idx_s[3*k +: 3] = idx_q;
    end
  endgenerate
  assign idx_o = idx_s[3*T_F +: 3];
  wire [2:0] idx_0 = idx_s[2:0];
  // MREG with T_L >= 1: the slot's kind and position are read one stage before T_L and the directional L and
  // the kind test registered, so that T_L's N̂·L product starts from registers (the registers of the slots
  // hold while a fragment is in flight: reg_ready_o of rtl/sc_light.v)
  localparam integer PRE_L = (MREG != 0 && T_L >= 1) ? 1 : 0;
  wire [2:0] idx_l = idx_s[3*(T_L-PRE_L) +: 3];
  wire [1:0] kind_l = kind_i[2*idx_l +: 2];
  wire [3*PW-1:0] pos_0 = pos_i[3*PW*idx_0 +: 3*PW];
  wire [3*PW-1:0] pos_l = pos_i[3*PW*idx_l +: 3*PW];

  // ---------------------------------------------------------------------------- L (and the distance)
  wire [3*LW-1:0]     l;      // unit direction to the light at T_L
  wire [3*(PW+1)-1:0] dv_d;   // P_j − P at T_L (point lights)
  wire [3*NW-1:0]     l_pt;   // L̂ of a point light at T_L
  generate
    if (POINT_L != 0) begin : g_l_point
      wire [3*(PW+1)-1:0] dv;
      for (gi = 0; gi < 3; gi = gi + 1) begin : g_dv
        wire [PW-1:0] pj = pos_0[gi*PW +: PW];
        wire [PW-1:0] pf = p_i[gi*PW +: PW];
        assign dv[gi*(PW+1) +: PW+1] = {pj[PW-1], pj} - {pf[PW-1], pf};
      end
      if (EXT_NORM != 0) begin : g_ext_l
        assign lv_o = dv;
        assign l_pt = lhat_i;
        sc_delay #(.W(3*(PW+1)), .DEPTH(T_L)) u_dly_dv (
            .clk_i(clk_i), .en_i(en_i), .d_i(dv), .q_o(dv_d));
      end else begin : g_own_l
        assign lv_o = {3*(PW+1){1'b0}};
        wire unused_lhat = &{1'b0, lhat_i};
        // MREG: P_j − P registered first (MREG_P; an input's subtraction and S1's squares in one stage miss
        // 4.0 ns); T_L of rtl/sc_light.v counts it
        wire [3*(PW+1)-1:0] dv_q;
        sc_delay #(.W(3*(PW+1)), .DEPTH(MREG_P * MREG)) u_dly_dvq (
            .clk_i(clk_i), .en_i(en_i), .d_i(dv), .q_o(dv_q));
        sc_normalize #(.FRAC(VF), .VW(PW+1), .MREG(MREG)) u_norm_l (
            .clk_i(clk_i), .en_i(en_i), .v_i(dv_q), .u_o(l_pt), .v_o(dv_d));
      end
    end else begin : g_no_point
      assign l_pt = {3*NW{1'b0}};
      assign dv_d = {3*(PW+1){1'b0}};
      assign lv_o = {3*(PW+1){1'b0}};
      wire unused_pt = &{1'b0, l_pt, dv_d, p_i, pos_0, lhat_i};
    end
    for (gi = 0; gi < 3; gi = gi + 1) begin : g_lsel
      wire [LW-1:0] lp_w = l_pt[gi*NW +: NW];   // L̂ (LW = NW)
      // directional: the register holds a unit direction; its code saturated to the signed F+2 bits
      // of [−2, 2) (out of contract beyond), then · 2^SG
      wire [FRAC+1:0]  pd_s;
      sc_sat #(.IW(PW), .OW(FRAC+2)) u_sat_ld (.d_i(pos_l[gi*PW +: PW]), .q_o(pd_s));
      wire [LW-1:0]    ld_w;
      if (SG > 0) begin : g_ld_sg
        assign ld_w = {pd_s, {SG{1'b0}}};
      end else begin : g_ld
        assign ld_w = pd_s;
      end
      wire [LW-1:0]    ld_l;   // ld_w at T_L
      wire             dir_l;  // the slot is directional, at T_L
      sc_delay #(.W(LW + 1), .DEPTH(PRE_L)) u_dly_ld (
          .clk_i(clk_i), .en_i(en_i), .d_i({kind_l == KIND_DIRECTIONAL[1:0], ld_w}), .q_o({dir_l, ld_l}));
      if (CAN_DIR != 0 && POINT_L != 0) begin : g_both
        assign l[gi*LW +: LW] = dir_l ? ld_l : lp_w;
      end else if (CAN_DIR != 0) begin : g_dir
        assign l[gi*LW +: LW] = ld_l;
        wire unused_dir = &{1'b0, dir_l};
        wire unused_lp = &{1'b0, lp_w};
      end else begin : g_pt
        assign l[gi*LW +: LW] = lp_w;
        wire unused_ld = &{1'b0, ld_l, dir_l};
      end
    end
    if (CAN_DIR == 0 || POINT_L == 0) begin : g_kind_unused
      wire unused_kind_l = &{1'b0, kind_l, pos_l};
    end
  endgenerate

  // ---------------------------------------------------------------------------- spot factor (spot)
  wire [VF:0]   spot_f;    // the spot factor at T_SP (VF fraction bits, <= 2^VF)
  generate
    if (CAN_SPOT != 0 && T_SP != T_L + 2 + D + SEB * (1 + MPW)) begin : g_check_tsp
      sc_light_lane_error_T_SP_must_be_T_L_plus_2_plus_D_plus_SEB_times_1_plus_MREG_POWI_MREG u_error ();
    end
    // rtl/sc_powi.v with MREG takes two edges per stage; configs.json's mreg_powi states it for the schedule
    if (MREG != 0 && MREG_POWI != 1) begin : g_check_mreg_powi
      sc_light_lane_error_light_latency_mreg_powi_must_be_1 u_error ();
    end
    if (CAN_SPOT != 0) begin : g_spot
      wire [2:0] idx_s1 = idx_s[3*(T_L+1) +: 3];
      wire [2:0] idx_s2 = idx_s[3*(T_L+2+D) +: 3];
      wire [3*LW-1:0] l_s1;
      sc_delay #(.W(3*LW), .DEPTH(1)) u_dly_ls (
          .clk_i(clk_i), .en_i(en_i), .d_i(l), .q_o(l_s1));
      for (gi = 0; gi < 3; gi = gi + 1) begin : g_op_s1
        wire [FRAC+1:0] sd = sdir_i[(3*idx_s1 + gi)*(FRAC+2) +: FRAC+2];
        wire [LW-1:0] b = l_s1[gi*LW +: LW];
        if (SG > 0) begin : g_sg
          assign opa[(15 + gi)*NW +: NW] = {sd, {SG{1'b0}}};
        end else begin : g_nsg
          assign opa[(15 + gi)*NW +: NW] = sd;
        end
        assign opb[(15 + gi)*BMX +: BMX] = {{(BMX-LW){b[LW-1]}}, b};
      end
      // S1: sdl = ⌊−(ŝ·L̂) / 2^VF⌋, exact (VF+7 bits)
      localparam integer SSW = NW + LW + 2;
      localparam integer SDW = SSW + 1 - VF;
      wire [SSW-1:0] ssum = dsum[5*SMX +: SSW];
      wire [SSW:0]   nsum = {SSW+1{1'b0}} - {ssum[SSW-1], ssum};
      wire unused_nsum = &{1'b0, nsum[VF-1:0]};
      reg  [SDW-1:0] sdl_q;
      always @(posedge clk_i) begin
        if (en_i) sdl_q <= nsum[SSW:VF];
      end
      // S2: in = sdl >= cos (signed), x = clamp(sdl, 0, 2^VF)
      wire [VF+1:0]  scos = scos_i[idx_s2*(VF+2) +: VF+2];
      wire [SDW-1:0] scos_x = {{(SDW-VF-2){scos[VF+1]}}, scos};
      wire           in_cone = $signed(sdl_q) >= $signed(scos_x);
      wire [VF:0]    sx;
      sc_clamp01 #(.IW(SDW), .FRAC(VF)) u_clamp_sx (.d_i(sdl_q), .q_o(sx));
      localparam integer PH0 = (T_L + 2 + D) % SH;
      sc_powi #(.FRAC(VF), .EB(SEB), .SH(SH), .PH0(PH0), .MREG(MREG)) u_powi (
          .clk_i(clk_i), .en_i(en_i), .x_i(sx), .e_i(sexp_i[SEB*idx_s2 +: SEB]), .zero_i(!in_cone),
          .ph_i(ph_i), .r_o(spot_f));
    end else begin : g_no_spot
      assign spot_f = {(VF+1){1'b0}};
      wire unused_spot = &{1'b0, sdir_i, scos_i, sexp_i};
    end
  endgenerate

  // ---------------------------------------------------------------------------- attenuation (point_att, spot)
  wire [FRAC+7:0] att_f;   // att at T_F
  generate
    if (CAN_ATT != 0) begin : g_att
      localparam integer DW = FRAC + 9;    // distance d < 2^(F+9) (|P_j − P| < √3·2^(F+8))
      localparam integer QW = FRAC + 27;   // q = kc + kl·d + kq·d² < 2^(F+27)
      wire [2:0] idx_a1 = idx_s[3*(T_L+1+D) +: 3];
      wire [2:0] idx_a2 = idx_s[3*(T_L+2+D) +: 3];
      wire [2:0] idx_t  = idx_s[3*T_ATT +: 3];
      localparam integer DDW = 2 * DW - F;
      // A1 (T_L+1): dl = ⌊(P_j − P)·L̂ / 2^VF⌋, d = max(dl, 0)
      for (gi = 0; gi < 3; gi = gi + 1) begin : g_op_a1
        wire [PW:0] b = dv_d[gi*(PW+1) +: PW+1];
        assign opa[(0 + gi)*NW +: NW]   = l_pt[gi*NW +: NW];
        assign opb[(0 + gi)*BMX +: BMX] = {{(BMX-PW-1){b[PW]}}, b};
      end
      wire [PW+NW+2:0] dla = dsum[0*SMX +: PW+NW+3];
      wire [DW-1:0] d_d = dla[PW+NW+2] ? {DW{1'b0}} : dla[VF+DW-1:VF];
      wire unused_dla = &{1'b0, dla[PW+NW+1:VF+DW], dla[VF-1:0]};
      reg [DW-1:0] a1_d_q;
      always @(posedge clk_i) begin
        if (en_i) a1_d_q <= d_d;
      end
      localparam integer MQ = MREG_ATT * MREG;   // q's extra stages (MREG, at every SHARE)
      // the cuts below make q MREG_ATT = 2 and sc_recip MREG_RECIP = 4 edges longer; configs.json states them for the
      // schedule (T_ATT here and the C model's light_pipe): another value there stops elaboration, not the co-simulation
      if (MREG != 0 && (MREG_ATT != 2 || MREG_RECIP != 4)) begin : g_check_mreg_att
        sc_light_lane_error_light_latency_mreg_att_must_be_2_and_mreg_recip_4 u_error ();
      end
      wire [QW-1:0] q_d;
      reg  [QW-1:0] q_q;   // q at T_L+3+D+MQ (MREG, or SH = 1) or T_L+4 (SH > 1 without MREG)
      always @(posedge clk_i) begin
        if (en_i) q_q <= q_d;
      end
      if (MQ != 0) begin : g_q5
        // MREG: the same q over MQ = 2 more edges, each product through rtl/sc_mul_reg.v (LAT = 2), with the
        // slot's kl, kc (and kq) read a stage early and registered, so that no slot multiplexer and no
        // separate adder stands in front of a tree. kc + ⌊kl·d / 2^F⌋ = ⌊(kl·d + kc·2^F) / 2^F⌋ and
        // q = s + ⌊kq·dd / 2^F⌋ = ⌊(kq·dd + s·2^F) / 2^F⌋ exactly (kc·2^F and s·2^F are multiples of 2^F):
        //   A2 (T_L+1+D, two edges): dd = ⌊d·d / 2^F⌋, s = ⌊(kl·d + kc·2^F) / 2^F⌋
        //   A3 (T_L+3+D, two edges): q = ⌊(kq·⌊dd / 2^F⌋ + s·2^F) / 2^F⌋ mod 2^QW (sc_mul_reg LAT = 1: its
        //   register on the tree's carry-save rows, its adder in front of q_q)
        wire [2:0] idx_a0 = idx_s[3*(T_L+D) +: 3];
        wire [2:0] idx_q2 = idx_s[3*(T_L+2+D) +: 3];
        wire unused_idx_a = &{1'b0, idx_a1, idx_a2};
        reg [PW-1:0] kl_q, kc_q, kq_q;
        always @(posedge clk_i) begin
          if (en_i) begin
            kl_q <= katt_i[(3*idx_a0 + 1)*PW +: PW];
            kc_q <= katt_i[(3*idx_a0 + 0)*PW +: PW];
            kq_q <= katt_i[(3*idx_q2 + 2)*PW +: PW];
          end
        end
        localparam integer KW = PW + DW + 1;   // kl·d + kc·2^F < 2^(PW+DW) + 2^(PW+F)
        // d·d is a square: sc_mul_reg LAT = 1 (the cell flow maps a square with one register) and dd's own
        // register after it, the same two edges as LAT = 2
        wire [2*DW-1:0] dd_p;
        wire [KW-1:0]   s_p;
        sc_mul_reg #(.AW(DW), .BW(DW), .PW(2*DW), .LAT(1)) u_dd (
            .clk_i(clk_i), .en_i(en_i), .a_i(a1_d_q), .b_i(a1_d_q), .c_i(1'b0), .p_o(dd_p));
        reg [DDW-1:0] a3_dd_q;
        always @(posedge clk_i) begin
          if (en_i) a3_dd_q <= dd_p[2*DW-1:F];
        end
        sc_mul_reg #(.AW(PW), .BW(DW), .PW(KW), .ADD(1), .CW(PW+F), .LAT(2)) u_s (
            .clk_i(clk_i), .en_i(en_i), .a_i(kl_q), .b_i(a1_d_q), .c_i({kc_q, {F{1'b0}}}), .p_o(s_p));
        wire [QW+F-1:0] q_p;
        sc_mul_reg #(.AW(PW), .BW(DDW), .PW(QW+F), .ADD(1), .CW(KW), .LAT(1)) u_q (
            .clk_i(clk_i), .en_i(en_i), .a_i(kq_q), .b_i(a3_dd_q), .c_i({s_p[KW-1:F], {F{1'b0}}}),
            .p_o(q_p));
        wire unused_q = &{1'b0, dd_p[F-1:0], s_p[F-1:0], q_p[F-1:0]};
        assign q_d = q_p[QW+F-1:F];
      end else if (SH == 1) begin : g_q3
        // A2: dd = ⌊d² / 2^F⌋, kld = ⌊kl·d / 2^F⌋; A3: q = kc + kld + ⌊kq·dd / 2^F⌋
        wire [PW-1:0] kl = katt_i[(3*idx_a1 + 1)*PW +: PW];
        wire [PW-1:0] kc = katt_i[(3*idx_a2 + 0)*PW +: PW];
        wire [PW-1:0] kq = katt_i[(3*idx_a2 + 2)*PW +: PW];
        wire [2*DW-1:0]    dd_p  = {{DW{1'b0}}, a1_d_q} * {{DW{1'b0}}, a1_d_q};
        wire [PW+DW-1:0]   kld_p = {{DW{1'b0}}, kl} * {{PW{1'b0}}, a1_d_q};
        wire unused_a2 = &{1'b0, dd_p[F-1:0], kld_p[F-1:0]};
        reg [DDW-1:0]      a2_dd_q;
        reg [PW+DW-F-1:0]  a2_kld_q;
        always @(posedge clk_i) begin
          if (en_i) begin
            a2_dd_q  <= dd_p[2*DW-1:F];
            a2_kld_q <= kld_p[PW+DW-1:F];
          end
        end
        wire [PW+DDW-1:0] kqdd_p = {{DDW{1'b0}}, kq} * {{PW{1'b0}}, a2_dd_q};
        wire unused_a3 = &{1'b0, kqdd_p[F-1:0]};
        assign q_d = {{(QW-PW){1'b0}}, kc} + {{(QW-(PW+DW-F)){1'b0}}, a2_kld_q}
                   + {{(QW-(PW+DDW-F)){1'b0}}, kqdd_p[PW+DDW-1:F]};
      end else begin : g_q4
        // A2 (T_L+1): dd = ⌊d² / 2^F⌋; A3 (T_L+2): ⌊kq·dd / 2^F⌋; A4 (T_L+3): q = kc + ⌊kl·d / 2^F⌋ + that:
        // the same q one stage later, its three products at three stages in one rtl/sc_mul_pool.v instance
        wire [2:0] idx_a3 = idx_s[3*(T_L+3+D) +: 3];
        wire [PW-1:0] kq = katt_i[(3*idx_a2 + 2)*PW +: PW];
        wire [PW-1:0] kl = katt_i[(3*idx_a3 + 1)*PW +: PW];
        wire [PW-1:0] kc = katt_i[(3*idx_a3 + 0)*PW +: PW];
        wire unused_idx_a1 = &{1'b0, idx_a1};
        reg  [DDW-1:0]       a2_dd_q;
        reg  [DW-1:0]        a2_d_q, a3_d_q;
        reg  [PW+DDW-F-1:0]  a3_kqdd_q;
        localparam integer AM = DDW, BM = DW, MP = AM + BM;
        localparam integer ST1 = T_L + 1 + D, ST2 = T_L + 2 + D, ST3 = T_L + 3 + D;
        wire [3*MP-1:0] ap;   // op 0 d·d (T_L+1), 1 dd·kq (T_L+2), 2 d·kl (T_L+3)
        localparam integer RS1 = ST1 % SH, RS2 = ST2 % SH, RS3 = ST3 % SH;
        wire [2:0] asel = {ph_i == RS3[1:0], ph_i == RS2[1:0], ph_i == RS1[1:0]};
        sc_mul_pool #(
            .NOP(3), .SH(SH), .ON(7), .ST({40'd0, ST3[7:0], ST2[7:0], ST1[7:0]}),
            .AW({40'd0, DW[7:0], DDW[7:0], DW[7:0]}), .BW({40'd0, PW[7:0], PW[7:0], DW[7:0]}),
            .AMX(AM), .BMX(BM), .SIGNED(0)
        ) u_mul_att (
            .clk_i(clk_i), .en_i(en_i),
            .a_i({{(AM-DW){1'b0}}, a3_d_q, a2_dd_q, {(AM-DW){1'b0}}, a1_d_q}),
            .b_i({{(BM-PW){1'b0}}, kl, {(BM-PW){1'b0}}, kq, a1_d_q}),
            .sel_i(asel), .p_o(ap));
        wire [2*DW-1:0]   dd_p   = ap[0*MP +: 2*DW];
        wire [PW+DDW-1:0] kqdd_p = ap[1*MP +: PW+DDW];
        wire [PW+DW-1:0]  kld_p  = ap[2*MP +: PW+DW];
        wire unused_ap = &{1'b0, ap, dd_p[F-1:0], kqdd_p[F-1:0], kld_p[F-1:0]};
        always @(posedge clk_i) begin
          if (en_i) begin
            a2_dd_q   <= dd_p[2*DW-1:F];
            a2_d_q    <= a1_d_q;
            a3_kqdd_q <= kqdd_p[PW+DDW-1:F];
            a3_d_q    <= a2_d_q;
          end
        end
        assign q_d = {{(QW-PW){1'b0}}, kc} + {{(QW-(PW+DW-F)){1'b0}}, kld_p[PW+DW-1:F]}
                   + {{(QW-(PW+DDW-F)){1'b0}}, a3_kqdd_q};
      end
      // att = 1/q at T_ATT for point_att, 2^F for the other kinds; then to T_F
      wire [FRAC+7:0] att_r;
      // q at T_L+3+D+MQ (+1 with SH > 1 without MREG): the recip's products share multipliers over SH stages by
      // the phase (rtl/sc_recip.v); with MREG each of its products takes two edges (MREG_RECIP more), unshared
      sc_recip #(.FRAC(FRAC), .QW(QW), .SH(SH), .PH0((T_L + 3 + D + MQ + ((SH > 1 && MQ == 0) ? 1 : 0)) % SH),
                 .MREG(MREG)) u_recip (
          .clk_i(clk_i), .en_i(en_i), .q_i(q_q), .ph_i(ph_i), .att_o(att_r));
      wire [1:0] kind_t = kind_i[2*idx_t +: 2];
      wire [FRAC+7:0] att_k = (kind_t == KIND_POINT_ATT[1:0] || kind_t == KIND_SPOT[1:0]) ? att_r : ATT_ONE;
      if (CAN_SPOT != 0) begin : g_att_spot
        // att · spot for a spot light at T_SA = max(T_ATT, T_SP), registered at T_SA+1, then to T_F
        localparam integer T_SA = (T_ATT > T_SP) ? T_ATT : T_SP;
        wire [2:0] idx_sa = idx_s[3*T_SA +: 3];
        wire [1:0] kind_sa = kind_i[2*idx_sa +: 2];
        wire [FRAC+7:0] att_sa;
        wire [VF:0]     sp_sa;
        sc_delay #(.W(FRAC+8), .DEPTH(T_SA - T_ATT)) u_dly_att_sa (
            .clk_i(clk_i), .en_i(en_i), .d_i(att_k), .q_o(att_sa));
        sc_delay #(.W(VF+1), .DEPTH(T_SA - T_SP)) u_dly_sp_sa (
            .clk_i(clk_i), .en_i(en_i), .d_i(spot_f), .q_o(sp_sa));
        // ⌊att·spot / 2^VF⌋ <= att (spot <= 2^VF)
        wire [FRAC+7:0] att_sa_w;   // registered at T_SA+1
        if (MREG != 0) begin : g_as_m
          // MREG: the product with its register (rtl/sc_mul_reg.v, the adder after it, in front of the delay
          // registers to T_F) and the kind's choice in front of the tree instead of after it: a light that is not
          // a spot multiplies by 2^VF, ⌊att·2^VF / 2^VF⌋ = att. The same value at the same stage
          wire [VF:0]        s_x = (kind_sa == KIND_SPOT[1:0]) ? sp_sa : {1'b1, {VF{1'b0}}};
          wire [FRAC+VF+8:0] as_q;
          sc_mul_reg #(.AW(FRAC+8), .BW(VF+1), .PW(FRAC+VF+9), .LAT(1)) u_as (
              .clk_i(clk_i), .en_i(en_i), .a_i(att_sa), .b_i(s_x), .c_i(1'b0), .p_o(as_q));
          wire unused_as = &{1'b0, as_q[FRAC+VF+8], as_q[VF-1:0]};
          assign att_sa_w = as_q[VF +: FRAC+8];
        end else begin : g_as
          wire [FRAC+VF+8:0] as_p = {{(VF+1){1'b0}}, att_sa} * {{(FRAC+8){1'b0}}, sp_sa};
          wire unused_as = &{1'b0, as_p[FRAC+VF+8], as_p[VF-1:0]};
          reg [FRAC+7:0] att_sa_q;
          always @(posedge clk_i) begin
            if (en_i) att_sa_q <= (kind_sa == KIND_SPOT[1:0]) ? as_p[VF +: FRAC+8] : att_sa;
          end
          assign att_sa_w = att_sa_q;
        end
        sc_delay #(.W(FRAC+8), .DEPTH(T_F - T_SA - 1)) u_dly_att (
            .clk_i(clk_i), .en_i(en_i), .d_i(att_sa_w), .q_o(att_f));
      end else begin : g_att_plain
        wire unused_spot_f = &{1'b0, spot_f};
        sc_delay #(.W(FRAC+8), .DEPTH(T_F - T_ATT)) u_dly_att (
            .clk_i(clk_i), .en_i(en_i), .d_i(att_k), .q_o(att_f));
      end
    end else begin : g_no_att
      assign att_f = ATT_ONE;
      wire unused_att = &{1'b0, katt_i, dv_d, spot_f};
    end
  endgenerate
  assign att_o = att_f;

  // ---------------------------------------------------------------------------- N̂·L, diffuse factor, front-facing
  wire [3*LW-1:0] l_a;     // L at T_A
  wire [NDW-1:0]  ndl;     // ⌊N̂·L / 2^F⌋ at T_A+1
  wire [CL-1:0]   diff_f;
  wire            f_f;
  generate
    if (NEED_N != 0) begin : g_ndl
      sc_delay #(.W(3*LW), .DEPTH(T_A - T_L)) u_dly_la (
          .clk_i(clk_i), .en_i(en_i), .d_i(l), .q_o(l_a));
      for (gi = 0; gi < 3; gi = gi + 1) begin : g_op_nl
        wire [LW-1:0] b = l_a[gi*LW +: LW];
        assign opa[(3 + gi)*NW +: NW]   = nn_a_i[gi*NW +: NW];
        assign opb[(3 + gi)*BMX +: BMX] = {{(BMX-LW){b[LW-1]}}, b};
      end
      wire [NW+LW+1:0] nsum = dsum[1*SMX +: NW+LW+2];
      wire unused_nsum = &{1'b0, nsum[VF-1:0]};
      // ndl saturated to [−8, 8): never with a unit L (|N| < 2√3); only a directional code beyond [−2, 2)
      // could reach it, and there diff (clamped to 1) and f (the sign) are unchanged
      wire [NDW-1:0] ndl_d;
      sc_sat #(.IW(NDF), .OW(NDW)) u_sat_ndl (.d_i(nsum[NW+LW+1:VF]), .q_o(ndl_d));
      reg [NDW-1:0] ndl_q;
      always @(posedge clk_i) begin
        if (en_i) ndl_q <= ndl_d;
      end
      assign ndl = ndl_q;
      localparam integer NSW = NDW - SG;   // ⌊ndl / 2^SG⌋: F fraction bits
      wire          neg   = ndl_q[NDW-1];
      wire [CL-1:0] diff1;
      // MREG (D != 0): the clamp takes ndl before its register and diff1 gets its own CL flip-flops beside
      // ndl_q, so that a set whose back takes diff at once (no units) starts the diffuse products' trees at a
      // flip-flop, not behind the clamp; the same value at the same stage
      wire [NSW-1:0] clamp_in = (D != 0) ? ndl_d[NDW-1:SG] : ndl_q[NDW-1:SG];
      wire [CL-1:0]  clamp_q;
      sc_clamp01 #(.IW(NSW), .FRAC(FRAC)) u_clamp_diff (.d_i(clamp_in), .q_o(clamp_q));
      sc_delay #(.W(CL), .DEPTH((D != 0) ? 1 : 0)) u_dly_clamp (
          .clk_i(clk_i), .en_i(en_i), .d_i(clamp_q), .q_o(diff1));
      wire          f1    = !neg && (ndl_q != {NDW{1'b0}});
      if (DIFFUSE != 0) begin : g_diff
        sc_delay #(.W(CL), .DEPTH(T_F - T_A - 1 - D)) u_dly_diff (
            .clk_i(clk_i), .en_i(en_i), .d_i(diff1), .q_o(diff_f));
      end else begin : g_no_diff
        assign diff_f = {CL{1'b0}};
        wire unused_diff = &{1'b0, diff1};
      end
      if (SPECULAR != 0) begin : g_f
        sc_delay #(.W(1), .DEPTH(T_F - T_A - 1 - D)) u_dly_f (
            .clk_i(clk_i), .en_i(en_i), .d_i(f1), .q_o(f_f));
      end else begin : g_no_f
        assign f_f = 1'b0;
        wire unused_f = &{1'b0, f1};
      end
    end else begin : g_no_ndl
      assign l_a    = {3*LW{1'b0}};
      assign ndl    = {NDW{1'b0}};
      assign diff_f = {CL{1'b0}};
      assign f_f    = 1'b0;
      wire unused_ndl = &{1'b0, l, l_a, ndl, nn_a_i};
    end
  endgenerate
  assign diff_o = diff_f;
  assign f_o    = f_f;

  // ---------------------------------------------------------------------------- x: the unit's input
  localparam integer HAS_XB = (SPECULAR != 0 && BLINN != 0) ? 1 : 0;
  localparam integer HAS_XP = (SPECULAR != 0 && PHONG != 0) ? 1 : 0;
  localparam integer T_X = (SPECULAR == 0) ? T_F :                                        // x of either reflection
                           (((HAS_XB != 0 && T_XB > T_XP) || HAS_XP == 0) ? T_XB : T_XP);
  wire [NW-1:0] xb_f, xp_f;   // Blinn's and Phong's x at T_X
  wire [NW-1:0] x_t;          // the mode's x at T_X
  generate
    if (SPECULAR != 0 && BLINN != 0) begin : g_blinn
      // H = L + V at T_H (V = (0, 0, 2^F) unless local viewer), Ĥ at T_H+NL
      wire [3*LW-1:0] l_h;
      sc_delay #(.W(3*LW), .DEPTH(T_H - T_L)) u_dly_lh (
          .clk_i(clk_i), .en_i(en_i), .d_i(l), .q_o(l_h));
      wire [3*HVW-1:0] h;
      for (gi = 0; gi < 3; gi = gi + 1) begin : g_h
        wire [LW-1:0] lc = l_h[gi*LW +: LW];
        wire [NW-1:0] vc = v_h_i[gi*NW +: NW];
        assign h[gi*HVW +: HVW] = {lc[LW-1], lc} + {{(HVW-NW){vc[NW-1]}}, vc};
      end
      wire [3*NW-1:0]  hn;
      if (EXT_NORM != 0) begin : g_ext_h
        assign hv_o = h;
        assign hn = hhat_i;
      end else begin : g_own_h
        assign hv_o = {3*HVW{1'b0}};
        wire unused_hhat = &{1'b0, hhat_i};
        wire [3*HVW-1:0] h_pass_unused;
        sc_normalize #(.FRAC(VF), .VW(HVW), .MREG(MREG)) u_norm_h (
            .clk_i(clk_i), .en_i(en_i), .v_i(h), .u_o(hn), .v_o(h_pass_unused));
      end
      // x = ⌊N̂·Ĥ / 2^VF⌋ (T_XB = T_H+NL+1)
      for (gi = 0; gi < 3; gi = gi + 1) begin : g_op_nh
        wire [NW-1:0] b = hn[gi*NW +: NW];
        assign opa[(12 + gi)*NW +: NW]   = nn_b_i[gi*NW +: NW];
        assign opb[(12 + gi)*BMX +: BMX] = {{(BMX-NW){b[NW-1]}}, b};
      end
      wire [2*NW+1:0] xsum = dsum[4*SMX +: 2*NW+2];
      localparam integer XFW = 2 * NW + 2 - VF;
      wire [XFW-1:0] xs = xsum[2*NW+1:VF];
      wire unused_xsum = &{1'b0, xsum[VF-1:0]};
      wire [NW-1:0] x_s;   // saturated to the unit's word, registered at T_XB, then to T_X
      sc_sat #(.IW(XFW), .OW(NW)) u_sat_x (.d_i(xs), .q_o(x_s));
      sc_delay #(.W(NW), .DEPTH(T_X - T_XB + 1)) u_dly_x (
          .clk_i(clk_i), .en_i(en_i), .d_i(x_s), .q_o(xb_f));
    end else begin : g_no_blinn
      assign xb_f = {NW{1'b0}};
      assign hv_o = {3*HVW{1'b0}};
      wire unused_b = &{1'b0, nn_b_i, v_h_i, hhat_i};
    end
    if (SPECULAR != 0 && PHONG != 0) begin : g_phong
      // R = ((ndl·N̂) >> (VF−1)) − L at T_A+1 (L delayed to T_A+1), registered at T_A+2
      wire [3*LW-1:0] l1;
      sc_delay #(.W(3*LW), .DEPTH(1 + 2 * D)) u_dly_l1 (
          .clk_i(clk_i), .en_i(en_i), .d_i(l_a), .q_o(l1));
      wire [3*RVW-1:0] rv;
      for (gi = 0; gi < 3; gi = gi + 1) begin : g_r
        assign opa[(6 + gi)*NW +: NW]   = nn_p_i[gi*NW +: NW];
        assign opb[(6 + gi)*BMX +: BMX] = {{(BMX-NDW){ndl[NDW-1]}}, ndl};
        wire [NDW+NW-1:0] rp = prod[(6 + gi)*PMX +: NDW+NW];
        wire [NDW+2:0] rs = rp[NDW+NW-1:VF-1];
        wire unused_rp = &{1'b0, rp[VF-2:0]};
        wire [LW-1:0] lc = l1[gi*LW +: LW];
        wire [RVF-1:0] rf = {rs[NDW+2], rs} - {{(RVF-LW){lc[LW-1]}}, lc};
        // saturated to [−8, 8): never with a unit N̂ and L (|R| = 1); the R·V̂ product is then 23 × 25
        // bits at F = 16, spec_guard 5 (two DSP48E1 instead of four)
        sc_sat #(.IW(RVF), .OW(RVW)) u_sat_r (.d_i(rf), .q_o(rv[gi*RVW +: RVW]));
      end
      if (LV != 0) begin : g_lv
        // x = ⌊R·V̂ / 2^VF⌋ at T_RV+1 (V̂ = (0, 0, 2^F) without the local-viewer mode: x = R_z)
        reg [3*RVW-1:0] rv_q;
        always @(posedge clk_i) begin
          if (en_i) rv_q <= rv;
        end
        wire [3*RVW-1:0] rv_d;
        sc_delay #(.W(3*RVW), .DEPTH(T_RV - T_A - 2 - 2 * D)) u_dly_rv (
            .clk_i(clk_i), .en_i(en_i), .d_i(rv_q), .q_o(rv_d));
        for (gi = 0; gi < 3; gi = gi + 1) begin : g_op_rv
          assign opa[(9 + gi)*NW +: NW]   = v_p_i[gi*NW +: NW];
          assign opb[(9 + gi)*BMX +: BMX] = rv_d[gi*RVW +: RVW];
        end
        wire [RVW+NW+1:0] xsum = dsum[3*SMX +: RVW+NW+2];
        localparam integer XFW = RVW + NW + 2 - VF;
        wire [XFW-1:0] xs = xsum[RVW+NW+1:VF];
        wire unused_xsum = &{1'b0, xsum[VF-1:0]};
        wire [NW-1:0] x_s;
        sc_sat #(.IW(XFW), .OW(NW)) u_sat_x (.d_i(xs), .q_o(x_s));
        sc_delay #(.W(NW), .DEPTH(T_X - T_XP + 1)) u_dly_x (
            .clk_i(clk_i), .en_i(en_i), .d_i(x_s), .q_o(xp_f));
      end else begin : g_inf
        // V = (0, 0, 1): x = R_z exactly (T_A+2)
        wire [RVW-1:0] xs = rv[2*RVW +: RVW];
        wire unused_rxy = &{1'b0, rv[2*RVW-1:0], v_p_i};
        wire [NW-1:0] x_s;
        sc_sat #(.IW(RVW), .OW(NW)) u_sat_x (.d_i(xs), .q_o(x_s));
        sc_delay #(.W(NW), .DEPTH(T_X - T_XP + 1)) u_dly_x (
            .clk_i(clk_i), .en_i(en_i), .d_i(x_s), .q_o(xp_f));
      end
    end else begin : g_no_phong
      assign xp_f = {NW{1'b0}};
      wire unused_p = &{1'b0, nn_p_i, v_p_i, ndl};
    end
    if (SPECULAR != 0 && BLINN != 0 && PHONG != 0) begin : g_x_both
      assign x_t = phong_i ? xp_f : xb_f;
    end else if (SPECULAR != 0 && PHONG != 0) begin : g_x_phong
      assign x_t = xp_f;
      wire unused_xb = &{1'b0, xb_f, phong_i};
    end else begin : g_x_blinn
      assign x_t = xb_f;
      wire unused_xp = &{1'b0, xp_f, phong_i};
    end
    sc_delay #(.W(NW), .DEPTH(T_F - T_X)) u_dly_xt (
        .clk_i(clk_i), .en_i(en_i), .d_i(x_t), .q_o(x_o));
    // x^n for a shininess below the units' range: the exact chain on clamp(x, 0, 1) from T_X, LNB stages
    if (SPECULAR != 0 && LOW_N != 0) begin : g_low
      if (T_F < T_X + LNB * (1 + MPW)) begin : g_check_tlo
        sc_light_lane_error_T_F_must_be_at_least_T_X_plus_LNB_times_1_plus_MREG_POWI_MREG u_error ();
      end
      wire [VF:0] lx, lo_r;
      sc_clamp01 #(.IW(NW), .FRAC(VF)) u_clamp_lx (.d_i(x_t), .q_o(lx));
      sc_powi #(.FRAC(VF), .EB(LNB), .SH(SH), .PH0(T_X % SH), .MREG(MREG)) u_powi_lo (
          .clk_i(clk_i), .en_i(en_i), .x_i(lx), .e_i(lo_e_i), .zero_i(1'b0), .ph_i(ph_i), .r_o(lo_r));
      sc_delay #(.W(VF+1), .DEPTH(T_F - T_X - LNB * (1 + MPW))) u_dly_lo (
          .clk_i(clk_i), .en_i(en_i), .d_i(lo_r), .q_o(lo_o));
    end else begin : g_no_low
      assign lo_o = {(VF+1){1'b0}};
      wire unused_lo = &{1'b0, lo_e_i};
    end
    if (SPECULAR != 0 && BLINN != 0 && PHONG == 0) begin : g_ndl_b
      wire unused_ndl_b = &{1'b0, ndl};   // Blinn needs only diff and f of N̂·L
    end
  endgenerate

endmodule

`default_nettype wire
