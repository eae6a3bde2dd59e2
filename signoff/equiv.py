#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Formal equivalence of two handoff bundles' RTL (Yosys 0.23 equiv_make / equiv_struct / equiv_simple / equiv_induct).

    signoff/equiv.py GOLD GATE [--top NAME] [--json OUT] [--timeout S]

GOLD and GATE are bundle directories (rtl/ and filelist.f, as `shadecore handoff` writes them). Each side is read
(every .v of its filelist.f, its rtl/ as the include path), elaborated from the top (default: the module the bundle's
filelist.f lists last), then `proc; flatten; memory; opt_clean`. equiv_make pairs the signals of the two designs by
name, equiv_struct -icells merges the cells (internal ones too) that are the same on both sides, equiv_simple (-seq 2)
and equiv_induct prove the
rest; equiv_status -assert fails on any unproven pair. The two tops must have the same ports (names and widths): a port
present on one side only would have no pair and so no proof.

What a proof says: from any state in which the paired registers agree, the two designs' paired signals (the ports
among them) agree on every clock: the same outputs for the same inputs, clock by clock. scripts/timing_report.py
--revalidate --equiv-from REV uses it to carry a row measured on an earlier RTL to the current one when the
configuration's logic did not change (an edit elsewhere, a parameter that is 0 here).

Exit 0 when proven; 1 when not (or on an error), with a one-line reason. --json writes {"proven", "equiv_cells",
"seconds", "top", "yosys"}.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time


class Failure(Exception):
    pass


def files_of(d):
    fl = os.path.join(d, "filelist.f")
    if not os.path.isfile(fl):
        raise Failure(f"{d}: no filelist.f (a handoff bundle is needed)")
    out = [os.path.join(d, x.strip()) for x in open(fl) if x.strip().endswith(".v")]
    for f in out:
        if not os.path.isfile(f):
            raise Failure(f"{d}: filelist.f names {f}, which does not exist")
    if not out:
        raise Failure(f"{d}: filelist.f lists no Verilog file")
    return out


def top_of(files):
    m = re.search(r"^\s*module\s+(\w+)", open(files[-1]).read(), re.M)
    if not m:
        raise Failure(f"{files[-1]}: no module (give --top)")
    return m.group(1)


def side(tag, d, top, ports):
    files = " ".join(files_of(d))
    return (f"read_verilog -defer -sv -I{os.path.join(d, 'rtl')} {files}\n"
            f"hierarchy -check -top {top}\n"
            "proc; flatten; memory; opt_clean\n"
            f"tee -q -o {ports} dump i:* o:*\n"
            f"rename -top {tag}\n"
            f"design -stash {tag}\n")


def ports_of(path):
    """{port: (width, direction)} of a side, from its RTLIL `dump i:* o:*` ("wire width 18 input 3 \\in_nx_i")."""
    out = {}
    for x in open(path):
        m = re.match(r"\s*wire\s+(?:width\s+(\d+)\s+)?(?:\w+\s+)*?(input|output|inout)\s+\d+\s+\\(\S+)", x)
        if m:
            out[m.group(3)] = (int(m.group(1) or 1), m.group(2))
    return out


SELF_GOLD = """module sc_t #(parameter integer D = 0) (input wire clk_i, input wire en_i, input wire [3:0] a_i,
    input wire [3:0] b_i, output wire [7:0] p_o);
  reg [3:0] a_q, b_q;
  reg [7:0] p_q;
  always @(posedge clk_i) if (en_i) begin a_q <= a_i; b_q <= b_i; p_q <= a_q * b_q + 8'd3; end
  assign p_o = p_q;
endmodule
module top (input wire clk_i, input wire en_i, input wire [3:0] a_i, input wire [3:0] b_i, output wire [7:0] p_o);
  sc_t u_t (.clk_i(clk_i), .en_i(en_i), .a_i(a_i), .b_i(b_i), .p_o(p_o));
endmodule
"""


def selftest():
    """Three pairs of two-file bundles: an edit that is a wire (a renamed net, a depth-0 generate) is proven; a changed
    constant and a register more are not; ports that differ are refused."""
    same = SELF_GOLD.replace("p_q <= a_q * b_q + 8'd3;", "p_q <= prod + 8'd3;").replace(
        "  always @(posedge", "  wire [7:0] prod;\n  generate if (D == 0) begin : g_w assign prod = a_q * b_q; end\n"
        "  endgenerate\n  always @(posedge", 1)
    cases = [("a wire more, D = 0", same, 0), ("the constant 3 -> 2", SELF_GOLD.replace("8'd3", "8'd2"), 1),
             ("an output bit more", SELF_GOLD.replace("output wire [7:0] p_o);\n  sc_t", "output wire [8:0] p_o);\n  sc_t"), 1)]
    bad = 0
    with tempfile.TemporaryDirectory(prefix="shadecore_equiv_selftest.") as tmp:
        for i, (what, text, want) in enumerate(cases):
            for tag, src in (("gold", SELF_GOLD), ("gate", text)):
                d = os.path.join(tmp, f"{i}_{tag}")
                os.makedirs(os.path.join(d, "rtl"))
                open(os.path.join(d, "rtl", "t.v"), "w").write(src)
                open(os.path.join(d, "filelist.f"), "w").write("+incdir+rtl\nrtl/t.v\n")
            p = subprocess.run([sys.executable, os.path.abspath(__file__), os.path.join(tmp, f"{i}_gold"),
                                os.path.join(tmp, f"{i}_gate"), "--top", "top"], capture_output=True, text=True)
            ok = (p.returncode == 0) == (want == 0)
            bad += not ok
            print(f"equiv selftest: {what}: exit {p.returncode} ({(p.stdout + p.stderr).strip()}) "
                  f"{'as expected' if ok else 'WRONG'}")
    print("equiv selftest: " + ("PASS" if not bad else f"FAIL ({bad} wrong)"))
    return 1 if bad else 0


def main():
    if sys.argv[1:] == ["--selftest"]:
        return selftest()
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("gold")
    ap.add_argument("gate")
    ap.add_argument("--top", default=None, help="top module (default: the last module of GATE's filelist.f)")
    ap.add_argument("--json", default=None, help="write the result here")
    ap.add_argument("--timeout", type=int, default=7200, help="seconds for Yosys (default 7200)")
    a = ap.parse_args()
    top = a.top or top_of(files_of(a.gate))
    t0 = time.time()
    with tempfile.TemporaryDirectory(prefix="shadecore_equiv.") as tmp:
        pg, pt = os.path.join(tmp, "gold.ports"), os.path.join(tmp, "gate.ports")
        ys = os.path.join(tmp, "equiv.ys")
        with open(ys, "w") as f:
            f.write(side("gold", os.path.abspath(a.gold), top, pg))
            f.write(side("gate", os.path.abspath(a.gate), top, pt))
            f.write("design -copy-from gold -as gold gold\n"
                    "design -copy-from gate -as gate gate\n"
                    "equiv_make gold gate equiv\n"
                    "hierarchy -top equiv\n"
                    "equiv_struct -icells\n"
                    "equiv_simple -seq 2\n"
                    "equiv_induct\n"
                    "equiv_status -assert\n")
        log = os.path.join(tmp, "equiv.log")
        try:
            p = subprocess.run(["yosys", "-q", "-l", log, ys], capture_output=True, text=True, timeout=a.timeout)
        except subprocess.TimeoutExpired:
            raise Failure(f"Yosys did not finish in {a.timeout} s")
        text = open(log).read() if os.path.exists(log) else ""
        if os.path.exists(pg) and os.path.exists(pt):
            gold_ports, gate_ports = ports_of(pg), ports_of(pt)
            if not gold_ports:
                raise Failure(f"no ports read for {top} (Yosys dump format?)")
            if gold_ports != gate_ports:
                diff = sorted(k for k in set(gold_ports) | set(gate_ports) if gold_ports.get(k) != gate_ports.get(k))
                raise Failure(f"the two tops' ports differ ({', '.join(diff[:4])}): not comparable")
        m = re.search(r"Found (\d+) \$equiv cells in equiv:\s*\n\s*Of those cells (\d+) are proven and (\d+) are unproven",
                      text)
        cells = int(m.group(1)) if m else None
        proven = p.returncode == 0 and m is not None and m.group(3) == "0" and "Equivalence successfully proven" in text
        if p.returncode and m is None:
            err = [x for x in (p.stderr + p.stdout + text).splitlines() if "ERROR" in x]
            raise Failure(f"Yosys failed: {(err or ['exit ' + str(p.returncode)])[-1].strip()}")
    res = {"proven": proven, "equiv_cells": cells, "unproven": int(m.group(3)) if m else None,
           "seconds": round(time.time() - t0, 1), "top": top,
           "yosys": subprocess.run(["yosys", "-V"], capture_output=True, text=True).stdout.strip()}
    if a.json:
        with open(a.json + ".tmp", "w") as f:
            json.dump(res, f, indent=1)
        os.replace(a.json + ".tmp", a.json)
    if proven:
        print(f"equiv: {top}: proven equivalent ({cells} paired signals, {res['seconds']} s)")
        return 0
    print(f"equiv: {top}: NOT proven ({res['unproven']} of {cells} paired signals unproven)")
    return 1


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Failure as e:
        print(f"equiv: error: {e}", file=sys.stderr)
        sys.exit(1)
