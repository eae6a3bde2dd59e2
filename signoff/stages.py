#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""What closing the target would take: every register of a signed-off bundle that misses it, and into how many
pieces its logic cone would have to be cut.

Reads a bundle that `shadecore handoff --signoff on` (signoff/signoff.py) has signed off: its mapped netlist
(signoff/netlist.v), the library copy and the target SDC (signoff/target.sdc: the target period with the bundle's
I/O assumptions, drive, load and the 1.15 late derate). OpenSTA lists every endpoint's required and actual arrival
time (`report_checks -format end`); each flip-flop is named by the RTL register its Q net carries (a bit of
u_core.g_pool.g_inst[0].u_norm.s1_s_q, say) and the bits are grouped back into registers, and registers into the
RTL instance that holds them.

For each register that misses: its worst slack, its worst arrival, and `pieces` = ceil(arrival / required), the
fewest stages its logic cone would need at the target. It is a lower bound: every cut adds a flip-flop's clock-to-Q
and setup again. The sum over the missing registers of bits x (pieces - 1) estimates the flip-flops the pipelining
adds (one register of the endpoint's width per extra piece: a cut inside a product registers its two carry-save
rows, about twice that; a cut at a narrow point of a cone, fewer).

Writes signoff/stages.json in the bundle and prints the worst registers. Needs OpenSTA (`sta`).

  signoff/stages.py BUNDLE [--top N] [--json F]
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import signoff  # noqa: E402  the sign-off's own STA script head and error rule

ROW = re.compile(r"^(\S+)\s+\((\S+)\)\s+(-?[0-9.]+)\s+(-?[0-9.]+)\s+(-?[0-9.]+)\s+\((MET|VIOLATED)\)\s*$")
BIT = re.compile(r"^(.*)\[(\d+)\]$")


def flop_names(netlist):
    """Instance -> the RTL name of its Q net (escaped identifiers unescaped), for every flip-flop of the netlist."""
    names = {}
    for m in re.finditer(r"\bDFF\w*\s+(\S+)\s*\((.*?)\);", open(netlist).read(), re.S):
        q = re.search(r"\.Q\(([^)]*)\)", m.group(2))
        if q:
            names[m.group(1).lstrip("\\")] = q.group(1).strip().lstrip("\\").strip()
    return names


def endpoints(a, sdir, sdc):
    """[(endpoint, cell, required, actual, slack)] for every timing endpoint at the SDC's period."""
    body = "report_checks -path_delay max -group_count 1000000 -endpoint_count 1 -format end -digits 3\n"
    with tempfile.NamedTemporaryFile("w", suffix=".tcl", dir=sdir, delete=False) as f:
        f.write(signoff.sta_script(a, sdir, sdc, body))
        tcl = f.name
    try:
        p = subprocess.run(["sta", "-no_splash", "-exit", tcl], cwd=sdir, capture_output=True, text=True,
                           timeout=a.timeout)
    finally:
        os.remove(tcl)
    if p.returncode or "Error" in p.stdout:
        signoff.die(f"OpenSTA failed (exit {p.returncode}): {(p.stderr or p.stdout).strip().splitlines()[-1:]}")
    rows = []
    for line in p.stdout.splitlines():
        m = ROW.match(line)
        if m:
            rows.append((m.group(1), m.group(2), float(m.group(3)), float(m.group(4)), float(m.group(5))))
    if not rows:
        signoff.die("OpenSTA listed no endpoints")
    return rows


def analyse(rows, names):
    regs = {}
    for ep, cell, req, act, slack in rows:
        inst, _, pin = ep.rpartition("/")
        name = names.get(inst, ep) if cell != "output" and pin else ep
        m = BIT.match(name)
        reg = m.group(1) if m else name
        r = regs.setdefault(reg, {"register": reg, "kind": "output" if cell == "output" else "flop", "bits": 0,
                                  "missing_bits": 0, "worst_slack_ns": slack, "worst_arrival_ns": act,
                                  "required_ns": req})
        r["bits"] += 1
        if slack < 0:
            r["missing_bits"] += 1
        if slack < r["worst_slack_ns"]:
            r.update(worst_slack_ns=slack, worst_arrival_ns=act, required_ns=req)
    out = []
    for r in regs.values():
        r["pieces"] = max(1, math.ceil(r["worst_arrival_ns"] / r["required_ns"] - 1e-9)) if r["required_ns"] > 0 else None
        r["instance"] = r["register"].rpartition(".")[0] or "(top)"
        out.append(r)
    out.sort(key=lambda r: r["worst_slack_ns"])
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bundle", help="a bundle signed off by `shadecore handoff --signoff on`")
    ap.add_argument("--top", help="top module (default: signoff/signoff.json's)")
    ap.add_argument("--json", help="where to write the JSON (default BUNDLE/signoff/stages.json)")
    ap.add_argument("--show", type=int, default=25, help="registers to print (default 25)")
    ap.add_argument("--timeout", type=int, default=7200, help="seconds for OpenSTA (default 7200)")
    a = ap.parse_args()
    sdir = os.path.join(os.path.abspath(a.bundle), "signoff")
    sj = os.path.join(sdir, "signoff.json")
    for p in (sj, os.path.join(sdir, "netlist.v"), os.path.join(sdir, "target.sdc")):
        if not os.path.isfile(p):
            signoff.die(f"{a.bundle} has not been signed off (no {os.path.relpath(p, a.bundle)}): "
                        "run shadecore handoff --signoff on")
    s = json.load(open(sj))
    a.top = a.top or s["top"]
    lib = os.path.join(sdir, "lib", signoff.LIBERTY)
    a.liberty = lib if os.path.isfile(lib) else os.path.join(signoff.LIB_DIR, signoff.LIBERTY)
    rows = endpoints(a, sdir, os.path.join(sdir, "target.sdc"))
    regs = analyse(rows, flop_names(os.path.join(sdir, "netlist.v")))
    missing = [r for r in regs if r["missing_bits"]]
    by_inst = {}
    for r in missing:
        i = by_inst.setdefault(r["instance"], {"instance": r["instance"], "registers": 0, "missing_bits": 0,
                                              "worst_slack_ns": 0.0, "max_pieces": 1})
        i["registers"] += 1
        i["missing_bits"] += r["missing_bits"]
        i["worst_slack_ns"] = min(i["worst_slack_ns"], r["worst_slack_ns"])
        i["max_pieces"] = max(i["max_pieces"], r["pieces"] or 1)
    doc = {"target_ns": s["sta"]["target_ns"], "wns_ns": s["sta"]["wns_ns"], "top": a.top,
           "endpoints": len(rows), "missing_endpoints": sum(1 for x in rows if x[4] < 0),
           "registers": len(regs), "missing_registers": len(missing),
           "max_pieces": max((r["pieces"] or 1 for r in missing), default=1),
           "extra_flops_estimate": sum(r["missing_bits"] * ((r["pieces"] or 1) - 1) for r in missing),
           "pieces_histogram": {str(k): sum(1 for r in missing if r["pieces"] == k)
                                for k in sorted({r["pieces"] for r in missing})},
           "by_instance": sorted(by_inst.values(), key=lambda i: i["worst_slack_ns"]),
           "missing": missing}
    out = a.json or os.path.join(sdir, "stages.json")
    tmp = out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(doc, f, indent=1)
    os.replace(tmp, out)
    print(f"stages: {doc['missing_registers']} of {doc['registers']} registers ({doc['missing_endpoints']} of "
          f"{doc['endpoints']} endpoints) miss {doc['target_ns']} ns; pieces needed (lower bound) "
          f"{doc['pieces_histogram']}; about {doc['extra_flops_estimate']} flip-flops more")
    for r in missing[:a.show]:
        print(f"  {r['worst_slack_ns']:+8.3f} ns  arrival {r['worst_arrival_ns']:7.3f} / {r['required_ns']:.3f}  "
              f"pieces >= {r['pieces']}  {r['missing_bits']:3d}/{r['bits']:<3d} bits  {r['register']}")
    print(f"stages: wrote {out}")


if __name__ == "__main__":
    main()
