# SPDX-License-Identifier: Apache-2.0
"""Timing and energy sign-off of a shadecore handoff bundle in a real standard-cell library.

Runs on a bundle written by `shadecore handoff` (filelist.f, tb/, vectors/, run_icarus.sh) and writes
its results into BUNDLE/signoff/ (and BUNDLE/constraints.sdc with the measured clock):

  synth    Yosys 0.23: prepare (proc, flatten, opt, wreduce), map every `$mul` to a Dadda tree with a
           Kogge-Stone adder (signoff/fastmul.py; every other `$add`/`$sub`/compare's carry unit `$lcu`
           Kogge-Stone too, instead of Yosys's Brent-Kung; rtl/sc_mul_reg.v and rtl/sc_sum_reg.v black boxes to tree |
           register | adder), synth, dfflibmap, then ABC with the library, the target delay and load
           and drive constraints (the same driving cell and load as the SDC): ABC's `buffer` pass
           builds the buffer trees of high-fanout nets (the pipeline enable, valid, stall). The mapped
           netlist is signoff/netlist.v (bus ports kept, internal nets split to bits).
  sta      OpenSTA under the SDC: the clock on clk_i, input and output delays as a fraction of the
           period (IO_FRACTION, 0.3), the driving cell on every input and a load of four INVX1 inputs
           on every output, and `set_timing_derate -late DERATE` (1.15) on cell delays as the
           allowance for wires (no wire-load model in the library; placed and routed numbers in
           docs/timing.md). WNS/TNS at the target; Fmax by bisection on the period (every
           constraint scales with it) to 1 ps; the critical path named by its start and end registers.
  gatesim  the bundle's own self-checking testbench on the mapped netlist, every vector file: 0 mismatches.
           Icarus (4-state, zero-delay) on the library's cell models (no X after reset either) while the run is
           small enough: cells x vectors <= ICARUS_MAX_WORK. Above it (full_shared: 230k cells x 13.9k vectors,
           well over 1.5 h of Icarus here) Verilator (2-state) on cell models Yosys writes from the Liberty
           file's own functions (`read_liberty` + `write_verilog`: Verilator 5.006 does not read the library's
           UDP tables); the 4-state X check of those cores is the bundle's RTL run in Icarus. --gatesim chooses.
  power    a second gate-level run without input gaps or output stalls dumps a VCD of the
           netlist's nets; per net toggles per clock and time-high fraction go to OpenSTA
           (`sta::set_power_pin_activity` on each net's driver, `..._input_port_activity` on the inputs) and
           `report_power` at the closing period. energy per result = power x period x cycles /
           results. Typical corner, no wires, zero-delay simulation: glitches are not counted.

Exit status 0 when every step ran (the timing target may be missed: that is a result, recorded in
signoff.json); 1 on a tool error; 2 when the gate-level simulation failed.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import fastmul  # noqa: E402

LIB_DIR = "/usr/share/qflow/tech/osu018"
LIBERTY = "osu018_stdcells.lib"
CELLS = "osu018_stdcells.v"
DRIVE_CELL = "INVX1"
IO_FRACTION = 0.3
DERATE = 1.15
CLOCK = "clk_i"
# gatesim auto: Icarus while mapped cells x vectors stays at or below this (gl_default 160k x 2.9k and phong_point
# 295k x 3.5k run in under 10 minutes of CPU here; full_shared's 230k x 13.9k, 3.2e9, ran at ~21 cycles per second
# and took over 1.5 hours), Verilator above it
ICARUS_MAX_WORK = 2e9
VL_CELLS = "cells_verilator.v"
# ABC's lean script (--abc lean): Yosys 0.23's own for `abc -liberty -D` without its SAT sweeping (`&fraig -x`, `scorr`) and the
# retiming commands (a no-op on the combinational logic Yosys hands over): `&fraig -x` alone ran over 20 minutes on
# a lighting core's 310k AND nodes of multiplier trees (where SAT sweeping finds little); `dc2` + `&dch -f` still
# restructure, `&nf` maps for delay, `buffer`/`upsize`/`dnsize` build and size the buffer trees. ({D}: the target.)
ABC_LEAN = "+strash;dc2;strash;&get,-n;&dch,-f;&nf,{D};&put;buffer;upsize,{D};dnsize,{D};stime,-p"
# keep: map the structure as built, without ABC's AIG rewriting (dc2) and choice computation (dch), which turn
# fastmul.py's Kogge-Stone adders after a product register into carry chains (sc_normalize at MREG = 1: 4.65 ns with
# lean, 3.77 with keep, 17 % more area); for the pipelined lighting core (MREG = 1, docs/signoff.md)
ABC_KEEP = "+strash;&get,-n;&nf,{D};&put;buffer;upsize,{D};dnsize,{D};stime,-p"


def die(msg, code=1):
    print(f"signoff: error: {msg}", file=sys.stderr)
    sys.exit(code)


def log(msg):
    print(f"signoff: {msg}", flush=True)


def run(cmd, cwd, logfile, timeout=None, env=None):
    """Run a tool, its output into logfile; returns (rc, text)."""
    t0 = time.time()
    try:
        p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout, env=env)
        out, rc = p.stdout + p.stderr, p.returncode
    except subprocess.TimeoutExpired as e:
        out = (e.stdout or b"").decode(errors="replace") if isinstance(e.stdout, bytes) else (e.stdout or "")
        out += f"\n(timed out after {timeout} s)\n"
        rc = 124
    with open(logfile, "w") as f:
        f.write(f"# {' '.join(cmd)}\n# cwd {cwd}, {time.time() - t0:.1f} s, exit {rc}\n")
        f.write(out)
    return rc, out


def tool_version(cmd, pattern=None):
    """The first line a tool prints of its version, or the first match of pattern in its output."""
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.TimeoutExpired):
        return "unknown"
    text = p.stdout + p.stderr
    if pattern:
        m = re.search(pattern, text)
        return m.group(0) if m else "unknown"
    lines = text.strip().splitlines()
    return lines[0] if lines else "unknown"


def read_filelist(bundle):
    incs, files = [], []
    with open(os.path.join(bundle, "filelist.f")) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("//") or line.startswith("#"):
                continue
            if line.startswith("+incdir+"):
                incs.append(line[len("+incdir+"):])
            else:
                files.append(line)
    return incs, files


def lib_input_cap(liberty, cell, pin="A"):
    """The capacitance of one input pin of a library cell (pF)."""
    text = open(liberty).read()
    m = re.search(r"cell\s*\(\s*%s\s*\)" % cell, text)
    pm = re.search(r"pin\s*\(\s*%s\s*\)[^}]*?capacitance\s*:\s*([0-9.eE+-]+)" % pin, text[m.end():])
    return float(pm.group(1))


def lib_output_pins(liberty):
    """{cell: [output pin names]} of the library."""
    out, cell = {}, None
    text = open(liberty).read()
    for m in re.finditer(r"cell\s*\(\s*(\w+)\s*\)|pin\s*\(\s*(\w+)\s*\)\s*\{\s*direction\s*:\s*output", text):
        if m.group(1):
            cell = m.group(1)
            out[cell] = []
        elif cell:
            out[cell].append(m.group(2))
    return out


# ------------------------------------------------------------------------------------------- synth
def synth(a, sdir):
    incs, files = read_filelist(a.bundle)
    lib = a.liberty
    inc = " ".join(f"-I{os.path.join(a.bundle, i)}" for i in incs)
    # rtl/sc_mul_reg.v (a product with its pipeline register, the units' MREG) and rtl/sc_sum_reg.v (a multi-operand
    # sum with one, the cs16 forms' squarers at MREG = 1): black boxes here, mapped by fastmul.py to tree | register |
    # adder (the register between the tree and the final adder)
    lib_files = [f for f in files if a.arith == "fast" and os.path.basename(f) in ("sc_mul_reg.v", "sc_sum_reg.v")]
    src = " ".join(os.path.join(a.bundle, f) for f in files if f not in lib_files)
    load = 4 * lib_input_cap(lib, DRIVE_CELL)
    with open(os.path.join(sdir, "abc.constr"), "w") as f:
        f.write(f"set_driving_cell {DRIVE_CELL}\nset_load {load:.5f}\n")
    prep = (f"read_verilog -defer {inc} {src}\n" +
            "".join(f"read_verilog -lib {inc} {os.path.join(a.bundle, f)}\n" for f in lib_files) +
            f"hierarchy -check -top {a.top}" + "".join(f" -chparam {k} {v}" for k, v in a.chparam) + "\n"
            "proc; flatten; opt_expr; opt_clean; check; opt -nodffe -nosdff; fsm; opt; wreduce; peepopt; opt_clean\n")
    with open(os.path.join(sdir, "prep.ys"), "w") as f:
        f.write(prep + "write_rtlil prep.il\nwrite_json prep.json\n")
    rc, _ = run(["yosys", "-q", "-s", "prep.ys"], sdir, os.path.join(sdir, "yosys_prep.log"), a.timeout)
    if rc:
        die(f"Yosys preparation failed (exit {rc}): {sdir}/yosys_prep.log")
    shapes = fastmul.shapes_of(os.path.join(sdir, "prep.json")) if a.arith == "fast" else []
    fastmul.write_map(shapes, os.path.join(sdir, "fastmul_map.v"))
    mregs = fastmul.mulreg_shapes_of(os.path.join(sdir, "prep.json")) if lib_files else []
    sums = fastmul.sumreg_shapes_of(os.path.join(sdir, "prep.json")) if lib_files else []
    fastmul.write_mulreg_map(mregs, os.path.join(sdir, "mulreg_map.v"), sums)
    if a.arith == "fast":
        fastmul.write_lcu_map(os.path.join(sdir, "lcu_map.v"))
    os.remove(os.path.join(sdir, "prep.json"))
    period_ps = int(round(a.target * 1000))
    mregcmd = ("techmap -autoproc -map mulreg_map.v; opt_clean\nselect -assert-none t:sc_mul_reg t:sc_sum_reg\n"
               if lib_files else "")
    if a.arith == "fast":
        # The word-level passes (synth's coarse and fine optimisation) run with every $mul hidden as a black box
        # (HIDDEN_MUL), so they never see the multipliers' bit heaps; then the Dadda trees (fastmul_map.v), every
        # other cell to gates with Kogge-Stone carries (lcu_map.v), and straight to ABC: no gate-level `opt` pass
        # (minutes each on a lighting core's ~300k gates; ABC optimises the logic itself).
        with open(os.path.join(sdir, "hidden_mul.v"), "w") as f:
            f.write(fastmul.HIDDEN_MUL)
        flow = (f"read_liberty -lib {lib}\nread_verilog -lib hidden_mul.v\nread_rtlil prep.il\n" + mregcmd +
                f"chtype -set {fastmul.HIDDEN_NAME} t:$mul\n"
                f"synth -top {a.top} -run coarse:fine\nopt -fast -full\nmemory_map\nopt -full\n"
                f"chtype -set $mul t:{fastmul.HIDDEN_NAME}\n"
                "techmap -map fastmul_map.v\nopt_clean\n"
                "techmap -map +/techmap.v -map lcu_map.v\nopt_clean\n")
    else:
        flow = f"read_liberty -lib {lib}\nread_rtlil prep.il\n" + mregcmd + f"synth -top {a.top} -run coarse:\n"
    script = (flow +
              f"dfflibmap -liberty {lib}\n"
              f"abc -liberty {lib} -D {period_ps} -constr abc.constr" +
              ({"lean": f" -script {ABC_LEAN}\n", "keep": f" -script {ABC_KEEP}\n"}.get(a.abc, "\n")) +
              "opt_clean -purge\nsetundef -zero\nsplitnets\nopt_clean -purge\n"
              "insbuf -buf BUFX2 A Y\n"
              "check -assert\n"
              f"tee -o area.rpt stat -liberty {lib}\n"
              "write_verilog -noattr -noexpr -nohex -nodec netlist.v\n")
    with open(os.path.join(sdir, "synth.ys"), "w") as f:
        f.write("# generated by signoff/signoff.py: the cell mapping (after prep.ys)\n" + script)
    t0 = time.time()
    rc, _ = run(["yosys", "-q", "-s", "synth.ys"], sdir, os.path.join(sdir, "yosys_synth.log"), a.timeout)
    if rc:
        die(f"Yosys cell mapping failed (exit {rc}): {sdir}/yosys_synth.log")
    os.remove(os.path.join(sdir, "prep.il"))
    area = open(os.path.join(sdir, "area.rpt")).read()
    cells = int(re.search(r"Number of cells:\s+(\d+)", area).group(1))
    um2 = float(re.search(r"Chip area for module .*?:\s*([0-9.]+)", area).group(1))
    flops = sum(int(m.group(1)) for m in re.finditer(r"\s(\d+)\s*$", "\n".join(
        l for l in area.splitlines() if re.search(r"\bDFF\w+\b", l)), re.M))
    log(f"synth: {cells} cells, {um2:.0f} um2, {flops} flip-flops, {len(shapes)} multiplier shape(s) "
        f"mapped fast, {len(mregs)} registered-product shape(s), {len(sums)} registered sum(s) ({time.time() - t0:.0f} s)")
    return {"cells": cells, "area_um2": um2, "flops": flops, "mul_shapes": len(shapes), "mulreg_shapes": len(mregs),
            "sumreg_shapes": len(sums),
            "load_pf": load}


# ------------------------------------------------------------------------------------------- ports
def netlist_ports(netlist, top):
    """[(name, direction, width)] of the netlist's top module, in order."""
    text = open(netlist).read()
    m = re.search(r"\bmodule\s+%s\s*\(" % re.escape(top), text)
    if not m:
        die(f"module {top} not in {netlist}")
    end = text.index("endmodule", m.end())
    body = text[m.end():end]
    ports = []
    for d in re.finditer(r"^\s*(input|output)\s+(\[(\d+):(\d+)\]\s+)?([\\\w.$\[\]]+)\s*;", body, re.M):
        w = abs(int(d.group(3)) - int(d.group(4))) + 1 if d.group(2) else 1
        ports.append((d.group(5), d.group(1), w))
    return ports


SIGNOFF_MARK = "# ---- added by signoff/signoff.py: drive, load and the wire allowance"


def base_sdc(top, ports):
    """The environment part of an SDC, for a directory that has no constraints.sdc of its own (a bundle has:
    `shadecore handoff` writes it from cli/templates/handoff/constraints.sdc, and that text is kept)."""
    def plist(d):
        return " ".join(f"{n}[*]" if w > 1 else n for n, dd, w in ports if dd == d and n != CLOCK)
    return f"""# constraints.sdc — {top} (no handoff SDC: written by signoff/signoff.py)
set CLK_PERIOD 10.0
create_clock -name clk -period $CLK_PERIOD [get_ports {CLOCK}]

# Assumed environment: every input arrives IO_FRACTION of the period after the edge, every output is
# needed IO_FRACTION of the period before the next edge. No multicycle or false paths.
set IO_FRACTION {IO_FRACTION}
set_input_delay  -clock clk [expr {{$IO_FRACTION * $CLK_PERIOD}}] [get_ports {{{plist("input")}}}]
set_output_delay -clock clk [expr {{$IO_FRACTION * $CLK_PERIOD}}] [get_ports {{{plist("output")}}}]
"""


def write_sdc(path, base, period, load, note):
    """The SDC at a period: the base's environment (the handoff's I/O assumptions and port lists) with its
    period set and the header's period note replaced, plus the sign-off's drive, load and derate."""
    text = base.split(SIGNOFF_MARK)[0].rstrip() + "\n"
    text = re.sub(r"^# (Target period from|No measured Fmax|or it was not measured|Measured: ).*\n", "", text,
                  flags=re.M)
    text, n = re.subn(r"^set CLK_PERIOD .*$", f"# Measured: {note}\nset CLK_PERIOD {period:.3f}", text, count=1,
                      flags=re.M)
    ins = re.search(r"^set_input_delay .*\[get_ports \{(.*)\}\]\s*$", text, re.M)
    outs = re.search(r"^set_output_delay .*\[get_ports \{(.*)\}\]\s*$", text, re.M)
    if n != 1 or not ins or not outs:
        die(f"cannot use the SDC as a base (no 'set CLK_PERIOD' or I/O delay lines): {path}")
    text += f"""
{SIGNOFF_MARK} (OSU 0.18 um typical, pre-layout)
# Inputs are driven by an {DRIVE_CELL}; outputs drive {load:.4f} pF (four {DRIVE_CELL} inputs).
set_driving_cell -lib_cell {DRIVE_CELL} [get_ports {{{ins.group(1)}}}]
set_load {load:.5f} [get_ports {{{outs.group(1)}}}]
# Wires: the library has no wire-load model; cell delays are derated by {DERATE} as the allowance for
# them (checked on a placed and routed unit: docs/postlayout.md).
set_timing_derate -late {DERATE}
"""
    with open(path, "w") as f:
        f.write(text)


def fmax_tcl(start):
    """Tcl for OpenSTA: Fmax by bisection on the period from `start` (ns), every input/output delay kept at
    IO_FRACTION of it, to 1 ps; prints `fmax_period P`. Needs an SDC that sets IO_FRACTION."""
    return f"""
proc set_period {{p}} {{
  global IO_FRACTION
  create_clock -name clk -period $p [get_ports {CLOCK}]
  set ins [list]
  set outs [list]
  foreach port [get_ports *] {{
    set n [get_full_name $port]
    if {{$n == "{CLOCK}"}} {{ continue }}
    if {{[get_property $port direction] == "input"}} {{ lappend ins $port }} else {{ lappend outs $port }}
  }}
  set_input_delay -clock clk [expr {{$IO_FRACTION * $p}}] $ins
  set_output_delay -clock clk [expr {{$IO_FRACTION * $p}}] $outs
}}
set lo 0.05
set hi {start}
set_period $hi
while {{[sta::worst_slack -max] < 0}} {{ set lo $hi; set hi [expr {{$hi * 2}}]; set_period $hi
  if {{$hi > 10000}} {{ puts "fmax_failed"; exit 1 }} }}
while {{$hi - $lo > 0.001}} {{
  set mid [expr {{($lo + $hi) / 2.0}}]
  set_period $mid
  if {{[sta::worst_slack -max] >= 0}} {{ set hi $mid }} else {{ set lo $mid }}
}}
puts "fmax_period $hi"
"""


# ------------------------------------------------------------------------------------------- sta
STA_HEAD = """read_liberty {lib}
read_verilog {net}
link_design {top}
"""


def sta_script(a, sdir, sdc, body):
    return STA_HEAD.format(lib=a.liberty, net=os.path.join(sdir, "netlist.v"), top=a.top) + \
        f"read_sdc {sdc}\n" + body


def sta(a, sdir, base, load):
    """WNS/TNS at the target, Fmax by bisection, reports at the closing period."""
    target_sdc = os.path.join(sdir, "target.sdc")
    write_sdc(target_sdc, base, a.target, load, f"the target period {a.target} ns")
    # Bisection on the period in one OpenSTA session: each constraint is a fraction of the period.
    body = ('puts "target_wns [sta::worst_slack -max]"\n'
            'puts "target_tns [sta::total_negative_slack -max]"\n' + fmax_tcl(a.target))
    with open(os.path.join(sdir, "fmax.tcl"), "w") as f:
        f.write(sta_script(a, sdir, target_sdc, body))
    rc, out = run(["sta", "-no_splash", "-exit", "fmax.tcl"], sdir, os.path.join(sdir, "sta_fmax.log"), a.timeout)
    if rc or "fmax_period" not in out:
        die(f"OpenSTA failed (exit {rc}): {sdir}/sta_fmax.log")
    wns = float(re.search(r"target_wns (\S+)", out).group(1))
    tns = float(re.search(r"target_tns (\S+)", out).group(1))
    fmax_p = float(re.search(r"fmax_period (\S+)", out).group(1))
    met = wns >= 0
    closing = a.target if met else math.ceil(fmax_p * 20 - 1e-9) / 20.0   # next 0.05 ns above Fmax
    return {"target_ns": a.target, "wns_ns": round(wns, 4), "tns_ns": round(tns, 4), "met": met,
            "fmax_period_ns": round(fmax_p, 3), "fmax_mhz": round(1000.0 / fmax_p, 1), "period_ns": closing}


def reports(a, sdir, sdc):
    """Timing report (worst paths, groups) at the SDC's period; returns the worst path's description."""
    body = """
report_checks -path_delay max -group_count 5 -fields {fanout cap slew} -digits 3
report_checks -path_delay min -digits 3
report_check_types -max_slew -max_capacitance -max_fanout -violators
puts "sdc_wns [sta::worst_slack -max]"
puts "sdc_tns [sta::total_negative_slack -max]"
"""
    with open(os.path.join(sdir, "timing.tcl"), "w") as f:
        f.write(sta_script(a, sdir, sdc, body))
    rc, out = run(["sta", "-no_splash", "-exit", "timing.tcl"], sdir, os.path.join(sdir, "timing.rpt"), a.timeout)
    if rc:
        die(f"OpenSTA timing report failed (exit {rc}): {sdir}/timing.rpt")
    first = out.split("Startpoint:")[1] if "Startpoint:" in out else ""
    sp = re.search(r"^\s*(\S+)", first)
    ep = re.search(r"Endpoint:\s*(\S+)", out)
    arrival = re.search(r"([0-9.]+)\s+data arrival time", out)
    cells_on_path = len(re.findall(r"^\s*[0-9.-]+\s+[0-9.-]+\s+[0-9.-]+\s+[0-9.-]+\s+[0-9.-]+\s+[\^v]", first.split("data arrival")[0], re.M))
    if cells_on_path == 0:
        cells_on_path = len(re.findall(r"[\^v] \S+/\S+ \(", first.split("data arrival")[0]))
    return {"start": sp.group(1) if sp else "?", "end": ep.group(1) if ep else "?",
            "arrival_ns": float(arrival.group(1)) if arrival else None, "levels": cells_on_path,
            "sdc_wns_ns": float(re.search(r"sdc_wns (\S+)", out).group(1))}


def name_path(netlist, inst):
    """The RTL register behind a flip-flop instance (its Q net), or the port name."""
    text = open(netlist).read()
    m = re.search(r"\bDFF\w+\s+%s\s*\((.*?)\);" % re.escape(inst), text, re.S)
    if not m:
        return inst
    q = re.search(r"\.Q\(([^)]*)\)", m.group(1))
    return q.group(1).strip().lstrip("\\").strip() if q else inst


def fo4(a, sdir):
    """FO4 delay of the library: INVX1 driving four INVX1 (an inverter chain, the middle stage)."""
    net = os.path.join(sdir, "fo4.v")
    with open(net, "w") as f:
        f.write("module fo4 (a, y);\n input a;\n output y;\n wire n1, n2;\n"
                " INVX1 u1 (.A(a), .Y(n1));\n INVX1 u2 (.A(n1), .Y(n2));\n"
                + "".join(f" INVX1 l{i} (.A(n2), .Y());\n" for i in range(3)) +
                " INVX1 u3 (.A(n2), .Y(y));\n" +
                "".join(f" INVX1 m{i} (.A(y), .Y());\n" for i in range(4)) + "endmodule\n")
    tcl = (f"read_liberty {a.liberty}\nread_verilog {net}\nlink_design fo4\n"
           "create_clock -name c -period 10\nset_input_delay 0 -clock c [get_ports a]\n"
           "set_output_delay 0 -clock c [get_ports y]\nset_input_transition 0.1 [get_ports a]\n"
           "report_checks -rise_through [get_pins u2/Y] -digits 4\n"
           "report_checks -fall_through [get_pins u2/Y] -digits 4\n")
    with open(os.path.join(sdir, "fo4.tcl"), "w") as f:
        f.write(tcl)
    rc, out = run(["sta", "-no_splash", "-exit", "fo4.tcl"], sdir, os.path.join(sdir, "fo4.log"))
    # the middle inverter u2 (driven by an INVX1, driving four): the mean of its rising and falling delay
    m = [float(x) for x in re.findall(r"^\s*([0-9.]+)\s+[0-9.]+\s+[v^]\s+u2/Y", out, re.M)]
    os.remove(net)
    return round(sum(m) / len(m), 4) if len(m) == 2 else None


# ------------------------------------------------------------------------------------------- gate sim
def gate_filelist(a, sdir, cells=CELLS, name="gates.f"):
    path = os.path.join(sdir, name)
    with open(path, "w") as f:
        f.write(f"signoff/netlist.v\nsignoff/lib/{cells}\n")
    return path


def gatesim_engine(a, cells):
    """The simulator of the gate-level run and why: --gatesim, or by the size of the run (auto)."""
    if a.gatesim != "auto":
        return a.gatesim, f"--gatesim {a.gatesim}"
    vectors = 0
    for f in sorted(os.listdir(os.path.join(a.bundle, "vectors"))):
        if f.endswith(".hex"):
            vectors += sum(1 for x in open(os.path.join(a.bundle, "vectors", f)) if re.match(r"[0-9a-fA-F]", x))
    work = cells * vectors
    if work <= ICARUS_MAX_WORK:
        return "icarus", f"{cells} cells x {vectors} vectors = {work:.3g} <= {ICARUS_MAX_WORK:.3g}"
    return "verilator", f"{cells} cells x {vectors} vectors = {work:.3g} > {ICARUS_MAX_WORK:.3g}"


def verilator_cells(a, sdir):
    """Verilog models of the library's cells from its Liberty functions (Yosys read_liberty: each cell's `function`
    and `ff`/`latch` groups as assigns and always blocks), for Verilator, which does not read the UDP tables of the
    library's own models."""
    out = os.path.join(sdir, "lib", VL_CELLS)
    rc, text = run(["yosys", "-q", "-p", f"read_liberty {a.liberty}; write_verilog -noattr {out}.tmp"], sdir,
                   os.path.join(sdir, "yosys_cells.log"), a.timeout)
    if rc or not os.path.exists(out + ".tmp"):
        die(f"yosys could not write cell models from {a.liberty}: {sdir}/yosys_cells.log")
    with open(out + ".tmp") as f:
        body = f.read()
    with open(out, "w") as f:
        f.write(f"// Cell models written by Yosys from {os.path.basename(a.liberty)}'s functions "
                "(signoff/signoff.py, gate-level simulation in Verilator)\n/* verilator lint_off DECLFILENAME */\n"
                + body)
    os.remove(out + ".tmp")


def gatesim(a, sdir, cells):
    engine, why = gatesim_engine(a, cells)
    if engine == "verilator":
        if not shutil.which("verilator"):
            die("verilator not found (scripts/setup.sh installs it); or --gatesim icarus")
        verilator_cells(a, sdir)
        flist = os.path.relpath(gate_filelist(a, sdir, VL_CELLS, "gates_verilator.f"), a.bundle)
        cmd, env = ["./run_verilator.sh"], dict(os.environ, FILELIST=flist)
    else:
        flist = os.path.relpath(gate_filelist(a, sdir), a.bundle)
        cmd, env = ["./run_icarus.sh"], dict(os.environ, FILELIST=flist)
    t0 = time.time()
    p = subprocess.run(cmd, cwd=a.bundle, env=env, capture_output=True, text=True, timeout=a.timeout)
    text = p.stdout + p.stderr
    with open(os.path.join(sdir, f"gatesim_{engine}.log"), "w") as f:
        f.write(f"# FILELIST={flist} {cmd[0]} (the bundle's bench on the mapped netlist; {engine}: {why})\n"
                f"# {time.time() - t0:.1f} s, exit {p.returncode}\n{text}")
    vectors = sum(int(n) for n in re.findall(r"^PASS (\d+) vectors \(", text, re.M))
    fails = len(re.findall(r"^FAIL", text, re.M))
    passed = p.returncode == 0 and f"{cmd[0][2:]}: PASS" in text
    mism = len(re.findall(r"^FAIL vector \d+:", text, re.M))
    log(f"gatesim ({engine}: {why}): {'PASS' if passed else 'FAIL'} {vectors} vectors, {mism} mismatching "
        f"({time.time() - t0:.0f} s)")
    return {"passed": passed, "vectors": vectors, "mismatches": mism if passed or mism else max(fails, 1),
            "simulator": engine, "simulator_why": why, "seconds": round(time.time() - t0, 1)}


# ------------------------------------------------------------------------------------------- power
def parse_vcd(path):
    """Per VCD variable (scope-free name, bit) toggles and time high; plus the last time stamp.

    Returns (ids, tog, high, t_end): ids maps an identifier code to its [(name, width)] declarations; tog and high
    map (identifier, bit) to the bit's 0<->1 transitions and the time it spent at 1 (x and z neither toggle nor
    count as high). One pass; each bit has a slot in flat lists (scalar changes, most of a gate-level dump, cost
    one dictionary look-up), so a netlist's 1.6 GB dump takes minutes, not an hour."""
    ids = {}           # id -> [(name, width)]
    slot = {}          # id -> (first slot, width); bit b of the variable is slot first + b
    val, last, hi, tg = [], [], [], []
    t = 0
    with open(path) as f:
        for line in f:
            if line.startswith("$var"):
                parts = line.split()
                w, ident = int(parts[2]), parts[3]
                ids.setdefault(ident, []).append((" ".join(parts[4:-1]), w))
                if ident not in slot:
                    slot[ident] = (len(val), w)
                    val.extend([None] * w)
                    last.extend([0] * w)
                    hi.extend([0] * w)
                    tg.extend([0] * w)
            elif line.startswith("$enddefinitions"):
                break
        scalar = {ident: k for ident, (k, w) in slot.items() if w == 1}
        for line in f:
            c = line[0]
            if c == "#":
                t = int(line[1:])
            elif c == "b" or c == "B":
                v, ident = line[1:].split()
                sw = slot.get(ident)
                if sw is None:
                    continue
                k0, w = sw
                v = v.rjust(w, "0" if v[0] in "01" else v[0])[-w:]
                for i in range(w):
                    b = v[i]
                    k = k0 + w - 1 - i
                    old = val[k]
                    if old == "1":
                        hi[k] += t - last[k]
                        if b == "0":
                            tg[k] += 1
                    elif old == "0" and b == "1":
                        tg[k] += 1
                    val[k] = b
                    last[k] = t
            elif c in "01xzXZ":
                k = scalar.get(line[1:-1])
                if k is None:
                    k = scalar.get(line[1:].strip())
                    if k is None:
                        continue
                old = val[k]
                if old == "1":
                    hi[k] += t - last[k]
                    if c == "0":
                        tg[k] += 1
                elif old == "0" and c == "1":
                    tg[k] += 1
                val[k] = c
                last[k] = t
    t_end = t
    tog, high = {}, {}
    for ident, (k0, w) in slot.items():
        for b in range(w):
            k = k0 + b
            if val[k] == "1":
                hi[k] += t_end - last[k]
            if tg[k]:
                tog[(ident, b)] = tg[k]
            if hi[k]:
                high[(ident, b)] = hi[k]
    return ids, tog, high, t_end


# Per-net activity into OpenSTA. Not `set_power_activity -pins`: in OpenSTA 2.0.17 (Debian 12) its -pins branch calls an
# undefined `get_pins_error` (every such line fails; a flow that ignored the errors was left with OpenSTA's own
# propagation from the input ports) and would keep input pins only. The command it means to call,
# `sta::set_power_pin_activity` (activity in transitions per clock period, as -activity), is called directly, and
# every name must resolve: the counts are checked. OpenSTA's first power computation clears the activities and
# propagates them from the inputs, wiping any set before it: so power is computed once first (that number, OpenSTA's
# own probabilistic estimate from the input ports' activity alone, is kept as `propagated_mw` for comparison), and
# the gate-level activities of the nets are set after it (the input ports' before: they survive it).
PROPAGATE_TCL = """set sc_prop [lindex [sta::design_power [sta::cmd_corner]] 3]
puts "propagated $sc_prop"
"""
PIN_ACT_TCL = """set sc_set 0
set sc_missing 0
proc sc_pin_act {name act duty} {
  global sc_set sc_missing
  set p [get_pins -quiet $name]
  if {[llength $p] != 1} { incr sc_missing; puts "activity: no pin $name"; return }
  sta::set_power_pin_activity $p $act $duty
  incr sc_set
}
proc sc_port_act {name act duty} {
  global sc_set sc_missing
  set p [get_ports -quiet $name]
  if {[llength $p] != 1} { incr sc_missing; puts "activity: no port $name"; return }
  sta::set_power_input_port_activity $p $act $duty
  incr sc_set
}
"""


def power(a, sdir, period):
    """Gate-level activity -> OpenSTA report_power; energy per result."""
    vcd = os.path.join(sdir, "activity.vcd")
    gate_filelist(a, sdir)  # Icarus on the library's models, whichever simulator checked the netlist
    env = dict(os.environ, FILELIST="signoff/gates.f", IN_GAP="0", OUT_STALL="0", RESET_AT="-1",
               VCD=os.path.abspath(vcd), VECTORS="vectors/random.hex")
    t0 = time.time()
    p = subprocess.run(["./run_icarus.sh"], cwd=a.bundle, env=env, capture_output=True, text=True,
                       timeout=a.timeout)
    text = p.stdout + p.stderr
    with open(os.path.join(sdir, "power_sim.log"), "w") as f:
        f.write(f"# VCD=... IN_GAP=0 OUT_STALL=0 RESET_AT=-1 FILELIST=signoff/gates.f ./run_icarus.sh\n{text}")
    # PASS <records> vectors (... [<k> fragments checked, ...] <c> cycles, ...): a result is a fragment (lighting
    # core, whose records include register writes) or a vector (a unit)
    m = re.search(r"^PASS (\d+) vectors \((.*)\)$", text, re.M)
    if p.returncode or not m or not os.path.exists(vcd):
        die(f"the activity simulation failed: {sdir}/power_sim.log", 2)
    frag = re.search(r"(\d+) fragments checked", m.group(2))
    results = int(frag.group(1)) if frag else int(m.group(1))
    cycles = int(re.search(r"(\d+) cycles", m.group(2)).group(1))
    t_sim = time.time()
    vcd_mb = os.path.getsize(vcd) / 1e6
    ids, tog, high, t_end = parse_vcd(vcd)
    os.remove(vcd)
    t_parse = time.time()
    # the netlist's nets: VCD names inside the dut scope are the netlist's net names (escaped names lose '\')
    outpins = lib_output_pins(a.liberty)
    text = open(os.path.join(sdir, "netlist.v")).read()
    driver = {}   # net expression -> "inst/pin"
    for cm in re.finditer(r"^\s*(\w+)\s+(\\?\S+)\s*\((.*?)\);", text, re.M | re.S):
        cell, inst, conns = cm.group(1), cm.group(2), cm.group(3)
        if cell not in outpins:
            continue
        for pm in re.finditer(r"\.(\w+)\(([^()]*)\)", conns):
            if pm.group(1) in outpins[cell]:
                driver[norm_net(pm.group(2))] = (inst, pm.group(1))
    ports = {p for p, d, w in netlist_ports(os.path.join(sdir, "netlist.v"), a.top) if d == "input"}
    lines, annotated = [], 0
    for ident, vars_ in ids.items():
        name, w = vars_[0]
        base = name.split(" ")[0].lstrip("\\")
        for bit in range(w):
            key = (ident, bit)
            act = tog.get(key, 0) / cycles
            duty = high.get(key, 0) / t_end if t_end else 0.0
            net = base if w == 1 and "[" not in name else f"{base}[{bit}]"
            if w == 1 and re.search(r"\[(\d+)\]$", name.replace(" ", "")):
                net = name.replace(" ", "").lstrip("\\")
            root = re.sub(r"\[\d+\]$", "", net)
            if root in ports:
                if root == CLOCK:
                    continue
                lines.append(f"sc_port_act {{{net}}} {act:.6g} {duty:.6g}")
                annotated += 1
            elif norm_net(net) in driver:
                inst, pin = driver[norm_net(net)]
                inst = inst.lstrip("\\")
                lines.append(f"sc_pin_act {{{inst}/{pin}}} {act:.6g} {duty:.6g}")
                annotated += 1
    sdc = os.path.join(a.bundle, "constraints.sdc")
    ports_first = sorted(lines, key=lambda line: not line.startswith("sc_port_act"))
    k = sum(1 for line in lines if line.startswith("sc_port_act"))
    body = (PIN_ACT_TCL + "\n".join(ports_first[:k]) + "\n" + PROPAGATE_TCL + "\n".join(ports_first[k:]) + "\nputs \"annotated $sc_set missing $sc_missing\"\nreport_power -digits 4\n"
            "puts \"total_power [lindex [sta::design_power [sta::cmd_corner]] 3]\"\n")
    with open(os.path.join(sdir, "power.tcl"), "w") as f:
        f.write(sta_script(a, sdir, sdc, body))
    t_tcl = time.time()
    rc, out = run(["sta", "-no_splash", "-exit", "power.tcl"], sdir, os.path.join(sdir, "power.rpt"), a.timeout)
    t_sta = time.time()
    tm = re.search(r"^Total\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)", out, re.M)
    cnt = re.search(r"^annotated (\d+) missing (\d+)$", out, re.M)
    if not cnt or int(cnt.group(1)) != annotated or int(cnt.group(2)) or re.search(r"^Error", out, re.M):
        die(f"OpenSTA did not take every activity ({annotated} written, "
            f"{'none' if not cnt else cnt.group(1) + ' taken, ' + cnt.group(2) + ' not found'}): {sdir}/power.rpt")
    if rc or not tm:
        die(f"OpenSTA report_power failed (exit {rc}): {sdir}/power.rpt")
    watts = float(tm.group(4))
    e_pj = watts * period * 1e-9 * cycles / results * 1e12
    log(f"power: {watts * 1e3:.3f} mW at {period} ns, {results} results in {cycles} cycles, "
        f"{annotated} nets annotated, {e_pj:.2f} pJ per result ({time.time() - t0:.0f} s: simulation {t_sim - t0:.0f} s, "
        f"{vcd_mb:.0f} MB VCD parsed in {t_parse - t_sim:.0f} s, netlist and Tcl {t_tcl - t_parse:.0f} s, OpenSTA "
        f"{t_sta - t_tcl:.0f} s)")
    return {"power_mw": round(watts * 1e3, 4), "internal_mw": round(float(tm.group(1)) * 1e3, 4),
            "switching_mw": round(float(tm.group(2)) * 1e3, 4), "leakage_mw": round(float(tm.group(3)) * 1e3, 6),
            "results": results, "cycles": cycles, "nets_annotated": annotated,
            "energy_pj_per_result": round(e_pj, 3),
            "propagated_mw": round(float(re.search(r"^propagated (\S+)", out, re.M).group(1)) * 1e3, 4)}


def norm_net(expr):
    """A net expression of the netlist (`\\a.b [3]`, `_012_`) in one spelling: `a.b[3]`."""
    e = expr.strip()
    if e.startswith("\\"):
        e = e[1:]
    return re.sub(r"\s+", "", e)


# ------------------------------------------------------------------------------------------- main
def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bundle", help="a bundle directory written by `shadecore handoff`")
    ap.add_argument("--top", help="top module (default: the module instantiated in tb/tb_dut.vh)")
    ap.add_argument("--target", type=float, default=4.0, help="target clock period in ns (default 4.0)")
    ap.add_argument("--arith", choices=["fast", "yosys"], default="fast",
                    help="multipliers: fast = Dadda + Kogge-Stone (signoff/fastmul.py), yosys = Yosys's own")
    ap.add_argument("--abc", choices=["full", "lean", "keep"], default="full",
                    help="ABC script: full = Yosys's own for -liberty -D, lean = without SAT sweeping (ABC_LEAN; "
                         "for the lighting cores, where the full script does not finish in hours), keep = lean "
                         "without AIG rewriting, the arithmetic mapped as fastmul.py builds it (ABC_KEEP; the "
                         "pipelined lighting core)")
    ap.add_argument("--liberty", default=None, help=f"Liberty file (default {LIB_DIR}/{LIBERTY})")
    ap.add_argument("--cells", default=None, help=f"the library's Verilog cell models (default {LIB_DIR}/{CELLS})")
    ap.add_argument("--steps", default="synth,sta,gatesim,power",
                    help="comma list of synth, sta, gatesim, power (default all; later steps need earlier results)")
    ap.add_argument("--gatesim", choices=["auto", "icarus", "verilator"], default="auto",
                    help="gate-level simulator: icarus (4-state, the library's models), verilator (2-state, models "
                         "from the Liberty functions), auto (default: icarus while cells x vectors <= "
                         f"{ICARUS_MAX_WORK:.0e})")
    ap.add_argument("--timeout", type=int, default=7200, help="seconds per tool run (default 7200)")
    ap.add_argument("--chparam", action="append", default=[], metavar="NAME=VALUE",
                    help="set a parameter of the top before elaboration (repeatable)")
    ap.add_argument("--retime", action="store_true",
                    help="only re-time the bundle's signoff/netlist.v with its own constraints.sdc and print the slack")
    a = ap.parse_args()
    a.bundle = os.path.abspath(a.bundle)
    try:
        a.chparam = [tuple(x.split("=", 1)) for x in a.chparam]
        for k, v in a.chparam:
            int(v)
    except ValueError:
        die("--chparam takes NAME=INTEGER")
    if not os.path.isfile(os.path.join(a.bundle, "filelist.f")):
        die(f"{a.bundle} is not a handoff bundle (no filelist.f)")
    sdir = os.path.join(a.bundle, "signoff")
    os.makedirs(os.path.join(sdir, "lib"), exist_ok=True)
    own_lib = os.path.join(sdir, "lib", LIBERTY)
    a.liberty = a.liberty or (own_lib if os.path.exists(own_lib) else os.path.join(LIB_DIR, LIBERTY))
    a.cells = a.cells or (os.path.join(sdir, "lib", CELLS) if os.path.exists(os.path.join(sdir, "lib", CELLS))
                          else os.path.join(LIB_DIR, CELLS))
    for p in (a.liberty, a.cells):
        if not os.path.isfile(p):
            die(f"no such file: {p} (Debian package qflow-tech-osu018)")
    if not a.top:
        m = re.search(r"^\s*(\w+)\s+dut\s*\(", open(os.path.join(a.bundle, "tb", "tb_dut.vh")).read(), re.M)
        if not m:
            die("cannot find the top in tb/tb_dut.vh: give --top")
        a.top = m.group(1)
    steps = set(a.steps.split(","))
    if steps - {"synth", "sta", "gatesim", "power"}:
        die(f"unknown step(s) {sorted(steps - {'synth', 'sta', 'gatesim', 'power'})}")
    for t in ["yosys", "sta", "iverilog", "vvp"]:
        if not shutil.which(t):
            die(f"{t} not found (scripts/setup.sh installs yosys, opensta, iverilog)")
    if a.retime:
        rep = reports(a, sdir, os.path.join(a.bundle, "constraints.sdc"))
        print(f"wns {rep['sdc_wns_ns']:.3f} ns at the bundle's constraints.sdc")
        return
    for src, dst in ((a.liberty, own_lib), (a.cells, os.path.join(sdir, "lib", CELLS))):
        if os.path.abspath(src) != os.path.abspath(dst):
            shutil.copyfile(src, dst)
    a.liberty = own_lib
    jpath = os.path.join(sdir, "signoff.json")
    res = json.load(open(jpath)) if os.path.exists(jpath) else {}
    res.update({"top": a.top, "library": "OSU 0.18 um (qflow-tech-osu018 osu018_stdcells.lib), typical 1.8 V 25 C",
                "target_ns": a.target, "derate_late": DERATE, "io_fraction": IO_FRACTION, "drive_cell": DRIVE_CELL,
                "arith": a.arith,
                "tools": {"yosys": tool_version(["yosys", "-V"]), "opensta": tool_version(["sta", "-version"]),
                          "iverilog": tool_version(["iverilog", "-V"])}})
    if "synth" in steps:
        res["synth"] = synth(a, sdir)
        res["fo4_ns"] = fo4(a, sdir)
    if "sta" in steps:
        sdc_path = os.path.join(a.bundle, "constraints.sdc")
        base = (open(sdc_path).read() if os.path.exists(sdc_path)
                else base_sdc(a.top, netlist_ports(os.path.join(sdir, "netlist.v"), a.top)))
        st = sta(a, sdir, base, res["synth"]["load_pf"])
        note = (f"the target {a.target} ns is met (WNS {st['wns_ns']:+.3f} ns)" if st["met"] else
                f"the target {a.target} ns is missed (WNS {st['wns_ns']:+.3f} ns): the period is Fmax "
                f"({st['fmax_period_ns']} ns) rounded up to 0.05 ns")
        write_sdc(sdc_path, base, st["period_ns"], res["synth"]["load_pf"], note)
        rep = reports(a, sdir, os.path.join(a.bundle, "constraints.sdc"))
        rep["start_reg"] = name_path(os.path.join(sdir, "netlist.v"), rep["start"])
        rep["end_reg"] = name_path(os.path.join(sdir, "netlist.v"), rep["end"])
        st["critical_path"] = rep
        if res.get("fo4_ns"):
            st["fo4_per_cycle"] = round(st["period_ns"] / res["fo4_ns"], 1)
        res["sta"] = st
        log(f"sta: WNS {st['wns_ns']:+.3f} ns at {a.target} ns ({'met' if st['met'] else 'MISSED'}), Fmax "
            f"{st['fmax_mhz']} MHz ({st['fmax_period_ns']} ns), closes at {st['period_ns']} ns; worst path "
            f"{rep['start_reg']} -> {rep['end_reg']} ({rep['levels']} cells)")
    if "gatesim" in steps:
        res["gatesim"] = gatesim(a, sdir, res["synth"]["cells"])
    if "power" in steps and res.get("gatesim", {}).get("passed"):
        res["power"] = power(a, sdir, res["sta"]["period_ns"])
    with open(jpath + ".tmp", "w") as f:
        json.dump(res, f, indent=1)
    os.replace(jpath + ".tmp", jpath)
    if "gatesim" in steps and not res["gatesim"]["passed"]:
        sys.exit(2)


if __name__ == "__main__":
    main()
