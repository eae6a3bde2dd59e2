// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/tests/tb_unit_share.v
// Purpose  : the pipelining parameter MREG at share > 1, unit by unit (ctest rtl.icarus.share_mreg.*): two
//            instances of the unit `UNIT (rtl/sc_cs16.v or rtl/sc_schlick_nr.v), SHARE = 1 and SHARE = SH, both
//            MREG = 1, take the same N codes (random, cos = 1.0 every 97th) with random input gaps and output
//            stalls of their own; their output streams (value and tag, in order) must be equal. The gaps matter:
//            GAP keeps fragments SHARE stages apart, not a multiple of it, and a squarer shared by two stages
//            further apart than that takes two fragments at once (a pool given SH = SHARE instead of ⌈SHARE/2⌉
//            fails here). Prints "PASS: ..." or "FAIL: ...".
// ============================================================================================
`default_nettype none
module tb;
  parameter integer SH = 4;
  parameter integer N  = 20000;
  localparam integer F = 16;
  reg clk = 0, rst_n = 0;
  always #5 clk = ~clk;
  reg [F+1:0] cosv [0:N-1];
  reg [10:0]  nv   [0:N-1];
  integer i, seed, ia, ib, oa, ob, errs, nz;
  reg mat_we; reg [10:0] mat_n; reg [F:0] mat_thr;
  wire a_rdy, b_rdy, a_ov, b_ov; wire [F:0] a_o, b_o; wire [7:0] a_t, b_t;
  reg a_or, b_or; reg a_iv = 1, b_iv = 1;
  `UNIT #(.FRAC(F), .TAGW(8), .SHARE(1), .MREG(1)) u_a (.clk_i(clk), .rst_ni(rst_n), .mat_we_i(mat_we),
     .mat_n_i(mat_n), .mat_thr_i(mat_thr), .in_valid_i(ia < N && !mat_we && a_iv), .in_ready_o(a_rdy), .in_cos_i(cosv[ia % N]),
     .in_tag_i(ia[7:0]), .out_valid_o(a_ov), .out_ready_i(a_or), .out_spec_o(a_o), .out_tag_o(a_t));
  `UNIT #(.FRAC(F), .TAGW(8), .SHARE(SH), .MREG(1)) u_b (.clk_i(clk), .rst_ni(rst_n), .mat_we_i(mat_we),
     .mat_n_i(mat_n), .mat_thr_i(mat_thr), .in_valid_i(ib < N && !mat_we && b_iv), .in_ready_o(b_rdy), .in_cos_i(cosv[ib % N]),
     .in_tag_i(ib[7:0]), .out_valid_o(b_ov), .out_ready_i(b_or), .out_spec_o(b_o), .out_tag_o(b_t));
  reg [F+8:0] qa [0:N-1]; reg [F+8:0] qb [0:N-1];
  initial begin
    seed = 7; errs = 0; ia = 0; ib = 0; oa = 0; ob = 0;
    for (i = 0; i < N; i = i + 1) begin
      cosv[i] = ($random(seed) & 1) ? (65536 - ($random(seed) & 4095)) : ($random(seed) & 18'h3ffff);
      if ((i % 97) == 0) cosv[i] = 65536;
    end
    mat_we = 1; mat_n = 200; mat_thr = 16'd40000; a_or = 1; b_or = 1;
    repeat (3) @(posedge clk);
    rst_n = 1; @(posedge clk); #1 mat_we = 0;
    while (oa < N || ob < N) begin
      @(posedge clk);
      if (ia < N && a_rdy && !mat_we && a_iv) ia = ia + 1;
      if (ib < N && b_rdy && !mat_we && b_iv) ib = ib + 1;
      if (a_ov && a_or) begin qa[oa] = {a_t, a_o}; oa = oa + 1; end
      if (b_ov && b_or) begin qb[ob] = {b_t, b_o}; ob = ob + 1; end
      #1 a_iv = ($random(seed) % 3) != 0; b_iv = ($random(seed) % 3) != 0; a_or = ($random(seed) % 4) != 0; b_or = ($random(seed) % 3) != 0;
    end
    for (i = 0; i < N; i = i + 1) if (qa[i] !== qb[i]) begin
      errs = errs + 1; if (errs < 5) $display("MISMATCH %0d: %h %h", i, qa[i], qb[i]);
    end
    nz = 0;
    for (i = 0; i < N; i = i + 1) if (qa[i][F:0] != 0) nz = nz + 1;
    if (nz < N / 4) errs = errs + 1;   // the stream must exercise the datapath, not only the cut
    $display("%s: %0d outputs (%0d non-zero), %0d mismatches (SH = %0d)", errs ? "FAIL" : "PASS", N, nz, errs, SH);
    $finish;
  end
endmodule
