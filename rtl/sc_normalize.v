// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_normalize.v
// Purpose  : vector normaliser u = v / |v| of the lighting core, division-free: a reciprocal
//            square root by leading-one normalisation of s = v·v to an even power of two, a
//            96-entry seed table and two Newton–Raphson steps y <- y·(3 − m·y²)/2, then one
//            multiply and a rounding shift per component. Bit-accurate C model: normalize3() in
//            cmodel/include/shadecore/units/normalize.hpp and units/recip.hpp (same names as NormalizeTrace).
//            A pipeline stage with an enable and no handshake of its own: it is embedded in the
//            global-enable pipeline of rtl/sc_light.v (en_i = that pipeline's enable).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC  F, fraction bits of the result (1.0 = 2^F)                 8 <= F <= 24 (default 16)
//         (the lighting core uses F + SGUARD of rtl/sc_light.v)
//   VW    width of each signed input component (any common fraction: the result does not
//         depend on it)                                              2 <= VW <= 41 (default 18)
//   MREG  the pipelining parameter, 0 or 1 (default 0): 1 cuts each of the seven products (the
//         squares of S1, S4..S9) with a register between its partial-product tree and its final
//         adder (rtl/sc_mul_stage.v, rtl/sc_mul_reg.v) and S1's sum after one more register:
//         LATENCY 10 -> 18, the same outputs (config/configs.json light.normalize_latency and
//         light.mreg_stages.normalize). The subtractions of S4 and S7 and the rounding add of S10
//         then go inside the products' trees as addends ("MREG = 1" below). S7's product (31 × 30 at
//         F = 21, the deepest tree) is two half-height products summed over its two edges instead.
//
// Ports : clk_i             clock, all flops on the rising edge
//         en_i              enable (the embedding pipeline's global enable)
//         v_i[3*VW-1:0]     {vz, vy, vx}, signed two's complement components
//         u_o[3*(F+2)-1:0]  {uz, uy, ux}, signed F+2 bits, u_i = round_half_up(v_i·2^F/|v|)
//                           (|u_i| <= 2^F); v = 0 gives u = 0
//         v_o[3*VW-1:0]     v_i delayed by the latency (aligned with u_o, for a caller that needs
//                           the vector with its normalised form; unused bits cost nothing)
//
// Latency : LATENCY = 10 + 8·MREG enabled edges (stages S1..S10; with MREG = 1 each product stage
//           is two and S1 three): u_o (and v_o) show the result for the v_i presented LATENCY
//           enabled edges ago.
//
// Datapath (R = F+6 fraction bits of y, MB = F+6+(F mod 2) even mantissa fraction bits, T = 10
// seed fraction bits, SWF = max(2·VW, MB+2) even, HW = SWF/2):
//
//   v_i ─► S1   s = vx² + vy² + vz²                          exact, 2·VW bits (in an SWF-bit frame)
//          S2   k = leading zero bit *pairs* of s (0..HW−1; HW−1 for s = 0)
//               m = (s << 2k)[SWF−1 : SWF−MB−2]              MB+2 bits, m/2^MB in [1, 4), truncated
//                                                            (= s·2^e2, e2 = MB − p + (p&1), p = msb(s))
//          S3   idx = m[MB+1 : MB−5];  y0 = SEED[idx] (T bits), a0 = A0[idx] = ⌊(y0·2^(R−T))² / 2^R⌋
//               (both tables elaborated from the integer rule of rsqrt_seed() by constant functions)
//          S4   c0 = 3·2^R − ⌊m·a0 / 2^MB⌋                   R+2 bits
//          S5   y1 = ⌊y0·2^(R−T)·c0 / 2^(R+1)⌋ = ⌊y0·c0 / 2^(T+1)⌋     R+1 bits
//          S6   a1 = ⌊y1² / 2^R⌋                              R+2 bits
//          S7   c1 = 3·2^R − ⌊m·a1 / 2^MB⌋                   R+2 bits
//          S8   y2 = ⌊y1·c1 / 2^(R+1)⌋                        R+1 bits (< 2^R for every m, F = 8..22;
//                                                            F = 23, 24: every 4th m and each run's ends)
//          S9   p_i = v_i·y2                                 kept modulo 2^(HW+F+7) (two's complement:
//                                                            only those low bits reach the result)
//          S10  u_i = ⌊(v_i·y2 + 2^(sh−1)) / 2^sh⌋, sh = HW + 5 − k (= R + MB/2 − F − e2/2 of the
//               C model), computed as ⌊(p_i·2^k + 2^(HW+4)) / 2^(HW+5)⌋: a left barrel shift by k,
//               a constant rounding add and a constant slice (arithmetic shift, ties toward +inf)
//
// Both data-dependent shifts (S2 by 2k, S10 by k) are log2-stage barrel shifters.
//
// MREG = 1: each product's final adder is after its register, so nothing else may follow it in its
// stage. S4 and S7 form c = ⌊(Kc − m·a)/2^MB⌋ with Kc = 3·2^(R+MB) + 2^MB − 1 (= 3·2^R − ⌊m·a/2^MB⌋
// exactly), as the signed product m·~a (= −m·a − m) plus the addend Kc + m, whose low part
// m + 2^MB − 1 is added at S3 and travels with m. Both products are split in two half-height trees
// (b = ~a = b_hi·2^H + b_lo: m·b_lo + (m·2^H)·b_hi), S4's each to its own register and adder with one
// more adder in front of S4's register, S7's through one rtl/sc_mul_reg.v (N = 2, LAT = 2). S9 adds 2^(HW+4−k) to v_i·y2 in its tree, so that
// S10 is the shift alone: (p + 2^(HW+4−k))·2^k = p·2^k + 2^(HW+4). For s = 0 the
// table index is 0 and y2 is meaningless, but every p_i = 0, so u = 0 as the C model's early return.
// ============================================================================================
`default_nettype none

module sc_normalize #(
    parameter integer FRAC = 16,
    parameter integer VW   = 18,
    parameter integer MREG = 0
) (
    input  wire                  clk_i,
    input  wire                  en_i,
    input  wire [3*VW-1:0]       v_i,
    output wire [3*(FRAC+2)-1:0] u_o,
    output wire [3*VW-1:0]       v_o
);

  localparam integer R   = FRAC + 6;                 // fraction bits of y (rsqrt_frac)
  localparam integer T   = 10;                       // seed fraction bits (kRsqrtTableFrac)
  localparam integer IB  = 7;                        // table index bits (kRsqrtIndexBits)
  localparam integer MB  = FRAC + 6 + (FRAC % 2);    // mantissa fraction bits, even (rsqrt_mant_frac)
  localparam integer MW  = MB + 2;                   // m in [2^MB, 2^(MB+2))
  localparam integer AW  = R + 1;                    // width of the a0 table entries
  localparam integer SWF = sc_max(2 * VW, MW);  // frame of s (even)
  localparam integer HW  = SWF / 2;                  // bit pairs in the frame
  localparam integer KW  = sc_bits(HW);                // width of k (k <= HW-1)
  localparam integer OW  = FRAC + 2;                 // output component width
  localparam integer PW  = HW + FRAC + 7;            // low bits of v_i·y2 that reach u_i
  localparam integer NS  = 10 + 8 * MREG;            // stages = latency

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (FRAC < 8 || FRAC > 24) begin : g_check_frac
      sc_normalize_error_illegal_FRAC_legal_range_is_8_to_24 u_error ();
    end
    if (VW < 2 || VW > 41) begin : g_check_vw
      sc_normalize_error_illegal_VW_legal_range_is_2_to_41 u_error ();
    end
    if (MREG != 0 && MREG != 1) begin : g_check_mreg
      sc_normalize_error_illegal_MREG_must_be_0_or_1 u_error ();
    end
  endgenerate

  // ---------------------------------------------------------------------------- constant functions
  `include "sc_util.vh"   // sc_bits (index width, >= 1), sc_max


  // rsqrt_seed(i) of the C model: the largest y in [0, 2^T] with (2y−1)²·(2i+1) <= 2^(2T+8),
  // i.e. 1/√(midpoint of [i/32, (i+1)/32)) with T fraction bits, rounded to nearest. Bisection in
  // 32-bit integers: (2·1024 − 1)²·255 < 2^31. 12 halvings of [0, 1024] always converge.
  function integer rsqrt_seed(input integer i);
    integer lo, hi, mid, t, it;
    begin
      lo = 0;
      hi = 1 << T;
      for (it = 0; it < 12; it = it + 1) begin
        if (lo < hi) begin
          mid = (lo + hi + 1) / 2;
          t   = 2 * mid - 1;
          if (t * t * (2 * i + 1) <= (1 << (2 * T + 8))) lo = mid;
          else hi = mid - 1;
        end
      end
      rsqrt_seed = lo;
    end
  endfunction

  // a0 = ⌊(seed·2^(R−T))² / 2^R⌋ = seed²·2^(R−2T) (exact for R >= 2T, truncated otherwise).
  function integer rsqrt_a0(input integer i);
    integer y;
    begin
      y = rsqrt_seed(i);
      if (R >= 2 * T) rsqrt_a0 = (y * y) << (R - 2 * T);
      else rsqrt_a0 = (y * y) >> (2 * T - R);
    end
  endfunction

  localparam [R+1:0]      THREE_R  = {2'b11, {R{1'b0}}};                 // 3·2^R
  localparam [PW-1:0]     HALF_SH  = {{(PW-HW-5){1'b0}}, 1'b1, {(HW+4){1'b0}}};  // 2^(HW+4)
  localparam integer      HWM1     = HW - 1;
  localparam [KW-1:0]     K_MAX    = HWM1[KW-1:0];

  // ---------------------------------------------------------------------------- input pass-through
  // v travels with the fragment to S10 (S9 needs it; v_o is its S10 copy).
  // Two rtl/sc_delay.v lines: S1..S8 (the S8 copy is multiplied in S9), then S9..S10 (v_o).
  wire [3*VW-1:0] v8;
  // v at the S9 product's operands: eight stages, and seven more before S9 with MREG = 1
  sc_delay #(.W(3 * VW), .DEPTH(8 + 7 * MREG)) u_v_s8 (.clk_i(clk_i), .en_i(en_i), .d_i(v_i), .q_o(v8));
  sc_delay #(.W(3 * VW), .DEPTH(NS - 8 - 7 * MREG)) u_v_s10 (.clk_i(clk_i), .en_i(en_i), .d_i(v8), .q_o(v_o));

  // ---------------------------------------------------------------------------- S1: s = v·v
  wire signed [VW-1:0]   vx = v_i[VW-1:0];
  wire signed [VW-1:0]   vy = v_i[2*VW-1:VW];
  wire signed [VW-1:0]   vz = v_i[3*VW-1:2*VW];
  wire [2*VW-1:0] sqx, sqy, sqz;   // each <= 2^(2VW-2): non-negative in 2VW bits
  wire [2:0]      sq_side;
  wire unused_sq_side = &{1'b0, sq_side};
  sc_mul_stage #(.AW(VW), .BW(VW), .PW(2 * VW), .SIGNED(1), .MREG(MREG)) u_sqx (
      .clk_i(clk_i), .en_i(en_i), .a_i(vx), .b_i(vx), .c_i(1'b0), .side_i(1'b0), .p_o(sqx), .side_o(sq_side[0]));
  sc_mul_stage #(.AW(VW), .BW(VW), .PW(2 * VW), .SIGNED(1), .MREG(MREG)) u_sqy (
      .clk_i(clk_i), .en_i(en_i), .a_i(vy), .b_i(vy), .c_i(1'b0), .side_i(1'b0), .p_o(sqy), .side_o(sq_side[1]));
  sc_mul_stage #(.AW(VW), .BW(VW), .PW(2 * VW), .SIGNED(1), .MREG(MREG)) u_sqz (
      .clk_i(clk_i), .en_i(en_i), .a_i(vz), .b_i(vz), .c_i(1'b0), .side_i(1'b0), .p_o(sqz), .side_o(sq_side[2]));
  // MREG = 1: the squares' final adders end a stage of their own (a register on the three squares)
  wire [6*VW-1:0] sq3;
  sc_delay #(.W(6 * VW), .DEPTH(MREG)) u_sq3 (
      .clk_i(clk_i), .en_i(en_i), .d_i({sqz, sqy, sqx}), .q_o(sq3));
  wire [2*VW-1:0] s_raw = sq3[0 +: 2*VW] + sq3[2*VW +: 2*VW] + sq3[4*VW +: 2*VW];   // < 3·2^(2VW-2) < 2^(2VW)
  wire [SWF-1:0]  s_d;
  generate
    if (SWF > 2 * VW) begin : g_frame_pad
      assign s_d = {{(SWF-2*VW){1'b0}}, s_raw};
    end else begin : g_frame
      assign s_d = s_raw;
    end
  endgenerate

  reg [SWF-1:0] s1_s_q;
  always @(posedge clk_i) begin
    if (en_i) s1_s_q <= s_d;
  end

  // ---------------------------------------------------------------------------- S2: even normalisation
  reg [KW-1:0] k_d;
  integer      i;
  always @* begin
    k_d = K_MAX;
    for (i = 0; i < HW; i = i + 1) begin
      if (s1_s_q[2*i +: 2] != 2'b00) k_d = K_MAX - i[KW-1:0];
    end
  end
  // barrel shifter: stage b shifts left by 2·2^b when k bit b is set (2k <= SWF-2, nothing lost)
  reg [SWF-1:0] mn_d;
  integer       sb;
  always @* begin
    mn_d = s1_s_q;
    for (sb = 0; sb < KW; sb = sb + 1) begin
      if (k_d[sb]) mn_d = mn_d << (2 << sb);
    end
  end
  generate
    if (SWF > MW) begin : g_trunc_m
      wire unused_mn = &{1'b0, mn_d[SWF-MW-1:0]};   // truncated (e2 < 0)
    end
  endgenerate

  reg [MW-1:0] s2_m_q;
  reg [KW-1:0] s2_k_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s2_m_q <= mn_d[SWF-1:SWF-MW];
      s2_k_q <= k_d;
    end
  end

  // ---------------------------------------------------------------------------- S3: seed table
  // Both tables are elaborated per index from the integer rule (localparams, not a copied list):
  // entry i at bits [i*T +: T] (seed) and [i*AW +: AW] (a0), for every 7-bit index (the C model
  // reads 32..127; index 0 only occurs for s = 0, whose result is 0 whatever the entry).
  genvar b, c;
  wire [128*T-1:0]  seed_tab;
  wire [128*AW-1:0] a0_tab;
  generate
    for (b = 0; b < 128; b = b + 1) begin : g_table
      localparam integer SEED = rsqrt_seed(b);
      localparam integer A0   = rsqrt_a0(b);
      assign seed_tab[b*T +: T]  = SEED[T-1:0];
      assign a0_tab[b*AW +: AW]  = A0[AW-1:0];
    end
  endgenerate
  wire [IB-1:0] idx = s2_m_q[MW-1:MW-IB];
  reg  [T-1:0]  s3_y0_q;
  reg  [AW-1:0] s3_a0_q;
  reg  [MW-1:0] s3_m_q;
  reg  [KW-1:0] s3_k_q;
  reg  [MB+2:0] s3_km_q;   // m + 2^MB − 1, the low part of the addend Kc + m of S4 and S7 (MREG = 1)
  always @(posedge clk_i) begin
    if (en_i) begin
      s3_km_q <= {1'b0, s2_m_q} + {3'b000, {MB{1'b1}}};
      s3_y0_q <= seed_tab[idx*T +: T];
      s3_a0_q <= a0_tab[idx*AW +: AW];
      s3_m_q  <= s2_m_q;
      s3_k_q  <= s2_k_q;
    end
  end

  // ---------------------------------------------------------------------------- S4: c0 = 3 − m·a0
  wire [MW+AW-1:0] ma0;
  wire [T-1:0]     y0_4;
  wire [MW-1:0]    m_4;
  wire [KW-1:0]    k_4;
  wire [MB+2:0]    km_4;
  wire [R+1:0]     c0_d;   // b < 2^(R+1) for every m in range
  generate
    if (MREG != 0) begin : g_c0_fold
      // Kc − m·a0 = m·~a0 + (Kc + m) (signed, modulo 2^(MW+AW)); c0 is its bits [MB+R+1 : MB]. As S7's c1 below,
      // the tree is split in two half-height ones, b = ~{0, a0} = b_hi·2^H0 + b_lo: m·b_lo + (Kc + m) (u_ma0, which
      // carries the sideband) and (m·2^H0)·b_hi (u_ma0h), each to two carry-save rows | register | its adder; the
      // two sums are added in front of s4_c_q. The same c0 at the same stage; the first edge one Dadda level less.
      localparam integer H0   = (AW + 1) / 2;        // low bits of b (unsigned)
      localparam integer BWX0 = H0 + 1;              // b_lo zero-extended, b_hi sign-extended (AW+1−H0 <= H0+1)
      localparam integer AWX0 = MW + 1 + H0;         // {0, m}·2^H0, signed, non-negative
      wire [AW:0]        b0    = ~{1'b0, s3_a0_q};
      wire [BWX0-1:0]    b0_lo = {1'b0, b0[H0-1:0]};
      wire [BWX0-1:0]    b0_hi = {{(BWX0-(AW+1-H0)){b0[AW]}}, b0[AW:H0]};
      wire [MW+AW-1:0]   ma0_lo, ma0_hi;
      sc_mul_stage #(.AW(MW + 1), .BW(BWX0), .PW(MW + AW), .SIGNED(1), .ADD(1), .CW(R + MB + 2), .MREG(1),
                     .SW(T + MW + KW + MB + 3)) u_ma0 (
          .clk_i(clk_i), .en_i(en_i), .a_i({1'b0, s3_m_q}), .b_i(b0_lo),
          .c_i({2'b11, {(R-3){1'b0}}, s3_km_q}),
          .side_i({s3_y0_q, s3_m_q, s3_k_q, s3_km_q}), .p_o(ma0_lo), .side_o({y0_4, m_4, k_4, km_4}));
      sc_mul_reg #(.AW(AWX0), .BW(BWX0), .PW(MW + AW), .SIGNED(1), .LAT(1)) u_ma0h (
          .clk_i(clk_i), .en_i(en_i), .a_i({1'b0, s3_m_q, {H0{1'b0}}}), .b_i(b0_hi), .c_i(1'b0), .p_o(ma0_hi));
      assign ma0  = ma0_lo + ma0_hi;
      assign c0_d = ma0[MB+R+1:MB];
    end else begin : g_c0_sub
      sc_mul_stage #(.AW(MW), .BW(AW), .PW(MW + AW), .MREG(0), .SW(T + MW + KW + MB + 3)) u_ma0 (
          .clk_i(clk_i), .en_i(en_i), .a_i(s3_m_q), .b_i(s3_a0_q), .c_i(1'b0),
          .side_i({s3_y0_q, s3_m_q, s3_k_q, s3_km_q}), .p_o(ma0), .side_o({y0_4, m_4, k_4, km_4}));
      assign c0_d = THREE_R - ma0[MB+R+1:MB];
    end
  endgenerate
  wire unused_ma0 = &{1'b0, ma0[MW+AW-1:MB+R+2], ma0[MB-1:0]};
  reg  [R+1:0]  s4_c_q;
  reg  [T-1:0]  s4_y0_q;
  reg  [MW-1:0] s4_m_q;
  reg  [KW-1:0] s4_k_q;
  reg  [MB+2:0] s4_km_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s4_km_q <= km_4;
      s4_c_q  <= c0_d;
      s4_y0_q <= y0_4;
      s4_m_q  <= m_4;
      s4_k_q  <= k_4;
    end
  end

  // ---------------------------------------------------------------------------- S5: y1
  wire [T+R+1:0] yc0;
  wire [MW-1:0]  m_5;
  wire [KW-1:0]  k_5;
  wire [MB+2:0]  km_5;
  sc_mul_stage #(.AW(T), .BW(R + 2), .PW(T + R + 2), .MREG(MREG), .SW(MW + KW + MB + 3)) u_yc0 (
      .clk_i(clk_i), .en_i(en_i), .a_i(s4_y0_q), .b_i(s4_c_q), .c_i(1'b0),
      .side_i({s4_m_q, s4_k_q, s4_km_q}), .p_o(yc0), .side_o({m_5, k_5, km_5}));
  wire unused_yc0 = &{1'b0, yc0[T:0]};
  reg  [R:0]    s5_y_q;
  reg  [MW-1:0] s5_m_q;
  reg  [KW-1:0] s5_k_q;
  reg  [MB+2:0] s5_km_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s5_km_q <= km_5;
      s5_y_q <= yc0[T+R+1:T+1];
      s5_m_q <= m_5;
      s5_k_q <= k_5;
    end
  end

  // ---------------------------------------------------------------------------- S6: a1 = y1²
  wire [2*R+1:0] yy1;
  wire [R:0]     y_6;
  wire [MW-1:0]  m_6;
  wire [KW-1:0]  k_6;
  wire [MB+2:0]  km_6;
  sc_mul_stage #(.AW(R + 1), .BW(R + 1), .PW(2 * R + 2), .MREG(MREG), .SW(R + 1 + MW + KW + MB + 3)) u_yy1 (
      .clk_i(clk_i), .en_i(en_i), .a_i(s5_y_q), .b_i(s5_y_q), .c_i(1'b0),
      .side_i({s5_y_q, s5_m_q, s5_k_q, s5_km_q}), .p_o(yy1), .side_o({y_6, m_6, k_6, km_6}));
  wire unused_yy1 = &{1'b0, yy1[R-1:0]};
  reg  [R+1:0]  s6_a_q;
  reg  [R:0]    s6_y_q;
  reg  [MW-1:0] s6_m_q;
  reg  [KW-1:0] s6_k_q;
  reg  [MB+2:0] s6_km_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s6_km_q <= km_6;
      s6_a_q <= yy1[2*R+1:R];
      s6_y_q <= y_6;
      s6_m_q <= m_6;
      s6_k_q <= k_6;
    end
  end

  // ---------------------------------------------------------------------------- S7: c1 = 3 − m·a1
  wire [MW+R+1:0] ma1;
  wire [R+1:0]  s7_c_q;
  wire [R:0]    s7_y_q;
  wire [KW-1:0] s7_k_q;
  generate
    if (MREG != 0) begin : g_c1_fold
      // as S4: Kc − m·a1 = m·b + (Kc + m), b = ~{0, a1} (signed, R+3 bits). Its 31 × 30 tree alone is
      // deeper than a 4.0 ns stage in the cell flow, so b is split, b = b_hi·2^H1 + b_lo, and the product is
      // the sum of two half-height products, m·b_lo + (m·2^H1)·b_hi (rtl/sc_mul_reg.v N = 2, LAT = 2): each
      // half's tree to two carry-save rows | register | the four rows reduced and added | register. That
      // last register is S7's (s7_c_q), so S7 keeps its two edges and the outputs are those of one product.
      localparam integer H1  = (R + 3) / 2;          // low bits of b (unsigned)
      localparam integer BWX = H1 + 1;               // b_lo zero-extended, b_hi sign-extended (R+3−H1 <= H1+1)
      localparam integer AWX = MW + 1 + H1;          // {0, m} and {0, m}·2^H1, signed, both non-negative
      wire [R+2:0] b1 = ~{1'b0, s6_a_q};
      wire [BWX-1:0] b_lo = {1'b0, b1[H1-1:0]};
      wire [BWX-1:0] b_hi = {{(BWX-(R+3-H1)){b1[R+2]}}, b1[R+2:H1]};
      wire [AWX-1:0] a_lo = {{(H1+1){1'b0}}, s6_m_q};
      wire [AWX-1:0] a_hi = {1'b0, s6_m_q, {H1{1'b0}}};
      sc_mul_reg #(.AW(AWX), .BW(BWX), .PW(MW + R + 2), .SIGNED(1), .ADD(1), .CW(R + MB + 2), .N(2), .LAT(2))
          u_ma1 (.clk_i(clk_i), .en_i(en_i), .a_i({a_hi, a_lo}), .b_i({b_hi, b_lo}),
                 .c_i({2'b11, {(R-3){1'b0}}, s6_km_q}), .p_o(ma1));
      sc_delay #(.W(R + 1 + KW), .DEPTH(2)) u_side7 (
          .clk_i(clk_i), .en_i(en_i), .d_i({s6_y_q, s6_k_q}), .q_o({s7_y_q, s7_k_q}));
      assign s7_c_q = ma1[MB+R+1:MB];
    end else begin : g_c1_sub
      wire [R:0]    y_7;
      wire [KW-1:0] k_7;
      sc_mul_stage #(.AW(MW), .BW(R + 2), .PW(MW + R + 2), .MREG(0), .SW(R + 1 + KW)) u_ma1 (
          .clk_i(clk_i), .en_i(en_i), .a_i(s6_m_q), .b_i(s6_a_q), .c_i(1'b0),
          .side_i({s6_y_q, s6_k_q}), .p_o(ma1), .side_o({y_7, k_7}));
      wire unused_km = &{1'b0, s6_km_q};
      reg  [R+1:0]  c_q;
      reg  [R:0]    y_q;
      reg  [KW-1:0] k_q;
      always @(posedge clk_i) begin
        if (en_i) begin
          c_q <= THREE_R - ma1[MB+R+1:MB];
          y_q <= y_7;
          k_q <= k_7;
        end
      end
      assign s7_c_q = c_q;
      assign s7_y_q = y_q;
      assign s7_k_q = k_q;
    end
  endgenerate
  wire unused_ma1 = &{1'b0, ma1[MW+R+1:MB+R+2], ma1[MB-1:0]};

  // ---------------------------------------------------------------------------- S8: y2
  wire [2*R+2:0] yc1;
  wire [KW-1:0]  k_8;
  sc_mul_stage #(.AW(R + 1), .BW(R + 2), .PW(2 * R + 3), .MREG(MREG), .SW(KW)) u_yc1 (
      .clk_i(clk_i), .en_i(en_i), .a_i(s7_y_q), .b_i(s7_c_q), .c_i(1'b0),
      .side_i(s7_k_q), .p_o(yc1), .side_o(k_8));
  wire unused_yc1 = &{1'b0, yc1[2*R+2], yc1[R:0]};   // y2 < 2^R: bit 2R+2 is 0
  reg  [R:0]    s8_y_q;
  reg  [KW-1:0] s8_k_q;
  always @(posedge clk_i) begin
    if (en_i) begin
      s8_y_q <= yc1[2*R+1:R+1];
      s8_k_q <= k_8;
    end
  end

  // ---------------------------------------------------------------------------- S9: p_i = v_i·y2
  reg [3*PW-1:0] s9_p_q;
  reg [KW-1:0]   s9_k_q;
  generate
    for (c = 0; c < 3; c = c + 1) begin : g_mul
      // two's complement product modulo 2^PW: v_i·y2 as a signed VW × (R+2)-bit product at its
      // natural widths (y2 < 2^(R+1), made signed by a zero bit), sign-extended or cut to PW bits
      // — the same PW low bits as the product of the PW-bit extensions, without the PW × PW
      // multiplier that a product of extended operands asks a synthesis tool for
      // y2 is split at 17 bits (v·y2 = v·y_lo + v·y_hi·2^17, exact): each part is a signed VW × 18-bit
      // product, one DSP48E1 tile (25 × 18) for VW <= 25, where a tool splitting the wider operand
      // (Yosys 0.23) spends four on VW × (R+2) (docs/lighting.md §8.1)
      localparam integer YL = 17;
      wire signed [VW-1:0]   vc = v8[c*VW +: VW];
      wire signed [VW+R+1:0] pn;
      if (MREG != 0) begin : g_mreg
        // MREG = 1: one registered product (its final adder after the register), not the split
        wire [VW+R+1:0] pr;
        wire            p_side;
        // with the rounding addend 2^(HW+4−k) (k <= HW−1: a one-hot of HW+5 bits; |v·y2| < 2^(VW+R),
        // so the sum is still exact in VW+R+2 signed bits)
        wire [HW+4:0] rnd = {1'b1, {(HW+4){1'b0}}} >> s8_k_q;
        sc_mul_stage #(.AW(VW), .BW(R + 2), .PW(VW + R + 2), .SIGNED(1), .ADD(1), .CW(HW + 5), .MREG(1)) u_p (
            .clk_i(clk_i), .en_i(en_i), .a_i(vc), .b_i({1'b0, s8_y_q}), .c_i(rnd), .side_i(1'b0),
            .p_o(pr), .side_o(p_side));
        wire unused_p_side = &{1'b0, p_side};
        assign pn = pr;
      end else if (R + 1 > YL) begin : g_split
        wire signed [YL:0]        ylo = {1'b0, s8_y_q[YL-1:0]};
        wire signed [R+1-YL:0]    yhi = {1'b0, s8_y_q[R:YL]};
        wire signed [VW+YL:0]     plo = vc * ylo;
        wire signed [VW+R+1-YL:0] phi = vc * yhi;
        assign pn = {{(R+1-YL){plo[VW+YL]}}, plo} + {phi, {YL{1'b0}}};
      end else begin : g_whole
        wire signed [R+1:0] yc = {1'b0, s8_y_q};
        assign pn = vc * yc;
      end
      wire [PW-1:0] p_d;
      if (PW > VW + R + 2) begin : g_ext
        assign p_d = {{(PW-VW-R-2){pn[VW+R+1]}}, pn};
      end else begin : g_cut
        assign p_d = pn[PW-1:0];
        if (PW < VW + R + 2) begin : g_hi
          wire unused_pn = &{1'b0, pn[VW+R+1:PW]};
        end
      end
      always @(posedge clk_i) begin
        if (en_i) s9_p_q[c*PW +: PW] <= p_d;
      end
    end
  endgenerate
  wire [KW-1:0] k_9;
  sc_delay #(.W(KW), .DEPTH(MREG)) u_k_9 (.clk_i(clk_i), .en_i(en_i), .d_i(s8_k_q), .q_o(k_9));
  always @(posedge clk_i) begin
    if (en_i) s9_k_q <= k_9;
  end

  // ---------------------------------------------------------------------------- S10: rounding shift
  reg [3*OW-1:0] s10_u_q;
  generate
    for (c = 0; c < 3; c = c + 1) begin : g_rnd
      // barrel shifter: p·2^k modulo 2^PW (stage b shifts left by 2^b when k bit b is set)
      reg [PW-1:0] psh;
      integer      pb;
      always @* begin
        psh = s9_p_q[c*PW +: PW];
        for (pb = 0; pb < KW; pb = pb + 1) begin
          if (s9_k_q[pb]) psh = psh << (1 << pb);
        end
      end
      // MREG = 1: the rounding constant is already in p (S9)
      wire [PW-1:0] r_d = (MREG != 0) ? psh : psh + HALF_SH;
      wire unused_r = &{1'b0, r_d[HW+4:0]};
      always @(posedge clk_i) begin
        if (en_i) s10_u_q[c*OW +: OW] <= r_d[PW-1:HW+5];
      end
    end
  endgenerate
  assign u_o = s10_u_q;

endmodule

`default_nettype wire
