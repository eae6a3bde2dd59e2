#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""ctest signoff.vcd_activity: signoff/signoff.py's parse_vcd (the toggles and time high the power step gives OpenSTA)
on a hand-written VCD whose counts are worked out below: scalars and vectors, x and z (neither toggle nor count as
high), a vector written shorter than its width (left-extended with 0, or with x after an x), a re-dump of an
unchanged value, an identifier declared twice, and a bit still high at the last time stamp."""
import os
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "signoff"))
import signoff  # noqa: E402

VCD = """$date today $end
$timescale 1ps $end
$scope module tb $end
$scope module dut $end
$var wire 1 ! a $end
$var wire 1 ! a_alias $end
$var wire 4 " v [3:0] $end
$var wire 1 # \\u.q [2] $end
$upscope $end
$upscope $end
$enddefinitions $end
#0
$dumpvars
x!
b0 "
0#
$end
#10
1!
b1010 "
1#
#20
0!
b11 "
#30
1!
bx1 "
z#
#40
b0101 "
1#
#45
b101 "
#50
0!
"""


class ParseVcd(unittest.TestCase):
    def test_counts(self):
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "a.vcd")
            with open(p, "w") as f:
                f.write(VCD)
            ids, tog, high, t_end = signoff.parse_vcd(p)
        self.assertEqual(t_end, 50)
        self.assertEqual(ids["!"], [("a", 1), ("a_alias", 1)])
        self.assertEqual(ids['"'], [("v [3:0]", 4)])
        self.assertEqual(ids["#"], [("\\u.q [2]", 1)])
        # a: x (0), 1 at 10 (no toggle from x), 0 at 20, 1 at 30, 0 at 50: 3 toggles, high 10..20 and 30..50
        self.assertEqual(tog.get(("!", 0), 0), 3)
        self.assertEqual(high.get(("!", 0), 0), 30)
        # v: 0000 -> 1010 (10) -> 0011 (20) -> xxx1 (30; "x1" left-extended with x) -> 0101 (40) -> 0101 (45, again)
        self.assertEqual(tog.get(('"', 0), 0), 1)   # bit 0: 0,0,1,1,1,1: one rise at 20
        self.assertEqual(high.get(('"', 0), 0), 30)  # 20..50
        self.assertEqual(tog.get(('"', 1), 0), 1)   # bit 1: 0,1,1,x,0,0: the rise at 10; 1->x and x->0 are none
        self.assertEqual(high.get(('"', 1), 0), 20)  # 10..30
        self.assertEqual(tog.get(('"', 2), 0), 0)   # bit 2: 0,0,0,x,1,1: x->1 is no toggle
        self.assertEqual(high.get(('"', 2), 0), 10)  # 40..50
        self.assertEqual(tog.get(('"', 3), 0), 2)   # bit 3: 0,1,0,x,0,0
        self.assertEqual(high.get(('"', 3), 0), 10)  # 10..20
        # q: 0, 1 at 10, z at 30, 1 at 40: one toggle, high 10..30 and 40..50
        self.assertEqual(tog.get(("#", 0), 0), 1)
        self.assertEqual(high.get(("#", 0), 0), 30)


if __name__ == "__main__":
    unittest.main()
