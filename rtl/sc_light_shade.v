// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_light_shade.v
// Purpose  : one lane of the lighting core's back end (rtl/sc_light.v): a light's colour products,
//            sum and attenuation per channel, bit for bit as LightCore::eval():
//   B1  ⌊diff·d_c / 2^F⌋, ⌊spec·s_c / 2^(F+SG)⌋ (spec = 0 unless f; spec has F+SG fraction bits)
//   B2  sum = ⌊a_c·Ia_jc / 2^F⌋ + ⌊·Id_jc / 2^F⌋ + ⌊·Is_jc / 2^F⌋ (0 for a lane with no light this pass;
//       the ambient product is formed here, per lane, from the slot's Ia_jc register)
//   B3  term = ⌊att·sum / 2^F⌋ (the stage exists only with the point_att capability; att = 2^F for
//       the other kinds, so term = sum exactly)
//   term_o is the lane's term saturated to 2^F: every term is >= 0, so the core's saturating sum of
//   saturated terms is exactly min(Σ, 2^F) of the unsaturated ones.
//   Light registers are read through the slot index that travels with the pass (idx_i at B0).
//   CSER = 1 (channel-serial, rtl/sc_light.v with SHARE >= 4, RGB and units): the lane computes one channel per
//   item — the core feeds a pass as three items, channels 0, 1, 2 on consecutive back-advancing edges
//   (ch_i at B0, travelling with the item) — through one set of multipliers instead of three; the
//   item's term is at term_o[CL-1:0] (the other channels' bits are 0).
//   SEP = 1 (separate_specular) with sep_i (light_model bit 4): B2 keeps the ambient + diffuse sum and the
//   specular product apart and B3 attenuates each (two products): term_o = ⌊att·(amb + diff)/2^F⌋, sterm_o =
//   ⌊att·spec/2^F⌋, each saturated to 2^F; without sep_i the whole sum in term_o as with SEP = 0 (bit for bit)
//   and sterm_o = 0.
//   D = 1 (rtl/sc_light.v MREG): every product stage is two, its product registered between the tree and the
//   final adder (rtl/sc_mul_stage.v): B1, B2 and B3 each one stage later than the one before (3 + 3D stages with
//   the point_att capability, 2 + 2D without); the same terms.
// Parameters: FRAC, NLT, NCH, SPW (unit output width), SG (the unit's extra fraction bits, SGUARD of
//             rtl/sc_light.v), AMBIENT, DIFFUSE, SPECULAR, CAN_ATT, CSER, SEP, TWO (two-sided: back_i at B0
//             chooses the back colour bank bamb_i / bdif_i / bspec_i for the item, each read at its stage),
//             COL (colour material: cm_i = {specular, diffuse, ambient} take the fragment's colour, col0_i at
//             B0 for diffuse and specular, col1_i at B1 for ambient, instead of either bank's register).
// Ports     : clk_i, en_i (the back-advancing condition); at B0 (the unit's output): spec_i, f_i,
//             diff_i, att_i, idx_i, v_i (a light in this lane); material mamb_i, mdif_i, mspec_i; every slot's
//             lamb_i, ldif_i, lspec_i (packed as sc_light_regfile.v); ch_i (CSER: the item's channel at
//             B0); sep_i (SEP: the separate mode, constant while a pass is in flight); term_o, sterm_o at the
//             last stage.
// ============================================================================================
`default_nettype none

module sc_light_shade #(
    parameter integer FRAC     = 16,
    parameter integer NLT      = 1,
    parameter integer NCH      = 3,
    parameter integer SPW      = 17,
    parameter integer SG       = 0,
    parameter integer AMBIENT  = 1,
    parameter integer DIFFUSE  = 1,
    parameter integer SPECULAR = 1,
    parameter integer CAN_ATT  = 0,
    parameter integer CSER     = 0,
    parameter integer SEP      = 0,
    parameter integer TWO      = 0,
    parameter integer COL      = 0,
    parameter integer D        = 0
) (
    input  wire                          clk_i,
    input  wire                          en_i,
    input  wire [SPW-1:0]                spec_i,
    input  wire                          f_i,
    input  wire                          sep_i,
    input  wire                          back_i,
    input  wire [NCH*(FRAC+1)-1:0]       bamb_i,
    input  wire [NCH*(FRAC+1)-1:0]       bdif_i,
    input  wire [NCH*(FRAC+1)-1:0]       bspec_i,
    input  wire [2:0]                    cm_i,
    input  wire [NCH*(FRAC+1)-1:0]       col0_i,
    input  wire [NCH*(FRAC+1)-1:0]       col1_i,
    input  wire [FRAC:0]                 diff_i,
    input  wire [FRAC+7:0]               att_i,
    input  wire [2:0]                    idx_i,
    input  wire                          v_i,
    input  wire [NCH*(FRAC+1)-1:0]       mamb_i,
    input  wire [NCH*(FRAC+1)-1:0]       mdif_i,
    input  wire [NCH*(FRAC+1)-1:0]       mspec_i,
    input  wire [NLT*NCH*(FRAC+1)-1:0]   lamb_i,
    input  wire [NLT*NCH*(FRAC+1)-1:0]   ldif_i,
    input  wire [NLT*NCH*(FRAC+1)-1:0]   lspec_i,
    input  wire [1:0]                    ch_i,
    output wire [NCH*(FRAC+1)-1:0]       term_o,
    output wire [NCH*(FRAC+1)-1:0]       sterm_o
);

  localparam integer F    = FRAC;
  localparam integer CL   = FRAC + 1;
  localparam integer SPF  = SPW - SG;   // width of spec at F fraction bits
  localparam integer SUMW = ((SPF + 2 > FRAC + 3) ? SPF + 2 : FRAC + 3) + 2;   // per-light sum
  localparam [CL-1:0] ONE = {1'b1, {FRAC{1'b0}}};
  localparam integer NPC = (CSER != 0) ? 1 : NCH;   // channels computed per item
  localparam integer NSUM = (SEP != 0) ? 2 : 1;       // sums attenuated per channel

  genvar c, k;

  // spec only counts when N̂·L > 0
  wire [SPW-1:0] spec_e = f_i ? spec_i : {SPW{1'b0}};
  // D: what B1 takes from B0 beside the products, D stages later (aligned with the registered products)
  wire [2:0]      idx_d;
  wire [1:0]      ch_d;
  wire            v_d, back_d;
  wire [FRAC+7:0] att_d;
  sc_delay #(.W(FRAC + 15), .DEPTH(D)) u_dly_b0 (
      .clk_i(clk_i), .en_i(en_i), .d_i({idx_i, ch_i, v_i, back_i, att_i}), .q_o({idx_d, ch_d, v_d, back_d, att_d}));
  // TWO: the item's colour bank — diffuse and specular read at B0, ambient at B1
  reg  b1_back_q;
  always @(posedge clk_i) begin
    if (en_i) b1_back_q <= back_d;
  end
  wire [NCH*CL-1:0] mdif_b  = (TWO != 0 && back_i) ? bdif_i : mdif_i;
  wire [NCH*CL-1:0] mspec_b = (TWO != 0 && back_i) ? bspec_i : mspec_i;
  wire [NCH*CL-1:0] mamb_b  = (TWO != 0 && b1_back_q) ? bamb_i : mamb_i;
  // COL: the fragment's colour replaces the material colours cm_i names (either bank), at B0 and at B1
  wire [NCH*CL-1:0] mdif_s  = (COL != 0 && cm_i[1]) ? col0_i : mdif_b;
  wire [NCH*CL-1:0] mspec_s = (COL != 0 && cm_i[2]) ? col0_i : mspec_b;
  wire [NCH*CL-1:0] mamb_s  = (COL != 0 && cm_i[0]) ? col1_i : mamb_b;

  reg  [2:0] b1_idx_q;
  reg  [1:0] b1_ch_q;
  reg        b1_v_q, b2_v_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      b1_idx_q <= idx_d;
      b1_ch_q  <= ch_d;
      b1_v_q   <= v_d;
      b2_v_q   <= b1_v_d;
    end
  end
  // D: what B2 takes from B1 beside the products
  wire            b1_v_d;
  wire [FRAC+7:0] b1_att_d;
  wire [FRAC+7:0] b2_att;   // att at B2 (point_att capability)
  generate
    if (CAN_ATT != 0) begin : g_b_att
      reg [FRAC+7:0] b1_att_q, b2_att_q;
      always @(posedge clk_i) begin
        if (en_i) begin
          b1_att_q <= att_d;
          b2_att_q <= b1_att_d;
        end
      end
      sc_delay #(.W(FRAC + 9), .DEPTH(D)) u_dly_b1 (
          .clk_i(clk_i), .en_i(en_i), .d_i({b1_v_q, b1_att_q}), .q_o({b1_v_d, b1_att_d}));
      assign b2_att = b2_att_q;
    end else begin : g_no_b_att
      assign b2_att = {(FRAC+8){1'b0}};
      assign b1_att_d = {(FRAC+8){1'b0}};
      sc_delay #(.W(1), .DEPTH(D)) u_dly_b1 (.clk_i(clk_i), .en_i(en_i), .d_i(b1_v_q), .q_o(b1_v_d));
      wire unused_b_att = &{1'b0, att_d, b2_att, b1_att_d};
    end
    if (SPECULAR == 0) begin : g_spec_unused
      wire unused_spec = &{1'b0, spec_e, mspec_i, lspec_i, mspec_s};
    end
    if (DIFFUSE == 0) begin : g_diff_unused
      wire unused_diff = &{1'b0, diff_i, mdif_i, ldif_i, mdif_s};
    end
    if (AMBIENT == 0) begin : g_amb_unused
      wire unused_amb = &{1'b0, lamb_i, mamb_i, mamb_s};
    end
    if (COL == 0) begin : g_no_col
      wire unused_col = &{1'b0, cm_i, col0_i, col1_i};
    end
    if (TWO == 0) begin : g_no_two
      wire unused_two = &{1'b0, back_i, b1_back_q, bamb_i, bdif_i, bspec_i};
    end
    for (c = 0; c < NPC; c = c + 1) begin : g_ch
      // the colour channel of this product set: c, or the item's channel (CSER) at B0 and B1
      localparam integer CI = c;
      wire [1:0] c0 = (CSER != 0) ? ch_i : CI[1:0];
      wire [1:0] c1 = (CSER != 0) ? b1_ch_q : CI[1:0];
      wire unused_c = &{1'b0, c0, c1};   // a term set may read neither
      // B1: pd = ⌊diff·d_c / 2^F⌋, ps = ⌊spec·s_c / 2^(F+SG)⌋
      wire [CL+1:0]   td;    // ⌊pd·Id_c / 2^F⌋ (B2 input)
      wire [SPF+1:0]  ts;    // ⌊ps·Is_c / 2^F⌋
      wire [CL:0]     amb;   // ⌊a_c·Ia_jc / 2^F⌋
      if (AMBIENT != 0) begin : g_a
        wire [CL-1:0]   la   = lamb_i[(NCH*b1_idx_q + {30'd0, c1})*CL +: CL];
        wire [2*CL-1:0] pa_p;
        wire u_pa_nc;   // no sideband
        wire unused_u_pa_nc = &{1'b0, u_pa_nc};
        sc_mul_stage #(.AW(CL), .BW(CL), .PW(2 * CL), .MREG(D)) u_pa (
            .clk_i(clk_i), .en_i(en_i), .a_i(mamb_s[c1*CL +: CL]), .b_i(la), .c_i(1'b0), .side_i(1'b0),
            .p_o(pa_p), .side_o(u_pa_nc));
        wire unused_pa = &{1'b0, pa_p[F-1:0]};
        assign amb = pa_p[2*CL-1:F];
      end else begin : g_no_a
        assign amb = {(CL+1){1'b0}};
      end
      if (DIFFUSE != 0) begin : g_d
        wire [2*CL-1:0] pd_p;
        wire u_pd_nc;   // no sideband
        wire unused_u_pd_nc = &{1'b0, u_pd_nc};
        sc_mul_stage #(.AW(CL), .BW(CL), .PW(2 * CL), .MREG(D)) u_pd (
            .clk_i(clk_i), .en_i(en_i), .a_i(diff_i), .b_i(mdif_s[c0*CL +: CL]), .c_i(1'b0), .side_i(1'b0),
            .p_o(pd_p), .side_o(u_pd_nc));
        wire unused_pd = &{1'b0, pd_p[F-1:0]};
        reg  [CL:0] b1_pd_q;
        always @(posedge clk_i) begin
          if (en_i) b1_pd_q <= pd_p[2*CL-1:F];
        end
        wire [CL-1:0] ld = ldif_i[(NCH*b1_idx_q + {30'd0, c1})*CL +: CL];
        wire [2*CL:0] td_p;
        wire u_td_nc;   // no sideband
        wire unused_u_td_nc = &{1'b0, u_td_nc};
        sc_mul_stage #(.AW(CL + 1), .BW(CL), .PW(2 * CL + 1), .MREG(D)) u_td (
            .clk_i(clk_i), .en_i(en_i), .a_i(b1_pd_q), .b_i(ld), .c_i(1'b0), .side_i(1'b0),
            .p_o(td_p), .side_o(u_td_nc));
        wire unused_td = &{1'b0, td_p[F-1:0]};
        assign td = td_p[2*CL:F];
      end else begin : g_no_d
        assign td = {(CL+2){1'b0}};
      end
      if (SPECULAR != 0) begin : g_s
        wire [SPW+CL-1:0] ps_p;
        wire u_ps_nc;   // no sideband
        wire unused_u_ps_nc = &{1'b0, u_ps_nc};
        sc_mul_stage #(.AW(SPW), .BW(CL), .PW(SPW + CL), .MREG(D)) u_ps (
            .clk_i(clk_i), .en_i(en_i), .a_i(spec_e), .b_i(mspec_s[c0*CL +: CL]), .c_i(1'b0), .side_i(1'b0),
            .p_o(ps_p), .side_o(u_ps_nc));
        wire unused_ps = &{1'b0, ps_p[F+SG-1:0]};
        reg  [SPF:0] b1_ps_q;
        always @(posedge clk_i) begin
          if (en_i) b1_ps_q <= ps_p[SPW+CL-1:F+SG];
        end
        wire [CL-1:0] ls = lspec_i[(NCH*b1_idx_q + {30'd0, c1})*CL +: CL];
        wire [SPF+CL:0] ts_p;
        wire u_ts_nc;   // no sideband
        wire unused_u_ts_nc = &{1'b0, u_ts_nc};
        sc_mul_stage #(.AW(SPF + 1), .BW(CL), .PW(SPF + CL + 1), .MREG(D)) u_ts (
            .clk_i(clk_i), .en_i(en_i), .a_i(b1_ps_q), .b_i(ls), .c_i(1'b0), .side_i(1'b0),
            .p_o(ts_p), .side_o(u_ts_nc));
        wire unused_ts = &{1'b0, ts_p[F-1:0]};
        assign ts = ts_p[SPF+CL:F];
      end else begin : g_no_s
        assign ts = {(SPF+2){1'b0}};
      end
      // B2: sum = amb + td + ts (0 without a light in this lane); SEP: amb + td and ts apart
      wire [SUMW-1:0] sum_p = {{(SUMW-CL-1){1'b0}}, amb} + {{(SUMW-CL-2){1'b0}}, td};
      wire [SUMW-1:0] sum_s = {{(SUMW-SPF-2){1'b0}}, ts};
      wire [SUMW-1:0] sum_d = sum_p + sum_s;
      reg  [SUMW-1:0] b2_sum_q;
      always @(posedge clk_i) begin
        if (en_i) b2_sum_q <= b1_v_d ? ((SEP != 0 && sep_i) ? sum_p : sum_d) : {SUMW{1'b0}};
      end
      wire [SUMW-1:0] b2_ssum;
      if (SEP != 0) begin : g_b2_sep
        reg [SUMW-1:0] b2_ssum_q;
        always @(posedge clk_i) begin
          if (en_i) b2_ssum_q <= (b1_v_d && sep_i) ? sum_s : {SUMW{1'b0}};
        end
        assign b2_ssum = b2_ssum_q;
      end else begin : g_b2_one
        assign b2_ssum = {SUMW{1'b0}};
      end
      // B3: ⌊att·sum / 2^F⌋ (point_att), saturated to 2^F; SEP: the specular sum likewise
      wire [NSUM*CL-1:0] t_out;   // the primary term, and with SEP the specular term
      for (k = 0; k < NSUM; k = k + 1) begin : g_b3
        wire [SUMW-1:0] sq = (k == 0) ? b2_sum_q : b2_ssum;
        if (CAN_ATT != 0) begin : g_att
          wire [SUMW+FRAC+7:0] at_p;
          wire u_at_nc;   // no sideband
          wire unused_u_at_nc = &{1'b0, u_at_nc};
          sc_mul_stage #(.AW(FRAC + 8), .BW(SUMW), .PW(SUMW + FRAC + 8), .MREG(D)) u_at (
              .clk_i(clk_i), .en_i(en_i), .a_i(b2_att), .b_i(sq), .c_i(1'b0), .side_i(1'b0),
              .p_o(at_p), .side_o(u_at_nc));
          wire unused_at = &{1'b0, at_p[F-1:0]};
          wire [SUMW+7:0] t_d = at_p[SUMW+FRAC+7:F];
          reg [CL-1:0] b3_term_q;
          always @(posedge clk_i) begin
            if (en_i) b3_term_q <= (t_d > {{(SUMW+7-F){1'b0}}, ONE}) ? ONE : t_d[CL-1:0];
          end
          assign t_out[k*CL +: CL] = b3_term_q;
        end else begin : g_sat
          assign t_out[k*CL +: CL] = (sq > {{(SUMW-CL){1'b0}}, ONE}) ? ONE : sq[CL-1:0];
        end
      end
      assign term_o[c*CL +: CL] = t_out[CL-1:0];
      if (SEP != 0) begin : g_sterm
        assign sterm_o[c*CL +: CL] = t_out[NSUM*CL-1:CL];
      end else begin : g_no_sterm
        assign sterm_o[c*CL +: CL] = {CL{1'b0}};
        wire unused_ssum = &{1'b0, b2_ssum, sep_i};
      end
    end
    if (NPC < NCH) begin : g_ser_pad
      assign term_o[NCH*CL-1:NPC*CL] = {((NCH-NPC)*CL){1'b0}};
      assign sterm_o[NCH*CL-1:NPC*CL] = {((NCH-NPC)*CL){1'b0}};
    end
    if (CSER == 0) begin : g_ch_unused
      wire unused_ch = &{1'b0, ch_i, b1_ch_q};
    end
  endgenerate
  wire unused_b2_v = &{1'b0, b2_v_q};

endmodule

`default_nettype wire
