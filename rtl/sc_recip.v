// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_recip.v
// Purpose  : attenuation reciprocal att = 1/q of the lighting core, division-free: leading-one
//            normalisation of q, the 64-entry table and the Newton–Raphson step of the Schlick NR
//            unit (same integer rule as schlick_nr_table() / schlick_nr_step(), computed here by
//            a constant function; rtl/sc_schlick_nr.v is not touched), a rounding shift and
//            saturation. Bit-accurate C model: recip_att() in cmodel/include/shadecore/units/normalize.hpp and units/recip.hpp
//            (same names as RecipTrace).
//            A pipeline stage with an enable and no handshake of its own: it is embedded in the
//            global-enable pipeline of rtl/sc_light.v (en_i = that pipeline's enable).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC  F, fraction bits of q and of att (1.0 = 2^F)               8 <= F <= 16 (default 16)
//   QW    width of the unsigned input q                              1 <= QW <= 64 (default 43)
//   SH    1..4, the lighting core's `share` (passes SH enabled edges apart or more): the four
//         Newton–Raphson products (S2..S5) share ⌈4/SH⌉ multipliers (rtl/sc_mul_pool.v), chosen by ph_i (default 1)
//   PH0   0..SH-1: ph_i ≡ PH0 + k (mod SH) while a pass's q is k stages past q_i (the pass at q_i
//         itself at PH0)                                                               (default 0)
//   MREG  0 or 1, the lighting core's pipelining parameter: each Newton–Raphson product
//         (S3..S6) takes two edges through rtl/sc_mul_reg.v (LAT = 2: its tree | register | its adder |
//         register), and g = 2^(R+1) − e is folded into the next product as y·~e + y (e < 2^(R+1), so
//         ~e + 1 = g over R+1 bits): no subtractor is left between two trees. The same att, 4 edges
//         later (config/configs.json light.latency mreg_recip; the shared datapath below is then
//         unused and removed by synthesis; with SH > 1 the four products are then not shared and ph_i
//         is not read)                                                                 (default 0)
//
// Ports : clk_i             clock, all flops on the rising edge
//         en_i              enable (the embedding pipeline's global enable)
//         q_i[QW-1:0]       q, unsigned, F fraction bits
//         ph_i[1:0]         the embedding pipeline's phase (SH > 1; ignored with SH = 1)
//         att_o[F+7:0]      att = round_half_up(2^F / (q/2^F)), F fraction bits, saturated to
//                           ATT_MAX = 2^(F+8) − 1 (q = 0 and every q < 2^(F−8) give ATT_MAX)
//
// Latency : LATENCY = 7 enabled edges (stages S1..S7); 11 with MREG = 1.
//
// Datapath (R = F+8 fraction bits of the reciprocal, P = 6 index bits, T = 10 table fraction bits,
// QWF = max(QW, R+1)):
//
//   q_i ─► S1  lz = leading zeros of q in QWF bits; p = QWF−1−lz (msb index)
//              mt = (q << lz)[QWF−1 : QWF−1−R]       R+1 bits, q/2^p in [1, 2), truncated
//              sat = q < 2^(F−8) (includes q = 0);  sh = R + p − 2F = QWF+7−F−lz  (>= 0 unless sat)
//          S2  y0 = TABLE[mt[R−1 : R−6]]             T bits; TABLE[i] = round(2^17 / (2^7 + 2i + 1))
//          S3  e = ⌊mt·y0 / 2^T⌋;  g = 2^(R+1) − e     R+2 bits
//          S4  y1 = ⌊y0·g / 2^T⌋                      R+1 bits (< 2^R for every mt, F = 8..16)
//          S5  e = ⌊mt·y1 / 2^R⌋;  g = 2^(R+1) − e     R+2 bits
//          S6  y2 = ⌊y1·g / 2^R⌋                      R+1 bits (< 2^R)
//          S7  a = ⌊(y2 + 2^(sh−1)) / 2^sh⌋ (sh > 0) or y2 (sh = 0), as ((({y2,0} >> sh) + 1) >> 1);
//              att = sat ? ATT_MAX : min(a, ATT_MAX)
//
// Both data-dependent shifts (S1 by lz, S7 by sh) are log2-stage barrel shifters.
// ============================================================================================
`default_nettype none

module sc_recip #(
    parameter integer FRAC = 16,
    parameter integer QW   = 43,
    parameter integer SH   = 1,
    parameter integer PH0  = 0,
    parameter integer MREG = 0
) (
    input  wire              clk_i,
    input  wire              en_i,
    input  wire [QW-1:0]     q_i,
    input  wire [1:0]        ph_i,
    output wire [FRAC+7:0]   att_o
);

  localparam integer F   = FRAC;
  localparam integer R   = FRAC + 8;                  // recip_frac
  localparam integer T   = 10;                        // kSchlickNrTableFrac
  localparam integer P   = 6;                         // kSchlickNrIndexBits
  localparam integer QWF = sc_max(QW, R + 1); // normalisation frame
  localparam integer LZW = sc_bits(QWF);                // width of lz (0..QWF-1)
  localparam integer SHC = QWF + 7 - FRAC;            // sh = SHC - lz
  localparam integer SHW = sc_bits(SHC + 1);            // width of sh (0..SHC)

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (FRAC < 8 || FRAC > 16) begin : g_check_frac
      sc_recip_error_illegal_FRAC_legal_range_is_8_to_16 u_error ();
    end
    if (QW < 1 || QW > 64) begin : g_check_qw
      sc_recip_error_illegal_QW_legal_range_is_1_to_64 u_error ();
    end
    if (SH < 1 || SH > 4 || PH0 < 0 || PH0 >= SH) begin : g_check_sh
      sc_recip_error_illegal_SH_1_to_4_and_PH0_0_to_SH_minus_1 u_error ();
    end
    if (MREG != 0 && MREG != 1) begin : g_check_mreg
      sc_recip_error_illegal_MREG_must_be_0_or_1 u_error ();
    end
  endgenerate

  // ---------------------------------------------------------------------------- constant functions
  `include "sc_util.vh"   // sc_bits (index width, >= 1), sc_max


  // schlick_nr_table(i) of the C model: round-half-up(2^(T+P+1) / (2^(P+1) + 2i + 1)), the
  // reciprocal of the midpoint of [1 + i/64, 1 + (i+1)/64) with T fraction bits (1016 .. 514).
  function integer nr_table(input integer i);
    integer num, den;
    begin
      den = (1 << (P + 1)) + 2 * i + 1;
      num = 1 << (T + P + 1);
      nr_table = (2 * num + den) / (2 * den);
    end
  endfunction

  localparam [R+1:0]  TWO_R   = {1'b1, {(R+1){1'b0}}};       // 2^(R+1)
  localparam [R:0]    ATT_MAX = {1'b0, {R{1'b1}}};           // 2^(F+8) − 1 = 2^R − 1
  localparam integer  LZM1    = QWF - 1;
  localparam [LZW-1:0] LZ_MAX = LZM1[LZW-1:0];
  localparam [LZW+SHW:0] SH_C = SHC[LZW+SHW:0];

  // ---------------------------------------------------------------------------- S1: normalise
  wire [QWF-1:0] qf;
  generate
    if (QWF > QW) begin : g_frame_pad
      assign qf = {{(QWF-QW){1'b0}}, q_i};
    end else begin : g_frame
      assign qf = q_i;
    end
  endgenerate

  reg [LZW-1:0] lz_d;
  integer       i;
  always @* begin
    lz_d = LZ_MAX;
    for (i = 0; i < QWF; i = i + 1) begin
      if (qf[i]) lz_d = LZ_MAX - i[LZW-1:0];
    end
  end
  // barrel shifter: stage b shifts left by 2^b when lz bit b is set (lz <= QWF-1, nothing lost)
  reg [QWF-1:0] qn_d;
  integer       sb;
  always @* begin
    qn_d = qf;
    for (sb = 0; sb < LZW; sb = sb + 1) begin
      if (lz_d[sb]) qn_d = qn_d << (1 << sb);
    end
  end
  generate
    if (QWF > R + 1) begin : g_trunc_mt
      wire unused_qn = &{1'b0, qn_d[QWF-R-2:0]};     // truncated (p > R)
    end
  endgenerate
  wire            sat_d = (qf[QWF-1:F-8] == {(QWF-F+8){1'b0}});   // q < 2^(F−8)
  wire [LZW+SHW:0] sh_x  = SH_C - {{(SHW+1){1'b0}}, lz_d};        // >= 0 unless sat
  wire unused_shx = &{1'b0, sh_x[LZW+SHW:SHW]};                   // sh <= SHC < 2^SHW

  reg [R:0]     s1_mt_q;
  reg [SHW-1:0] s1_sh_q;
  reg           s1_sat_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s1_mt_q  <= qn_d[QWF-1:QWF-1-R];
      s1_sh_q  <= sh_x[SHW-1:0];
      s1_sat_q <= sat_d;
    end
  end

  // ---------------------------------------------------------------------------- S2: table
  // The table is elaborated per index from the integer rule (localparams, not a copied list).
  genvar b;
  wire [64*T-1:0] tab;
  generate
    for (b = 0; b < 64; b = b + 1) begin : g_table
      localparam integer Y0 = nr_table(b);
      assign tab[b*T +: T] = Y0[T-1:0];
    end
  endgenerate
  wire [P-1:0] idx = s1_mt_q[R-1:R-P];

  reg [T-1:0]   s2_y0_q;
  reg [R:0]     s2_mt_q;
  reg [SHW-1:0] s2_sh_q;
  reg           s2_sat_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s2_y0_q  <= tab[idx*T +: T];
      s2_mt_q  <= s1_mt_q;
      s2_sh_q  <= s1_sh_q;
      s2_sat_q <= s1_sat_q;
    end
  end

  // ---------------------------------------------------------------------------- the products
  // op: 0 e1 = mt·y1 (S4), 1 y2 = g·y1 (S5), 2 y1 = g·y0 (S3), 3 e0 = mt·y0 (S2); the pool is below
  localparam integer MA = R + 2;   // widest a (g)
  localparam integer MB = R + 1;   // widest b (y1)
  localparam integer MP = MA + MB;
  wire [4*MP-1:0] pp;              // op o's product in the low bits of [o*MP +: MP]
  wire unused_pp = &{1'b0, pp};

  // ---------------------------------------------------------------------------- S3/S4: first step
  wire [R+T:0] e0_p = pp[3*MP +: R+T+1];                              // mt·y0 < 2^(R+1+T)
  wire [R+1:0] g0_d = TWO_R - {1'b0, e0_p[R+T:T]};                     // 2 − e, e < 2
  wire unused_e0 = &{1'b0, e0_p[T-1:0]};
  reg  [R+1:0]   s3_g_q;
  reg  [T-1:0]   s3_y0_q;
  reg  [R:0]     s3_mt_q;
  reg  [SHW-1:0] s3_sh_q;
  reg            s3_sat_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s3_g_q   <= g0_d;
      s3_y0_q  <= s2_y0_q;
      s3_mt_q  <= s2_mt_q;
      s3_sh_q  <= s2_sh_q;
      s3_sat_q <= s2_sat_q;
    end
  end

  wire [R+T+1:0] y1_p = pp[2*MP +: R+T+2];                  // y0·g
  wire unused_y1 = &{1'b0, y1_p[R+T+1], y1_p[T-1:0]};   // y1 < 2^R: bit R+T+1 is 0
  reg  [R:0]     s4_y1_q;
  reg  [R:0]     s4_mt_q;
  reg  [SHW-1:0] s4_sh_q;
  reg            s4_sat_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s4_y1_q  <= y1_p[R+T:T];
      s4_mt_q  <= s3_mt_q;
      s4_sh_q  <= s3_sh_q;
      s4_sat_q <= s3_sat_q;
    end
  end

  // ---------------------------------------------------------------------------- S5/S6: second step
  wire [2*R+1:0] e1_p = pp[0*MP +: 2*R+2];                  // mt·y1
  wire [R+1:0]   g1_d = TWO_R - e1_p[2*R+1:R];
  wire unused_e1 = &{1'b0, e1_p[R-1:0]};
  reg  [R+1:0]   s5_g_q;
  reg  [R:0]     s5_y1_q;
  reg  [SHW-1:0] s5_sh_q;
  reg            s5_sat_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s5_g_q   <= g1_d;
      s5_y1_q  <= s4_y1_q;
      s5_sh_q  <= s4_sh_q;
      s5_sat_q <= s4_sat_q;
    end
  end

  wire [2*R+2:0] y2_p = pp[1*MP +: 2*R+3];                  // y1·g
  wire unused_y2 = &{1'b0, y2_p[2*R+2:2*R+1], y2_p[R-1:0]};   // y2 < 2^R
  reg  [R:0]     s6_y2_q;
  reg  [SHW-1:0] s6_sh_q;
  reg            s6_sat_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s6_y2_q  <= y2_p[2*R:R];
      s6_sh_q  <= s5_sh_q;
      s6_sat_q <= s5_sat_q;
    end
  end

  // the products' pool: op o at stage S_k is selected when ph_i ≡ PH0 + k (mod SH)
  localparam integer R1 = R + 1, R2 = R + 2, TT = T;
  localparam integer P2 = (PH0 + 2) % SH, P3 = (PH0 + 3) % SH, P4 = (PH0 + 4) % SH, P5 = (PH0 + 5) % SH;
  wire [3:0] psel = {ph_i == P2[1:0], ph_i == P3[1:0], ph_i == P5[1:0], ph_i == P4[1:0]};
  sc_mul_pool #(
      .NOP(4), .SH(SH), .ON(15),
      .ST({32'd0, 8'd2, 8'd3, 8'd5, 8'd4}),
      .AW({32'd0, R1[7:0], R2[7:0], R2[7:0], R1[7:0]}),
      .BW({32'd0, TT[7:0], TT[7:0], R1[7:0], R1[7:0]}),
      .AMX(MA), .BMX(MB), .SIGNED(0)
  ) u_mul (
      .clk_i(clk_i), .en_i(en_i),
      .a_i({{(MA-R1){1'b0}}, s2_mt_q, s3_g_q, s5_g_q, {(MA-R1){1'b0}}, s4_mt_q}),
      .b_i({{(MB-TT){1'b0}}, s2_y0_q, {(MB-TT){1'b0}}, s3_y0_q, s5_y1_q, s4_y1_q}),
      .sel_i(psel), .p_o(pp));

  // ---------------------------------------------------------------------------- MREG: S3..S6 over two edges each
  wire [R:0]     y2_6;    // y2, sh and sat at S7's input
  wire [SHW-1:0] sh_6;
  wire           sat_6;
  generate
    if (MREG == 0) begin : g_one
      assign y2_6  = s6_y2_q;
      assign sh_6  = s6_sh_q;
      assign sat_6 = s6_sat_q;
    end else begin : g_mreg
      wire unused_one = &{1'b0, s6_y2_q, s6_sh_q, s6_sat_q, ph_i};
      // S3: e0 = ⌊mt·y0 / 2^T⌋
      wire [R+T:0] me0_p;
      sc_mul_reg #(.AW(R+1), .BW(T), .PW(R+T+1), .LAT(2)) u_e0 (
          .clk_i(clk_i), .en_i(en_i), .a_i(s2_mt_q), .b_i(s2_y0_q), .c_i(1'b0), .p_o(me0_p));
      wire unused_me0 = &{1'b0, me0_p[T-1:0]};
      // S4: y1 = ⌊y0·g0 / 2^T⌋, y0·g0 = y0·~e0 + y0
      wire [T-1:0] my0_4;
      sc_delay #(.W(T), .DEPTH(2)) u_dly_y0 (.clk_i(clk_i), .en_i(en_i), .d_i(s2_y0_q), .q_o(my0_4));
      wire [R+T+1:0] my1_p;
      sc_mul_reg #(.AW(R+1), .BW(T), .PW(R+T+2), .ADD(1), .CW(T), .LAT(2)) u_y1 (
          .clk_i(clk_i), .en_i(en_i), .a_i(~me0_p[R+T:T]), .b_i(my0_4), .c_i(my0_4), .p_o(my1_p));
      wire [R:0] my1 = my1_p[R+T:T];
      wire unused_my1 = &{1'b0, my1_p[R+T+1], my1_p[T-1:0]};
      // S5: e1 = ⌊mt·y1 / 2^R⌋ (< 2^(R+1): mt < 2^(R+1), y1 < 2^R)
      wire [R:0] mmt_5;
      sc_delay #(.W(R+1), .DEPTH(4)) u_dly_mt (.clk_i(clk_i), .en_i(en_i), .d_i(s2_mt_q), .q_o(mmt_5));
      wire [2*R+1:0] me1_p;
      sc_mul_reg #(.AW(R+1), .BW(R+1), .PW(2*R+2), .LAT(2)) u_e1 (
          .clk_i(clk_i), .en_i(en_i), .a_i(mmt_5), .b_i(my1), .c_i(1'b0), .p_o(me1_p));
      wire unused_me1 = &{1'b0, me1_p[2*R+1], me1_p[R-1:0]};
      // S6: y2 = ⌊y1·g1 / 2^R⌋, y1·g1 = y1·~e1 + y1
      wire [R:0] my1_6;
      sc_delay #(.W(R+1), .DEPTH(2)) u_dly_y1 (.clk_i(clk_i), .en_i(en_i), .d_i(my1), .q_o(my1_6));
      wire [2*R+1:0] my2_p;
      sc_mul_reg #(.AW(R+1), .BW(R+1), .PW(2*R+2), .ADD(1), .CW(R+1), .LAT(2)) u_y2 (
          .clk_i(clk_i), .en_i(en_i), .a_i(~me1_p[2*R:R]), .b_i(my1_6), .c_i(my1_6), .p_o(my2_p));
      wire unused_my2 = &{1'b0, my2_p[2*R+1], my2_p[R-1:0]};   // y2 < 2^R
      assign y2_6 = my2_p[2*R:R];
      sc_delay #(.W(SHW+1), .DEPTH(8)) u_dly_sh (
          .clk_i(clk_i), .en_i(en_i), .d_i({s2_sat_q, s2_sh_q}), .q_o({sat_6, sh_6}));
    end
  endgenerate

  // ---------------------------------------------------------------------------- S7: round, saturate
  // barrel shifter: {y2, 0} >> sh (stage b shifts right by 2^b when sh bit b is set)
  reg [R+1:0] z_d;
  integer     rb;
  always @* begin
    z_d = {y2_6, 1'b0};
    for (rb = 0; rb < SHW; rb = rb + 1) begin
      if (sh_6[rb]) z_d = z_d >> (1 << rb);
    end
  end
  wire [R+1:0] a_p = z_d + {{(R+1){1'b0}}, 1'b1};          // no carry out: z <= 2^(R+2) − 2
  wire [R:0]   a_d = a_p[R+1:1];
  wire unused_a = &{1'b0, a_p[0]};
  wire [R:0]   att_d = (sat_6 || a_d > ATT_MAX) ? ATT_MAX : a_d;
  wire unused_att = &{1'b0, att_d[R]};                     // <= ATT_MAX < 2^R

  reg [F+7:0] s7_att_q;
  always @(posedge clk_i) begin
    if (en_i) s7_att_q <= att_d[R-1:0];
  end
  assign att_o = s7_att_q;

endmodule

`default_nettype wire
