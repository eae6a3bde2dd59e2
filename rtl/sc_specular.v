// ============================================================================================
// Filename : rtl/sc_specular.v
// Purpose  : top level of the specular shading core: selects one hardware unit by VARIANT and
//            exposes the common port list of docs/spec.md §4. The testbench (sim/) and the
//            lint/synthesis checks (rtl/CMakeLists.txt) always use this module.
//
// Parameters:
//   VARIANT  which unit; the ids come from config/configs.json "variants" through the generated
//            include sc_variants.vh (build/generated/rtl/, put it on the include path: -I).
//              VARIANT_CS16 (0): rtl/sc_cs16.v, latency 7, one fragment per clock
//              VARIANT_SCHLICK_DIV (1): rtl/sc_schlick_div.v, latency FRAC+4, one per clock
//              VARIANT_SCHLICK_NR (2): rtl/sc_schlick_nr.v, latency 10, one per clock
//              VARIANT_SCHLICK_ITER (3): rtl/sc_schlick_iter.v, latency FRAC+4, one per FRAC+4 clocks
//            (the Schlick units take FRAC and TAGW only; GUARD and CUTOFF do not apply to them)
//   FRAC, GUARD, CUTOFF, TAGW: passed to the unit; legal ranges in the unit's header
//            (cs16: 8 <= FRAC <= 24, 4 <= GUARD <= 8, FRAC+GUARD <= 31, CUTOFF 0/1, TAGW >= 1).
// Latency / throughput: those of the selected unit (cs16: 7 cycles, 1 per clock).
//
// Adding a unit: add {"name", "id"} to config/configs.json "variants", then one labelled
// generate branch below with the same port list.
// ============================================================================================
`default_nettype none

module sc_specular #(
    parameter integer VARIANT = 0,
    parameter integer FRAC    = 16,
    parameter integer GUARD   = 5,
    parameter integer CUTOFF  = 0,
    parameter integer TAGW    = 8
) (
    input  wire              clk_i,
    input  wire              rst_ni,
    input  wire              mat_we_i,
    input  wire [10:0]       mat_n_i,
    input  wire [FRAC:0]     mat_thr_i,
    input  wire              in_valid_i,
    output wire              in_ready_o,
    input  wire [FRAC+1:0]   in_cos_i,
    input  wire [TAGW-1:0]   in_tag_i,
    output wire              out_valid_o,
    input  wire              out_ready_i,
    output wire [FRAC:0]     out_spec_o,
    output wire [TAGW-1:0]   out_tag_o
);

`include "sc_variants.vh"

  generate
    if (VARIANT == VARIANT_CS16) begin : g_cs16
      sc_cs16 #(
          .FRAC  (FRAC),
          .GUARD (GUARD),
          .CUTOFF(CUTOFF),
          .TAGW  (TAGW)
      ) u_unit (
          .clk_i      (clk_i),
          .rst_ni     (rst_ni),
          .mat_we_i   (mat_we_i),
          .mat_n_i    (mat_n_i),
          .mat_thr_i  (mat_thr_i),
          .in_valid_i (in_valid_i),
          .in_ready_o (in_ready_o),
          .in_cos_i   (in_cos_i),
          .in_tag_i   (in_tag_i),
          .out_valid_o(out_valid_o),
          .out_ready_i(out_ready_i),
          .out_spec_o (out_spec_o),
          .out_tag_o  (out_tag_o)
      );
    end else if (VARIANT == VARIANT_SCHLICK_DIV) begin : g_schlick_div
      sc_schlick_div #(
          .FRAC(FRAC),
          .TAGW(TAGW)
      ) u_unit (
          .clk_i      (clk_i),
          .rst_ni     (rst_ni),
          .mat_we_i   (mat_we_i),
          .mat_n_i    (mat_n_i),
          .mat_thr_i  (mat_thr_i),
          .in_valid_i (in_valid_i),
          .in_ready_o (in_ready_o),
          .in_cos_i   (in_cos_i),
          .in_tag_i   (in_tag_i),
          .out_valid_o(out_valid_o),
          .out_ready_i(out_ready_i),
          .out_spec_o (out_spec_o),
          .out_tag_o  (out_tag_o)
      );
    end else if (VARIANT == VARIANT_SCHLICK_NR) begin : g_schlick_nr
      sc_schlick_nr #(
          .FRAC(FRAC),
          .TAGW(TAGW)
      ) u_unit (
          .clk_i      (clk_i),
          .rst_ni     (rst_ni),
          .mat_we_i   (mat_we_i),
          .mat_n_i    (mat_n_i),
          .mat_thr_i  (mat_thr_i),
          .in_valid_i (in_valid_i),
          .in_ready_o (in_ready_o),
          .in_cos_i   (in_cos_i),
          .in_tag_i   (in_tag_i),
          .out_valid_o(out_valid_o),
          .out_ready_i(out_ready_i),
          .out_spec_o (out_spec_o),
          .out_tag_o  (out_tag_o)
      );
    end else if (VARIANT == VARIANT_SCHLICK_ITER) begin : g_schlick_iter
      sc_schlick_iter #(
          .FRAC(FRAC),
          .TAGW(TAGW)
      ) u_unit (
          .clk_i      (clk_i),
          .rst_ni     (rst_ni),
          .mat_we_i   (mat_we_i),
          .mat_n_i    (mat_n_i),
          .mat_thr_i  (mat_thr_i),
          .in_valid_i (in_valid_i),
          .in_ready_o (in_ready_o),
          .in_cos_i   (in_cos_i),
          .in_tag_i   (in_tag_i),
          .out_valid_o(out_valid_o),
          .out_ready_i(out_ready_i),
          .out_spec_o (out_spec_o),
          .out_tag_o  (out_tag_o)
      );
    end else begin : g_check_variant
      $error("sc_specular: unknown VARIANT (see config/configs.json \"variants\")");
    end
  endgenerate

endmodule

`default_nettype wire
