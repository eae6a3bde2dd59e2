// SPDX-License-Identifier: Apache-2.0
// handoff/tb/tb_common.vh — shared by the bundles' testbenches (tb/tb_shadecore.v, tb/tb_shadecore_light.v),
// included inside the module body. Plain Verilog-2005.

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
