#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""ctest scripts.timing_report_cache: the cache rules of scripts/timing_report.py on hand-made bundles (nothing is
synthesised): what of a bundle decides its row (inputs_sha), which RTL files key a unit's row and a lighting set's,
and when --from-bundle takes a row from a bundle signed off outside the report."""
import json
import os
import shutil
import sys
import tempfile
import types
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import timing_report as tr  # noqa: E402


def bundle(d, top_comment, vec="0001\n", sdc_period="20.0", tb="module tb; endmodule\n"):
    for sub in ("rtl", "tb", "vectors"):
        os.makedirs(os.path.join(d, sub), exist_ok=True)
    open(os.path.join(d, "rtl", "top.v"), "w").write(f"// Made by  : {top_comment}\nmodule top; endmodule\n")
    open(os.path.join(d, "tb", "tb.v"), "w").write(tb)
    open(os.path.join(d, "vectors", "hard.hex"), "w").write(f"// made by: {top_comment}\n{vec}")
    open(os.path.join(d, "filelist.f"), "w").write("rtl/top.v\n")
    open(os.path.join(d, "constraints.sdc"), "w").write(
        f"set CLK_PERIOD {sdc_period}\nset IO_FRACTION 0.3\nset_input_delay -clock clk 1 [get_ports {{a}}]\n"
        "set_output_delay -clock clk 1 [get_ports {y}]\n")


class InputsSha(unittest.TestCase):
    def test_the_writing_command_and_the_period_do_not_count(self):
        with tempfile.TemporaryDirectory() as t:
            a, b = os.path.join(t, "a"), os.path.join(t, "b")
            bundle(a, "shadecore handoff --out /x/a --signoff on", sdc_period="20.0")
            bundle(b, "shadecore handoff --out /y/b --signoff off", sdc_period="14.450")
            self.assertEqual(tr.inputs_sha(a), tr.inputs_sha(b))

    def test_vectors_bench_and_io_constraints_count(self):
        with tempfile.TemporaryDirectory() as t:
            base = os.path.join(t, "base")
            bundle(base, "c")
            for name, kw in (("vec", {"vec": "0002\n"}), ("tb", {"tb": "module tb2; endmodule\n"})):
                d = os.path.join(t, name)
                bundle(d, "c", **kw)
                self.assertNotEqual(tr.inputs_sha(base), tr.inputs_sha(d), name)
            d = os.path.join(t, "io")
            bundle(d, "c")
            open(os.path.join(d, "constraints.sdc"), "a").write("set IO_FRACTION 0.2\n")
            self.assertNotEqual(tr.inputs_sha(base), tr.inputs_sha(d))


class RtlOf(unittest.TestCase):
    def test_a_unit_row_takes_its_own_files_a_lighting_row_all(self):
        cfg = json.load(open(os.path.join(ROOT, "config", "configs.json")))
        rows = {r["name"]: r for r in tr.rows_of(cfg, [], ["default"])}
        cs16 = tr.rtl_of(cfg, rows["cs16"])
        self.assertIn("rtl/sc_cs16.v", cs16)
        self.assertIn("rtl/sc_specular.v", cs16)
        self.assertNotIn("rtl/sc_normalize.v", cs16)   # a lighting-core file: work on it keeps the unit's row
        self.assertNotIn("rtl/sc_schlick_nr.v", cs16)
        self.assertEqual(tr.rtl_of(cfg, rows["gl_default"]), ["rtl/*.v", "rtl/*.vh"])
        for f in cs16:
            self.assertTrue(os.path.isfile(os.path.join(ROOT, f)), f)


ROW = {"table": False, "kind": "lighting", "name": "x", "config": {"name": "default"}}


class Patching(unittest.TestCase):
    """A scratch directory and timing_report functions replaced for one test."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def patch(self, name, f):
        old = getattr(tr, name)
        setattr(tr, name, f)
        self.addCleanup(setattr, tr, name, old)


class Revalidate(unittest.TestCase):
    def test_a_row_without_recorded_inputs_or_a_table_row_is_not_revalidated(self):
        a = types.SimpleNamespace()
        self.assertIsNone(tr.revalidate(a, {"table": True}, {"signoff": {"inputs": {"bundle": "x"}}})[0])
        self.assertIsNone(tr.revalidate(a, {"table": False}, {"signoff": {}})[0])


WIRE = "module top (input wire clk_i, input wire a, output reg y);\n  always @(posedge clk_i) y <= {};\nendmodule\n"


@unittest.skipUnless(shutil.which("yosys"), "yosys is not installed")
class EquivFrom(Patching):
    """--revalidate --equiv-from REV: a row whose bundle's RTL changed is carried only when the bundle with REV's RTL is
    the measured one byte for byte and signoff/equiv.py proves the two RTLs equivalent (real Yosys, a one-flop top)."""

    def setUp(self):
        super().setUp()
        self.now_rtl, self.rev_rtl = WIRE.format("~~a"), WIRE.format("a")
        self.vec = "0001\n"

        def write(d, rtl):
            bundle(d, "c", vec=self.vec)
            open(os.path.join(d, "rtl", "top.v"), "w").write(rtl)
        measured = os.path.join(self.tmp.name, "measured")
        write(measured, self.rev_rtl)
        self.hit = {"signoff": {"inputs": {"bundle": tr.inputs_sha(measured), "flow": tr.sha_tree(tr.FLOW),
                                           "target": 4.0}}}
        self.patch("bundle", lambda a, r, d, signoff="on": write(d, self.now_rtl))
        self.patch("git", lambda *args: "f" * 40 + "\n" if args[0] == "rev-parse" else self.rev_rtl)
        self.patch("git_has", lambda rev, path: path == "rtl/top.v")
        self.a = types.SimpleNamespace(target=4.0, equiv_from="HEAD~1", timeout=120)
        self.r = ROW

    def test_an_equivalent_rtl_is_carried_with_its_record(self):
        inp, carry = tr.revalidate(self.a, self.r, self.hit)
        self.assertIsNotNone(inp)
        self.assertNotEqual(inp["bundle"], self.hit["signoff"]["inputs"]["bundle"])
        self.assertEqual(carry["from_rev"], "f" * 40)
        self.assertGreater(carry["equiv_cells"], 0)

    def test_another_function_another_stimulus_or_no_equiv_from_is_not(self):
        self.now_rtl = WIRE.format("~a")
        inp, why = tr.revalidate(self.a, self.r, self.hit)
        self.assertIsNone(inp)
        self.assertIn("not proven equivalent", why)
        self.now_rtl = WIRE.format("~~a")
        self.vec = "0002\n"   # the vectors changed too: the bundle with REV's RTL is not the measured one
        inp, why = tr.revalidate(self.a, self.r, self.hit)
        self.assertIsNone(inp)
        self.assertIn("is not the one measured", why)
        self.vec = "0001\n"
        self.a.equiv_from = None
        self.assertEqual(tr.revalidate(self.a, self.r, self.hit), (None, "its bundle changed"))

    def kept(self):
        """A bundle written from REV's RTL and signed off to the end (a run started before the RTL changed)."""
        d = os.path.join(self.tmp.name, "kept")
        bundle(d, "c", vec=self.vec)
        open(os.path.join(d, "rtl", "top.v"), "w").write(self.rev_rtl)
        os.makedirs(os.path.join(d, "signoff"))
        for f in tr.FLOW:
            shutil.copyfile(os.path.join(ROOT, f), os.path.join(d, "signoff", os.path.basename(f)))
        json.dump({"target_ns": 4.0, "synth": {"cells": 1}, "sta": {"wns_ns": 0.1}, "gatesim": {"passed": True},
                   "power": {"power_mw": 1.0}}, open(os.path.join(d, "signoff", "signoff.json"), "w"))
        self.patch("stages_of", lambda d, r: None)
        return d

    def test_from_bundle_takes_a_bundle_of_an_equivalent_earlier_rtl_as_carried(self):
        d = self.kept()
        s = tr.from_bundle(self.a, self.r, d)
        self.assertEqual(s["carried"][0]["from_rev"], "f" * 40)
        self.assertEqual(s["carried"][0]["measured_bundle"], tr.inputs_sha(d))
        self.assertNotEqual(s["inputs"]["bundle"], tr.inputs_sha(d))   # the bundle these sources write now

    def test_from_bundle_equiv_takes_its_own_rtl_when_only_the_rtl_differs(self):
        d = self.kept()
        open(os.path.join(d, "rtl", "top.v"), "a").write("// an edit never committed\n")
        self.a.equiv_from, self.a.equiv = None, True
        s = tr.from_bundle(self.a, self.r, d)
        self.assertEqual(s["carried"][0]["from_rev"], "bundle")
        self.assertEqual(s["carried"][0]["measured_bundle"], tr.inputs_sha(d))
        self.now_rtl = WIRE.format("~a")
        with self.assertRaises(tr.Failure) as e:
            tr.from_bundle(self.a, self.r, d)
        self.assertIn("not proven equivalent", str(e.exception))
        self.now_rtl = WIRE.format("~~a")
        open(os.path.join(d, "vectors", "hard.hex"), "a").write("0003\n")   # and something beside the RTL differs
        with self.assertRaises(tr.Failure) as e:
            tr.from_bundle(self.a, self.r, d)
        self.assertIn("with its own RTL is not the one measured", str(e.exception))

    def test_from_bundle_refuses_another_function_or_no_equiv_from(self):
        d = self.kept()
        self.now_rtl = WIRE.format("~a")
        with self.assertRaises(tr.Failure) as e:
            tr.from_bundle(self.a, self.r, d)
        self.assertIn("not proven equivalent", str(e.exception))
        self.now_rtl = WIRE.format("~~a")
        self.a.equiv_from = None
        with self.assertRaises(tr.Failure) as e:
            tr.from_bundle(self.a, self.r, d)
        self.assertIn("is not the bundle these sources write", str(e.exception))


class FromBundle(Patching):
    """--from-bundle takes a row only from the bundle these sources write, signed off to the end by this flow."""

    def setUp(self):
        super().setUp()
        self.d = os.path.join(self.tmp.name, "kept")
        bundle(self.d, "shadecore handoff --out /kept --signoff on", sdc_period="14.450")
        open(os.path.join(self.d, "tb", "tb_config.vh"), "w").write("localparam integer LATENCY = 37;\n")
        os.makedirs(os.path.join(self.d, "signoff"))
        for f in tr.FLOW:
            open(os.path.join(self.d, "signoff", os.path.basename(f)), "wb").write(open(os.path.join(ROOT, f), "rb").read())
        self.s = {"target_ns": 4.0, "synth": {"cells": 1}, "sta": {"wns_ns": -1.0}, "gatesim": {"passed": True},
                  "power": {"power_mw": 1.0}}
        self.write()
        self.vec = "0001\n"
        # the bundle "these sources" write: the hand-made one again (what `shadecore handoff --signoff off` would)
        self.patch("bundle", lambda a, r, d, signoff="on": bundle(d, "shadecore handoff --signoff off", vec=self.vec,
                                                                   tb="module tb; endmodule\n")
                   or open(os.path.join(d, "tb", "tb_config.vh"), "w").write("localparam integer LATENCY = 37;\n"))
        self.patch("stages_of", lambda d, r: None)
        self.a = types.SimpleNamespace(target=4.0)
        self.r = ROW

    def write(self):
        json.dump(self.s, open(os.path.join(self.d, "signoff", "signoff.json"), "w"))

    def refused(self, part):
        with self.assertRaises(tr.Failure) as e:
            tr.from_bundle(self.a, self.r, self.d)
        self.assertIn(part, str(e.exception))

    def test_the_same_bundle_signed_off_to_the_end_is_taken(self):
        s = tr.from_bundle(self.a, self.r, self.d)
        self.assertEqual(s["latency_cycles"], 37)
        self.assertEqual(s["inputs"]["bundle"], tr.inputs_sha(self.d))
        self.assertEqual(s["inputs"]["target"], 4.0)
        self.assertIn("--from-bundle", s["log"])

    def test_another_bundle_a_missing_or_failed_step_another_flow_or_target_are_refused(self):
        self.vec = "0002\n"
        self.refused("is not the bundle these sources write")
        self.vec = "0001\n"
        del self.s["power"]
        self.write()
        self.refused("has no power result")
        self.s["power"] = {"power_mw": 1.0}
        self.s["gatesim"] = {"passed": False}
        self.write()
        self.refused("gate-level simulation failed")
        self.s["gatesim"] = {"passed": True}
        self.s["target_ns"] = 5.0
        self.write()
        self.refused("not --target 4.0")
        self.s["target_ns"] = 4.0
        self.write()
        open(os.path.join(self.d, "signoff", "fastmul.py"), "a").write("# changed\n")
        self.refused("another signoff/fastmul.py")



class ClosesWithMreg(unittest.TestCase):
    """A row that misses the target leads its reason with its +mreg row of the same width when that row meets it."""

    @staticmethod
    def row(name, met, kind="unit", width="default (F=16, G=5)", period=4.9, lat=7, flops=275):
        return {"name": name, "kind": kind, "width": width, "met": met, "period_ns": period, "wns_ns": 0.4 if met else -0.9,
                "latency_cycles": lat, "flops": flops, "reason": "misses 4.0 ns by 0.9 ns"}

    def test_a_meeting_mreg_row_is_named(self):
        rows = [self.row("cs16", False), self.row("cs16+mreg", True, period=4.0, lat=12, flops=666)]
        tr.closes_with_mreg(rows)
        self.assertEqual(rows[0]["closes_with"], "cs16+mreg")
        self.assertTrue(rows[0]["reason"].startswith("closes with the pipelining parameter MREG = 1: row cs16+mreg"))
        self.assertIn("at 12 cycles instead of 7", rows[0]["reason"])
        self.assertIn("misses 4.0 ns by 0.9 ns", rows[0]["reason"])
        self.assertNotIn("closes_with", rows[1])

    def test_another_width_is_not_a_lighting_set_is(self):
        rows = [self.row("cs16", False, width="narrow (F=10, G=5)"), self.row("cs16+mreg", True),
                self.row("gl_default", False, kind="lighting"), self.row("gl_default+mreg", True, kind="lighting")]
        tr.closes_with_mreg(rows)
        self.assertNotIn("closes_with", rows[0])
        self.assertEqual(rows[0]["reason"], "misses 4.0 ns by 0.9 ns")
        self.assertEqual(rows[2]["closes_with"], "gl_default+mreg")
        self.assertTrue(rows[2]["reason"].startswith("closes with the pipelining parameter MREG = 1: row gl_default+mreg"))

    def test_an_mreg_row_that_misses_too_says_how_far_it_gets(self):
        rows = [self.row("gl_default", False, kind="lighting", period=9.5, lat=21, flops=4365),
                self.row("gl_default+mreg", False, kind="lighting", period=4.2, lat=38, flops=11137)]
        tr.closes_with_mreg(rows)
        self.assertFalse(any("closes_with" in r for r in rows))
        self.assertTrue(rows[0]["reason"].startswith("with the pipelining parameter MREG = 1 (row gl_default+mreg"))
        self.assertIn("it closes at 4.2 ns instead of 9.5, at 38 cycles instead of 21", rows[0]["reason"])
        self.assertTrue(rows[0]["reason"].endswith("Without it, it misses 4.0 ns by 0.9 ns"))
        self.assertEqual(rows[1]["reason"], "misses 4.0 ns by 0.9 ns")

if __name__ == "__main__":
    unittest.main(verbosity=1)
