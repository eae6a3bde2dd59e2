// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : formal/sc_formal_light.v
// Purpose  : formal harness of the lighting core rtl/sc_light.v (issue 21, docs/formal.md §7):
//            instantiates sc_light with the parameters of a feature set (FeatureSet::verilog_params,
//            set by scripts/formal.py with chparam), leaves every input free ($anyseq each cycle),
//            assumes reset in the first cycle and asserts port-level properties. The arithmetic is
//            abstracted by scripts/formal.py (yosys cutpoint: the lane, shade and normalise modules'
//            outputs are free values, the units' and register file's wide arithmetic cells too); every
//            register of sc_light.v itself (valid bits, pass scheduler, tag lines, accumulator,
//            in-flight counter) and the units' control are real.
//
// Two groups (docs/formal.md §7.2):
//   always (proved by k-induction; they are one-step properties of the real registers)
//     l_in_ready_reset   in_ready_o low while rst_ni is low
//     l_reg_ready_reset  reg_ready_o low while rst_ni is low (writes in reset are not taken)
//     l_in_ready_we      in_ready_o low while reg_we_i is high (docs/spec.md §8: writes drain first)
//     l_hold_valid, l_hold_r/g/b, l_hold_tag
//                        a valid output not taken at an edge with rst_ni high is still valid after it
//                        with the same colour and tag (with the abstraction the colour that enters the
//                        accumulator is a free value, the accumulator and the tag line are real)
//   `ifdef LIGHT_BMC (bounded: checked by BMC from reset; not inductive without invariants over the
//   core's internal pipeline, see docs/formal.md)
//     l_no_spurious      an output is valid only while accepted - taken since the last reset > 0
//                        (after reset no out_valid_o until a fragment was accepted; no duplicate)
//     l_count_bound      accepted - taken <= MAXF (the core's stage count; nothing piles up)
//     l_reg_ready_idle   reg_ready_o == rst_ni && (accepted - taken == 0): a register write is
//                        taken exactly when no fragment is in flight (docs/spec.md §8)
//     l_order            the n-th taken colour (n = any constant, since the last reset) was accepted,
//                        and carries the n-th accepted tag: in acceptance order, none lost, none
//                        duplicated (with l_live: none lost for ever)
//     l_live             with out_ready_i high and no reset, a fragment in flight comes out within
//                        LMAX clocks (LightCore::latency(), the largest over every register state)
//     l_tput_busy, l_tput_free
//                        after the light_mode register of every slot was written through the port,
//                        with k lights on (enable and a kind the slot can take), an accepted fragment
//                        keeps in_ready_o low for P - 1 clocks, P = max(1, ceil(k / LANES)), and
//                        (out_ready_i and rst_ni high in the P clocks after it, reg_we_i low in the
//                        P-th) in_ready_o is high again P clocks after the acceptance (non-iterative
//                        units only: ITER = 0 in every set run)
//
//   `ifdef LIGHT_INV (with LIGHT_BMC; diffuse only): invariants over sc_light's registers, observed through
//   wires scripts/formal.py connects after flattening, that make l_no_spurious, l_count_bound and
//   l_reg_ready_idle k-inductive there (job light_inv.diffuse)
//
// Mutants (scripts/formal.py MUTATIONS, light_*) edit a temporary copy of rtl/sc_light.v.
// Not a synthesizable module: only for `read_verilog -formal` (scripts/formal.py).
// ============================================================================================
`default_nettype none

module sc_formal_light #(
    parameter integer FRAC         = 16,
    parameter integer GUARD        = 5,
    parameter integer SGUARD       = 0,
    parameter integer LIGHTS       = 1,
    parameter integer SLOT_KINDS   = 1,
    parameter integer SLOT_SPOT    = 0,
    parameter integer LANES        = 1,
    parameter integer SHARE        = 1,   // passed through; the l_tput_* issue-slot properties assume 1
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
    // harness: bound on fragments in flight and on the clocks to an output (LightCore::latency())
    parameter integer MAXF         = 44,
    parameter integer LMAX         = 44
) (
    input wire clk_i
);
`include "sc_light_regs.vh"

  localparam integer CL  = FRAC + 1;
  localparam integer CW  = 7;          // harness counters (MAXF < 64)
  localparam integer NLT = LIGHTS;
  localparam [CW-1:0] MAXF_C = MAXF;
  localparam [CW-1:0] LMAX_C = LMAX;

  (* anyseq *) reg              rst_ni;
  (* anyseq *) reg              reg_we_i;
  (* anyseq *) reg [8:0]        reg_addr_i;
  (* anyseq *) reg [31:0]       reg_data_i;
  (* anyseq *) reg              in_valid_i;
  (* anyseq *) reg [FRAC+1:0]   in_nx_i, in_ny_i, in_nz_i;
  (* anyseq *) reg [FRAC+7:0]   in_px_i, in_py_i, in_pz_i;
  (* anyseq *) reg [TAGW-1:0]   in_tag_i;
  (* anyseq *) reg              in_back_i;
  (* anyseq *) reg [FRAC:0]     in_cr_i, in_cg_i, in_cb_i;
  (* anyseq *) reg              out_ready_i;
  wire            reg_ready_o, in_ready_o, out_valid_o;
  wire [CL-1:0]   out_r_o, out_g_o, out_b_o, out_sr_o, out_sg_o, out_sb_o;
  wire [TAGW-1:0] out_tag_o;

  sc_light #(
      .FRAC(FRAC), .GUARD(GUARD), .SGUARD(SGUARD), .LIGHTS(LIGHTS), .SLOT_KINDS(SLOT_KINDS), .SLOT_SPOT(SLOT_SPOT), .LANES(LANES), .SHARE(SHARE),
      .AMBIENT(AMBIENT), .DIFFUSE(DIFFUSE), .UNITS(UNITS), .CUTOFF(CUTOFF), .ENERGY(ENERGY),
      .BLINN(BLINN), .PHONG(PHONG), .LOCAL_VIEWER(LOCAL_VIEWER), .NORMALIZE(NORMALIZE), .LOW_N(LOW_N), .SEP_SPEC(SEP_SPEC), .TWO_SIDE(TWO_SIDE), .COL_MAT(COL_MAT),
      .CHANNELS(CHANNELS), .TAGW(TAGW)
  ) dut (
      .clk_i(clk_i), .rst_ni(rst_ni), .reg_we_i(reg_we_i), .reg_addr_i(reg_addr_i),
      .reg_data_i(reg_data_i), .reg_ready_o(reg_ready_o), .in_valid_i(in_valid_i),
      .in_ready_o(in_ready_o), .in_nx_i(in_nx_i), .in_ny_i(in_ny_i), .in_nz_i(in_nz_i),
      .in_px_i(in_px_i), .in_py_i(in_py_i), .in_pz_i(in_pz_i), .in_tag_i(in_tag_i), .in_back_i(in_back_i),
      .in_cr_i(in_cr_i), .in_cg_i(in_cg_i), .in_cb_i(in_cb_i),
      .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .out_r_o(out_r_o), .out_g_o(out_g_o),
      .out_b_o(out_b_o), .out_sr_o(out_sr_o), .out_sg_o(out_sg_o), .out_sb_o(out_sb_o), .out_tag_o(out_tag_o));

  wire accept = in_valid_i && in_ready_o;
  wire take   = out_valid_o && out_ready_i;

  // ---------------------------------------------------------------------------- environment
  // reset assumed in cycle 0; f_first, f_past (formal/sc_formal_env.vh)
`include "sc_formal_env.vh"

  // ---------------------------------------------------------------------------- always: proved
  always @* begin
    l_in_ready_reset:  assert (rst_ni || !in_ready_o);
    l_reg_ready_reset: assert (rst_ni || !reg_ready_o);
    l_in_ready_we:     assert (!reg_we_i || !in_ready_o);
  end
  always @(posedge clk_i) begin
    if (f_past && $past(f_past) && $past(rst_ni) && $past(out_valid_o) && !$past(out_ready_i)) begin
      l_hold_valid: assert (out_valid_o);
      l_hold_r:     assert (out_r_o == $past(out_r_o));
      l_hold_g:     assert (out_g_o == $past(out_g_o));
      l_hold_b:     assert (out_b_o == $past(out_b_o));
      l_hold_s:     assert ({out_sr_o, out_sg_o, out_sb_o} == $past({out_sr_o, out_sg_o, out_sb_o}));
      l_hold_tag:   assert (out_tag_o == $past(out_tag_o));
    end
  end

`ifdef LIGHT_BMC
  // ---------------------------------------------------------------------------- bounded group
  // accepted - taken since the last reset (a reset drops everything in flight; a colour taken at a
  // reset edge counts as transferred, docs/spec.md §4)
  reg [CW-1:0] f_cnt, f_nacc, f_ntake;
  always @(posedge clk_i) begin
    if (!rst_ni) begin
      f_cnt <= 0; f_nacc <= 0; f_ntake <= 0;
    end else begin
      f_cnt   <= f_cnt + accept - take;
      f_nacc  <= f_nacc + accept;
      f_ntake <= f_ntake + take;
    end
  end
  always @* begin
    if (f_past) begin
      l_no_spurious:    assert (!out_valid_o || f_cnt != 0);
      l_count_bound:    assert (f_cnt <= MAXF_C);
      l_reg_ready_idle: assert (reg_ready_o == (rst_ni && f_cnt == 0));
    end
  end

  // the n-th fragment since the last reset (n any constant): its tag in, its colour out
  (* anyconst *) reg [CW-1:0] f_sel;
  reg            f_sel_in, f_sel_out;
  reg [TAGW-1:0] f_sel_tag;
  always @(posedge clk_i) begin
    if (!rst_ni) begin
      f_sel_in <= 1'b0; f_sel_out <= 1'b0;
    end else begin
      if (accept && f_nacc == f_sel) begin
        f_sel_in  <= 1'b1;
        f_sel_tag <= in_tag_i;
      end
      if (take && f_ntake == f_sel) f_sel_out <= 1'b1;
    end
  end
  always @* begin
    if (f_past && take && f_ntake == f_sel) begin
      l_order: assert (f_sel_in && !f_sel_out && out_tag_o == f_sel_tag);
    end
  end

  // bounded liveness: clocks with out_ready_i high, no reset and something in flight, without a take
  reg [CW-1:0] f_idle;
  always @(posedge clk_i) begin
    if (!rst_ni || !out_ready_i || take || f_cnt == 0) f_idle <= 0;
    else f_idle <= f_idle + 1'b1;
  end
  always @* begin
    if (f_past) l_live: assert (f_idle < LMAX_C);
  end

  // throughput: a shadow of the light_mode registers, written through the port
  reg [4*NLT-1:0] f_mode;
  reg [NLT-1:0]   f_known = {NLT{1'b0}};
  wire            wr = reg_we_i && reg_ready_o;
  integer j, i, q;
  always @(posedge clk_i) begin
    for (i = 0; i < NLT; i = i + 1) begin
      if (wr && reg_addr_i == REG_LIGHT_MODE + LIGHT_STRIDE * i) begin
        f_mode[4*i +: 4] <= reg_data_i[3:0];
        f_known[i]       <= 1'b1;
      end
    end
  end
  reg [3:0] f_k;          // lights on
  reg [2:0] f_kind;
  reg [3:0] f_p;          // passes of a fragment: max(1, ceil(f_k / LANES)), without a divider
  always @* begin
    f_k = 4'd0;
    for (j = 0; j < NLT; j = j + 1) begin
      f_kind = f_mode[4*j+1 +: 3];
      if (f_mode[4*j] && ((f_kind <= 3'd2 && ((SLOT_KINDS >> (3 * j + f_kind)) & 1) != 0) ||
                          (f_kind == 3'd3 && ((SLOT_SPOT >> j) & 1) != 0))) f_k = f_k + 4'd1;
    end
    f_p = 4'd1;
    for (q = 1; q < 8; q = q + 1) begin
      if (f_k > q * LANES) f_p = q + 1;
    end
  end
  reg        f_tp_on = 1'b0;   // counting the clocks after an acceptance
  reg [3:0]  f_tp_p, f_tp_j;
  reg        f_tp_run;    // out_ready_i and rst_ni high in every clock since the acceptance
  always @(posedge clk_i) begin
    if (accept && (&f_known)) begin
      f_tp_on  <= 1'b1;
      f_tp_p   <= f_p;
      f_tp_j   <= 4'd1;
      f_tp_run <= 1'b1;
    end else if (f_tp_on) begin
      if (f_tp_j == f_tp_p || !rst_ni) f_tp_on <= 1'b0;
      f_tp_j   <= f_tp_j + 1'b1;
      f_tp_run <= f_tp_run && out_ready_i && rst_ni;
    end
  end
  always @* begin
    if (f_past && f_tp_on) begin   // f_tp_on: no reset at the edges since the acceptance
      if (f_tp_j < f_tp_p) l_tput_busy: assert (!in_ready_o);
      if (f_tp_j == f_tp_p && f_tp_run && out_ready_i && rst_ni && !reg_we_i) l_tput_free: assert (in_ready_o);
    end
  end
`ifdef LIGHT_INV
  // ---------------------------------------------------------------------------- strengthening (diffuse)
  // Job light_inv.diffuse (docs/formal.md §7.2): invariants over the core's internal state that make the
  // count properties above k-inductive for the diffuse core (LIGHTS = 1, UNITS = 0: front T_F = 1 stage,
  // back NB = 3 stages, CNTW = 3, one pass per fragment). The o_* wires are left undriven here; after
  // flattening scripts/formal.py connects each to the named register of sc_light (yosys connect -set), so
  // they observe the real state. Only for that parameter set.
  (* keep *) wire        o_vf;      // dut.vf_q
  (* keep *) wire [2:0]  o_vb;      // dut.vb_q
  (* keep *) wire        o_hold;    // dut.hold_q
  (* keep *) wire [2:0]  o_cnt;     // dut.cnt_q
  (* keep *) wire [TAGW+2:0] o_ftag;  // dut.u_dly_tag's register {tag, back, first, last}
  (* keep *) wire [3*(TAGW+1)-1:0] o_btag;  // dut.u_dly_btag's line, stage k = {tag, last} at k*(TAGW+1)
  wire [2:0] f_inflight = o_vf + o_vb[0] + o_vb[1] + o_vb[2];
  always @* begin
    if (f_past) begin
      i_hold:  assert (!o_hold);                       // one light: every pass is its fragment's last
      i_front: assert (!o_vf || o_ftag[0]);
      i_back0: assert (!o_vb[0] || o_btag[0]);
      i_back1: assert (!o_vb[1] || o_btag[TAGW+1]);
      i_back2: assert (!o_vb[2] || o_btag[2*(TAGW+1)]);
      i_cnt:   assert (f_cnt == {{(CW-3){1'b0}}, f_inflight} && o_cnt == f_inflight);
    end
  end
`endif
`endif

endmodule

`default_nettype wire
