// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_light_regfile.v
// Purpose  : register file of the lighting core rtl/sc_light.v (bit for bit LightRegs::write and
//            LightCore::modes() of cmodel/include/shadecore/light.hpp; map: config/configs.json
//            "light", generated into sc_light_regs.vh).
//
//   A write (wr_i: the core's reg_we_i && reg_ready_o) stores the low bits of the register's width;
//   other addresses, reserved ones and the registers of absent capabilities are ignored. Registers
//   are not reset. The register-only scene term e + a·A is recomputed into a register at every edge:
//   one edge behind a write, before any fragment needs it (a write only happens with the core empty,
//   and the first fragment after it needs it later). The per-light ambient product a·Ia_j is formed
//   per pass in rtl/sc_light_shade.v (one multiplier per lane and channel, not one per slot).
//
//   Mode decode (docs/lighting.md §4): a light slot is on when its mode's enable bit is set and its
//   kind is one the slot can take (SLOT_KINDS, SLOT_SPOT for kind 3); local viewer and normalize are on only where the
//   hardware exists; the reflection is Phong when bit 1 is set and Phong exists, or when only Phong
//   exists; mat_unit selects the unit with that variant id, and a variant that is absent selects the
//   first unit for transport with its specular term forced to 0 (unit_kill_o).
//
// Parameters: as rtl/sc_light.v (FRAC, SLOT_KINDS, SLOT_SPOT, AMBIENT, DIFFUSE, UNITS, ENERGY, BLINN,
//             PHONG, LOCAL_VIEWER, NORMALIZE, CHANNELS); NLT, NCH, AW as the core computes them;
//             UFRAC = FRAC + SGUARD, the units' format (mat_thr UFRAC+1 bits, mat_coef UFRAC+8).
// Ports     : clk_i; wr_i, addr_i[AW-1:0], data_i[31:0] (a write this edge);
//             per slot j, packed at j: pos_o (3 × F+8), katt_o (kc, kl, kq × F+8), kind_o (2 bits, the
//             register's kind), on_o (1 bit), spot (slots that can be spot, else 0): sdir_o (3 × F+2),
//             scos_o (UFRAC+2), sexp_o (SEB = SPOT_EXP_BITS of sc_light_regs.vh, from rtl/sc_light.v), lamb_o (per channel Ia_jc, F+1 bits),
//             ldif_o, lspec_o (per channel F+1); material: scene_o (min(e + a·A >> F, 2^F)), mdif_o,
//             mspec_o; unit: mat_we_o, mat_n_o, mat_thr_o, mat_coef_o (the values after this edge's
//             write, with mat_we_o at the write edge), unit_sel_o (one-hot over variant ids),
//             unit_kill_o; modes: lv_o, phong_o, normalize_o, sep_o (light_model bit 4 with SEP), two_o (bit 3
//             with TWO_SIDE); TWO_SIDE's back colour bank bamb_o, bscene_o, bdif_o, bspec_o (0 without it);
//             the scene term's operands em_o, bem_o (emission, front and back), ga_o (global ambient);
//             COL_MAT's cm_o = {specular, diffuse, ambient, emission}: what the fragment colour replaces.
// ============================================================================================
`default_nettype none

module sc_light_regfile #(
    parameter integer FRAC         = 16,
    parameter integer UFRAC        = 16,
    parameter integer SLOT_KINDS   = 1,
    parameter integer SLOT_SPOT    = 0,
    parameter integer SEB          = 8,
    parameter integer AMBIENT      = 1,
    parameter integer DIFFUSE      = 1,
    parameter integer UNITS        = 1,
    parameter integer ENERGY       = 0,
    parameter integer BLINN        = 1,
    parameter integer PHONG        = 0,
    parameter integer LOCAL_VIEWER = 0,
    parameter integer NORMALIZE    = 1,
    parameter integer SEP          = 0,
    parameter integer TWO_SIDE     = 0,
    parameter integer COL_MAT      = 0,
    parameter integer NLT          = 1,
    parameter integer NCH          = 3,
    parameter integer AW           = 9,
    parameter integer MREG         = 0
) (
    input  wire                  clk_i,
    input  wire                  wr_i,
    input  wire [AW-1:0]         addr_i,
    input  wire [31:0]           data_i,
    output wire [NLT*3*(FRAC+8)-1:0] pos_o,
    output wire [NLT*3*(FRAC+8)-1:0] katt_o,
    output wire [NLT*2-1:0]      kind_o,
    output wire [NLT-1:0]        on_o,
    output wire [NLT*3*(FRAC+2)-1:0] sdir_o,
    output wire [NLT*(UFRAC+2)-1:0]  scos_o,
    output wire [NLT*SEB-1:0]    sexp_o,
    output wire [NLT*NCH*(FRAC+1)-1:0] lamb_o,
    output wire [NCH*(FRAC+1)-1:0] mamb_o,
    output wire [NLT*NCH*(FRAC+1)-1:0] ldif_o,
    output wire [NLT*NCH*(FRAC+1)-1:0] lspec_o,
    output wire [NCH*(FRAC+1)-1:0] scene_o,
    output wire [NCH*(FRAC+1)-1:0] mdif_o,
    output wire [NCH*(FRAC+1)-1:0] mspec_o,
    output wire [NCH*(FRAC+1)-1:0] bamb_o,
    output wire [NCH*(FRAC+1)-1:0] bscene_o,
    output wire [NCH*(FRAC+1)-1:0] bdif_o,
    output wire [NCH*(FRAC+1)-1:0] bspec_o,
    output wire [NCH*(FRAC+1)-1:0] em_o,
    output wire [NCH*(FRAC+1)-1:0] bem_o,
    output wire [NCH*(FRAC+1)-1:0] ga_o,
    output wire [3:0]            cm_o,
    output wire                  mat_we_o,
    output wire [10:0]           mat_n_o,
    output wire [UFRAC:0]        mat_thr_o,
    output wire [UFRAC+7:0]      mat_coef_o,
    output wire [7:0]            unit_sel_o,
    output wire                  unit_kill_o,
    output wire                  lv_o,
    output wire                  phong_o,
    output wire                  normalize_o,
    output wire                  sep_o,
    output wire                  two_o
);

`include "sc_light_regs.vh"

  localparam integer F  = FRAC;
  localparam integer PW = FRAC + 8;
  localparam integer CL = FRAC + 1;
  localparam integer SPECULAR = (UNITS != 0) ? 1 : 0;
  localparam integer LV = (SPECULAR != 0 && LOCAL_VIEWER != 0) ? 1 : 0;

  function integer reg_at(input [AW-1:0] base, input integer off);
    reg_at = {{(32-AW){1'b0}}, base} + off;
  endfunction
  function integer slot_kinds(input integer j);
    slot_kinds = (SLOT_KINDS >> (3 * j)) & 7;
  endfunction
  function integer first_unit(input integer dummy);
    integer v;
    begin
      first_unit = 0;
      for (v = 7; v >= 0; v = v - 1) begin
        if (((UNITS >> v) & 1) != 0) first_unit = v;
      end
      first_unit = first_unit + 0 * dummy;
    end
  endfunction

  wire unused_data = &{1'b0, data_i};   // which bits are read depends on the capabilities
  genvar j, c, gi;

  // ---------------------------------------------------------------------------- global modes
  // light_model: one register of the fields this core has (positions LM_* from config/configs.json
  // light_model_bits); a field of an absent capability reads 0 (no flip-flop)
  localparam [LIGHT_MODEL_BITS-1:0] LM_HAS =
      (((SPECULAR != 0 || NORMALIZE != 0) ? 1 : 0) << LM_LOCAL_VIEWER) |
      (((SPECULAR != 0 || NORMALIZE != 0) ? 1 : 0) << LM_PHONG) |
      (((SPECULAR != 0 || NORMALIZE != 0) ? 1 : 0) << LM_NORMALIZE) |
      (((TWO_SIDE != 0) ? 1 : 0) << LM_TWO_SIDE) |
      (((SEP != 0) ? 1 : 0) << LM_SEPARATE_SPECULAR);
  wire [LIGHT_MODEL_BITS-1:0] model_w;
  generate
    for (gi = 0; gi < LIGHT_MODEL_BITS; gi = gi + 1) begin : g_model
      if (LM_HAS[gi]) begin : g_bit
        reg b_q;
        always @(posedge clk_i) begin
          if (wr_i && addr_i == REG_LIGHT_MODEL) b_q <= data_i[gi];
        end
        assign model_w[gi] = b_q;
      end else begin : g_none
        assign model_w[gi] = 1'b0;
      end
    end
  endgenerate
  assign lv_o        = (LV != 0) && model_w[LM_LOCAL_VIEWER];
  assign phong_o     = (SPECULAR != 0) && (PHONG != 0) && (BLINN == 0 || model_w[LM_PHONG]);
  assign normalize_o = (NORMALIZE != 0) && model_w[LM_NORMALIZE];
  assign two_o       = model_w[LM_TWO_SIDE];       // GL_LIGHT_MODEL_TWO_SIDE
  assign sep_o       = model_w[LM_SEPARATE_SPECULAR];  // GL_SEPARATE_SPECULAR_COLOR

  // ---------------------------------------------------------------------------- material colours, scene term
  // bank 0 the front material (mat_*), bank 1 with TWO_SIDE the back colour bank (back_mat_*: two-sided lighting)
  localparam integer NBK = (TWO_SIDE != 0) ? 2 : 1;
  wire [NCH*CL-1:0]   mamb_w;
  wire [NCH*CL-1:0]   ga_w;          // global ambient
  wire [2*NCH*CL-1:0] em_bk, amb_bk, dif_bk, spec_bk, scene_bk;
  generate
    for (c = 0; c < NCH; c = c + 1) begin : g_ga
      localparam integer A_GA = reg_at(REG_GLOBAL_AMBIENT, c);
      if (AMBIENT != 0) begin : g_amb
        reg [CL-1:0] ga_q;
        always @(posedge clk_i) begin
          if (wr_i && addr_i == A_GA[AW-1:0]) ga_q <= data_i[CL-1:0];
        end
        assign ga_w[c*CL +: CL] = ga_q;
      end else begin : g_no_amb
        assign ga_w[c*CL +: CL] = {CL{1'b0}};
      end
    end
    for (gi = 0; gi < 2; gi = gi + 1) begin : g_bank
      for (c = 0; c < NCH; c = c + 1) begin : g_mat
        localparam integer O = (gi * NCH + c) * CL;
        localparam integer A_EM = reg_at((gi == 0) ? REG_MAT_EMISSION : REG_BACK_MAT_EMISSION, c);
        localparam integer A_MA = reg_at((gi == 0) ? REG_MAT_AMBIENT : REG_BACK_MAT_AMBIENT, c);
        localparam integer A_MD = reg_at((gi == 0) ? REG_MAT_DIFFUSE : REG_BACK_MAT_DIFFUSE, c);
        localparam integer A_MS = reg_at((gi == 0) ? REG_MAT_SPECULAR : REG_BACK_MAT_SPECULAR, c);
        if (AMBIENT != 0 && gi < NBK) begin : g_amb
          reg [CL-1:0] em_q, mamb_q, scene_q;
          always @(posedge clk_i) begin
            if (wr_i && addr_i == A_EM[AW-1:0]) em_q   <= data_i[CL-1:0];
            if (wr_i && addr_i == A_MA[AW-1:0]) mamb_q <= data_i[CL-1:0];
          end
          wire [CL-1:0] sc;
          // (MREG: two edges from a write to scene_q; no fragment is in flight then, and the first one after it
          // reaches the accumulator T_F + NB >= 4 edges after it is taken)
          sc_light_scene #(.FRAC(FRAC), .MREG(MREG)) u_scene (
              .clk_i(clk_i), .en_i(1'b1), .em_i(em_q), .am_i(mamb_q), .ga_i(ga_w[c*CL +: CL]), .scene_o(sc));
          always @(posedge clk_i) begin
            scene_q <= sc;
          end
          assign em_bk[O +: CL]    = em_q;
          assign amb_bk[O +: CL]   = mamb_q;
          assign scene_bk[O +: CL] = scene_q;
        end else begin : g_no_amb
          assign em_bk[O +: CL]    = {CL{1'b0}};
          assign amb_bk[O +: CL]   = {CL{1'b0}};
          assign scene_bk[O +: CL] = {CL{1'b0}};
        end
        if (DIFFUSE != 0 && gi < NBK) begin : g_dif
          reg [CL-1:0] mdif_q;
          always @(posedge clk_i) begin
            if (wr_i && addr_i == A_MD[AW-1:0]) mdif_q <= data_i[CL-1:0];
          end
          assign dif_bk[O +: CL] = mdif_q;
        end else begin : g_no_dif
          assign dif_bk[O +: CL] = {CL{1'b0}};
        end
        if (SPECULAR != 0 && gi < NBK) begin : g_spec
          reg [CL-1:0] mspec_q;
          always @(posedge clk_i) begin
            if (wr_i && addr_i == A_MS[AW-1:0]) mspec_q <= data_i[CL-1:0];
          end
          assign spec_bk[O +: CL] = mspec_q;
        end else begin : g_no_spec
          assign spec_bk[O +: CL] = {CL{1'b0}};
        end
      end
    end
  endgenerate
  generate
    if (AMBIENT == 0) begin : g_no_ga
      wire unused_ga = &{1'b0, ga_w};
    end
  endgenerate
  assign mamb_w   = amb_bk[NCH*CL-1:0];
  assign scene_o  = scene_bk[NCH*CL-1:0];
  assign mdif_o   = dif_bk[NCH*CL-1:0];
  assign mspec_o  = spec_bk[NCH*CL-1:0];
  assign bamb_o   = amb_bk[2*NCH*CL-1:NCH*CL];
  assign bscene_o = scene_bk[2*NCH*CL-1:NCH*CL];
  assign bdif_o   = dif_bk[2*NCH*CL-1:NCH*CL];
  assign bspec_o  = spec_bk[2*NCH*CL-1:NCH*CL];
  // colour material (COL_MAT): the scene term's operands, for the core's per-fragment scene term
  assign em_o     = em_bk[NCH*CL-1:0];
  assign bem_o    = em_bk[2*NCH*CL-1:NCH*CL];
  assign ga_o     = ga_w;

  // ---------------------------------------------------------------------------- colour material
  // GL_COLOR_MATERIAL (register colour_material: bit 0 enable, bits 3:1 the glColorMaterial mode): cm_o =
  // {specular, diffuse, ambient, emission}, the material colours the fragment's colour replaces
  generate
    if (COL_MAT != 0) begin : g_cm
      reg [3:0] cm_q;
      always @(posedge clk_i) begin
        if (wr_i && addr_i == REG_COLOUR_MATERIAL) cm_q <= data_i[3:0];
      end
      wire [2:0] md = cm_q[3:1];
      assign cm_o = cm_q[0] ? {md == 3'd3, md == 3'd2 || md == 3'd4, md == 3'd1 || md == 3'd4, md == 3'd0} : 4'd0;
    end else begin : g_no_cm
      assign cm_o = 4'd0;
    end
  endgenerate

  // ---------------------------------------------------------------------------- unit material, unit select
  // The units' own copies are loaded at the same edge with the same values (mat_we_o with the next
  // register values; legal at any write, since a write only happens with the core empty).
  generate
    if (SPECULAR != 0) begin : g_unit_mat
      wire hit_n = wr_i && (addr_i == REG_MAT_N);
      wire hit_t = wr_i && (addr_i == REG_MAT_THR);
      reg [10:0]   mat_n_q;
      reg [UFRAC:0] mat_thr_q;
      reg [3:0]    unit_q;
      assign mat_n_o   = hit_n ? data_i[10:0] : mat_n_q;
      assign mat_thr_o = hit_t ? data_i[UFRAC:0] : mat_thr_q;
      always @(posedge clk_i) begin
        mat_n_q   <= mat_n_o;
        mat_thr_q <= mat_thr_o;
        if (wr_i && addr_i == REG_MAT_UNIT) unit_q <= data_i[3:0];
      end
      if (ENERGY != 0) begin : g_coef
        wire hit_c = wr_i && (addr_i == REG_MAT_COEF);
        reg [UFRAC+7:0] mat_coef_q;
        assign mat_coef_o = hit_c ? data_i[UFRAC+7:0] : mat_coef_q;
        always @(posedge clk_i) begin
          mat_coef_q <= mat_coef_o;
        end
        assign mat_we_o = hit_n || hit_t || hit_c;
      end else begin : g_no_coef
        assign mat_coef_o = {(UFRAC+8){1'b0}};
        assign mat_we_o   = hit_n || hit_t;
      end
      // one-hot over variant ids 0..7; an absent variant: the first unit, specular forced to 0
      localparam integer FIRST = first_unit(0);
      localparam [7:0] UMASK = UNITS[7:0];
      wire present = !unit_q[3] && UMASK[unit_q[2:0]];
      for (gi = 0; gi < 8; gi = gi + 1) begin : g_sel
        if (((UNITS >> gi) & 1) != 0) begin : g_u
          assign unit_sel_o[gi] = present ? (unit_q[2:0] == gi) : (gi == FIRST);
        end else begin : g_no_u
          assign unit_sel_o[gi] = 1'b0;
        end
      end
      assign unit_kill_o = !present;
    end else begin : g_no_unit_mat
      assign mat_we_o    = 1'b0;
      assign mat_n_o     = 11'd0;
      assign mat_thr_o   = {(UFRAC+1){1'b0}};
      assign mat_coef_o  = {(UFRAC+8){1'b0}};
      assign unit_sel_o  = 8'd0;
      assign unit_kill_o = 1'b1;
    end
  endgenerate

  // ---------------------------------------------------------------------------- light slots
  generate
    for (j = 0; j < NLT; j = j + 1) begin : g_slot
      localparam integer KINDS  = slot_kinds(j);
      localparam integer CAN_D  = KINDS & 1;
      localparam integer CAN_S  = (SLOT_SPOT >> j) & 1;  // spot (kind 3)
      localparam integer CAN_PT = (((KINDS >> 1) & 3) != 0 || CAN_S != 0) ? 1 : 0;   // point, point_att or spot
      localparam integer CAN_A  = (((KINDS >> 2) & 1) != 0 || CAN_S != 0) ? 1 : 0;   // point_att or spot
      localparam integer NEED_P = ((CAN_D != 0 && (DIFFUSE != 0 || SPECULAR != 0)) || CAN_PT != 0) ? 1 : 0;
      localparam integer ABASE  = LIGHT_STRIDE * j;
      localparam integer A_MODE = reg_at(REG_LIGHT_MODE, ABASE);
      localparam integer A_POS  = reg_at(REG_LIGHT_POSITION, ABASE);
      localparam integer A_KC   = reg_at(REG_LIGHT_KC, ABASE);
      localparam integer A_KL   = reg_at(REG_LIGHT_KL, ABASE);
      localparam integer A_KQ   = reg_at(REG_LIGHT_KQ, ABASE);

      // mode: enable and kind; on when the slot can take the kind
      reg [3:0] mode_q;
      always @(posedge clk_i) begin
        if (wr_i && addr_i == A_MODE[AW-1:0]) mode_q <= data_i[3:0];
      end
      wire [2:0] kind = mode_q[3:1];
      localparam [3:0] KMASK = {CAN_S[0], KINDS[2:0]};
      assign on_o[j]         = mode_q[0] && !kind[2] && KMASK[kind[1:0]];
      assign kind_o[2*j +: 2] = kind[1:0];

      if (NEED_P != 0) begin : g_pos
        for (gi = 0; gi < 3; gi = gi + 1) begin : g_c
          localparam integer A = A_POS + gi;
          reg [PW-1:0] pos_q;
          always @(posedge clk_i) begin
            if (wr_i && addr_i == A[AW-1:0]) pos_q <= data_i[PW-1:0];
          end
          assign pos_o[(3*j + gi)*PW +: PW] = pos_q;
        end
      end else begin : g_no_pos
        assign pos_o[3*j*PW +: 3*PW] = {3*PW{1'b0}};
      end
      if (CAN_A != 0) begin : g_att
        reg [PW-1:0] kc_q, kl_q, kq_q;
        always @(posedge clk_i) begin
          if (wr_i && addr_i == A_KC[AW-1:0]) kc_q <= data_i[PW-1:0];
          if (wr_i && addr_i == A_KL[AW-1:0]) kl_q <= data_i[PW-1:0];
          if (wr_i && addr_i == A_KQ[AW-1:0]) kq_q <= data_i[PW-1:0];
        end
        assign katt_o[3*j*PW +: 3*PW] = {kq_q, kl_q, kc_q};
      end else begin : g_no_att
        assign katt_o[3*j*PW +: 3*PW] = {3*PW{1'b0}};
      end
      localparam integer A_SD = reg_at(REG_LIGHT_SPOT_DIRECTION, ABASE);
      localparam integer A_SC = reg_at(REG_LIGHT_SPOT_COS, ABASE);
      localparam integer A_SE = reg_at(REG_LIGHT_SPOT_EXPONENT, ABASE);
      if (CAN_S != 0) begin : g_spot
        for (gi = 0; gi < 3; gi = gi + 1) begin : g_c
          localparam integer A = A_SD + gi;
          reg [F+1:0] sdir_q;
          always @(posedge clk_i) begin
            if (wr_i && addr_i == A[AW-1:0]) sdir_q <= data_i[F+1:0];
          end
          assign sdir_o[(3*j + gi)*(F+2) +: F+2] = sdir_q;
        end
        reg [UFRAC+1:0] scos_q;
        reg [SEB-1:0]   sexp_q;
        always @(posedge clk_i) begin
          if (wr_i && addr_i == A_SC[AW-1:0]) scos_q <= data_i[UFRAC+1:0];
          if (wr_i && addr_i == A_SE[AW-1:0]) sexp_q <= data_i[SEB-1:0];
        end
        assign scos_o[j*(UFRAC+2) +: UFRAC+2] = scos_q;
        assign sexp_o[SEB*j +: SEB] = sexp_q;
      end else begin : g_no_spot
        assign sdir_o[3*j*(F+2) +: 3*(F+2)] = {3*(F+2){1'b0}};
        assign scos_o[j*(UFRAC+2) +: UFRAC+2] = {(UFRAC+2){1'b0}};
        assign sexp_o[SEB*j +: SEB] = {SEB{1'b0}};
      end
      for (c = 0; c < NCH; c = c + 1) begin : g_col
        localparam integer A_LA = reg_at(REG_LIGHT_AMBIENT, ABASE + c);
        localparam integer A_LD = reg_at(REG_LIGHT_DIFFUSE, ABASE + c);
        localparam integer A_LS = reg_at(REG_LIGHT_SPECULAR, ABASE + c);
        if (AMBIENT != 0) begin : g_amb
          reg [CL-1:0] lamb_q;
          always @(posedge clk_i) begin
            if (wr_i && addr_i == A_LA[AW-1:0]) lamb_q <= data_i[CL-1:0];
          end
          assign lamb_o[(NCH*j + c)*CL +: CL] = lamb_q;
        end else begin : g_no_amb
          assign lamb_o[(NCH*j + c)*CL +: CL] = {CL{1'b0}};
        end
        if (DIFFUSE != 0) begin : g_dif
          reg [CL-1:0] ldif_q;
          always @(posedge clk_i) begin
            if (wr_i && addr_i == A_LD[AW-1:0]) ldif_q <= data_i[CL-1:0];
          end
          assign ldif_o[(NCH*j + c)*CL +: CL] = ldif_q;
        end else begin : g_no_dif
          assign ldif_o[(NCH*j + c)*CL +: CL] = {CL{1'b0}};
        end
        if (SPECULAR != 0) begin : g_spec
          reg [CL-1:0] lspec_q;
          always @(posedge clk_i) begin
            if (wr_i && addr_i == A_LS[AW-1:0]) lspec_q <= data_i[CL-1:0];
          end
          assign lspec_o[(NCH*j + c)*CL +: CL] = lspec_q;
        end else begin : g_no_spec
          assign lspec_o[(NCH*j + c)*CL +: CL] = {CL{1'b0}};
        end
      end
    end
  endgenerate
  assign mamb_o = mamb_w;

endmodule

`default_nettype wire
