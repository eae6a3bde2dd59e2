// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_energy.v
// Purpose  : energy-normalisation output stage — multiplies the specular unit's output by the
//            per-material coefficient coef(n) and rounds, exactly as docs/spec.md §7
//            (bit-accurate C model: cmodel/include/shadecore/units/coef.hpp, energy_eval(); stage names
//            N1/N2 as there).
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   FRAC      F, fraction bits of the unit output, of the coefficient and of the result
//             8 <= F <= 24                                                    (default 16)
//   COEFW     coefficient width I+F (I integer bits); also the result width
//             F+1 <= COEFW <= F+16; F+8 holds every model's coef for n = 16..1024 (max ≈ 173.4)
//                                                                             (default FRAC+8)
//   COEF_SRC  0 = the coefficient comes from this stage's material register (mat_we_i/mat_coef_i)
//             1 = the coefficient arrives with each fragment on in_coef_i (used when chained
//                 behind a unit that carries it in its tag, see rtl/sc_specular.v)  (default 0)
//   TAGW      width of the opaque tag that travels with each fragment, >= 1   (default 8)
//   MREG      0 or 1, the pipelining parameter (default 0): 1 forms N1's product with the rounding
//             constant as its addend through rtl/sc_mul_reg.v, so that the cell flow puts N1's register
//             between the product's tree and its final adder and N2 is that adder alone. The same
//             latency and outputs.
//
// Ports : docs/spec.md §4 convention (clk_i, rst_ni synchronous active-low, AXI-Stream style
//         valid/ready, TAGW tag sideband), plus
//           mat_we_i, mat_coef_i[COEFW-1:0]  material setup: coefficient code (coef_code())
//           in_spec_i[F:0]                   unit output, unsigned, 1.0 = 2^F (<= 2^F)
//           in_coef_i[COEFW-1:0]             per-fragment coefficient (COEF_SRC = 1 only)
//           out_norm_o[COEFW-1:0]            normalised output, unsigned, 1.0 = 2^F
//
// Latency   : LATENCY = 2 advancing edges (one global enable, as rtl/sc_cs16.v): a fragment
//             accepted at an edge is on out_* after the 2nd advancing edge; with out_ready_i
//             high throughout, accepted in cycle t → out_valid_o in cycle t+2.
// Throughput: one fragment per clock while out_ready_i is high.
// Handshake : in_ready_o = rst_ni && (!out_valid_o || out_ready_i) (combinational from
//             out_ready_i, as in sc_cs16); outputs hold while out_valid_o && !out_ready_i.
// Reset     : synchronous, active-low, clears the valid bits (in-flight fragments dropped).
// Material  : (COEF_SRC = 0) mat_we_i loads mat_coef_i at a rising edge; a fragment accepted at
//             that same edge uses the old coefficient. The product is formed at acceptance, so
//             fragments in flight never see a later write.
//
// Datapath:
//
//   in_spec_i[F:0] × coef[COEFW-1:0]            (exact, F+1+COEFW bits)
//   ┌──▼─────────────────────┐
//   │ N1  p[F+COEFW:0]  tag  │
//   └──┬─────────────────────┘
//      │  out = (p + 2^(F−1)) >> F              (round half up; spec <= 2^F and
//      │                                         coef <= 2^COEFW − 1 ⇒ out < 2^COEFW)
//   ┌──▼───────────────────────┐
//   │ N2  out[COEFW-1:0]  tag  │──► out_norm_o, out_tag_o, out_valid_o
//   └──────────────────────────┘
// ============================================================================================
`default_nettype none

module sc_energy #(
    parameter integer FRAC     = 16,
    parameter integer COEFW    = FRAC + 8,
    parameter integer COEF_SRC = 0,
    parameter integer TAGW     = 8,
    parameter integer MREG     = 0
) (
    input  wire              clk_i,
    input  wire              rst_ni,
    // material
    input  wire              mat_we_i,
    input  wire [COEFW-1:0]  mat_coef_i,
    // fragment in
    input  wire              in_valid_i,
    output wire              in_ready_o,
    input  wire [FRAC:0]     in_spec_i,
    input  wire [COEFW-1:0]  in_coef_i,
    input  wire [TAGW-1:0]   in_tag_i,
    // result out
    output wire              out_valid_o,
    input  wire              out_ready_i,
    output wire [COEFW-1:0]  out_norm_o,
    output wire [TAGW-1:0]   out_tag_o
);

  localparam integer F  = FRAC;
  localparam integer PW = FRAC + 1 + COEFW;  // product width

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (FRAC < 8 || FRAC > 24) begin : g_check_frac
      sc_energy_error_illegal_FRAC_legal_range_is_8_to_24 u_error ();
    end
    if (COEFW < FRAC + 1 || COEFW > FRAC + 16) begin : g_check_coefw
      sc_energy_error_illegal_COEFW_legal_range_is_FRAC_plus_1_to_FRAC_plus_16 u_error ();
    end
    if (COEF_SRC != 0 && COEF_SRC != 1) begin : g_check_src
      sc_energy_error_illegal_COEF_SRC_0_is_material_register_1_is_in_coef_i u_error ();
    end
    if (TAGW < 1) begin : g_check_tagw
      sc_energy_error_illegal_TAGW_must_be_at_least_1 u_error ();
    end
    if (MREG != 0 && MREG != 1) begin : g_check_mreg
      sc_energy_error_illegal_MREG_must_be_0_or_1 u_error ();
    end
  endgenerate

  localparam [PW-1:0] HALF = {{(PW-F){1'b0}}, 1'b1, {(F-1){1'b0}}};  // 2^(F-1)

  // ---------------------------------------------------------------------------- handshake
  wire       adv;                          // global enable (rtl/sc_pipe_ctrl.v)
  wire [1:0] v_stage;                      // valid bit of each stage (unused: adv qualifies the data)
  sc_pipe_ctrl #(.DEPTH(2)) u_ctrl (
      .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
      .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .en_o(adv), .valid_o(v_stage));
  wire unused_v_stage = &{1'b0, v_stage};

  // ---------------------------------------------------------------------------- coefficient source
  wire [COEFW-1:0] coef;
  generate
    if (COEF_SRC == 0) begin : g_coef_material
      reg [COEFW-1:0] mat_coef_q;
      always @(posedge clk_i) begin
        if (mat_we_i) mat_coef_q <= mat_coef_i;
      end
      assign coef = mat_coef_q;
      wire unused_in_coef = &{1'b0, in_coef_i};
    end else begin : g_coef_fragment
      assign coef = in_coef_i;
      wire unused_mat = &{1'b0, mat_we_i, mat_coef_i};
    end
  endgenerate

  // ---------------------------------------------------------------------------- N1: exact product
  // MREG = 0: N1 registers the product, N2 adds the rounding constant. MREG = 1: N1 registers
  // spec·coef + 2^(F−1) (rtl/sc_mul_reg.v: its tree in N1, its final adder in N2), N2 takes the slice.
  wire [PW-1:0] r_d;   // spec·coef + 2^(F−1) at N2 (< 2^(F+COEFW): no carry out of PW bits)
  reg [TAGW-1:0] n1_tag_q;
  always @(posedge clk_i) begin
    if (adv) n1_tag_q <= in_tag_i;
  end
  generate
    if (MREG != 0) begin : g_mreg
      sc_mul_reg #(.AW(F + 1), .BW(COEFW), .PW(PW), .SIGNED(0), .ADD(1), .CW(F)) u_p (
          .clk_i(clk_i), .en_i(adv), .a_i(in_spec_i), .b_i(coef), .c_i(HALF[F-1:0]), .p_o(r_d));
    end else begin : g_comb
      // coef split at 17 bits (spec·coef = spec·c_lo + spec·c_hi·2^17, exact): each part fits one DSP48E1
      // tile (25 × 18) for F <= 23, where a tool splitting the wider operand (Yosys 0.23) spends four
      localparam integer CL = 17;
      wire [PW-1:0] p_d;
      if (COEFW > CL) begin : g_split
        wire [F+CL:0]       plo = {{CL{1'b0}}, in_spec_i} * {{(F+1){1'b0}}, coef[CL-1:0]};
        wire [F+COEFW-CL:0] phi = {{(COEFW-CL){1'b0}}, in_spec_i} * {{(F+1){1'b0}}, coef[COEFW-1:CL]};
        assign p_d = {{(COEFW-CL){1'b0}}, plo} + {phi, {CL{1'b0}}};
      end else begin : g_whole
        assign p_d = {{COEFW{1'b0}}, in_spec_i} * {{(F+1){1'b0}}, coef};
      end
      reg [PW-1:0] n1_p_q;
      always @(posedge clk_i) begin
        if (adv) n1_p_q <= p_d;
      end
      assign r_d = n1_p_q + HALF;
    end
  endgenerate

  // ---------------------------------------------------------------------------- N2: round half up
  // r_d >> F fits COEFW bits; bit PW-1 is always 0 and bits F-1..0 are rounded away.
  wire unused_r = &{1'b0, r_d[PW-1], r_d[F-1:0]};

  reg [COEFW-1:0] n2_out_q;
  reg [TAGW-1:0]  n2_tag_q;
  always @(posedge clk_i) begin
    if (adv) begin
      n2_out_q <= r_d[F+COEFW-1:F];
      n2_tag_q <= n1_tag_q;
    end
  end

  assign out_norm_o = n2_out_q;
  assign out_tag_o  = n2_tag_q;

`ifdef FORMAL
  // Material rule of docs/spec.md §4 (proved with the unit, docs/formal.md): a material register
  // loads exactly at an edge with mat_we_i high (in reset too) and holds otherwise, and a fragment
  // accepted at an edge captures the material as it was before that edge (the old one at a write).
  reg f_init = 1'b0;
  always @(posedge clk_i) f_init <= 1'b1;
  generate
    if (COEF_SRC == 0) begin : g_f_mat
      always @(posedge clk_i) begin
        if (f_init) begin
          mat_load_coef: assert (coef == ($past(mat_we_i) ? $past(mat_coef_i) : $past(coef)));
        end
      end
    end
  endgenerate
`endif

endmodule

`default_nettype wire
