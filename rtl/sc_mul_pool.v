// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_mul_pool.v
// Purpose  : the one multiplier-sharing rule of the lighting core (issue 18, `share`): NOP products
//            ("ops") of a global-enable pipeline, op o read at its stage ST(o); ops whose stages
//            differ mod SH share one multiplier instance. Used by rtl/sc_light_lane.v (the dot
//            products), rtl/sc_cs16.v (the four squarings), rtl/sc_schlick_nr.v and rtl/sc_recip.v
//            (the Newton–Raphson products). Purely combinational.
//
//   With SH = 1 every op that is on has its own multiplier, of its own operand widths: the same
//   products as written out one by one. With SH > 1 op o (in order o = 0, 1, ...) joins the first
//   instance that has no op at a stage ≡ ST(o) (mod SH); an instance multiplies the operands of the
//   op whose sel_i bit is set (an AND-OR selection; all zero when none is), each operand extended
//   (SIGNED: sign, else zero) to the instance's widest op. The low AW(o)+BW(o) bits of a product do
//   not depend on that extension, so every op reads exactly its own product. An instance holding a
//   single op multiplies it directly (no selection). The caller guarantees that at most one op of an
//   instance has its sel_i bit set: the pass of a pipeline whose passes are at least SH stages apart
//   is at most at one of SH consecutive stages (the lane: sel from the issue phase; the units: sel =
//   the stage's valid bit, passes kept SH apart by rtl/sc_pipe_ctrl.v's GAP).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   NOP    ops, 1..8
//   SH     stages per pass (the core's SHARE), 1..4
//   ON     bit o: op o exists (an op that is off has no multiplier and a zero product)
//   ST     op o's stage at bits [8o +: 8] (only its residue mod SH matters)
//   AW, BW op o's operand widths at bits [8o +: 8], 1..64 each
//   AMX, BMX  the port slot widths: >= every AW(o), BW(o)
//   SIGNED 1: operands and products are two's complement; 0: unsigned
//   LAT    0: combinational products; 1: each instance is an rtl/sc_mul_reg.v (LAT = 1, the register between
//          its tree and its final adder, clocked with en_i): op o's product is read one enabled edge after
//          its operands, at stage ST(o) + 1, the same sharing rule (the pipelining parameter MREG at share > 1)
// Ports : clk_i, en_i (LAT = 1: the instances' registers; unused with LAT = 0)
//         a_i[o*AMX +: AW(o)], b_i[o*BMX +: BW(o)] op o's operands (higher slot bits ignored);
//         sel_i[o] op o's pass is at its stage (SH > 1); p_o[o*PMX +: AW(o)+BW(o)] its product
//         (PMX = AMX + BMX; the slot's higher bits are the extension).
// ============================================================================================
`default_nettype none

module sc_mul_pool #(
    parameter integer NOP    = 1,
    parameter integer SH     = 1,
    parameter integer ON     = 255,
    parameter [63:0]  ST     = 64'd0,
    parameter [63:0]  AW     = 64'h0101010101010101,
    parameter [63:0]  BW     = 64'h0101010101010101,
    parameter integer AMX    = 2,
    parameter integer BMX    = 2,
    parameter integer SIGNED = 0,
    parameter integer LAT    = 0
) (
    input  wire                     clk_i,
    input  wire                     en_i,
    input  wire [NOP*AMX-1:0]       a_i,
    input  wire [NOP*BMX-1:0]       b_i,
    input  wire [NOP-1:0]           sel_i,
    output wire [NOP*(AMX+BMX)-1:0] p_o
);

  localparam integer PMX = AMX + BMX;

  function integer mp_fld(input [63:0] v, input integer o);   // the 8-bit field o of a packed parameter
    mp_fld = {24'd0, v[8*o +: 8]};
  endfunction
  function integer mp_on(input integer o);
    mp_on = (ON >> o) & 1;
  endfunction
  // the instance of op o: the first one with no op at its stage's residue (ops 0..o-1 placed first)
  function integer mp_inst(input integer o);
    integer j, i, used, r, res, found;
    begin
      used = 0;
      res = 0;
      for (j = 0; j <= o; j = j + 1) begin
        if (mp_on(j) != 0) begin
          r = (SH > 1) ? mp_fld(ST, j) % SH : 0;
          found = -1;
          for (i = NOP - 1; i >= 0; i = i - 1) begin
            if (((used >> (i * 4 + r)) & 1) == 0) found = i;
          end
          used = used | (1 << (found * 4 + r));
          if (j == o) res = found;
        end
      end
      mp_inst = res;
    end
  endfunction
  function integer mp_inst_w(input integer i, input integer b_side);   // an instance's widest a (b) operand
    integer o, w;
    begin
      mp_inst_w = 1;
      for (o = 0; o < NOP; o = o + 1) begin
        w = mp_fld(b_side != 0 ? BW : AW, o);
        if (mp_on(o) != 0 && mp_inst(o) == i && w > mp_inst_w) mp_inst_w = w;
      end
    end
  endfunction
  function integer mp_inst_ops(input integer i);
    integer o;
    begin
      mp_inst_ops = 0;
      for (o = 0; o < NOP; o = o + 1) begin
        if (mp_on(o) != 0 && mp_inst(o) == i) mp_inst_ops = mp_inst_ops + 1;
      end
    end
  endfunction

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  genvar o, i;
  generate
    if (NOP < 1 || NOP > 8) begin : g_check_nop
      sc_mul_pool_error_illegal_NOP_legal_range_is_1_to_8 u_error ();
    end
    if (SH < 1 || SH > 4) begin : g_check_sh
      sc_mul_pool_error_illegal_SH_legal_range_is_1_to_4 u_error ();
    end
    if (LAT != 0 && LAT != 1) begin : g_check_lat
      sc_mul_pool_error_illegal_LAT_must_be_0_or_1 u_error ();
    end
    for (o = 0; o < NOP; o = o + 1) begin : g_check_op
      if (mp_on(o) != 0 && (mp_fld(AW, o) < 1 || mp_fld(AW, o) > AMX || mp_fld(BW, o) < 1 || mp_fld(BW, o) > BMX))
      begin : g_check_w
        sc_mul_pool_error_illegal_op_width_must_be_1_to_AMX_or_BMX u_error ();
      end
    end
  endgenerate

  wire [NOP*PMX-1:0] ip;   // instance i's product at [i*PMX +: PMX], extended
  generate
    for (i = 0; i < NOP; i = i + 1) begin : g_inst
      localparam integer IA = mp_inst_w(i, 0);
      localparam integer IB = mp_inst_w(i, 1);
      localparam integer NI = mp_inst_ops(i);
      if (NI == 0) begin : g_none
        assign ip[i*PMX +: PMX] = {PMX{1'b0}};
      end else begin : g_mul
        wire [NOP*IA-1:0] a_t;   // op o's a, extended to IA and selected, at [o*IA +: IA]
        wire [NOP*IB-1:0] b_t;
        for (o = 0; o < NOP; o = o + 1) begin : g_op
          localparam integer OA = mp_fld(AW, o);
          localparam integer OB = mp_fld(BW, o);
          if (mp_on(o) != 0 && mp_inst(o) == i) begin : g_in
            wire          sel = (NI == 1) || sel_i[o];
            wire [OA-1:0] a = a_i[o*AMX +: OA];
            wire [OB-1:0] b = b_i[o*BMX +: OB];
            wire [IA-1:0] ax;
            wire [IB-1:0] bx;
            if (IA > OA) begin : g_xa
              wire sa = (SIGNED != 0) && a[OA-1];
              assign ax = {{(IA-OA){sa}}, a};
            end else begin : g_a
              assign ax = a;
            end
            if (IB > OB) begin : g_xb
              wire sb = (SIGNED != 0) && b[OB-1];
              assign bx = {{(IB-OB){sb}}, b};
            end else begin : g_b
              assign bx = b;
            end
            assign a_t[o*IA +: IA] = ax & {IA{sel}};
            assign b_t[o*IB +: IB] = bx & {IB{sel}};
          end else begin : g_out
            assign a_t[o*IA +: IA] = {IA{1'b0}};
            assign b_t[o*IB +: IB] = {IB{1'b0}};
          end
        end
        reg [IA-1:0] a_s;
        reg [IB-1:0] b_s;
        integer k;
        always @* begin
          a_s = {IA{1'b0}};
          b_s = {IB{1'b0}};
          for (k = 0; k < NOP; k = k + 1) begin
            a_s = a_s | a_t[k*IA +: IA];
            b_s = b_s | b_t[k*IB +: IB];
          end
        end
        wire [IA+IB-1:0] p;
        if (LAT != 0) begin : g_r
          sc_mul_reg #(.AW(IA), .BW(IB), .PW(IA + IB), .SIGNED(SIGNED)) u_mul (
              .clk_i(clk_i), .en_i(en_i), .a_i(a_s), .b_i(b_s), .c_i(1'b0), .p_o(p));
        end else if (SIGNED != 0) begin : g_s
          assign p = $signed(a_s) * $signed(b_s);
        end else begin : g_u
          assign p = a_s * b_s;
        end
        if (PMX > IA + IB) begin : g_x
          assign ip[i*PMX +: PMX] = {{(PMX-IA-IB){(SIGNED != 0) && p[IA+IB-1]}}, p};
        end else begin : g_w
          assign ip[i*PMX +: PMX] = p;
        end
      end
    end
    for (o = 0; o < NOP; o = o + 1) begin : g_out
      if (mp_on(o) != 0) begin : g_on
        assign p_o[o*PMX +: PMX] = ip[mp_inst(o)*PMX +: PMX];
      end else begin : g_off
        assign p_o[o*PMX +: PMX] = {PMX{1'b0}};
      end
    end
  endgenerate
  wire unused_in = &{1'b0, a_i, b_i, sel_i, clk_i, en_i};   // slot bits above an op's width; sel_i with SH = 1; clk/en with LAT = 0

endmodule

`default_nettype wire
