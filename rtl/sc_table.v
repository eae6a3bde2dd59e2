// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_table.v
// Purpose  : table-and-interpolate specular unit — the fixed-function GPUs' shine table (Mesa:
//            256 entries tab[i] = (i/255)^n, f = 255·cos θ, linear interpolation):
//              f = (E−1)·c,  i = ⌊f⌋,  out = V[i] + round(frac(f)·D[i])
//            with a per-material table RAM of E = 2^K words {D[i], V[i]} written by the host
//            (docs/spec.md §9; bit-accurate C model: cmodel/include/shadecore/units/table.hpp,
//            table_eval(), same stage names as TableTrace; contents: table_setup()).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC     F, fraction bits of cos θ, of the entries and of the output   8 <= F <= 24 (default 16)
//   ENTRIES  E, table size: 256 or 1024 (K = log2 E index bits)                       (default 256)
//   TAGW     width of the opaque tag that travels with each fragment, >= 1             (default 8)
//
// Ports : docs/spec.md §4 (clk_i, rst_ni synchronous active-low, AXI-Stream style valid/ready),
//         plus the table write port:
//   tab_we_i             write strobe: at a rising edge with tab_we_i high, word tab_addr_i of the
//                        RAM becomes {tab_delta_i, tab_value_i}; addresses >= E are ignored
//   tab_addr_i[9:0]      entry index i (10 bits for every E)
//   tab_value_i[F:0]     V[i] = ⌊(i/(E−1))^n · 2^F + ½⌋, unsigned, 1.0 = 2^F
//   tab_delta_i[F:0]     D[i] = V[i+1] − V[i] (D[E−1] = 0), unsigned
//
// Latency   : LATENCY = 3 (S0 RAM read, S1 multiply, S2 add); one fragment per clock.
// Handshake : in_ready_o = rst_ni && (!out_valid_o || out_ready_i), one global enable (as rtl/sc_cs16.v).
// Reset     : synchronous, active-low; clears the valid bits only. The RAM is not reset.
// Table     : a material change costs E writes (E clock cycles; one word per edge, also during reset).
//             The RAM is read synchronously AT THE ACCEPTING EDGE (address from in_cos_i), so a
//             fragment accepted at an edge sees every write before that edge and none at or after it
//             (a write at the accepting edge itself does not reach it); fragments in flight are never
//             affected by a reload. Rule for the host: do not present fragments while a new table is
//             being written (they would be shaded with a half-old, half-new table); no drain is needed.
//             mat_n_i, mat_thr_i and mat_we_i are not used (the table is the material).
//
// Datapath (K = log2 E; every box is a register stage on the global enable):
//
//   in_cos_i[F+1:0] signed
//      │  clamp to [0, 2^F] → c;  p = (c << K) − c = (E−1)·c   (F+K bits, exact)
//      │  i = p >> F (K bits, <= E−1),  fr = p mod 2^F (F bits)
//   ┌──▼──────────────────────────────────┐
//   │ S0  {D, V} = RAM[i] (sync read)  fr  tag │   RAM: E × (2F+2) bits, one read + one write port
//   └──┬──────────────────────────────────┘
//      │  prod = D·fr + 2^(F−1)              (2F+1 bits, exact)
//   ┌──▼─────────────────┐
//   │ S1  V  prod  tag    │
//   └──┬─────────────────┘
//      │  out = V + (prod >> F)              (F+1 bits; <= 2^F for table_setup() contents)
//   ┌──▼─────────────────┐
//   │ S2  out  tag        │──► out_spec_o[F:0], out_tag_o, out_valid_o
//   └────────────────────┘
// ============================================================================================
`default_nettype none

module sc_table #(
    parameter integer FRAC    = 16,
    parameter integer ENTRIES = 256,
    parameter integer TAGW    = 8
) (
    // table write port
    input  wire              tab_we_i,
    input  wire [9:0]        tab_addr_i,
    input  wire [FRAC:0]     tab_value_i,
    input  wire [FRAC:0]     tab_delta_i,
    // the unit ports (the material ones unused: the table is the material): clk_i, rst_ni;
    // mat_we_i, mat_n_i, mat_thr_i; in_valid_i, in_ready_o, in_cos_i, in_tag_i; out_valid_o,
    // out_ready_i, out_spec_o[FRAC:0], out_tag_o
`include "sc_unit_ports.vh"
);

  localparam integer F  = FRAC;
  localparam integer K  = (ENTRIES == 1024) ? 10 : 8;   // index bits (checked below)
  localparam integer WW = 2 * FRAC + 2;                 // RAM word {D, V}
  localparam integer PW = FRAC + K;                     // (E−1)·c < 2^(F+K)

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (FRAC < 8 || FRAC > 24) begin : g_check_frac
      sc_table_error_illegal_FRAC_legal_range_is_8_to_24 u_error ();
    end
    if (ENTRIES != 256 && ENTRIES != 1024) begin : g_check_entries
      sc_table_error_illegal_ENTRIES_must_be_256_or_1024 u_error ();
    end
    if (TAGW < 1) begin : g_check_tagw
      sc_table_error_illegal_TAGW_must_be_at_least_1 u_error ();
    end
  endgenerate

  localparam [F:0]    ONE  = {1'b1, {F{1'b0}}};                      // 2^F, cos θ = 1.0
  localparam [2*F:0]  HALF = {{(F+1){1'b0}}, 1'b1, {(F-1){1'b0}}};   // 2^(F−1)

  wire unused_mat = &{1'b0, mat_we_i, mat_n_i, mat_thr_i};

  // ---------------------------------------------------------------------------- handshake
  wire       adv;                          // global enable (rtl/sc_pipe_ctrl.v)
  wire [2:0] v_stage;                      // valid bit of each stage (unused: adv qualifies the data)
  sc_pipe_ctrl #(.DEPTH(3)) u_ctrl (
      .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
      .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .en_o(adv), .valid_o(v_stage));
  wire unused_v_stage = &{1'b0, v_stage};

  // ---------------------------------------------------------------------------- table RAM (write port)
  // Inferable: one write port, one synchronous read port with enable (iCE40: SB_RAM40_4K).
  reg [WW-1:0] ram_q [0:ENTRIES-1];
  wire         wr_in_range;                            // addresses >= E are ignored
  generate
    if (K < 10) begin : g_addr_hi
      assign wr_in_range = ~|tab_addr_i[9:K];
    end else begin : g_addr_full
      assign wr_in_range = 1'b1;
    end
  endgenerate
  always @(posedge clk_i) begin
    if (tab_we_i && wr_in_range) begin
      ram_q[tab_addr_i[K-1:0]] <= {tab_delta_i, tab_value_i};
    end
  end

  // ---------------------------------------------------------------------------- before S0: clamp, index
  wire        cos_neg  = in_cos_i[F+1];
  wire        cos_over = !cos_neg && (in_cos_i[F:0] > ONE);
  wire [F:0]  c_d      = cos_neg ? {(F+1){1'b0}} : (cos_over ? ONE : in_cos_i[F:0]);
  wire [PW:0] p_d      = {c_d, {K{1'b0}}} - {{K{1'b0}}, c_d};   // (E−1)·c, exact, < 2^(F+K)
  wire [K-1:0] idx_d   = p_d[PW-1:F];
  wire [F-1:0] fr_d    = p_d[F-1:0];
  wire unused_p = &{1'b0, p_d[PW]};

  // ---------------------------------------------------------------------------- S0: RAM read at the accepting edge
  reg [WW-1:0]   s0_word_q;
  reg [F-1:0]    s0_fr_q;
  reg [TAGW-1:0] s0_tag_q;
  always @(posedge clk_i) begin
    if (adv) begin
      s0_word_q <= ram_q[idx_d];
    end
  end
  always @(posedge clk_i) begin
    if (adv) begin
      s0_fr_q  <= fr_d;
      s0_tag_q <= in_tag_i;
    end
  end

  // ---------------------------------------------------------------------------- S1: multiply
  wire [F:0]   s0_v = s0_word_q[F:0];
  wire [F:0]   s0_d = s0_word_q[WW-1:F+1];
  wire [2*F:0] prod_d = ({{F{1'b0}}, s0_d} * {{(F+1){1'b0}}, s0_fr_q}) + HALF;   // < 2^(2F+1)

  reg [F:0]      s1_v_q;
  reg [2*F:0]    s1_prod_q;
  reg [TAGW-1:0] s1_tag_q;
  always @(posedge clk_i) begin
    if (adv) begin
      s1_v_q    <= s0_v;
      s1_prod_q <= prod_d;
      s1_tag_q  <= s0_tag_q;
    end
  end

  // ---------------------------------------------------------------------------- S2: add (mod 2^(F+1))
  wire [F:0] sum_d = s1_v_q + s1_prod_q[2*F:F];
  wire unused_prod = &{1'b0, s1_prod_q[F-1:0]};

  reg [F:0]      s2_out_q;
  reg [TAGW-1:0] s2_tag_q;
  always @(posedge clk_i) begin
    if (adv) begin
      s2_out_q <= sum_d;
      s2_tag_q <= s1_tag_q;
    end
  end

  assign out_spec_o = s2_out_q;
  assign out_tag_o  = s2_tag_q;

endmodule

`default_nettype wire
