// SPDX-License-Identifier: Apache-2.0
// handoff/tb/tb_common.vh — the stream skeleton shared by the bundles' testbenches (tb/tb_shadecore.v for a
// specular unit, tb/tb_shadecore_light.v for the lighting core, bare or behind its AXI wrapper), included inside
// the module body after the bench's pins. Plain Verilog-2005.
//
// What is here: the vector memory and its plusargs, the ring of fragments in flight (record index and advance
// count at acceptance), the checks every result gets (order by tag, latency in advancing edges, stability under
// backpressure), the reset pulse in the middle of the stream with the fragments in flight sent again, the random
// input gaps and output backpressure (one xorshift32 stream, in one order), the watchdog and the tail.
// What the bench gives it:
//   localparams  RW (32-bit words per record), PAYW (width of out_payload), WHAT ("result", "colour": messages);
//                from tb_config.vh FRAC, TAGW, LATENCY, LATENCY_MIN, LATENCY_SLACK, MAXREC, NREC_DEFAULT, TB_SEED
//   parameters   RESET_CYCLES, WATCHDOG, TAIL, IN_GAP_PCT, OUT_STALL_PCT
//   signals      rst_n, in_valid, in_ready, out_valid, out_ready, out_tag, out_payload (what must hold still
//                while out_ready is low: the result's value bits)
//   task         check_value(input integer r): out_payload against record r's expected words (FAIL vector r: ...)
//   function     nominal_latency(input integer r): record r's latency without backpressure (<= LATENCY)

  // xorshift32: the same sequence on every simulator.
  function [31:0] xs32;
    input [31:0] x;
    reg [31:0] y;
    begin
      y = x ^ (x << 13);
      y = y ^ (y >> 17);
      xs32 = y ^ (y << 5);
    end
  endfunction

  // Ends the simulation with a failing exit status (Icarus); other simulators stop.
  task fail_exit;
    begin
`ifdef __ICARUS__
      $finish_and_return(1);
`else
      $stop;
`endif
    end
  endtask

  // +vcd=FILE: a VCD of the design under test's own nets, one level deep (every net of a mapped,
  // flattened netlist; the cells' insides are not dumped). signoff/signoff.py counts their toggles for
  // the power report.
  reg [8*512-1:0] vcd_file;
  initial begin
    if ($value$plusargs("vcd=%s", vcd_file)) begin
      $dumpfile(vcd_file);
      $dumpvars(1, dut);
    end
  end

  // ---------------------------------------------------------------------------- vectors and state
  reg [31:0] mem [0:RW*MAXREC-1];
  reg [8*1024-1:0] vec_file;

  // In flight: record index and advance count at acceptance, oldest first (a ring).
  localparam integer QCAP = 256;
  integer q_rec [0:QCAP-1];
  integer q_adv [0:QCAP-1];
  integer q_head, q_count;

  integer nrec, nfrag, seed, in_gap, out_stall, reset_at;
  integer cyc, adv, idle, tail, checked, accepted, dropped, resets;
  integer next_rec, cur, rst_left, lat, e, k;
  reg     have, valid_q, mid_done, held, done;
  reg [31:0] rng;
  reg [TAGW-1:0] held_tag;
  reg [PAYW-1:0] held_payload;

  // The plusargs (vectors, nvec, seed, in_gap, out_stall) and the vector file: nrec records of RW words.
  task read_vectors;
    begin
      if (!$value$plusargs("vectors=%s", vec_file)) vec_file = "vectors/hard.hex";
      if (!$value$plusargs("nvec=%d", nrec)) nrec = NREC_DEFAULT;
      if (!$value$plusargs("seed=%d", seed)) seed = TB_SEED;
      if (!$value$plusargs("in_gap=%d", in_gap)) in_gap = IN_GAP_PCT;
      if (!$value$plusargs("out_stall=%d", out_stall)) out_stall = OUT_STALL_PCT;
      if (nrec < 1 || nrec > MAXREC) begin
        $display("FAIL +nvec=%0d out of range 1..%0d (MAXREC in tb_config.vh)", nrec, MAXREC);
        fail_exit;
      end
      for (e = 0; e < RW * nrec; e = e + 1) mem[e] = 32'bx;
      $readmemh(vec_file, mem, 0, RW * nrec - 1);
      for (e = 0; e < nrec; e = e + 1)
        for (k = 0; k < RW; k = k + 1)
          if (^mem[RW*e+k] === 1'bx) begin
            $display("FAIL vector file has fewer than %0d records or a malformed word (record %0d word %0d)", nrec, e, k);
            fail_exit;
          end
    end
  endtask

  // After the bench counted nfrag: +reset_at (default half the fragments), the counters, the first reset pulse.
  task start_stream;
    begin
      if (!$value$plusargs("reset_at=%d", reset_at)) reset_at = nfrag / 2;
      rng = (seed == 0) ? 32'h1234_5678 : seed;
      cyc = 0; adv = 0; idle = 0; tail = 0; checked = 0; accepted = 0; dropped = 0; resets = 0;
      next_rec = 0; cur = 0; rst_left = RESET_CYCLES; q_head = 0; q_count = 0;
      have = 1'b0; valid_q = 1'b0; mid_done = 1'b0; held = 1'b0; done = 1'b0;
      held_tag = 0; held_payload = 0;
      rst_n = 1'b0; in_valid = 1'b0; out_ready = 1'b0;
    end
  endtask

  // Checks the output taken at this edge with `adv_at` advancing edges counted: order (its tag is the oldest
  // fragment's), value (the bench's check_value), latency; then it leaves the ring.
  task take_result;
    input integer adv_at;
    begin
      if (q_count == 0) begin
        $display("FAIL cycle %0d: %0s with tag 0x%h but nothing in flight (duplicated or spurious)", cyc, WHAT, out_tag);
        fail_exit;
      end
      e = q_rec[q_head];
      if (out_tag !== e[TAGW-1:0]) begin
        $display("FAIL cycle %0d: %0s tag 0x%h, expected 0x%h of vector %0d (lost, duplicated or reordered)",
                 cyc, WHAT, out_tag, e[TAGW-1:0], e);
        fail_exit;
      end
      check_value(e);
      lat = adv_at - q_adv[q_head];
      k   = nominal_latency(e);
      if (lat > k + LATENCY_SLACK || lat < LATENCY_MIN || k > LATENCY || (out_stall == 0 && lat != k)) begin
        $display("FAIL vector %0d: latency %0d advancing cycles, expected %0d..%0d (%0d without backpressure)",
                 e, lat, LATENCY_MIN, k + LATENCY_SLACK, k);
        fail_exit;
      end
      checked = checked + 1;
      q_head  = (q_head + 1) % QCAP;
      q_count = q_count - 1;
    end
  endtask

  // The output held back by out_ready low at the last edge must not have moved.
  task check_held;
    begin
      if (held && (!out_valid || out_tag !== held_tag || out_payload !== held_payload)) begin
        $display("FAIL cycle %0d: output changed while held back by out_ready_i low (tag 0x%h -> 0x%h)",
                 cyc, held_tag, out_tag);
        fail_exit;
      end
    end
  endtask

  // An edge with rst_n low: an output taken at it counts; the fragments in flight are dropped and presented
  // again from the oldest of them (no register or material write lies between them).
  task reset_edge;
    begin
      if (out_valid && out_ready) take_result(adv + 1);
      if (q_count > 0) begin
        next_rec = q_rec[q_head];
        dropped  = dropped + q_count;
        have     = 1'b0;
      end
      q_count = 0;
      held    = 1'b0;
    end
  endtask

  // An edge out of reset: the advance count, the output and input handshakes, what is held for the next edge.
  task stream_edge;
    begin
      if (out_valid && out_ready) begin
        take_result(adv);
        idle = 0;
      end
      if (in_valid && in_ready) begin
        q_rec[(q_head + q_count) % QCAP] = cur;
        q_adv[(q_head + q_count) % QCAP] = adv;
        q_count  = q_count + 1;
        accepted = accepted + 1;
        have     = 1'b0;
        valid_q  = 1'b0;
        idle     = 0;
      end
      held         = out_valid && !out_ready;
      held_tag     = out_tag;
      held_payload = out_payload;
    end
  endtask

  task watchdog;
    begin
      idle = idle + 1;
      if (idle > WATCHDOG) begin
        $display("FAIL watchdog: no transfer for %0d cycles (%0d of %0d fragments checked)", WATCHDOG, checked, nfrag);
        fail_exit;
      end
    end
  endtask

  // Drive side, 1 time unit after the edge: the reset pulse (one, after reset_at accepted fragments; begun is 1
  // in the step that begins it), then the next record when none is held.
  task drive_reset;
    output begun;
    begin
      begun = 1'b0;
      if (rst_left > 0) rst_left = rst_left - 1;
      if (rst_left == 0 && !mid_done && reset_at >= 0 && accepted >= reset_at) begin
        rst_left = RESET_CYCLES;
        mid_done = 1'b1;
        resets   = resets + 1;
        begun    = 1'b1;
      end
      rst_n = (rst_left == 0);
      if (!have && next_rec < nrec) begin
        have     = 1'b1;
        cur      = next_rec;
        next_rec = next_rec + 1;
        valid_q  = 1'b0;
      end
    end
  endtask

  // in_valid for a fragment that is ready to go: never in reset (AXI-Stream), a random gap before it is raised,
  // then high until it is taken.
  task drive_valid;
    begin
      if (rst_left != 0) begin
        valid_q = 1'b0;
      end else if (!valid_q) begin
        rng     = xs32(rng);
        valid_q = (rng % 100) >= in_gap;
      end
    end
  endtask

  task drive_ready;
    begin
      rng       = xs32(rng);
      out_ready = (rng % 100) >= out_stall;
    end
  endtask

  // Once nothing is left to send or in flight: TAIL more cycles watched for spurious output; then done (the
  // bench prints its PASS line when `done` rises).
  task watch_tail;
    begin
      if (next_rec == nrec && !have && q_count == 0) begin
        tail = tail + 1;
        if (tail > TAIL) begin
          if (checked != nfrag) begin
            $display("FAIL end of stream: %0d of %0d fragments checked", checked, nfrag);
            fail_exit;
          end
          done = 1'b1;
        end
      end
    end
  endtask
