// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_specular.v
// Purpose  : top level of the specular shading core: selects one hardware unit by VARIANT and
//            exposes the common port list of docs/spec.md §4. The testbench (sim/) and the
//            lint/synthesis checks (rtl/CMakeLists.txt) always use this module.
//
// Parameters:
//   VARIANT  which unit; the ids come from config/configs.json "variants" through the generated
//            include sc_variants.vh (rtl/, generated from config/configs.json by CMake; -Irtl).
//              VARIANT_CS16 (0): rtl/sc_cs16.v, latency 7, one fragment per clock
//              VARIANT_SCHLICK_DIV (1): rtl/sc_schlick_div.v, latency FRAC+4, one per clock
//              VARIANT_SCHLICK_NR (2): rtl/sc_schlick_nr.v, latency 10, one per clock
//              VARIANT_SCHLICK_ITER (3): rtl/sc_schlick_iter.v, latency FRAC+4, one per FRAC+4 clocks
//              VARIANT_CS16_FAITHFUL (4), VARIANT_CS16_COMPACT (5) — every variant with a "squarer"
//                entry: rtl/sc_cs16.v FORM = 1 with rtl/sc_square.v (docs/spec.md §3.4), latency 5,
//                one per clock; the form's constants come from sc_variants.vh (cs16_sq_param)
//              VARIANT_TABLE256 (6), VARIANT_TABLE1024 (7): rtl/sc_table.v with 256 / 1024 entries
//                (VARIANT_<NAME>_ENTRIES), latency 3, one per clock; the table is loaded through the
//                tab_*_i ports (docs/spec.md §9)
//            (the Schlick and table units take FRAC and TAGW only; GUARD and CUTOFF do not apply to them)
//   FRAC, GUARD, CUTOFF, TAGW: passed to the unit; legal ranges in the unit's header
//            (cs16: 8 <= FRAC <= 24, 4 <= GUARD <= 8, FRAC+GUARD <= 31, CUTOFF 0/1, TAGW >= 1).
//   ENERGY   0 (default): out_spec_o is the unit's output, F+1 bits.
//            1: the energy-normalisation stage rtl/sc_energy.v (docs/spec.md §7) follows the unit:
//            out_spec_o = round(unit output × mat_coef), COEFW bits, 1.0 = 2^F. The coefficient is
//            registered from mat_coef_i at mat_we_i (same rule as mat_n_i) and travels with the
//            fragment through the unit in the upper tag bits, so a material write never affects a
//            fragment in flight.
//   SHARE    1..4 (the lighting core's `share`; default 1): cs16 and schlick_nr share their multipliers
//            over SHARE consecutive stages and accept a fragment at most every SHARE clocks (their
//            headers); the other units ignore it.
//   MREG     0 or 1 (default 0): the pipelining parameter of cs16 (SHARE = 1; rtl/sc_cs16.v: latency 7 -> 12),
//            its forms cs16_faithful and cs16_compact (5 -> 11), schlick_div (F+4 -> F+5) and schlick_nr
//            (SHARE = 1; 10 -> 16): a register inside each product (rtl/sc_mul_reg.v, rtl/sc_sum_reg.v),
//            the same outputs; the other units ignore it (config/configs.json variants[].mreg_stages).
//   COEFW    coefficient (and, with ENERGY = 1, output) width I+F, FRAC+1..FRAC+16 (default FRAC+8,
//            enough for every model's coef over n = 16..1024). mat_coef_i is ignored when ENERGY = 0.
// Table port: tab_we_i, tab_addr_i[9:0], tab_value_i[FRAC:0], tab_delta_i[FRAC:0] write one entry of a
//            table unit's RAM per edge (docs/spec.md §9); every other unit ignores them (like mat_coef_i
//            with ENERGY = 0): tie tab_we_i low.
// Latency / throughput: those of the selected unit (cs16: 7 cycles, 1 per clock), + 2 with ENERGY = 1.
//
// Adding a unit: add {"name", "id"} to config/configs.json "variants", then one labelled
// generate branch below with the same port list (a new cs16 squaring form needs only its
// "squarer" entry in configs.json).
// ============================================================================================
`default_nettype none

module sc_specular #(
    parameter integer VARIANT = 0,
    parameter integer FRAC    = 16,
    parameter integer GUARD   = 5,
    parameter integer CUTOFF  = 0,
    parameter integer TAGW    = 8,
    parameter integer ENERGY  = 0,
    parameter integer COEFW   = FRAC + 8,
    parameter integer SHARE   = 1,
    parameter integer MREG    = 0
) (
    input  wire              clk_i,
    input  wire              rst_ni,
    input  wire              mat_we_i,
    input  wire [10:0]       mat_n_i,
    input  wire [FRAC:0]     mat_thr_i,
    input  wire [COEFW-1:0]  mat_coef_i,
    input  wire              tab_we_i,
    input  wire [9:0]        tab_addr_i,
    input  wire [FRAC:0]     tab_value_i,
    input  wire [FRAC:0]     tab_delta_i,
    input  wire              in_valid_i,
    output wire              in_ready_o,
    input  wire [FRAC+1:0]   in_cos_i,
    input  wire [TAGW-1:0]   in_tag_i,
    output wire              out_valid_o,
    input  wire              out_ready_i,
    output wire [((ENERGY != 0) ? COEFW : FRAC + 1)-1:0] out_spec_o,
    output wire [TAGW-1:0]   out_tag_o
);

`include "sc_variants.vh"

  // The unit's result side: straight to the ports (ENERGY = 0) or into sc_energy (ENERGY = 1), whose
  // coefficient rides in the unit's tag above the caller's tag bits.
  localparam integer CW    = (ENERGY != 0) ? COEFW : 0;
  localparam integer UTAGW = TAGW + CW;
  wire             u_out_valid, u_out_ready;
  wire [FRAC:0]    u_out_spec;
  wire [UTAGW-1:0] u_in_tag, u_out_tag;
  // GUARD and CUTOFF configure cs16 only. Referenced here so that lint does not flag them as unused
  // when sc_specular sits below another top with a Schlick VARIANT (they are ignored then).
  wire unused_cfg = (GUARD == 0) || (CUTOFF == 0) || (SHARE == 0) || (MREG == 0);
  // The table write port is used by the table units only.
  // (The table sizes are referenced here too: outside g_table they would be unused parameters.)
  wire is_table = ((VARIANT == VARIANT_TABLE256) || (VARIANT == VARIANT_TABLE1024)) &&
                  (VARIANT_TABLE256_ENTRIES > 0) && (VARIANT_TABLE1024_ENTRIES > 0);
  wire unused_tab = &{1'b0, is_table ? 1'b0 : &{1'b0, tab_we_i, tab_addr_i, tab_value_i, tab_delta_i}};

  // Every unit's ports (rtl/sc_unit_ports.vh) are connected alike: the caller's, with the tag and
  // the result side through u_* (above).
`define SC_SPECULAR_UNIT_PORTS \
          .clk_i      (clk_i), \
          .rst_ni     (rst_ni), \
          .mat_we_i   (mat_we_i), \
          .mat_n_i    (mat_n_i), \
          .mat_thr_i  (mat_thr_i), \
          .in_valid_i (in_valid_i), \
          .in_ready_o (in_ready_o), \
          .in_cos_i   (in_cos_i), \
          .in_tag_i   (u_in_tag), \
          .out_valid_o(u_out_valid), \
          .out_ready_i(u_out_ready), \
          .out_spec_o (u_out_spec), \
          .out_tag_o  (u_out_tag)
  generate
    if (VARIANT == VARIANT_CS16) begin : g_cs16
      sc_cs16 #(
          .FRAC  (FRAC),
          .GUARD (GUARD),
          .CUTOFF(CUTOFF),
          .TAGW  (UTAGW),
          .SHARE (SHARE),
          .MREG  (MREG)
      ) u_unit (
          `SC_SPECULAR_UNIT_PORTS
      );
    end else if (VARIANT == VARIANT_SCHLICK_DIV) begin : g_schlick_div
      sc_schlick_div #(
          .FRAC(FRAC),
          .TAGW(UTAGW),
          .MREG(MREG)
      ) u_unit (
          `SC_SPECULAR_UNIT_PORTS
      );
    end else if (VARIANT == VARIANT_SCHLICK_NR) begin : g_schlick_nr
      sc_schlick_nr #(
          .FRAC (FRAC),
          .TAGW (UTAGW),
          .SHARE(SHARE),
          .MREG (MREG)
      ) u_unit (
          `SC_SPECULAR_UNIT_PORTS
      );
    end else if (VARIANT == VARIANT_SCHLICK_ITER) begin : g_schlick_iter
      sc_schlick_iter #(
          .FRAC(FRAC),
          .TAGW(UTAGW)
      ) u_unit (
          `SC_SPECULAR_UNIT_PORTS
      );
    end else if (cs16_sq_param(VARIANT, 0) == 1) begin : g_cs16_form
      // cs16 forms with folded truncated squarers (config/configs.json "squarer", docs/spec.md §3.4):
      // the same sc_cs16, FORM = 1, the stage widths/truncation from sc_variants.vh.
      sc_cs16 #(
          .FRAC    (FRAC),
          .GUARD   (GUARD),
          .CUTOFF  (CUTOFF),
          .TAGW    (UTAGW),
          .FORM    (1),
          .SQ_REL_G(cs16_sq_param(VARIANT, 1)),
          .SQ_A1   (cs16_sq_param(VARIANT, 2)),
          .SQ_A2   (cs16_sq_param(VARIANT, 3)),
          .SQ_A3   (cs16_sq_param(VARIANT, 4)),
          .SQ_A4   (cs16_sq_param(VARIANT, 5)),
          .SQ_K1   (cs16_sq_param(VARIANT, 6)),
          .SQ_K2   (cs16_sq_param(VARIANT, 7)),
          .SQ_K3   (cs16_sq_param(VARIANT, 8)),
          .SQ_K4   (cs16_sq_param(VARIANT, 9)),
          .SQ_COMP (cs16_sq_param(VARIANT, 10)),
          .MREG    (MREG)
      ) u_unit (
          `SC_SPECULAR_UNIT_PORTS
      );
    end else if (VARIANT == VARIANT_TABLE256 || VARIANT == VARIANT_TABLE1024) begin : g_table
      sc_table #(
          .FRAC   (FRAC),
          .ENTRIES((VARIANT == VARIANT_TABLE256) ? VARIANT_TABLE256_ENTRIES : VARIANT_TABLE1024_ENTRIES),
          .TAGW   (UTAGW)
      ) u_unit (
          .tab_we_i   (tab_we_i),
          .tab_addr_i (tab_addr_i),
          .tab_value_i(tab_value_i),
          .tab_delta_i(tab_delta_i),
          `SC_SPECULAR_UNIT_PORTS
      );
    end else begin : g_check_variant
      // Portable Verilog-2005 elaboration error (Icarus, Verilator, Yosys): an undefined module
      // named after the message.
      sc_specular_error_unknown_VARIANT_see_config_configs_json_variants u_error ();
    end
  endgenerate
`undef SC_SPECULAR_UNIT_PORTS

  generate
    if (ENERGY == 0) begin : g_no_energy
      assign u_in_tag    = in_tag_i;
      assign out_valid_o = u_out_valid;
      assign u_out_ready = out_ready_i;
      assign out_spec_o  = u_out_spec;
      assign out_tag_o   = u_out_tag;
      wire unused_coef = &{1'b0, mat_coef_i};
    end else if (ENERGY == 1) begin : g_energy
      reg [COEFW-1:0] mat_coef_q;
      always @(posedge clk_i) begin
        if (mat_we_i) mat_coef_q <= mat_coef_i;
      end
      assign u_in_tag = {mat_coef_q, in_tag_i};
      sc_energy #(
          .FRAC    (FRAC),
          .COEFW   (COEFW),
          .COEF_SRC(1),
          .TAGW    (TAGW),
          .MREG    (MREG)
      ) u_energy (
          .clk_i      (clk_i),
          .rst_ni     (rst_ni),
          .mat_we_i   (1'b0),
          .mat_coef_i ({COEFW{1'b0}}),
          .in_valid_i (u_out_valid),
          .in_ready_o (u_out_ready),
          .in_spec_i  (u_out_spec),
          .in_coef_i  (u_out_tag[UTAGW-1:TAGW]),
          .in_tag_i   (u_out_tag[TAGW-1:0]),
          .out_valid_o(out_valid_o),
          .out_ready_i(out_ready_i),
          .out_norm_o (out_spec_o),
          .out_tag_o  (out_tag_o)
      );
    end else begin : g_check_norm
      // Portable elaboration error, as g_check_variant above.
      sc_specular_error_illegal_ENERGY_0_is_off_1_is_sc_energy_after_the_unit u_error ();
    end
  endgenerate

`ifdef FORMAL
  // Material rule of docs/spec.md §4 (proved with the unit, docs/formal.md): a material register
  // loads exactly at an edge with mat_we_i high (in reset too) and holds otherwise, and a fragment
  // accepted at an edge captures the material as it was before that edge (the old one at a write).
  reg f_init = 1'b0;
  always @(posedge clk_i) f_init <= 1'b1;
  generate
    if (ENERGY == 1) begin : g_f_energy
      always @(posedge clk_i) begin
        if (f_init) begin
          mat_load_coef: assert (u_in_tag[UTAGW-1:TAGW] == ($past(mat_we_i) ? $past(mat_coef_i) : $past(u_in_tag[UTAGW-1:TAGW])));
        end
      end
    end
  endgenerate
`endif

endmodule

`default_nettype wire
