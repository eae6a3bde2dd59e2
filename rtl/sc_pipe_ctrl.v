// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_pipe_ctrl.v
// Purpose  : the one valid/ready pipeline control of the one-fragment-per-clock units (issue 21):
//            a DEPTH-stage global-enable pipeline of docs/spec.md §4. Used by rtl/sc_cs16.v,
//            rtl/sc_schlick_div.v, rtl/sc_schlick_nr.v, rtl/sc_table.v and rtl/sc_energy.v, which
//            clock every data register of their stages with en_o.
//
// Parameters (illegal values stop elaboration with a message, in Icarus, Verilator and Yosys):
//   DEPTH  number of register stages (= the unit's latency), >= 1                    (default 1)
//   GAP    1..DEPTH: a fragment is accepted only when stages 0..GAP-2 are empty, so any two fragments
//          in flight are at least GAP stages apart (a unit whose multipliers rtl/sc_mul_pool.v shares
//          over GAP = SHARE consecutive stages; the lighting core issues its passes that far apart,
//          so only passes a stall has bunched wait)                                  (default 1)
//
// Ports : clk_i, rst_ni (synchronous, active-low: clears every valid bit; fragments in flight
//         are dropped), in_valid_i/in_ready_o and out_valid_o/out_ready_i (docs/spec.md §4),
//         en_o the global enable (every stage moves), valid_o[DEPTH-1:0] the stage valid bits
//         (stage 0 first; out_valid_o = valid_o[DEPTH-1]).
//
// Control   : en_o = !out_valid_o || out_ready_i (the output stage is empty or being taken);
//             in_ready_o = rst_ni && en_o (combinational from out_ready_i: ready may depend on
//             ready, no valid depends on a ready). At a rising edge with rst_ni high and en_o
//             high the valid bits shift by one stage and in_valid_i enters stage 0, so a fragment
//             is accepted exactly when in_valid_i && in_ready_o. With GAP > 1, in_ready_o is also
//             low while a fragment is in stages 0..GAP-2 (a registered condition). A held output (out_valid_o &&
//             !out_ready_i) freezes the whole pipeline: en_o is low and no data register loads.
//
// Formal (`ifdef FORMAL`, proved by k-induction with yosys-smtbmc, docs/formal.md):
//   pc_ready_reset   in_ready_o is low while rst_ni is low
//   pc_count         accepted - taken since the last reset == number of valid bits (<= DEPTH)
//   pc_no_spurious   after a reset no valid output until a fragment has been accepted
//   pc_hold          a valid output not taken stays valid (rst_ni high at that edge)
//   pc_gap           no two valid stages are closer than GAP
// ============================================================================================
`default_nettype none

module sc_pipe_ctrl #(
    parameter integer DEPTH = 1,
    parameter integer GAP   = 1
) (
    input  wire             clk_i,
    input  wire             rst_ni,
    input  wire             in_valid_i,
    output wire             in_ready_o,
    output wire             out_valid_o,
    input  wire             out_ready_i,
    output wire             en_o,
    output wire [DEPTH-1:0] valid_o
);

  `include "sc_util.vh"

  // ---------------------------------------------------------------------------- check configuration
  // Portable Verilog-2005 elaboration error: a failing check instantiates a module that does not
  // exist, named after the message; every tool stops with "unknown module <message>".
  generate
    if (DEPTH < 1) begin : g_check_depth
      sc_pipe_ctrl_error_illegal_DEPTH_must_be_at_least_1 u_error ();
    end
    if (GAP < 1 || GAP > DEPTH) begin : g_check_gap
      sc_pipe_ctrl_error_illegal_GAP_legal_range_is_1_to_DEPTH u_error ();
    end
  endgenerate

  reg  [DEPTH-1:0] v_q;                    // valid bit of each stage, stage 0 first
  wire             adv = !v_q[DEPTH-1] || out_ready_i;
  assign en_o        = adv;
  wire             gap_ok;                 // stages 0..GAP-2 empty
  generate
    if (GAP > 1) begin : g_gap
      assign gap_ok = ~|v_q[GAP-2:0];
    end else begin : g_nogap
      assign gap_ok = 1'b1;
    end
  endgenerate
  assign in_ready_o  = rst_ni && adv && gap_ok;
  assign out_valid_o = v_q[DEPTH-1];
  assign valid_o     = v_q;

  generate
    if (DEPTH == 1) begin : g_one
      always @(posedge clk_i) begin
        if (!rst_ni) begin
          v_q <= 1'b0;
        end else if (adv) begin
          v_q <= in_valid_i && gap_ok;
        end
      end
    end else begin : g_line
      always @(posedge clk_i) begin
        if (!rst_ni) begin
          v_q <= {DEPTH{1'b0}};
        end else if (adv) begin
          v_q <= {v_q[DEPTH-2:0], in_valid_i && gap_ok};
        end
      end
    end
  endgenerate

`ifdef FORMAL
  // Step 0 of a proof has arbitrary registers: the properties below are checked from cycle 1 on (f_past);
  // the harness (formal/sc_formal_unit.v, formal/sc_formal_ctrl.v) assumes rst_ni low in cycle 0.
  // f_past is 1 in every cycle after the first, so in an induction step every property is active.
  localparam integer CW = sc_bits(DEPTH + 2);
  reg          f_past   = 1'b0;            // cycle >= 1 (the harness resets in cycle 0)
  reg [CW-1:0] f_cnt    = {CW{1'b0}};      // accepted - taken since the last reset
  reg          f_acc    = 1'b0;            // a fragment was accepted since the last reset
  wire         f_accept = in_valid_i && in_ready_o;
  wire         f_take   = out_valid_o && out_ready_i;

  // number of valid bits in flight
  integer      f_i;
  reg [CW-1:0] f_pop;
  always @* begin
    f_pop = {CW{1'b0}};
    for (f_i = 0; f_i < DEPTH; f_i = f_i + 1) f_pop = f_pop + {{(CW-1){1'b0}}, v_q[f_i]};
  end

  always @(posedge clk_i) begin
    f_past <= 1'b1;
    if (!rst_ni) begin
      f_cnt  <= {CW{1'b0}};
      f_acc  <= 1'b0;
    end else begin
      f_cnt  <= f_cnt + {{(CW-1){1'b0}}, f_accept} - {{(CW-1){1'b0}}, f_take};
      if (f_accept) f_acc <= 1'b1;
    end
  end

  always @* begin
    // in_ready_o low in reset (from step 0: it is combinational)
    pc_ready_reset: assert (rst_ni || !in_ready_o);
    if (f_past) begin
      pc_count:       assert (f_cnt == f_pop);
      pc_count_bound: assert (f_cnt <= DEPTH);
      pc_no_spurious: assert (f_acc || !out_valid_o);
      pc_acc:         assert (f_acc || f_cnt == 0);
    end
  end

  // any two valid stages at least GAP apart
  integer f_j, f_k;
  reg     f_close;
  always @* begin
    f_close = 1'b0;
    for (f_j = 0; f_j < DEPTH; f_j = f_j + 1) begin
      for (f_k = f_j + 1; f_k < DEPTH; f_k = f_k + 1) begin
        if (f_k < f_j + GAP && v_q[f_j] && v_q[f_k]) f_close = 1'b1;
      end
    end
    if (f_past) begin
      pc_gap: assert (!f_close);
    end
  end

  always @(posedge clk_i) begin
    if (f_past && $past(f_past) && $past(rst_ni) && $past(out_valid_o) && !$past(out_ready_i)) begin
      pc_hold: assert (out_valid_o);
    end
  end
`endif

endmodule

`default_nettype wire
