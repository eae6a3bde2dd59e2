// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : formal/sc_formal_axi.v
// Purpose  : formal harness of the AXI wrapper rtl/sc_light_axi.v (issue 39, docs/formal.md §9): the wrapper around
//            the lighting core of a feature set (FeatureSet::verilog_params, set by scripts/formal.py), every
//            input free ($anyseq each cycle: the bus masters are not assumed to follow any rule), reset assumed
//            in the first cycle; the core's arithmetic abstracted as in the core's jobs (docs/formal.md §7.3).
//
// Properties (proved by k-induction; AXI4-Lite slave and AXI4-Stream rules, and the wrapper's stated ones):
//   a_reset         while rst_ni is low: AWREADY, WREADY, BVALID, ARREADY, RVALID, S TREADY, M TVALID low
//   a_aw_w          AWREADY == WREADY, and only with AWVALID && WVALID (the wrapper takes a write whole)
//   a_b_hold        a response not taken (BVALID && !BREADY, rst_ni high) stays, with the same BRESP
//   a_r_hold        the same for RVALID, RDATA, RRESP
//   a_m_hold        a colour not taken (M TVALID && !TREADY) stays, with the same TDATA, TUSER, TLAST
//   a_w_one, a_r_one        at most one write / one read between acceptance and response
//   a_b_req, a_r_req        BVALID / RVALID only with a request outstanding (no response without a request)
//   a_aw_free, a_ar_free    AWREADY / ARREADY only with nothing outstanding (one response per request)
//   a_r_next        a read accepted at an edge (rst_ni high) is answered at the next: bounded read latency
//   a_order         a fragment is accepted on the stream only with no write outstanding (the ordering rule:
//                   a write is never overtaken by a fragment between its acceptance and its response)
//   i_w, i_r        invariants tying the harness's counts to the wrapper's state (observed through wires that
//                   scripts/formal.py connects after flattening): what makes the counts k-inductive
//   `ifdef AXI_BMC (bounded, BMC from reset; job axi_bmc.diffuse)
//     a_b_bounded   with M TREADY high (assumed in this group), a write is answered within LMAX + 2 clocks of its
//                   acceptance (the core drains first): bounded write latency while not stalled
// Not here: the values (the co-simulation, sim/tb_light_axi.hpp, checks every register, response and colour).
// Mutants: scripts/formal.py MUTATIONS axi_* edit a temporary copy of rtl/sc_light_axi.v.
// Not a synthesizable module: only for `read_verilog -formal` (scripts/formal.py).
// ============================================================================================
`default_nettype none

module sc_formal_axi #(
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
    parameter integer MREG         = 0,
    parameter integer MAXF         = 44,   // (the core harness's bounds; unused here)
    parameter integer LMAX         = 44
) (
    input wire clk_i
);
  localparam integer SW = (3*(FRAC+2)+3*(FRAC+8)+1+3*(FRAC+1)+7)/8*8;
  localparam integer MW = (6*(FRAC+1)+7)/8*8;

  (* anyseq *) reg          rst_ni;
  (* anyseq *) reg          awvalid, wvalid, bready, arvalid, rready, s_tvalid, s_tlast, m_tready;
  (* anyseq *) reg [10:0]   awaddr, araddr;
  (* anyseq *) reg [31:0]   wdata;
  (* anyseq *) reg [3:0]    wstrb;
  (* anyseq *) reg [SW-1:0] s_tdata;
  (* anyseq *) reg [TAGW-1:0] s_tuser;
  wire          awready, wready, bvalid, arready, rvalid, s_tready, m_tvalid, m_tlast;
  wire [1:0]    bresp, rresp;
  wire [31:0]   rdata;
  wire [MW-1:0] m_tdata;
  wire [TAGW-1:0] m_tuser;

  sc_light_axi #(
      .FRAC(FRAC), .GUARD(GUARD), .SGUARD(SGUARD), .LIGHTS(LIGHTS), .SLOT_KINDS(SLOT_KINDS), .SLOT_SPOT(SLOT_SPOT),
      .LANES(LANES), .SHARE(SHARE), .AMBIENT(AMBIENT), .DIFFUSE(DIFFUSE), .UNITS(UNITS), .CUTOFF(CUTOFF),
      .ENERGY(ENERGY), .BLINN(BLINN), .PHONG(PHONG), .LOCAL_VIEWER(LOCAL_VIEWER), .NORMALIZE(NORMALIZE),
      .LOW_N(LOW_N), .SEP_SPEC(SEP_SPEC), .TWO_SIDE(TWO_SIDE), .COL_MAT(COL_MAT), .CHANNELS(CHANNELS), .TAGW(TAGW),
      .MREG(MREG)
  ) dut (
      .clk_i(clk_i), .rst_ni(rst_ni),
      .s_axil_awvalid_i(awvalid), .s_axil_awready_o(awready), .s_axil_awaddr_i(awaddr),
      .s_axil_wvalid_i(wvalid), .s_axil_wready_o(wready), .s_axil_wdata_i(wdata), .s_axil_wstrb_i(wstrb),
      .s_axil_bvalid_o(bvalid), .s_axil_bready_i(bready), .s_axil_bresp_o(bresp),
      .s_axil_arvalid_i(arvalid), .s_axil_arready_o(arready), .s_axil_araddr_i(araddr),
      .s_axil_rvalid_o(rvalid), .s_axil_rready_i(rready), .s_axil_rdata_o(rdata), .s_axil_rresp_o(rresp),
      .s_axis_tvalid_i(s_tvalid), .s_axis_tready_o(s_tready), .s_axis_tdata_i(s_tdata), .s_axis_tuser_i(s_tuser),
      .s_axis_tlast_i(s_tlast),
      .m_axis_tvalid_o(m_tvalid), .m_axis_tready_i(m_tready), .m_axis_tdata_o(m_tdata), .m_axis_tuser_o(m_tuser),
      .m_axis_tlast_o(m_tlast));

  // reset assumed in cycle 0; f_first, f_past (formal/sc_formal_env.vh)
`include "sc_formal_env.vh"

  wire aw_acc = awvalid && awready && wvalid && wready;
  wire b_take = bvalid && bready;
  wire ar_acc = arvalid && arready;
  wire r_take = rvalid && rready;
  // requests accepted - responses taken since the last reset (a reset drops both)
  reg [1:0] f_w, f_r;
  always @(posedge clk_i) begin
    if (!rst_ni) begin
      f_w <= 2'd0;
      f_r <= 2'd0;
    end else begin
      f_w <= f_w + {1'b0, aw_acc} - {1'b0, b_take};
      f_r <= f_r + {1'b0, ar_acc} - {1'b0, r_take};
    end
  end
  // the wrapper's state, connected by scripts/formal.py after flattening (dut.w_state_q, dut.r_busy_q)
  wire [1:0] o_wstate;
  wire       o_rbusy;

  always @* begin
    a_reset: assert (rst_ni || !(awready || wready || bvalid || arready || rvalid || s_tready || m_tvalid));
    a_aw_w:  assert (awready == wready && (!awready || (awvalid && wvalid)));
    if (f_past) begin
      a_w_one:   assert (f_w <= 2'd1);
      a_r_one:   assert (f_r <= 2'd1);
      a_b_req:   assert (!bvalid || f_w == 2'd1);
      a_r_req:   assert (!rvalid || f_r == 2'd1);
      a_aw_free: assert (!awready || f_w == 2'd0);
      a_ar_free: assert (!arready || f_r == 2'd0);
      a_order:   assert (!(s_tvalid && s_tready) || f_w == 2'd0);
      i_w:       assert (f_w == {1'b0, o_wstate != 2'd0});
      i_r:       assert (f_r == {1'b0, o_rbusy});
    end
  end
  always @(posedge clk_i) begin
    if (f_past && $past(f_past) && rst_ni && $past(rst_ni)) begin
      if ($past(bvalid) && !$past(bready)) begin
        a_b_hold: assert (bvalid && bresp == $past(bresp));
      end
      if ($past(rvalid) && !$past(rready)) begin
        a_r_hold: assert (rvalid && rdata == $past(rdata) && rresp == $past(rresp));
      end
      if ($past(m_tvalid) && !$past(m_tready)) begin
        a_m_hold: assert (m_tvalid && m_tdata == $past(m_tdata) && m_tuser == $past(m_tuser) && m_tlast == $past(m_tlast));
      end
      if ($past(ar_acc)) begin
        a_r_next: assert (rvalid);
      end
    end
  end

`ifdef AXI_BMC
  // ---------------------------------------------------------------------------- bounded (job axi_bmc.*)
  // With the colour stream never stalled (M TREADY high: assumed in this group only), a write accepted at an edge is
  // answered (BVALID) within LMAX + 2 clocks: the core drains what is in flight (LightCore::latency() = LMAX), takes
  // the write, and the response follows. A reset in between ends the wait. Not k-inductive at the ports alone (the
  // drain depends on the core's internal pipeline, as the core's l_live): checked by BMC from reset.
  localparam integer WMAX = LMAX + 2;
  reg [7:0] f_wage;
  reg       f_wpend;
  always @(posedge clk_i) begin
    if (!rst_ni || bvalid) begin
      f_wpend <= 1'b0;
      f_wage  <= 8'd0;
    end else if (aw_acc) begin
      f_wpend <= 1'b1;
      f_wage  <= 8'd0;
    end else if (f_wpend && f_wage != 8'hff) begin
      f_wage <= f_wage + 8'd1;
    end
  end
  always @* begin
    assume (m_tready);
    if (f_past && f_wpend) begin
      a_b_bounded: assert (f_wage <= WMAX[7:0]);
    end
  end
`endif
endmodule

`default_nettype wire
