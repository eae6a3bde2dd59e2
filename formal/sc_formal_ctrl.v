// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : formal/sc_formal_ctrl.v
// Purpose  : formal harness of rtl/sc_pipe_ctrl.v on its own (issue 21, docs/formal.md): free inputs,
//            rst_ni assumed low in the first cycle; the properties are those inside the primitive
//            (`ifdef FORMAL) plus, here, that en_o is exactly "output stage empty or being taken".
// ============================================================================================
`default_nettype none

module sc_formal_ctrl #(
    parameter integer DEPTH = 1,
    parameter integer GAP   = 1
) (
    input wire clk_i
);
  (* anyseq *) reg rst_ni;
  (* anyseq *) reg in_valid_i;
  (* anyseq *) reg out_ready_i;
  wire             in_ready_o, out_valid_o, en_o;
  wire [DEPTH-1:0] valid_o;

  sc_pipe_ctrl #(.DEPTH(DEPTH), .GAP(GAP)) dut (
      .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
      .out_valid_o(out_valid_o), .out_ready_i(out_ready_i), .en_o(en_o), .valid_o(valid_o));

  reg f_first = 1'b1;
  always @(posedge clk_i) f_first <= 1'b0;
  always @* begin
    if (f_first) assume (!rst_ni);
    c_en:      assert (en_o == (!out_valid_o || out_ready_i));
    c_out:     assert (out_valid_o == valid_o[DEPTH-1]);
  end
endmodule

`default_nettype wire
