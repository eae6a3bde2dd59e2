// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : formal/sc_formal_unit.v
// Purpose  : formal harness of one unit (issue 21, docs/formal.md): instantiates rtl/sc_specular.v
//            (KIND = 0: VARIANT, FRAC, GUARD, CUTOFF, ENERGY) or rtl/sc_energy.v on its own (KIND = 1,
//            COEF_SRC = 0), leaves every input free (yosys-smtbmc picks them each cycle), assumes
//            reset in the first cycle and asserts the port-level properties below. The control
//            properties inside the RTL (`ifdef FORMAL in rtl/sc_pipe_ctrl.v, rtl/sc_schlick_iter.v
//            and the material checks of the units) are proved in the same run.
//
//   u_ready_reset  in_ready_o is low while rst_ni is low
//   u_hold         a valid output not taken at an edge with rst_ni high is still valid after it,
//                  with the same out_spec_o and out_tag_o (data and tag held)
// ("no valid output after a reset until something was accepted" and "accepted - taken = valid bits in
// flight" are asserted inside the control, where they are inductive: pc_no_spurious, pc_count.)
//
// Not a synthesizable module: only for `read_verilog -formal` (scripts/formal.py).
// ============================================================================================
`default_nettype none

module sc_formal_unit #(
    parameter integer KIND    = 0,   // 0: sc_specular, 1: sc_energy (COEF_SRC = 0)
    parameter integer VARIANT = 0,
    parameter integer FRAC    = 16,
    parameter integer GUARD   = 5,
    parameter integer CUTOFF  = 0,
    parameter integer ENERGY  = 0,
    parameter integer TAGW    = 4
) (
    input wire clk_i
);
  localparam integer COEFW = FRAC + 8;
  localparam integer OW    = (KIND == 1 || ENERGY != 0) ? COEFW : FRAC + 1;

  // free inputs: driven by $anyseq every cycle
  (* anyseq *) reg              rst_ni;
  (* anyseq *) reg              mat_we_i;
  (* anyseq *) reg [10:0]       mat_n_i;
  (* anyseq *) reg [FRAC:0]     mat_thr_i;
  (* anyseq *) reg [COEFW-1:0]  mat_coef_i;
  (* anyseq *) reg              tab_we_i;
  (* anyseq *) reg [9:0]        tab_addr_i;
  (* anyseq *) reg [FRAC:0]     tab_value_i;
  (* anyseq *) reg [FRAC:0]     tab_delta_i;
  (* anyseq *) reg              in_valid_i;
  (* anyseq *) reg [FRAC+1:0]   in_cos_i;
  (* anyseq *) reg [FRAC:0]     in_spec_i;
  (* anyseq *) reg [TAGW-1:0]   in_tag_i;
  (* anyseq *) reg              out_ready_i;

  wire            in_ready_o;
  wire            out_valid_o;
  wire [OW-1:0]   out_spec_o;
  wire [TAGW-1:0] out_tag_o;

  generate
    if (KIND == 0) begin : g_spec
      wire unused_h = &{1'b0, in_spec_i};
      sc_specular #(
          .VARIANT(VARIANT), .FRAC(FRAC), .GUARD(GUARD), .CUTOFF(CUTOFF), .TAGW(TAGW), .ENERGY(ENERGY),
          .COEFW(COEFW)
      ) dut (
          .clk_i(clk_i), .rst_ni(rst_ni), .mat_we_i(mat_we_i), .mat_n_i(mat_n_i),
          .mat_thr_i(mat_thr_i), .mat_coef_i(mat_coef_i), .tab_we_i(tab_we_i),
          .tab_addr_i(tab_addr_i), .tab_value_i(tab_value_i), .tab_delta_i(tab_delta_i),
          .in_valid_i(in_valid_i), .in_ready_o(in_ready_o), .in_cos_i(in_cos_i),
          .in_tag_i(in_tag_i), .out_valid_o(out_valid_o), .out_ready_i(out_ready_i),
          .out_spec_o(out_spec_o), .out_tag_o(out_tag_o));
    end else begin : g_energy
      wire unused_h = &{1'b0, mat_n_i, mat_thr_i, tab_we_i, tab_addr_i, tab_value_i, tab_delta_i,
                        in_cos_i};
      sc_energy #(.FRAC(FRAC), .COEFW(COEFW), .COEF_SRC(0), .TAGW(TAGW)) dut (
          .clk_i(clk_i), .rst_ni(rst_ni), .mat_we_i(mat_we_i), .mat_coef_i(mat_coef_i),
          .in_valid_i(in_valid_i), .in_ready_o(in_ready_o), .in_spec_i(in_spec_i),
          .in_coef_i({COEFW{1'b0}}), .in_tag_i(in_tag_i), .out_valid_o(out_valid_o),
          .out_ready_i(out_ready_i), .out_norm_o(out_spec_o), .out_tag_o(out_tag_o));
    end
  endgenerate

  // ---------------------------------------------------------------------------- environment
  // reset assumed in cycle 0; f_first, f_past (formal/sc_formal_env.vh)
`include "sc_formal_env.vh"

  // ---------------------------------------------------------------------------- properties
  always @* begin
    u_ready_reset: assert (rst_ni || !in_ready_o);
  end
  always @(posedge clk_i) begin
    if (f_past && $past(f_past) && $past(rst_ni) && $past(out_valid_o) && !$past(out_ready_i)) begin
      u_hold_valid: assert (out_valid_o);
      u_hold_data:  assert (out_spec_o == $past(out_spec_o));
      u_hold_tag:   assert (out_tag_o == $past(out_tag_o));
    end
  end

endmodule

`default_nettype wire
