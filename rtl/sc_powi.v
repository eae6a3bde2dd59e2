// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_powi.v
// Purpose  : x^e for an integer exponent by an exact square-and-multiply chain, bit for bit as
//            powi_chain() of cmodel/include/shadecore/light.hpp: the lighting core's spot factor
//            (max(−L̂·ŝ, 0))^e (rtl/sc_light_lane.v). Division-free, one register stage per
//            exponent bit, inside a global-enable pipeline.
//
//   x in [0, 1] as a code of FRAC fraction bits (x <= 2^FRAC, FRAC+1 bits). Stage k (k = 0 .. EB−1,
//   the exponent's bits low first): r ← ⌊r·p / 2^FRAC⌋ where bit k of e is set, p ← ⌊p² / 2^FRAC⌋;
//   from r = 2^FRAC (x^0 = 1 for every x, 0 included; 0 with zero_i) and p = x. Every value stays in
//   [0, 2^FRAC]; the truncations are the only rounding: the result is at most e − 1 codes below
//   x^e·2^FRAC (e >= 1), never above (docs/lighting.md §3.4).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC  fraction bits, 8..24 (config/configs.json limits.frac; the core's VF) (default 16)
//   EB    exponent bits = register stages, 2..8                              (default 8)
//   SH    stages per pass (the core's SHARE), 1..4: the EB products r·p and the EB−1 squarings share
//         multipliers over SH consecutive stages (rtl/sc_mul_pool.v), chosen by the phase ph_i
//   PH0   the phase (mod SH) at which a pass is at stage 0                  (default 0)
//   MREG  0/1, the lighting core's pipelining parameter: 1 registers each stage's two products between
//         their trees and their adders (rtl/sc_mul_pool.v LAT = 1, r and e waiting beside them), so a
//         stage takes two edges: EB·(1 + MREG) in all (config/configs.json light.latency mreg_powi = 1 per
//         stage), the same r                                                     (default 0)
// Ports : clk_i, en_i (the pipeline's enable); x_i[FRAC:0], e_i[EB-1:0], zero_i at stage 0;
//         ph_i[1:0] the phase; r_o[FRAC:0] EB·(1 + MREG) enabled edges later.
// ============================================================================================
`default_nettype none

module sc_powi #(
    parameter integer FRAC = 16,
    parameter integer EB   = 8,
    parameter integer SH   = 1,
    parameter integer PH0  = 0,
    parameter integer MREG = 0
) (
    input  wire            clk_i,
    input  wire            en_i,
    input  wire [FRAC:0]   x_i,
    input  wire [EB-1:0]   e_i,
    input  wire            zero_i,
    input  wire [1:0]      ph_i,
    output wire [FRAC:0]   r_o
);

  // ---------------------------------------------------------------------------- check configuration
  generate
    if (FRAC < 8 || FRAC > 24) begin : g_check_frac
      sc_powi_error_illegal_FRAC_legal_range_is_8_to_24 u_error ();
    end
    if (EB < 2 || EB > 8) begin : g_check_eb
      sc_powi_error_illegal_EB_legal_range_is_2_to_8 u_error ();
    end
    if (SH < 1 || SH > 4) begin : g_check_sh
      sc_powi_error_illegal_SH_legal_range_is_1_to_4 u_error ();
    end
    if (MREG != 0 && MREG != 1) begin : g_check_mreg
      sc_powi_error_illegal_MREG_must_be_0_or_1 u_error ();
    end
  endgenerate

  localparam integer W  = FRAC + 1;
  localparam integer PW = 2 * W;
  localparam [W-1:0] ONE = {1'b1, {FRAC{1'b0}}};
  localparam integer SHC = (SH < 1) ? 1 : ((SH > 4) ? 4 : SH);
  localparam integer EBC = (EB < 2) ? 2 : ((EB > 8) ? 8 : EB);

  localparam integer MR = (MREG != 0) ? 1 : 0;
  // op o at stage o·(1 + MREG) (mod SH, from PH0), every operand W bits
  function [63:0] st_pack(input integer n);
    integer o, t;
    begin
      st_pack = 64'd0;
      for (o = 0; o < n; o = o + 1) begin
        t = o * (1 + MR);   // < 256
        st_pack = st_pack | ({32'd0, t} << (8 * o));
      end
    end
  endfunction
  localparam [63:0] ST_M = st_pack(EBC);
  localparam [63:0] WW   = {8{W[7:0]}};

  wire [EBC*W-1:0]  r_s, p_s;    // r, p at stage k (k = 0 .. EB−1) at [k*W +: W]
  wire [EBC*EB-1:0] e_s;
  wire [EBC*W-1:0]  ma, mb;      // products r·p (op k) and p·p (op k, k < EB−1)
  wire [EBC*PW-1:0] mp, sp;
  wire [EBC-1:0]    sel;
  assign r_s[0 +: W]  = zero_i ? {W{1'b0}} : ONE;
  assign p_s[0 +: W]  = x_i;
  assign e_s[0 +: EB] = e_i;

  genvar k;
  generate
    for (k = 0; k < EBC; k = k + 1) begin : g_sel
      localparam integer RI = (PH0 + k * (1 + MR)) % SHC;
      assign sel[k] = (SHC == 1) || (ph_i == RI[1:0]);
      assign ma[k*W +: W] = r_s[k*W +: W];
      assign mb[k*W +: W] = p_s[k*W +: W];
    end
    if (SHC == 1) begin : g_no_ph
      wire unused_ph = &{1'b0, ph_i};
    end
  endgenerate
  sc_mul_pool #(
      .NOP(EBC), .SH(SHC), .ON(255), .ST(ST_M), .AW(WW), .BW(WW), .AMX(W), .BMX(W), .SIGNED(0), .LAT(MR)
  ) u_mul_r (
      .clk_i(clk_i), .en_i(en_i),
      .a_i(ma), .b_i(mb), .sel_i(sel), .p_o(mp));
  sc_mul_pool #(
      .NOP(EBC - 1), .SH(SHC), .ON(255), .ST(ST_M), .AW(WW), .BW(WW), .AMX(W), .BMX(W), .SIGNED(0), .LAT(MR)
  ) u_mul_p (
      .clk_i(clk_i), .en_i(en_i),
      .a_i(mb[0 +: (EBC-1)*W]), .b_i(mb[0 +: (EBC-1)*W]), .sel_i(sel[EBC-2:0]), .p_o(sp[0 +: (EBC-1)*PW]));
  assign sp[(EBC-1)*PW +: PW] = {PW{1'b0}};

  generate
    for (k = 0; k < EBC; k = k + 1) begin : g_st
      wire [PW-1:0] rp = mp[k*PW +: PW];
      wire [PW-1:0] pp = sp[k*PW +: PW];
      // values <= 2^FRAC: ⌊product / 2^FRAC⌋ <= 2^FRAC fits W bits. MREG: the products come one edge after
      // their operands, r and e wait beside them (M register of stage k)
      wire [W-1:0]  r_k;
      wire [EB-1:0] e_k;
      sc_delay #(.W(W + EB), .DEPTH(MR)) u_dly_m (
          .clk_i(clk_i), .en_i(en_i), .d_i({r_s[k*W +: W], e_s[k*EB +: EB]}), .q_o({r_k, e_k}));
      wire [W-1:0] r_n = e_k[k] ? rp[FRAC +: W] : r_k;
      wire unused_p = &{1'b0, rp[PW-1:FRAC+W], rp[FRAC-1:0], pp[PW-1:FRAC+W], pp[FRAC-1:0]};
      wire unused_pl = (k + 1 < EBC) ? 1'b0 : &{1'b0, pp};   // the last stage squares nothing
      reg [W-1:0] r_q;
      always @(posedge clk_i) begin
        if (en_i) r_q <= r_n;
      end
      if (k + 1 < EBC) begin : g_next
        reg [W-1:0]  p_q;
        reg [EB-1:0] e_q;
        always @(posedge clk_i) begin
          if (en_i) begin
            p_q <= pp[FRAC +: W];
            e_q <= e_k;
          end
        end
        assign r_s[(k+1)*W +: W]   = r_q;
        assign p_s[(k+1)*W +: W]   = p_q;
        assign e_s[(k+1)*EB +: EB] = e_q;
      end else begin : g_last
        assign r_o = r_q;
        wire unused_e = &{1'b0, e_k};   // the last stage reads bit EB−1 only
      end
    end
  endgenerate

endmodule

`default_nettype wire
