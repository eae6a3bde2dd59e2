#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Checks of scripts/cost_report.py's parsing and pure helpers on captured tool output (tests/data/cost_report/:
Yosys 0.23 `stat -json [-tech cmos]`, `ltp -noff`, `dump t:$mem_v2`, nextpnr-ice40 0.4 log lines, icetime
reports). Seconds; no synthesis is run. ctest: scripts.cost_report_parsing."""
import os
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "scripts"))
import cost_report as cr  # noqa: E402

DATA = os.path.join(HERE, "data", "cost_report")


def sample(name):
    with open(os.path.join(DATA, name)) as f:
        return f.read()


class StatJson(unittest.TestCase):
    def test_exact_transistor_count(self):
        s = cr.parse_stat_json("log text before\n" + sample("stat_cmos.json"))
        self.assertEqual(s["cells"], 1130)
        self.assertEqual(s["transistors"], 9916)
        self.assertTrue(s["transistors_exact"])
        self.assertEqual(cr.count(s["by_type"], r"\$_S?DFFE?_\w+"), 119)  # after dffunmap: $_DFF_P_ only
        self.assertEqual(s["by_type"]["$_XOR_"], 197)

    def test_plus_marks_cells_without_cost(self):
        s = cr.parse_stat_json(sample("stat_cmos_with_ram.json"))
        self.assertEqual(s["transistors"], 10990)
        self.assertFalse(s["transistors_exact"])  # the $mem_v2 black box has no CMOS cost
        self.assertEqual(cr.count(s["by_type"], r"\$mem(_v2)?"), 1)

    def test_no_json_is_an_error(self):
        with self.assertRaises(cr.Failure):
            cr.parse_stat_json("ERROR: something")


class OtherParsers(unittest.TestCase):
    def test_ltp(self):
        self.assertEqual(cr.parse_ltp(sample("ltp.txt")), 50)
        self.assertIsNone(cr.parse_ltp("nothing"))

    def test_mem_dump(self):
        self.assertEqual(cr.parse_mem_dump(sample("mem_dump.txt")), [(256, 16)])
        self.assertEqual(cr.parse_mem_dump(""), [])

    def test_nextpnr(self):
        log = sample("nextpnr.log")
        self.assertEqual(cr.parse_nextpnr_fmax(log), 26.96)  # the last (post-route) figure
        self.assertEqual(cr.parse_nextpnr_lcs(log), 761)

    def test_icetime(self):
        self.assertEqual(cr.parse_icetime(sample("icetime_lut.rpt")), 27.17)
        self.assertEqual(cr.icetime_dsp_on_path(sample("icetime_lut.rpt")), [])
        self.assertEqual(cr.parse_icetime(sample("icetime_dsp_endpoint.rpt")), 77.08)
        self.assertEqual(cr.icetime_dsp_on_path(sample("icetime_dsp_endpoint.rpt")), ["SB_MAC16_MAS_U_16X16_BYPASS"])
        # net names containing "SB_MAC16" are not cells on the path; the pipelined MAC16 endpoint is
        self.assertEqual(cr.icetime_dsp_on_path(sample("icetime_dsp_pipelined.rpt")),
                         ["SB_MAC16_MAS_U_16X16_ALL_PIPELINE"])


class Pure(unittest.TestCase):
    def test_per_n_bands(self):
        csv = ("n,approx_max,approx_max_code,approx_min,approx_min_code,quant_max_ulp,quant_max_code,quant_min_ulp,"
               "quant_min_code,total_max,total_max_code,total_min,total_min_code,nonzero_codes\n"
               "16,0,0,0,0,0,0,0,0,1e-3,1,-2e-3,2,5\n"
               "31,0,0,0,0,0,0,0,0,4e-3,1,-1e-3,2,5\n"
               "1024,0,0,0,0,0,0,0,0,0.25,1,-0.5,2,5\n")
        self.assertEqual(cr.per_n_bands(csv), [4e-3, None, None, None, None, 0.5])

    def test_pareto(self):
        pts = [(10, 0.1, "a"), (5, 0.2, "b"), (20, 0.1, "c"), (30, 0.01, "d"), (7, 0.3, "e"), (None, 0.001, "f")]
        self.assertEqual([p[2] for p in cr.pareto(pts)], ["b", "a", "d"])

    def test_n_range(self):
        self.assertEqual(cr.parse_n_range("16..1024"), (16, 1024))
        self.assertEqual(cr.parse_n_range("128"), (128, 128))
        for bad in ("", "16-32", "64..16", "a..b"):
            with self.assertRaises(ValueError):
                cr.parse_n_range(bad)

    def test_wrapper(self):
        ports = [("clk_i", "input", 1), ("rst_ni", "input", 1), ("in_cos_i", "input", 18),
                 ("in_ready_o", "output", 1), ("out_spec_o", "output", 17)]
        v = cr.wrapper_verilog(ports, {"VARIANT": 0, "FRAC": 16, "GUARD": 5})
        self.assertIn("reg  [18:0] sin;", v)  # 1 + 18 input bits (clk_i is the clock)
        self.assertIn("reg  [17:0] sout;", v)
        self.assertIn(".rst_ni(sin[0:0])", v)
        self.assertIn(".in_cos_i(sin[18:1])", v)
        self.assertIn(".out_spec_o(outs[17:1])", v)
        self.assertIn("sc_specular #(.VARIANT(0), .FRAC(16), .GUARD(5))", v)

    def test_rate_and_format(self):
        self.assertEqual(cr.rate({"throughput": 1.0}), "1")
        self.assertEqual(cr.rate({"throughput": 1 / 20}), "1/20")
        self.assertEqual(cr.fmt(None), "—")
        self.assertEqual(cr.fmt(True), "yes")

    def test_refresh_sections_replaces_the_read_sections_once(self):
        md = ("# Cost report\n\n## FPGA\n\nkept\n\n## In a standard-cell library: clock, latency, energy (old)\n\n"
              "stale row\n\n## Pareto plot\n\nplot\n")
        rows = [{"variant": "cs16", "config": "default", "total_abs_max": 0.017}]
        out = cr.refresh_sections(md, rows)
        self.assertIn("## FPGA\n\nkept", out)
        self.assertNotIn("stale row", out)
        self.assertLessEqual(out.count("## In a standard-cell library"), 1)
        self.assertEqual(out.count("## Pareto plot"), 1)
        self.assertTrue(out.endswith("## Pareto plot\n\nplot\n"))
        self.assertEqual(cr.refresh_sections(out, rows), out)  # idempotent
        with self.assertRaises(cr.Failure):
            cr.refresh_sections("# no plot section\n", rows)


if __name__ == "__main__":
    unittest.main(verbosity=1)
