#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Post-layout check of a signed-off handoff bundle: place and route its mapped netlist with qflow
(graywolf, qrouter), extract the routed wires' RC, re-time with OpenSTA, and compare with pre-layout.

Runs on a bundle whose OSU 0.18 um sign-off ran (signoff/signoff.py: BUNDLE/signoff/netlist.v,
BUNDLE/constraints.sdc, BUNDLE/signoff/signoff.json) and answers: how far was pre-layout timing
from post-layout, and does the SDC's `set_timing_derate -late 1.15` cover the wires?

  netlist  signoff/netlist.v is read (structural Verilog: library cells, no assigns, no constants)
           and written again with qflow's names: instance k of cell C (1-based, in file order) is
           C_k, the name blif2cel gives the k-th `.gate C` of a BLIF; internal nets are n0, n1, ...;
           ports keep their names. The same netlist goes to qflow as BLIF (synthesis/TOP.blif) and
           to OpenSTA (TOP.v), so names in the DEF, the RC file and the SPEF match the timed netlist.
           Pre-layout OpenSTA on it gives the same slack as on signoff/netlist.v (checked).
  place    `qflow -T osu018 place route TOP` in a qflow project (qflow 1.3 scripts; qflow's
           synthesis step is skipped: its outputs, the BLIF and TOP_powerground, are written here):
           blif2cel, graywolf, place2def, addspacers (power stripes, FILL), arrangepins;
  route    qrouter (stage 1-3, `qrouter::standard_route`), which also writes the routed nets'
           RC trees (TOP.rc: per route branch the R and C that qrouter computes from the LEF's
           RPERSQ / CPERSQDIST / EDGECAPACITANCE). Every net must be routed ("Final: No failed
           routes"), and the routed DEF's connectivity must equal the netlist's (checked net by net).
  extract  rc2dly (qflow) turns TOP.rc into SPEF; its output is repaired for OpenSTA 2.0.17:
           the header says `*C_UNIT 1 FF` but the values are pF (-> `1 PF`), `*BUS_DELIMITER <>`
           but names use [] (-> `[]`), and internal nodes are written NET_K (-> *NET:K). OpenSTA
           must read it with no warning, and every routed net must carry parasitics.
  sta      OpenSTA under the bundle's SDC: (a) pre-layout, no derate (the SDC without its
           set_timing_derate line); (b) pre-layout with the SDC's derate (the sign-off as shipped);
           (c) post-layout: the SPEF, no derate. Each at the SDC's period and at 4.0 ns: WNS and
           the worst path (start, end, arrival, the input delay in that arrival); Fmax by
           bisection (every constraint scales with the period, as in signoff.py). Then the derate
           that pre-layout needs to be as pessimistic as post-layout, at the SDC's period: the
           smallest d (scanned in steps of 0.005) with WNS_pre(d) <= WNS_post; with
           slack_pre(d) <= slack_post at every near-critical endpoint (post-layout slack within 10 %
           of the period of WNS); and at every endpoint. The same for (c2): the SPEF with every wire capacitance multiplied by
           --cap-scale (default 2): qrouter counts one edge's fringe capacitance per wire, the LEF's
           perimeter model two (x1.88-1.94 by layer), and neither has coupling to neighbours.

Not modelled: clock tree (the clock is ideal, its routed net unused by the timing), coupling
capacitance and crosstalk, process/voltage/temperature corners (typical only), hold fixing.

Writes BUNDLE/signoff/postlayout.json (only when every step ran), BUNDLE/signoff/postlayout.log
(the steps and their tool logs, also on failure), and the work files in BUNDLE/signoff/postlayout/
(qflow project, DEF, RC, SPEF, STA scripts and reports). Exit status 0 on success, 1 on a tool or
flow failure, 77 when a required tool is not installed.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import signoff  # noqa: E402  the flow's tool runner, version probe and Fmax bisection

LIB_DIR = "/usr/share/qflow/tech/osu018"
TECH = "osu018"
LIBERTY = os.path.join(LIB_DIR, "osu018_stdcells.lib")
LEF = os.path.join(LIB_DIR, "osu018_stdcells.lef")
QFLOW = "/usr/bin/qflow"
QFLOW_BIN = "/usr/lib/qflow/bin"
CLOCK = "clk_i"
REPORT_PERIOD = 4.0
DERATE_STEP = 0.005
DERATE_MAX = 2.0
NEAR_FRACTION = 0.1      # near-critical endpoints: post-layout slack within this fraction of the period of WNS

LOG = []


class Fail(Exception):
    pass


def log(msg):
    line = f"postlayout: {msg}"
    print(line, flush=True)
    LOG.append(line)


def run(cmd, cwd, logfile, timeout, env=None):
    """signoff.run (output into logfile), recorded in the run log; returns (rc, text, seconds)."""
    t0 = time.time()
    rc, out = signoff.run(cmd, cwd, logfile, timeout, env)
    dt = time.time() - t0
    LOG.append(f"---- {' '.join(cmd)} (cwd {cwd}, {dt:.1f} s, exit {rc}) -> {logfile}")
    return rc, out, dt


tool_version = signoff.tool_version


# ------------------------------------------------------------------------------------- netlist
NET_RE = r"(\\\S+\s|[A-Za-z_][\w$]*(?:\s*\[\s*\d+\s*\])?)"
KEYWORDS = {"input", "output", "inout", "wire", "reg", "assign", "module", "endmodule", "supply0", "supply1"}


def parse_netlist(path):
    """(top, ports [(name, dir, (msb, lsb) or None)], instances [(cell, name, [(pin, net)])])."""
    text = open(path).read()
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    mods = re.findall(r"\bmodule\s+(\S+)\s*\(", text)
    if len(mods) != 1:
        raise Fail(f"{path}: expected one module, found {len(mods)}")
    m = re.search(r"\bmodule\s+(\S+)\s*\((.*?)\)\s*;(.*?)\bendmodule", text, re.S)
    top, body = m.group(1), m.group(3)
    if re.search(r"^\s*assign\b", body, re.M):
        raise Fail(f"{path}: has assign statements (expected a netlist of cells only, as signoff.py writes)")
    if re.search(r"\d+'[bhdo]", body):
        raise Fail(f"{path}: has constants (tie cells are not handled here)")
    ports = []
    for d in re.finditer(r"^\s*(input|output|inout)\s+(?:wire\s+)?(?:\[\s*(\d+)\s*:\s*(\d+)\s*\]\s*)?([^;]+);",
                         body, re.M):
        for name in d.group(4).split(","):
            rng = (int(d.group(2)), int(d.group(3))) if d.group(2) else None
            ports.append((name.strip(), d.group(1), rng))
    insts = []
    for im in re.finditer(r"^\s*([A-Za-z_]\w*)\s+(\\\S+\s|[A-Za-z_][\w$]*)\s*\((.*?)\)\s*;", body, re.M | re.S):
        if im.group(1) in KEYWORDS:
            continue
        pins = []
        for pm in re.finditer(r"\.(\w+)\s*\(\s*" + NET_RE + r"?\s*\)", im.group(3)):
            if pm.group(2):
                pins.append((pm.group(1), re.sub(r"\s+", "", pm.group(2))))
        insts.append((im.group(1), im.group(2).strip(), pins))
    if not insts:
        raise Fail(f"{path}: no cell instances found")
    return top, ports, insts


def port_bits(name, rng):
    if not rng:
        return [name]
    lo, hi = min(rng), max(rng)
    return [f"{name}[{i}]" for i in range(lo, hi + 1)]


def rename(ports, insts):
    """qflow names: instance k (1-based) of cell C is C_k; internal nets n0..; ports keep names."""
    pbits = {b for n, d, r in ports for b in port_bits(n, r)}
    netmap, count, rows = {}, {}, []
    for cell, inst, pins in insts:
        k = count.get(cell, 0) + 1
        count[cell] = k
        new = []
        for p, n in pins:
            if n not in pbits and n not in netmap:
                netmap[n] = f"n{len(netmap)}"
            new.append((p, n if n in pbits else netmap[n]))
        rows.append((cell, f"{cell}_{k}", inst, new))
    return rows, netmap


def write_blif(path, top, ports, rows):
    ins = [b for n, d, r in ports if d == "input" for b in port_bits(n, r)]
    outs = [b for n, d, r in ports if d == "output" for b in port_bits(n, r)]
    with open(path, "w") as f:
        f.write(f".model {top}\n.inputs {' '.join(ins)}\n.outputs {' '.join(outs)}\n\n")
        for cell, name, orig, pins in rows:
            f.write(f".gate {cell} " + " ".join(f"{p}={n}" for p, n in pins) + "\n")
        f.write(".end\n")


def write_verilog(path, top, ports, rows, netmap):
    with open(path, "w") as f:
        f.write(f"// {top} with qflow's instance names (signoff/postlayout.py)\n")
        f.write(f"module {top}({', '.join(n for n, d, r in ports)});\n")
        for n, d, r in ports:
            f.write(f"  {d} {'[%d:%d] ' % r if r else ''}{n};\n")
        for v in netmap.values():
            f.write(f"  wire {v};\n")
        for cell, name, orig, pins in rows:
            f.write(f"  {cell} {name} (" + ", ".join(f".{p}({n})" for p, n in pins) + ");\n")
        f.write("endmodule\n")


# ----------------------------------------------------------------------------------- lef / def
def lef_info(lef):
    """{macro: (width, height) um}, {macro: {pin: direction}}, {macro: class}."""
    text = open(lef).read()
    sizes, dirs, classes = {}, {}, {}
    for m in re.finditer(r"^MACRO\s+(\S+)(.*?)^END\s+\1", text, re.M | re.S):
        s = re.search(r"SIZE\s+([\d.]+)\s+BY\s+([\d.]+)", m.group(2))
        if s:
            sizes[m.group(1)] = (float(s.group(1)), float(s.group(2)))
        c = re.search(r"CLASS\s+(\w+)", m.group(2))
        classes[m.group(1)] = c.group(1) if c else "?"
        dirs[m.group(1)] = {p.group(1): p.group(2) for p in
                            re.finditer(r"PIN\s+(\S+)\s.*?DIRECTION\s+(\w+)", m.group(2), re.S)}
    return sizes, dirs, classes


def parse_def(path):
    """Die (um), components {name: macro}, nets {name: set((inst or PIN, pin))}, wire length (um)."""
    text = open(path).read()
    units = float(re.search(r"UNITS\s+DISTANCE\s+MICRONS\s+(\d+)", text).group(1))
    d = re.search(r"DIEAREA\s*\(\s*(-?\d+)\s+(-?\d+)\s*\)\s*\(\s*(-?\d+)\s+(-?\d+)\s*\)", text)
    die = [int(x) / units for x in d.groups()]
    comps = {}
    cm = re.search(r"^COMPONENTS\s+\d+\s*;(.*?)^END\s+COMPONENTS", text, re.M | re.S)
    for c in re.finditer(r"-\s+(\S+)\s+(\S+)", cm.group(1)):
        comps[c.group(1)] = c.group(2)
    nets, wl, vias = {}, {}, 0
    nm = re.search(r"^NETS\s+\d+\s*;(.*?)^END\s+NETS", text, re.M | re.S)
    for stmt in nm.group(1).split(";"):
        stmt = stmt.strip()
        if not stmt.startswith("-"):
            continue
        head, _, rest = stmt.partition("+")
        routing = ""
        for attr in ("+" + rest).split("+"):
            if attr.strip().startswith("ROUTED"):
                routing = attr
        toks = head.split()
        name = toks[1]
        nets[name] = set(re.findall(r"\(\s*(\S+)\s+(\S+)\s*\)", head))
        # routing: "+ ROUTED L ( x y ) ( x y ) [VIA] NEW L ( x y ) ..."
        for seg in re.split(r"\bNEW\b|\bROUTED\b", routing):
            sm = re.match(r"\s*(\w+)\s*(.*)", seg)
            if not sm:
                continue
            layer = sm.group(1)
            pts, last = [], None
            for tok in re.finditer(r"\(\s*(\S+)\s+(\S+)(?:\s+\S+)?\s*\)|\b([A-Za-z]\w*)\b", sm.group(2)):
                if tok.group(3):
                    if tok.group(3) not in ("ROUTED", "NEW", "SHAPE", "STRIPE"):
                        vias += 1
                    continue
                x = last[0] if tok.group(1) == "*" else int(tok.group(1))
                y = last[1] if tok.group(2) == "*" else int(tok.group(2))
                if last is not None:
                    wl[layer] = wl.get(layer, 0.0) + (abs(x - last[0]) + abs(y - last[1])) / units
                last = (x, y)
                pts.append(last)
    return {"die": die, "comps": comps, "nets": nets, "wirelength_um": wl, "vias": vias}


def check_connectivity(deff, rows, dirs):
    """The routed DEF's nets must connect exactly the pins the netlist connects."""
    want = {}
    for cell, name, orig, pins in rows:
        for p, n in pins:
            want.setdefault(n, set()).add((name, p))
    # port nets: the DEF lists ( PIN port ) as well
    bad = []
    for n, conns in want.items():
        got = {c for c in deff["nets"].get(n, set()) if c[0] != "PIN"}
        if got != conns:
            bad.append(n)
    extra = [n for n, c in deff["nets"].items()
             if n not in want and n not in ("vdd", "gnd") and any(x[0] != "PIN" for x in c)]
    if bad or extra:
        raise Fail(f"routed DEF connectivity differs from the netlist: {len(bad)} nets differ "
                   f"(e.g. {bad[:3]}), {len(extra)} extra nets (e.g. {extra[:3]})")
    for cell, name, orig, pins in rows:
        if deff["comps"].get(name) != cell:
            raise Fail(f"routed DEF: component {name} is {deff['comps'].get(name)}, netlist says {cell}")
    return len(want)


# ----------------------------------------------------------------------------------------- spef
def fix_spef(src, dst, cap_scale=1.0):
    """rc2dly's SPEF -> what OpenSTA reads: C unit, bus delimiter, internal node names; caps scaled."""
    out, section = [], None
    node = re.compile(r"(?<![\w*:])(\d+)_(\d+)(?![\w:])")
    with open(src) as f:
        for line in f:
            s = line.rstrip("\n")
            if s.startswith("*C_UNIT"):
                if s.split()[1:] != ["1", "FF"]:
                    raise Fail(f"rc2dly SPEF: unexpected {s!r}")
                s = "*C_UNIT 1 PF"
            elif s.startswith("*BUS_DELIMITER"):
                s = "*BUS_DELIMITER []"
            elif s.startswith("*D_NET"):
                section = "conn"
                p = s.split()
                s = f"{p[0]} {p[1]} {float(p[2]) * cap_scale:.6g}"
            elif s in ("*CAP", "*RES", "*CONN", "*END"):
                section = s
            elif section == "*CAP" and s.strip():
                p = node.sub(r"*\1:\2", s).split()
                p[-1] = f"{float(p[-1]) * cap_scale:.6g}"
                s = " ".join(p)
            elif section == "*RES" and s.strip():
                s = node.sub(r"*\1:\2", s)
            out.append(s)
    with open(dst, "w") as f:
        f.write("\n".join(out) + "\n")
    return sum(1 for s in out if s.startswith("*D_NET"))


# ------------------------------------------------------------------------------------------ sta
STA_HEAD = """read_liberty {lib}
read_verilog {net}
link_design {top}
"""

PATH_BODY = """
puts "wns [sta::worst_slack -max]"
puts "tns [sta::total_negative_slack -max]"
report_checks -path_delay max -fields {cap slew fanout} -digits 4
"""

ENDPOINT_BODY = """
puts "wns [sta::worst_slack -max]"
report_checks -path_delay max -format end -group_count 1000000 -endpoint_count 1 -digits 4
"""


SCAN_BODY = """
set d 1.0
while {{$d <= {dmax} + 1e-9}} {{
  set_timing_derate -late $d
  puts "DERATE $d [sta::worst_slack -max]"
  report_checks -path_delay max -format end -group_count 1000000 -endpoint_count 1 -digits 4
  set d [expr {{$d + {step}}}]
}}
"""


def sdc_variants(sdc_text):
    """(underated SDC text, derated SDC text, period, derate)."""
    pm = re.search(r"^\s*set\s+CLK_PERIOD\s+([0-9.]+)", sdc_text, re.M)
    if not pm:
        raise Fail("constraints.sdc has no `set CLK_PERIOD` line (not written by signoff.py?)")
    dm = re.findall(r"^\s*set_timing_derate\s+-late\s+([0-9.]+)\s*$", sdc_text, re.M)
    if len(dm) != 1:
        raise Fail(f"constraints.sdc: expected one `set_timing_derate -late D` line, found {len(dm)}")
    nod = re.sub(r"^\s*set_timing_derate\b[^\n]*\n", "# (set_timing_derate removed: pre-layout without derate)\n",
                 sdc_text, flags=re.M)
    return nod, sdc_text, float(pm.group(1)), float(dm[0])


def with_period(sdc_text, period):
    return re.sub(r"^(\s*set\s+CLK_PERIOD\s+)[0-9.]+", lambda m: f"{m.group(1)}{period:.3f}", sdc_text, flags=re.M)


def sta_run(work, name, netlist, top, sdc, body, spef, timeout):
    script = STA_HEAD.format(lib=LIBERTY, net=netlist, top=top)
    if spef:
        script += f"read_spef {spef}\n"
    script += f"read_sdc {sdc}\n" + body
    tcl = os.path.join(work, f"{name}.tcl")
    with open(tcl, "w") as f:
        f.write(script)
    rc, out, dt = run(["sta", "-no_splash", "-exit", tcl], work, os.path.join(work, f"{name}.rpt"), timeout)
    if rc:
        raise Fail(f"OpenSTA failed (exit {rc}): {work}/{name}.rpt")
    warn = [l for l in out.splitlines() if l.startswith(("Warning", "Error"))]
    if warn:
        raise Fail(f"OpenSTA warned ({len(warn)}x, first: {warn[0]}): {work}/{name}.rpt")
    return out


def parse_path(out, orig_names, regs):
    wns = float(re.search(r"^wns (\S+)", out, re.M).group(1))
    tns = float(re.search(r"^tns (\S+)", out, re.M).group(1))
    sp = re.search(r"Startpoint:\s*(\S+)", out).group(1)
    ep = re.search(r"Endpoint:\s*(\S+)", out).group(1)
    arr = float(re.search(r"([-0-9.]+)\s+data arrival time", out).group(1))
    ind = re.search(r"([-0-9.]+)\s+[-0-9.]+\s+[\^v]\s+input external delay", out)
    cells = len([p for p in re.findall(r"[\^v] (\S+)/\S+ \(", out.split("data arrival time")[0]) if p != ep])
    return {"wns_ns": round(wns, 4), "tns_ns": round(tns, 4), "start": orig_names.get(sp, sp),
            "end": orig_names.get(ep, ep), "start_reg": regs.get(sp, sp), "end_reg": regs.get(ep, ep),
            "start_layout": sp, "end_layout": ep, "arrival_ns": arr,
            "input_delay_ns": float(ind.group(1)) if ind else 0.0, "cells_on_path": cells}


def parse_scan(out):
    """{derate: (wns, {endpoint: slack})}."""
    res = {}
    for block in out.split("DERATE ")[1:]:
        head = block.split("\n", 1)[0].split()
        d, w = round(float(head[0]), 4), float(head[1])
        eps = {m.group(1): float(m.group(2)) for m in
               re.finditer(r"^(\S+) \(\S+\)\s+[-0-9.]+\s+[-0-9.]+\s+([-0-9.]+) \((?:MET|VIOLATED)\)", block, re.M)}
        if not eps:
            eps = {m.group(1): float(m.group(2)) for m in
                   re.finditer(r"^(\S+)\s+[-0-9.]+\s+[-0-9.]+\s+([-0-9.]+) \((?:MET|VIOLATED)\)", block, re.M)}
        res[d] = (w, eps)
    return res


def endpoint_slacks(out):
    m = parse_scan("DERATE 1.0 0\n" + out)
    return m[1.0][1]


def needed_derate(scan, post_wns, post_eps, near, tol=5e-4):
    """Smallest scanned derate d with: WNS_pre(d) <= WNS_post; slack_pre(d) <= slack_post at every
    endpoint; the same at every near-critical endpoint (post-layout slack <= WNS_post + near)."""
    crit = {e: s for e, s in post_eps.items() if s <= post_wns + near}
    d_wns = d_all = d_near = None
    for d in sorted(scan):
        wns, eps = scan[d]
        if d_wns is None and wns <= post_wns + tol:
            d_wns = d
        if d_all is None and all(eps[e] <= s + tol for e, s in post_eps.items()):
            d_all = d
        if d_near is None and all(eps[e] <= s + tol for e, s in crit.items()):
            d_near = d
    return d_wns, d_all, d_near, len(crit)


# ----------------------------------------------------------------------------------------- main
def flow(a, log_path):
    bundle = a.bundle
    sdir = os.path.join(bundle, "signoff")
    netlist = os.path.join(sdir, "netlist.v")
    sdc_path = os.path.join(bundle, "constraints.sdc")
    so_json = os.path.join(sdir, "signoff.json")
    for p in (netlist, sdc_path, so_json):
        if not os.path.isfile(p):
            raise Fail(f"{p} missing: run the sign-off first (shadecore handoff --signoff on, or signoff/signoff.py)")
    so = json.load(open(so_json))
    top = so.get("top")
    nod_sdc, der_sdc, sdc_period, derate = sdc_variants(open(sdc_path).read())
    periods = [sdc_period] + ([REPORT_PERIOD] if abs(sdc_period - REPORT_PERIOD) > 1e-9 else [])

    work = os.path.join(sdir, "postlayout")
    if os.path.exists(work):
        shutil.rmtree(work)
    proj = os.path.join(work, "qflow")
    for d in ("source", "synthesis", "layout", "log"):
        os.makedirs(os.path.join(proj, d))
    sta_dir = os.path.join(work, "sta")
    os.makedirs(sta_dir)

    # ---- netlist with qflow's names
    ntop, ports, insts = parse_netlist(netlist)
    if top and ntop != top:
        raise Fail(f"netlist top {ntop} != signoff.json top {top}")
    top = ntop
    rows, netmap = rename(ports, insts)
    sizes, dirs, classes = lef_info(LEF)
    for cell, name, orig, pins in rows:
        if cell not in sizes:
            raise Fail(f"cell {cell} ({orig}) is not in {LEF}")
    orig_names = {name: orig for cell, name, orig, pins in rows}
    orig_names.update({f"{name}/{p}": f"{orig}/{p}" for cell, name, orig, pins in rows for p, n in pins})
    # the RTL register behind a flip-flop: its Q net in signoff/netlist.v
    regs = {}
    for (cell, inst, pins), (c2, name, orig, new_pins) in zip(insts, rows):
        q = dict(pins).get("Q")
        if q:
            regs[name] = regs[f"{name}/D"] = q.lstrip("\\")
    net_v = os.path.join(sta_dir, f"{top}.v")
    write_verilog(net_v, top, ports, rows, netmap)
    write_verilog(os.path.join(proj, "source", f"{top}.v"), top, ports, rows, netmap)
    write_blif(os.path.join(proj, "synthesis", f"{top}.blif"), top, ports, rows)
    with open(os.path.join(proj, "synthesis", f"{top}_powerground"), "w") as f:
        f.write('set vddnet="vdd"\nset gndnet="gnd"\n')
    with open(os.path.join(proj, "log", "synth.log"), "w") as f:
        f.write("synthesis: skipped, the netlist is signoff/netlist.v (signoff/postlayout.py)\n")
    pv = ["#!/usr/bin/tcsh -f", "# signoff/postlayout.py"]
    if a.density:
        pv.append(f"set initial_density = {a.density}")
    with open(os.path.join(proj, "project_vars.sh"), "w") as f:
        f.write("\n".join(pv) + "\n")
    cell_area = sum(sizes[c][0] * sizes[c][1] for c, n, o, p in rows)
    log(f"netlist: {top}, {len(rows)} cells, {cell_area:.0f} um2 (LEF sizes), {len(netmap)} internal nets")

    # ---- place and route (qflow)
    log("place and route: qflow -T osu018 place route " + top + " (graywolf, qrouter) ...")
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    rc, out, t_pr = run([QFLOW, "-T", TECH, "place", "route", top], proj,
                        os.path.join(work, "qflow.log"), a.timeout, env)
    for lg in ("place.log", "route.log"):
        p = os.path.join(proj, "log", lg)
        if os.path.exists(p):
            LOG.append(f"---- qflow {lg}:\n" + "".join(open(p).readlines()[-15:]).rstrip())
    route_log = os.path.join(proj, "log", "route.log")
    rtext = open(route_log).read() if os.path.exists(route_log) else ""
    if rc:
        raise Fail(f"qflow place/route failed (exit {rc}): {work}/qflow.log, {proj}/log/")
    if "error condition" in out or "Premature exit" in out:
        raise Fail(f"qflow stopped on an error condition: {work}/qflow.log")
    if "Final: No failed routes!" not in rtext:
        fm = re.findall(r"Final:.*", rtext)
        raise Fail(f"qrouter did not route every net ({fm[-1] if fm else 'no Final line'}): {route_log}")
    lay = os.path.join(proj, "layout")
    def_path, rc_path = os.path.join(lay, f"{top}.def"), os.path.join(lay, f"{top}.rc")
    for p in (def_path, rc_path):
        if not os.path.isfile(p):
            raise Fail(f"qflow wrote no {p}")
    stages = re.findall(r"Progress: Stage (\d) total routes completed: (\d+)", rtext)
    log(f"place and route: {t_pr:.0f} s, qrouter: Final: No failed routes")

    deff = parse_def(def_path)
    nnets = check_connectivity(deff, rows, dirs)
    x0, y0, x1, y1 = deff["die"]
    die_w, die_h = x1 - x0, y1 - y0
    n_fill = sum(1 for n, c in deff["comps"].items() if c == "FILL")
    wl_total = sum(deff["wirelength_um"].values())
    log(f"layout: die {die_w:.1f} x {die_h:.1f} um = {die_w * die_h:.0f} um2, cell utilisation "
        f"{100 * cell_area / (die_w * die_h):.1f} %, {n_fill} FILL cells, routed wire {wl_total / 1000:.1f} mm, "
        f"DEF connectivity = netlist ({nnets} nets)")

    # ---- extraction
    raw_spef = os.path.join(work, f"{top}.rc2dly.spef")
    rc, out, _ = run([os.path.join(QFLOW_BIN, "rc2dly"), "-D", ":", "-r", rc_path, "-l", LIBERTY, "-d", raw_spef],
                     work, os.path.join(work, "rc2dly.log"), a.timeout)
    if rc or not os.path.isfile(raw_spef):
        raise Fail(f"rc2dly failed (exit {rc}): {work}/rc2dly.log")
    spef = os.path.join(sta_dir, f"{top}.spef")
    n_dnet = fix_spef(raw_spef, spef)
    spef2 = os.path.join(sta_dir, f"{top}.cap{a.cap_scale:g}.spef")
    fix_spef(raw_spef, spef2, a.cap_scale)
    wire_c = pin_c = 0.0
    for line in open(spef):
        if line.startswith("*D_NET"):
            wire_c += float(line.split()[2])
        elif line.startswith("*I ") and " *L " in line:
            pin_c += float(line.split()[-1])
    routed = [n for n in deff["nets"] if n not in ("vdd", "gnd") and n != CLOCK]
    if n_dnet < len(routed):
        raise Fail(f"SPEF has {n_dnet} nets, the layout {len(routed)} signal nets")
    log(f"extraction: rc2dly -> SPEF, {n_dnet} nets, total wire capacitance {wire_c:.3f} pF "
        f"and {pin_c:.3f} pF of input pins on the nets (repaired: C unit pF, bus [], internal nodes NET:K)")

    # ---- STA
    sdcs = {}
    for tag, text in (("nod", nod_sdc), ("der", der_sdc)):
        for p in periods:
            path = os.path.join(sta_dir, f"{tag}_{p:.3f}.sdc")
            with open(path, "w") as f:
                f.write(with_period(text, p))
            sdcs[(tag, p)] = path
    cases = [("pre", "nod", None, "pre-layout, no derate"),
             ("pre_derated", "der", None, f"pre-layout, set_timing_derate -late {derate} (the bundle's SDC)"),
             ("post", "nod", spef, "post-layout: qrouter RC (rc2dly SPEF), no derate"),
             ("post_cap_x", "nod", spef2, f"post-layout, every wire capacitance x{a.cap_scale:g} (sensitivity), no derate")]
    results = {}
    for key, tag, sp, desc in cases:
        r = {"what": desc, "at": {}}
        for p in periods:
            out = sta_run(sta_dir, f"{key}_{p:.3f}", net_v, top, sdcs[(tag, p)], PATH_BODY, sp, a.timeout)
            r["at"][f"{p:.3f}"] = parse_path(out, orig_names, regs)
        out = sta_run(sta_dir, f"{key}_fmax", net_v, top, sdcs[(tag, sdc_period)],
                      signoff.fmax_tcl(sdc_period), sp, a.timeout)
        fm = re.search(r"fmax_period (\S+)", out)
        if not fm:
            raise Fail(f"Fmax bisection failed: {sta_dir}/{key}_fmax.rpt")
        r["fmax_period_ns"] = round(float(fm.group(1)), 3)
        r["fmax_mhz"] = round(1000.0 / float(fm.group(1)), 1)
        results[key] = r
        w = r["at"][f"{sdc_period:.3f}"]
        log(f"sta {key:12s}: WNS {w['wns_ns']:+.3f} ns at {sdc_period} ns, worst arrival {w['arrival_ns']:.3f} ns "
            f"({w['start_reg']} -> {w['end_reg']}), Fmax period {r['fmax_period_ns']:.3f} ns")
    # sign-off consistency: the derated pre-layout run must reproduce signoff.json's slack at the SDC period
    so_wns = so.get("sta", {}).get("critical_path", {}).get("sdc_wns_ns")
    mine = results["pre_derated"]["at"][f"{sdc_period:.3f}"]["wns_ns"]
    if so_wns is not None and abs(so_wns - mine) > 0.002:
        raise Fail(f"pre-layout re-time with qflow names gives WNS {mine} ns, signoff.json {so_wns:.4f} ns")

    # ---- the derate post-layout asks for
    ends = {}
    for key, sp in (("post", spef), ("post_cap_x", spef2)):
        out = sta_run(sta_dir, f"{key}_endpoints", net_v, top, sdcs[("nod", sdc_period)],
                      ENDPOINT_BODY, sp, a.timeout)
        ends[key] = (float(re.search(r"^wns (\S+)", out, re.M).group(1)), endpoint_slacks(out))
    out = sta_run(sta_dir, "pre_derate_scan", net_v, top, sdcs[("nod", sdc_period)],
                  SCAN_BODY.format(dmax=DERATE_MAX, step=DERATE_STEP), None, a.timeout)
    scan = parse_scan(out)
    if len(scan) < 10 or any(len(v[1]) != len(ends["post"][1]) for v in scan.values()):
        raise Fail(f"derate scan: endpoint lists differ between runs: {sta_dir}/pre_derate_scan.rpt")
    need = {}
    near = NEAR_FRACTION * sdc_period
    at_sdc = scan[min(scan, key=lambda d: abs(d - derate))][1]
    for key in ("post", "post_cap_x"):
        d_wns, d_all, d_near, n_near = needed_derate(scan, *ends[key], near)
        post_eps = ends[key][1]
        uncovered = sorted(([orig_names.get(e, e), regs.get(e, e), round(s, 4), round(at_sdc[e], 4)]
                            for e, s in post_eps.items() if at_sdc[e] > s + 5e-4), key=lambda x: x[2])
        need[key] = {"derate_for_wns": d_wns, "derate_for_every_endpoint": d_all,
                     "derate_for_near_critical_endpoints": d_near,
                     "near_critical_endpoints": n_near, "near_critical_window_ns": round(near, 4),
                     "endpoints": len(post_eps),
                     "endpoints_not_covered_by_sdc_derate": uncovered[:20],
                     "endpoints_not_covered_fields": ["endpoint", "register", "post-layout slack ns",
                                                      f"pre-layout slack with derate {derate} ns"],
                     "endpoints_not_covered_count": len(uncovered)}
        log(f"derate {key:12s}: WNS_pre(d) <= WNS_post from d = {d_wns}; every near-critical endpoint "
            f"({n_near}, post slack <= WNS + {near:.3f} ns) from d = {d_near}; every endpoint "
            f"({len(post_eps)}) from d = {d_all}; {len(uncovered)} endpoints not covered by {derate} "
            f"(scan 1.0..{DERATE_MAX} step {DERATE_STEP}; None = beyond)")

    # ---- summary
    per = {}
    for p in periods:
        k = f"{p:.3f}"
        pre, post = results["pre"]["at"][k], results["post"]["at"][k]
        post2 = results["post_cap_x"]["at"][k]
        per[k] = {
            "post_over_pre_arrival": round(post["arrival_ns"] / pre["arrival_ns"], 4),
            "post_over_pre_path_delay": round((post["arrival_ns"] - post["input_delay_ns"]) /
                                              (pre["arrival_ns"] - pre["input_delay_ns"]), 4),
            "post_cap_x_over_pre_arrival": round(post2["arrival_ns"] / pre["arrival_ns"], 4),
            "derated_covers_post": results["pre_derated"]["at"][k]["wns_ns"] <= post["wns_ns"],
        }
    wl = {k: round(v, 1) for k, v in sorted(deff["wirelength_um"].items())}
    res = {
        "bundle": bundle, "top": top, "library": so.get("library"),
        "sdc_period_ns": sdc_period, "report_period_ns": REPORT_PERIOD, "derate_late": derate,
        "tools": {"qflow": tool_version([QFLOW, "-v"], r"Qflow version \S+ revision \S+"),
                  "graywolf": "graywolf " + tool_version(["dpkg-query", "-W", "-f", "${Version}", "graywolf"]),
                  "qrouter": tool_version([os.path.join(QFLOW_BIN, "qrouter"), "-v", "0", "-h"], r"\d+\.\d+\.\d+\S*"),
                  "rc2dly": QFLOW_BIN + "/rc2dly (qflow)",
                  "opensta": tool_version(["sta", "-version"]),
                  "debian_packages": {p: tool_version(["dpkg-query", "-W", "-f", "${Version}", p])
                                      for p in ("qflow", "qflow-tech-osu018", "graywolf", "qrouter", "opensta")}},
        "layout": {"cells": len(rows), "cell_area_um2": round(cell_area, 1), "fill_cells": n_fill,
                   "die_um": [round(die_w, 2), round(die_h, 2)], "die_area_um2": round(die_w * die_h, 1),
                   "utilisation": round(cell_area / (die_w * die_h), 4),
                   "initial_density": a.density, "nets": nnets,
                   "wirelength_um": wl, "wirelength_total_um": round(wl_total, 1), "vias": deff["vias"],
                   "wire_cap_pf": round(wire_c, 4), "pin_cap_pf": round(pin_c, 4), "place_route_s": round(t_pr, 1),
                   "qrouter_stages": [[int(s), int(n)] for s, n in stages]},
        "cap_scale": a.cap_scale,
        "sta": results, "compare": per, "derate_needed": need,
        "not_modelled": ["clock tree (ideal clock; the routed clock net is not used by the timing)",
                         "coupling capacitance and crosstalk (qrouter: area + one edge's fringe per wire)",
                         "corners: typical 1.8 V 25 C only", "hold fixing, IR drop"],
    }
    return res, work


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bundle", help="a bundle directory with the sign-off (signoff/netlist.v, constraints.sdc)")
    ap.add_argument("--density", type=float, default=None,
                    help="qflow initial_density (decongest: FILL spread through the rows); default: qflow's "
                         "default, no decongest")
    ap.add_argument("--cap-scale", type=float, default=2.0,
                    help="wire capacitance multiplier of the sensitivity run c2 (default 2.0)")
    ap.add_argument("--timeout", type=int, default=7200, help="seconds per tool run (default 7200)")
    a = ap.parse_args()
    a.bundle = os.path.abspath(a.bundle)
    sdir = os.path.join(a.bundle, "signoff")
    out_json = os.path.join(sdir, "postlayout.json")
    log_path = os.path.join(sdir, "postlayout.log")
    missing = [t for t in (QFLOW, os.path.join(QFLOW_BIN, "graywolf"), os.path.join(QFLOW_BIN, "qrouter"),
                           os.path.join(QFLOW_BIN, "rc2dly"), LIBERTY, LEF) if not os.path.exists(t)]
    if not shutil.which("sta"):
        missing.append("sta (OpenSTA)")
    if missing:
        print(f"postlayout: error: not installed: {', '.join(missing)} (Debian: qflow qflow-tech-osu018 opensta)",
              file=sys.stderr)
        return 77
    if not os.path.isdir(sdir):
        print(f"postlayout: error: {a.bundle} has no signoff/ (run the sign-off first)", file=sys.stderr)
        return 1
    if os.path.exists(out_json):
        os.remove(out_json)
    t0 = time.time()
    code = 0
    try:
        res, work = flow(a, log_path)
        res["seconds"] = round(time.time() - t0, 1)
        res["date_utc"] = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
        tmp = out_json + ".tmp"
        with open(tmp, "w") as f:
            json.dump(res, f, indent=1)
            f.write("\n")
        os.replace(tmp, out_json)
        log(f"wrote {out_json} ({res['seconds']:.0f} s)")
    except Fail as e:
        msg = f"postlayout: error: {e}"
        print(msg, file=sys.stderr)
        LOG.append(msg)
        code = 1
    finally:
        with open(log_path + ".tmp", "w") as f:
            f.write("\n".join(LOG) + "\n")
        os.replace(log_path + ".tmp", log_path)
    return code


if __name__ == "__main__":
    sys.exit(main())
