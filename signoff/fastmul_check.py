#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The default suite's proof of signoff/fastmul.py's maps (ctest timing.fastmul_equiv): the same checks as
`fastmul.py --selftest` — each $mul map against Yosys's $mul, the Kogge-Stone $lcu, the sc_mul_reg and sc_sum_reg
maps against their RTL, all by SAT — with the sums of three signed products at 3 x 3 instead of 3 x 4 (the
selftest's 3 x 4 cases take about 340 s of SAT here, which timed CI out; 3 x 3 about 40 s). fastmul.py itself is not
edited for this: its bytes are part of every timing row's key (scripts/timing_report.py FLOW), so its own --selftest
stays as it was and runs in ctest timing.fastmul_equiv_full (label long)."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import fastmul  # noqa: E402

SHAPES = [(4, 4, 8, False, False), (5, 3, 8, True, False), (6, 6, 12, False, True), (6, 6, 12, True, True),
          (7, 5, 7, False, False), (5, 5, 14, True, False), (3, 6, 9, True, False), (8, 8, 9, False, True),
          (6, 6, 12, False, False), (6, 6, 12, True, False)]
# (AW, BW, PW, SIGNED, SQUARE, CW, N, LAT): one product and a square with and without an addend, unequal widths,
# a sum of two and of three products (signed), an unsigned sum of two with an addend, LAT = 2
MULREG = [s + (0,) for s in SHAPES[:4]] + [(7, 5, 12, False, False, 0), (5, 6, 12, True, False, 6),
                                          (4, 4, 8, False, True, 9), (3, 4, 9, True, False, 0, 2),
                                          (3, 3, 8, True, False, 0, 3), (3, 3, 7, False, False, 5, 2),
                                          (3, 3, 8, True, False, 0, 3, 2), (4, 3, 8, False, False, 4, 1, 2)]


def main():
    rtl = os.path.join(HERE, "..", "rtl")
    ok = fastmul.selftest(SHAPES)
    ok &= fastmul.lcu_selftest()
    ok &= fastmul.mulreg_selftest(MULREG, os.path.join(rtl, "sc_mul_reg.v"))
    ok &= fastmul.sumreg_selftest(os.path.join(rtl, "sc_sum_reg.v"))
    print("fastmul_check: " + ("PASS" if ok else "FAIL"))
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
