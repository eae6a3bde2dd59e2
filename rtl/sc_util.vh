// SPDX-License-Identifier: Apache-2.0
// ============================================================================================
// Filename : rtl/sc_util.vh
// Purpose  : the one copy of the constant helper functions of the unit RTL (issue 21). Included
//            INSIDE a module body (`include "sc_util.vh"), so there is no include guard: every
//            module that includes it gets its own copy of the functions (Verilog-2005 functions
//            are module-scoped). Files that include it: rtl/sc_cs16.v, rtl/sc_normalize.v,
//            rtl/sc_recip.v, rtl/sc_pipe_ctrl.v, rtl/sc_light.v.
//
//   sc_clog2(x) = ceil(log2(x)) for x >= 1; sc_clog2(1) = 0 (and 0 for x <= 1).
//   sc_bits(x)  = bits of an index 0..x-1 = max(1, sc_clog2(x)): sc_bits(1) = sc_bits(2) = 1.
//   sc_max(a,b), sc_min(a,b) of two integers.
// ============================================================================================
function integer sc_clog2(input integer x);
  integer v;
  begin
    sc_clog2 = 0;
    v = 1;
    while (v < x) begin
      v = v * 2;
      sc_clog2 = sc_clog2 + 1;
    end
  end
endfunction

function integer sc_bits(input integer x);
  begin
    sc_bits = (sc_clog2(x) < 1) ? 1 : sc_clog2(x);
  end
endfunction

function integer sc_max(input integer a, input integer b);
  begin
    sc_max = (a > b) ? a : b;
  end
endfunction

function integer sc_min(input integer a, input integer b);
  begin
    sc_min = (a < b) ? a : b;
  end
endfunction
