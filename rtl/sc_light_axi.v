// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_light_axi.v
// Purpose  : the lighting core rtl/sc_light.v as a drop-in bus block (issue 39, docs/handoff.md "AXI view"):
//            an AXI4-Lite slave in front of its register file and AXI4-Stream fragments in and colours out.
//            The core is instantiated unchanged with the same parameters (one elaboration key: a feature set
//            decides the capabilities and, through FRAC and TAGW, the packing); the bare core stays available.
//
// AXI4-Lite slave (32-bit data; byte address = register address * 4, AXI_ADDR = REG_ADDR_BITS + 2 bits; the two
// low address bits are ignored; no AxPROT ports: every access is treated alike):
//   * Existence (config/configs.json light.registers[].needs, generated into sc_light_axi.vh): an address is a
//     register of this build when every capability its register needs is built — ambient, diffuse, specular
//     (UNITS != 0), energy, colour_material, two_side; per light slot j < LIGHTS: attenuation (the slot can be
//     point_att or spot), spot (SLOT_SPOT). Reserved addresses, the reserved back-face unit registers, slots at or
//     above LIGHTS and registers of absent capabilities are not: a write there answers SLVERR and changes
//     nothing, a read answers SLVERR with RDATA 0. The three channel addresses of a colour register exist also
//     in a mono core (CHANNELS = 1; the core ignores g and b).
//   * Writes: AWREADY and WREADY are raised together, in the cycle both AWVALID and WVALID are high and no write
//     is in progress (one write at a time). WSTRB must be 4'hF; any other strobe answers SLVERR and writes
//     nothing (no partial writes: each register is one word). An accepted write is stored in the read-back
//     shadow at the acceptance edge, then held on the core's register port (reg_we_i) until the core takes it
//     (reg_ready_o: every fragment in flight has left the core — the bus write waits, it is never dropped);
//     BVALID rises the cycle after the core took it (OKAY) or after acceptance (SLVERR), and is held until BREADY.
//     Order against fragments: a fragment accepted on the stream at or before the write's acceptance edge is lit
//     with the registers before the write; from the cycle after acceptance until the response's handshake
//     (BVALID && BREADY) no fragment is accepted (TREADY low); every fragment accepted after it sees the write. A
//     driver that waits for BRESP before it streams the fragments of a new state needs no other synchronisation.
//   * Reads: ARREADY is high while no read is in progress; RVALID rises the cycle after acceptance with the word
//     last written to that address (the shadow: REG_WORDS x 32 bits, one simple dual-port RAM — a block RAM on
//     an FPGA, a RAM macro or flip-flops in a cell library; not reset: a register never written reads an
//     undefined word, as the core's registers are not reset), and is held until RREADY. A read accepted at the
//     edge of a write to the same address returns the word before that write (reads and writes are not ordered
//     against each other on AXI).
// AXI4-Stream slave (fragments) and master (colours): TDATA packed as sc_light_axi.vh says (config/configs.json
//   light.axi s_axis / m_axis: the fields LSB first, zero padding to whole bytes; the pad bits of S TDATA are
//   ignored, those of M TDATA are 0); TUSER = the fragment tag (TAGW bits); TLAST travels with its fragment
//   (the core runs with TAGW + 1 tag bits, the top one TLAST); no TKEEP/TSTRB (all bytes valid), no TID/TDEST.
//   Order is kept (the core is in order). Handshake: TREADY of the slave is the core's in_ready_o while no write is
//   outstanding (the ordering rule above); in_ready_o depends combinationally on the master's TREADY (rtl/sc_light.v
//   "Handshake"); TVALID and TDATA of the master are the
//   core's output stage (held under backpressure). Latency: the core's (no register slices in this wrapper).
// Reset: rst_ni synchronous, active low (the project convention, docs/spec.md §4): the core's fragments in flight
//   are dropped, a write waiting for the core and a response not yet taken are cleared (the write may or may not
//   have reached the core: the master that resets the block resends it, as it resends its fragments), the
//   registers and the shadow keep their values. While rst_ni is low every VALID and READY output is low (AXI's
//   reset rule), and the core's output stage is not drained into the bus.
// Parameters: exactly those of rtl/sc_light.v (FeatureSet::verilog_params), passed through.
// ============================================================================================
`default_nettype none

module sc_light_axi #(
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
    input  wire                      clk_i,
    input  wire                      rst_ni,
    // AXI4-Lite slave
    input  wire                      s_axil_awvalid_i,
    output wire                      s_axil_awready_o,
    input  wire [10:0]               s_axil_awaddr_i,
    input  wire                      s_axil_wvalid_i,
    output wire                      s_axil_wready_o,
    input  wire [31:0]               s_axil_wdata_i,
    input  wire [3:0]                s_axil_wstrb_i,
    output wire                      s_axil_bvalid_o,
    input  wire                      s_axil_bready_i,
    output wire [1:0]                s_axil_bresp_o,
    input  wire                      s_axil_arvalid_i,
    output wire                      s_axil_arready_o,
    input  wire [10:0]               s_axil_araddr_i,
    output wire                      s_axil_rvalid_o,
    input  wire                      s_axil_rready_i,
    output wire [31:0]               s_axil_rdata_o,
    output wire [1:0]                s_axil_rresp_o,
    // AXI4-Stream slave: fragments
    input  wire                      s_axis_tvalid_i,
    output wire                      s_axis_tready_o,
    input  wire [(3*(FRAC+2)+3*(FRAC+8)+1+3*(FRAC+1)+7)/8*8-1:0] s_axis_tdata_i,
    input  wire [TAGW-1:0]           s_axis_tuser_i,
    input  wire                      s_axis_tlast_i,
    // AXI4-Stream master: colours
    output wire                      m_axis_tvalid_o,
    input  wire                      m_axis_tready_i,
    output wire [(6*(FRAC+1)+7)/8*8-1:0] m_axis_tdata_o,
    output wire [TAGW-1:0]           m_axis_tuser_o,
    output wire                      m_axis_tlast_o
);
`include "sc_light_regs.vh"
`include "sc_light_axi.vh"

  localparam [1:0] RESP_OKAY = 2'b00, RESP_SLVERR = 2'b10;
  localparam integer AW = REG_ADDR_BITS;
  localparam integer REG_WORDS = 1 << AW;

  // the port widths above are the generated packing's (a configs.json edit that changes it stops elaboration)
  generate
    if (AXIS_IN_TDATA != (3*(FRAC+2)+3*(FRAC+8)+1+3*(FRAC+1)+7)/8*8 || AXIS_OUT_TDATA != (6*(FRAC+1)+7)/8*8
        || AW + 2 != 11) begin : g_bad_packing
      sc_light_axi_error_port_widths_disagree_with_sc_light_axi_vh u_error ();
    end
  endgenerate

  // ---------------------------------------------------------------------------- which addresses are registers
  localparam integer SPEC = (UNITS != 0) ? 1 : 0;
  localparam integer CAPS = ((AMBIENT != 0 ? 1 : 0) << AXI_NEED_AMBIENT) | ((DIFFUSE != 0 ? 1 : 0) << AXI_NEED_DIFFUSE)
                          | (SPEC << AXI_NEED_SPECULAR) | ((SPEC != 0 && ENERGY != 0 ? 1 : 0) << AXI_NEED_ENERGY)
                          | ((COL_MAT != 0 ? 1 : 0) << AXI_NEED_COLOUR_MATERIAL) | ((TWO_SIDE != 0 ? 1 : 0) << AXI_NEED_TWO_SIDE);
  function integer slot_caps(input integer j);  // CAPS plus what slot j can do
    integer k;
    begin
      k = (SLOT_KINDS >> (3 * j)) & 7;
      slot_caps = CAPS | (((((k >> 2) & 1) != 0 || ((SLOT_SPOT >> j) & 1) != 0) ? 1 : 0) << AXI_NEED_ATTENUATION)
                       | (((SLOT_SPOT >> j) & 1) << AXI_NEED_SPOT);
    end
  endfunction
  function exists(input [AW-1:0] w);
    integer a, n, j;
    begin
      a = {{(32-AW){1'b0}}, w};
      if (a >= AXI_LIGHT_BASE && a < AXI_LIGHT_BASE + MAX_LIGHTS * LIGHT_STRIDE) begin
        j = (a - AXI_LIGHT_BASE) / LIGHT_STRIDE;
        n = axi_light_needs((a - AXI_LIGHT_BASE) % LIGHT_STRIDE);
        exists = j < LIGHTS && n >= 0 && (n & ~slot_caps(j)) == 0;
      end else begin
        n = axi_global_needs(w);
        exists = n >= 0 && (n & ~CAPS) == 0;
      end
    end
  endfunction

  // ---------------------------------------------------------------------------- the core
  wire core_reg_ready, core_in_ready, core_out_valid;
  wire stream_open;   // no write between its acceptance and its response (the ordering rule above)
  wire [FRAC:0] o_r, o_g, o_b, o_sr, o_sg, o_sb;
  wire [TAGW:0] o_tag;
  localparam [1:0] W_IDLE = 2'd0, W_CORE = 2'd1, W_RESP = 2'd2;
  reg [1:0]    w_state_q;
  reg [AW-1:0] w_addr_q;
  reg [31:0]   w_data_q;
  reg          w_err_q;

  sc_light #(
      .FRAC(FRAC), .GUARD(GUARD), .SGUARD(SGUARD), .LIGHTS(LIGHTS), .SLOT_KINDS(SLOT_KINDS), .SLOT_SPOT(SLOT_SPOT),
      .LANES(LANES), .SHARE(SHARE), .AMBIENT(AMBIENT), .DIFFUSE(DIFFUSE), .UNITS(UNITS), .CUTOFF(CUTOFF),
      .ENERGY(ENERGY), .BLINN(BLINN), .PHONG(PHONG), .LOCAL_VIEWER(LOCAL_VIEWER), .NORMALIZE(NORMALIZE),
      .LOW_N(LOW_N), .SEP_SPEC(SEP_SPEC), .TWO_SIDE(TWO_SIDE), .COL_MAT(COL_MAT), .CHANNELS(CHANNELS),
      .TAGW(TAGW + 1), .MREG(MREG)
  ) u_core (
      .clk_i(clk_i), .rst_ni(rst_ni),
      .reg_we_i(w_state_q == W_CORE), .reg_addr_i(w_addr_q), .reg_data_i(w_data_q), .reg_ready_o(core_reg_ready),
      .in_valid_i(s_axis_tvalid_i && stream_open), .in_ready_o(core_in_ready),
      .in_nx_i(s_axis_tdata_i[AXIS_IN_NX_LSB +: AXIS_IN_NX_W]),
      .in_ny_i(s_axis_tdata_i[AXIS_IN_NY_LSB +: AXIS_IN_NY_W]),
      .in_nz_i(s_axis_tdata_i[AXIS_IN_NZ_LSB +: AXIS_IN_NZ_W]),
      .in_px_i(s_axis_tdata_i[AXIS_IN_PX_LSB +: AXIS_IN_PX_W]),
      .in_py_i(s_axis_tdata_i[AXIS_IN_PY_LSB +: AXIS_IN_PY_W]),
      .in_pz_i(s_axis_tdata_i[AXIS_IN_PZ_LSB +: AXIS_IN_PZ_W]),
      .in_tag_i({s_axis_tlast_i, s_axis_tuser_i}),
      .in_back_i(s_axis_tdata_i[AXIS_IN_BACK_LSB]),
      .in_cr_i(s_axis_tdata_i[AXIS_IN_CR_LSB +: AXIS_IN_CR_W]),
      .in_cg_i(s_axis_tdata_i[AXIS_IN_CG_LSB +: AXIS_IN_CG_W]),
      .in_cb_i(s_axis_tdata_i[AXIS_IN_CB_LSB +: AXIS_IN_CB_W]),
      .out_valid_o(core_out_valid), .out_ready_i(m_axis_tready_i && rst_ni),
      .out_r_o(o_r), .out_g_o(o_g), .out_b_o(o_b), .out_sr_o(o_sr), .out_sg_o(o_sg), .out_sb_o(o_sb),
      .out_tag_o(o_tag)
  );
  wire unused_pad = &{1'b0, s_axis_tdata_i[AXIS_IN_TDATA-1:AXIS_IN_BITS - 1]};
  wire unused_addr = &{1'b0, s_axil_awaddr_i[1:0], s_axil_araddr_i[1:0]};

  assign s_axis_tready_o = core_in_ready && stream_open;
  assign m_axis_tvalid_o = core_out_valid && rst_ni;   // VALID low in reset (AXI)
  assign m_axis_tuser_o  = o_tag[TAGW-1:0];
  assign m_axis_tlast_o  = o_tag[TAGW];
  wire [AXIS_OUT_BITS-1:0] o_bits;
  assign o_bits[AXIS_OUT_R_LSB +: AXIS_OUT_R_W]   = o_r;
  assign o_bits[AXIS_OUT_G_LSB +: AXIS_OUT_G_W]   = o_g;
  assign o_bits[AXIS_OUT_B_LSB +: AXIS_OUT_B_W]   = o_b;
  assign o_bits[AXIS_OUT_SR_LSB +: AXIS_OUT_SR_W] = o_sr;
  assign o_bits[AXIS_OUT_SG_LSB +: AXIS_OUT_SG_W] = o_sg;
  assign o_bits[AXIS_OUT_SB_LSB +: AXIS_OUT_SB_W] = o_sb;
  generate
    if (AXIS_OUT_TDATA > AXIS_OUT_BITS) begin : g_opad
      assign m_axis_tdata_o = {{(AXIS_OUT_TDATA - AXIS_OUT_BITS){1'b0}}, o_bits};
    end else begin : g_nopad
      assign m_axis_tdata_o = o_bits;
    end
  endgenerate

  // ---------------------------------------------------------------------------- writes
  wire aw_take = rst_ni && w_state_q == W_IDLE && s_axil_awvalid_i && s_axil_wvalid_i;
  wire [AW-1:0] aw_word = s_axil_awaddr_i[AW+1:2];
  wire aw_ok = exists(aw_word) && s_axil_wstrb_i == 4'hF;
  assign s_axil_awready_o = aw_take;
  assign s_axil_wready_o  = aw_take;
  always @(posedge clk_i) begin
    if (!rst_ni) begin
      w_state_q <= W_IDLE;
    end else begin
      case (w_state_q)
        W_IDLE: if (aw_take) w_state_q <= aw_ok ? W_CORE : W_RESP;
        W_CORE: if (core_reg_ready) w_state_q <= W_RESP;
        W_RESP: if (s_axil_bready_i) w_state_q <= W_IDLE;
        default: w_state_q <= W_IDLE;
      endcase
    end
  end
  always @(posedge clk_i) begin
    if (aw_take) begin
      w_addr_q <= aw_word;
      w_data_q <= s_axil_wdata_i;
      w_err_q  <= !aw_ok;
    end
  end
  assign stream_open     = w_state_q == W_IDLE;
  assign s_axil_bvalid_o = rst_ni && w_state_q == W_RESP;
  assign s_axil_bresp_o  = w_err_q ? RESP_SLVERR : RESP_OKAY;

  // ---------------------------------------------------------------------------- reads: the shadow
  reg [31:0] shadow [0:REG_WORDS-1];
  reg        r_busy_q, r_err_q;
  reg [31:0] r_data_q;
  wire ar_take = rst_ni && !r_busy_q && s_axil_arvalid_i;
  wire [AW-1:0] ar_word = s_axil_araddr_i[AW+1:2];
  always @(posedge clk_i) begin
    if (aw_take && aw_ok) shadow[aw_word] <= s_axil_wdata_i;
    if (ar_take) r_data_q <= shadow[ar_word];
  end
  always @(posedge clk_i) begin
    if (!rst_ni) begin
      r_busy_q <= 1'b0;
    end else if (ar_take) begin
      r_busy_q <= 1'b1;
    end else if (s_axil_rready_i) begin
      r_busy_q <= 1'b0;
    end
  end
  always @(posedge clk_i) begin
    if (ar_take) r_err_q <= !exists(ar_word);
  end
  assign s_axil_arready_o = rst_ni && !r_busy_q;
  assign s_axil_rvalid_o  = rst_ni && r_busy_q;
  assign s_axil_rresp_o   = r_err_q ? RESP_SLVERR : RESP_OKAY;
  assign s_axil_rdata_o   = r_err_q ? 32'd0 : r_data_q;
endmodule

`default_nettype wire
