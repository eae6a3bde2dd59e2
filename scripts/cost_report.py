#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The fair cost report: every unit (variant) x width (config) of config/configs.json measured the same way.

Per (variant, config) row, each metric is one cached job:
  sweep   `shadecore sweep --json --csv` (exhaustive over every code for the n range; per-n total error)
  cosim   `shadecore cosim --mode random` (latency, throughput = vectors/cycles, co-simulation speed)
  generic Yosys `synth -flatten; abc` cells, flip-flops, depth (`ltp -noff`), CMOS transistors
          (`dffunmap; stat -tech cmos`); RAMs: bits, and logic with the RAM kept as a black box
  hx8k    iCE40 `synth_ice40` (LUT4 only) + nextpnr-ice40 HX8K ct256 + icetime Fmax
  up5k    iCE40 `synth_ice40 -dsp` (SB_MAC16 count, 8 on a UP5K); where it fits, nextpnr-ice40 --up5k sg48
          on a generated serial wrapper (4 pins) and the Fmax from icetime (nextpnr 0.4 ignores SB_MAC16 delays)
  ecp5    `synth_ecp5` MULT18X18D, LUT4, TRELLIS_FF, DP16KD
  xc7     `synth_xilinx -family xc7 -flatten` DSP48E1, LUT1..6, FD*, CARRY4, block RAM
Cache: OUT/tradeoffs.cache.json (see --cache). Synthesis results are keyed by a hash of the elaborated,
flattened design of that row (Yosys, attributes stripped, private names enumerated), so a change to an
unrelated unit or a new generate branch in rtl/sc_specular.v keeps them; sweep/cosim results are keyed by
that hash plus the SHA-256 of the shadecore binary (and the co-simulator).
Writes OUT/tradeoffs.md (generated, do not edit), OUT/tradeoffs.json (one object per row) and OUT/tradeoffs.png.
Long (about an hour from an empty cache at -j 1); run by hand, not a test."""
import argparse
import concurrent.futures as cf
import datetime
import fcntl
import hashlib
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figures  # noqa: E402  scripts/figures.py: machine line, footer

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROG = "cost_report"
HX8K_LCS = 7680
UP5K = {"lcs": 5280, "dsp": 8, "bram": 30}
METRICS = ("sweep", "cosim", "generic", "hx8k", "up5k", "ecp5", "xc7")
SIM_METRICS = ("sweep", "cosim")
# Bumped when a metric's flow changes (invalidates its cached results).
FLOW_VERSION = {"sweep": "1", "cosim": "1", "generic": "1", "hx8k": "1", "up5k": "2", "ecp5": "1", "xc7": "2"}
# Rough first-run durations [s] at F = 16 for the ETA before any job of that metric has finished.
DEFAULT_SECONDS = {"sweep": 60, "cosim": 30, "generic": 90, "hx8k": 240, "up5k": 300, "ecp5": 120, "xc7": 150}
# n bands of the "which unit for which n" section (total error per band from the per-n sweep rows).
N_BANDS = ((16, 31), (32, 63), (64, 127), (128, 255), (256, 511), (512, 1024))
NICE = ["nice", "-n", "5"]


class Failure(Exception):
    """A step failed; the message is one line."""


def one_line(s, limit=300):
    s = " ".join(str(s).split())
    return s if len(s) <= limit else "…" + s[-limit:]


def run(cmd, cwd=None, timeout=7200):
    try:
        p = subprocess.run(NICE + cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise Failure(f"{os.path.basename(cmd[0])} timed out after {timeout} s")
    except OSError as e:
        raise Failure(f"cannot run {cmd[0]}: {e}")
    if p.returncode != 0:
        tail = (p.stderr.strip() or p.stdout.strip()).splitlines()[-3:]
        raise Failure(f"{os.path.basename(cmd[0])} exited with {p.returncode}: {one_line(' | '.join(tail))}")
    return p.stdout


# ---------------------------------------------------------------------------------------------------
# Pure parsing helpers (tests/cost_report_check.py runs them on captured Yosys/nextpnr/icetime output)

def parse_stat_json(text):
    """`stat -json [-tech cmos]` output (possibly after other log text) -> {cells, by_type, transistors,
    transistors_exact}. transistors_exact is False when Yosys printed "N+" (cells without a CMOS cost)."""
    start = text.find("{")
    if start < 0:
        raise Failure("no JSON in the Yosys stat output")
    dec = json.JSONDecoder()
    obj, _ = dec.raw_decode(text[start:])
    d = obj.get("design") or next(iter(obj["modules"].values()))
    res = {"cells": int(d["num_cells"]), "by_type": {k: int(v) for k, v in d["num_cells_by_type"].items()}}
    t = d.get("estimated_num_transistors")
    if t is not None:
        t = str(t)
        res["transistors"] = int(t.rstrip("+"))
        res["transistors_exact"] = not t.endswith("+")
    return res


def count(by_type, pattern):
    """Sum of the cell counts whose type matches the regular expression (full match)."""
    return sum(v for k, v in by_type.items() if re.fullmatch(pattern, k))


def parse_ltp(text):
    m = re.findall(r"Longest topological path in \S+ \(length=(\d+)\)", text)
    return int(m[-1]) if m else None


def parse_mem_dump(text):
    """`dump t:$mem_v2` -> [(size, width)] of every memory (words, bits per word)."""
    mems = []
    for cell in re.split(r"\n\s*cell ", text)[1:]:
        size = re.search(r"parameter \\SIZE (\d+)", cell)
        width = re.search(r"parameter \\WIDTH (\d+)", cell)
        if size and width:
            mems.append((int(size.group(1)), int(width.group(1))))
    return mems


def parse_icetime(text):
    m = re.findall(r"Total path delay: ([\d.]+) ns \(([\d.]+) MHz\)", text) or \
        re.findall(r"Timing estimate: ([\d.]+) ns \(([\d.]+) MHz\)", text)
    return float(m[-1][1]) if m else None


def icetime_dsp_on_path(report):
    """SB_MAC16 cells on the critical path listed by `icetime -mtr` (their configured mode, e.g.
    "SB_MAC16_MAS_U_16X16_BYPASS"), [] when the path is fabric only. icetime ends or starts such a path at the
    SB_MAC16 port ("[setup]: 0.000 ns") in the modes seen here, i.e. without the multiplier's own delay."""
    crit = report.split("Resolvable net names on path")[0]
    return re.findall(r"^\s+MAC16_\S+ \((SB_MAC16\w*)\)", crit, flags=re.M)


def parse_nextpnr_fmax(log):
    m = re.findall(r"Max frequency for clock '[^']*': ([\d.]+) MHz", log)
    return float(m[-1]) if m else None


def parse_nextpnr_lcs(log):
    m = re.findall(r"ICESTORM_LC:\s+(\d+)/\s*(\d+)", log)
    return int(m[-1][0]) if m else None


def per_n_bands(csv_text, bands=N_BANDS):
    """`shadecore sweep --csv` rows -> [max |total error| per band or None] (total = cos^n - output)."""
    lines = csv_text.strip().splitlines()
    head = lines[0].split(",")
    i_n, i_hi, i_lo = head.index("n"), head.index("total_max"), head.index("total_min")
    worst = [None] * len(bands)
    for line in lines[1:]:
        f = line.split(",")
        n, e = int(f[i_n]), max(abs(float(f[i_hi])), abs(float(f[i_lo])))
        for k, (lo, hi) in enumerate(bands):
            if lo <= n <= hi:
                worst[k] = e if worst[k] is None else max(worst[k], e)
    return worst


def pareto(points):
    """points: [(cost, error, payload)] -> the non-dominated ones (no other point is <= in both and < in one),
    sorted by cost."""
    pts = sorted((p for p in points if p[0] is not None and p[1] is not None), key=lambda p: (p[0], p[1]))
    front, best = [], math.inf
    for p in pts:
        if p[1] < best:
            front.append(p)
            best = p[1]
    return front


def parse_n_range(s):
    m = re.fullmatch(r"(\d+)(?:\.\.(\d+))?", s)
    if not m:
        raise ValueError(f"malformed n range '{s}' (expected N or LO..HI)")
    lo, hi = int(m.group(1)), int(m.group(2) or m.group(1))
    if lo > hi:
        raise ValueError(f"n range '{s}': LO > HI")
    return lo, hi


def wrapper_verilog(ports, params):
    """A serial wrapper around sc_specular for a small package: every input port (clk_i excepted) is driven
    by one shift register fed from pin si_i, every output is captured into a parallel-load shift register
    read out on so_o (load when ld_i, registered). 4 pins; every core port is live, every path into and out
    of the core starts and ends at a flip-flop. ports: [(name, direction, width)]."""
    ins = [(n, w) for n, d, w in ports if d == "input" and n != "clk_i"]
    outs = [(n, w) for n, d, w in ports if d == "output"]
    ni, no = sum(w for _, w in ins), sum(w for _, w in outs)
    conns, pos = [".clk_i(clk_i)"], 0
    for n, w in ins:
        conns.append(f".{n}(sin[{pos + w - 1}:{pos}])")
        pos += w
    pos = 0
    for n, w in outs:
        conns.append(f".{n}(outs[{pos + w - 1}:{pos}])")
        pos += w
    ps = ", ".join(f".{k}({v})" for k, v in params.items())
    shift_in = f"{{sin[{ni - 2}:0], si_i}}" if ni > 1 else "si_i"
    shift_out = f"{{1'b0, sout[{no - 1}:1]}}" if no > 1 else "1'b0"
    return "\n".join([
        "// generated by scripts/cost_report.py: serial wrapper for place and route on a small package",
        "`default_nettype none",
        "module sc_wrap (input wire clk_i, input wire si_i, input wire ld_i, output wire so_o);",
        f"  reg  [{ni - 1}:0] sin;",
        f"  reg  [{no - 1}:0] sout;",
        "  reg ld_q;",
        f"  wire [{no - 1}:0] outs;",
        "  always @(posedge clk_i) begin",
        "    ld_q <= ld_i;",
        f"    sin  <= {shift_in};",
        f"    sout <= ld_q ? outs : {shift_out};",
        "  end",
        "  assign so_o = sout[0];",
        f"  sc_specular #({ps}) u_core ({', '.join(conns)});",
        "endmodule", ""])


# ---------------------------------------------------------------------------------------------------
# Sources, design hash, cache

def rtl_files():
    d = os.path.join(ROOT, "rtl")
    return sorted(os.path.join(d, f) for f in os.listdir(d) if f.endswith(".v"))


def sha_files(paths):
    h = hashlib.sha256()
    for p in paths:
        h.update(os.path.relpath(p, ROOT).encode())
        with open(p, "rb") as f:
            h.update(hashlib.sha256(f.read()).digest())
    return h.hexdigest()


def source_hash():
    d = os.path.join(ROOT, "rtl")
    files = sorted(os.path.join(d, f) for f in os.listdir(d) if f.endswith((".v", ".vh")))
    return sha_files(files + [os.path.join(ROOT, "config", "configs.json")])


def params_of(variant, cfg):
    return {"VARIANT": variant["id"], "FRAC": cfg["frac"], "GUARD": cfg["guard"]}


def read_core(params):
    ch = " ".join(f"-set {k} {v}" for k, v in params.items())
    return f"read_verilog -I{os.path.join(ROOT, 'rtl')} {' '.join(rtl_files())}; chparam {ch} sc_specular"


def elaborate(params, tmp):
    """Hash of the elaborated, flattened design (attributes stripped, private names enumerated: unrelated
    source edits leave it unchanged) and its port list."""
    v, j = os.path.join(tmp, "canon.v"), os.path.join(tmp, "ports.json")
    run(["yosys", "-q", "-p", f"{read_core(params)}; hierarchy -top sc_specular; proc; flatten; opt_clean; "
         f"rename -enumerate; write_verilog -noattr {v}; write_json {j}"])
    with open(v, "rb") as f:
        dh = hashlib.sha256(f.read()).hexdigest()
    mod = json.load(open(j))["modules"]["sc_specular"]
    ports = [(n, p["direction"], len(p["bits"])) for n, p in mod["ports"].items()]
    return dh, ports


class Cache:
    def __init__(self, path):
        self.path, self.lock, self.data = path, threading.Lock(), {"entries": {}}
        if os.path.exists(path):
            try:
                self.data = json.load(open(path))
                assert isinstance(self.data.get("entries"), dict)
            except (ValueError, AssertionError, OSError) as e:
                raise Failure(f"cache {path} is unreadable ({one_line(e, 80)}); delete it or pass another --cache")

    def get(self, key):
        with self.lock:
            return self.data["entries"].get(key)

    def put(self, key, entry, prefix=None):
        """Stores entry under key, drops superseded entries of the same (variant, config, metric) prefix and
        writes the file atomically (temporary file, rename). Under an flock on CACHE.lock the file is re-read
        first, so two runs sharing a cache (e.g. one per --metrics subset) do not drop each other's entries."""
        with self.lock:
            d = os.path.dirname(os.path.abspath(self.path))
            os.makedirs(d, exist_ok=True)
            with open(os.path.join(d, "." + os.path.basename(self.path) + ".lock"), "w") as lk:
                fcntl.flock(lk, fcntl.LOCK_EX)
                if os.path.exists(self.path):
                    try:
                        self.data["entries"].update(json.load(open(self.path))["entries"])
                    except (ValueError, KeyError, OSError):
                        pass
                e = self.data["entries"]
                if prefix:
                    for k in [k for k in e if k.startswith(prefix) and k != key]:
                        del e[k]
                e[key] = entry
                fd, tmp = tempfile.mkstemp(prefix=".tradeoffs.cache.", dir=d)
                try:
                    with os.fdopen(fd, "w") as f:
                        json.dump(self.data, f, indent=1, sort_keys=True)
                        f.write("\n")
                    os.chmod(tmp, 0o644)
                    os.replace(tmp, self.path)
                except BaseException:
                    if os.path.exists(tmp):
                        os.unlink(tmp)
                    raise


# ---------------------------------------------------------------------------------------------------
# Metrics: each returns a dict of row fields

def m_sweep(ctx, variant, cfg, design, tmp):
    rng = ctx.n_for.get(cfg["name"], ctx.n)
    sj, sc = os.path.join(tmp, "sweep.json"), os.path.join(tmp, "sweep.csv")
    run([ctx.cli, "sweep", "--variant", variant["name"], "--config", cfg["name"], "--n", rng, "--threads",
         str(ctx.sweep_threads), "--no-progress", "--json", sj, "--csv", sc])
    s = json.load(open(sj))
    return {"quant_max": s["quant_ulp"]["max"]["value"], "quant_min": s["quant_ulp"]["min"]["value"],
            "total_max": s["total"]["max"]["value"], "total_min": s["total"]["min"]["value"], "sweep_n": rng,
            "sweep_seconds": s.get("seconds"), "err_by_n": per_n_bands(open(sc).read())}


def m_cosim(ctx, variant, cfg, design, tmp):
    cj = os.path.join(tmp, "cosim.json")
    run([ctx.cli, "cosim", "--variant", variant["name"], "--config", cfg["name"], "--mode", "random", "--count",
         str(ctx.cosim_count), "--shards", "1", "--seed", "1", "--json", cj]
        # A table unit's material change is a load of E cycles without fragments: one material per run, so the
        # rate is the unit's own (the load cost is stated in docs/table.md), as for every other unit.
        + (["--mat-rate", "0"] if variant.get("contract") == "table" else []))
    c = json.load(open(cj))
    if c["mismatches"]:
        raise Failure(f"co-simulation FAILED: {c['mismatches']} mismatches")
    ii = c["cycles"] / c["vectors"]
    return {"latency": c["latency_spec"], "vectors_per_s": c["vectors_per_s"], "cycles": c["cycles"],
            "vectors": c["vectors"], "mismatches": c["mismatches"],
            # the random stimulus offers a fragment every cycle and never stalls the output, so the
            # measured cycles per fragment is the initiation interval (+ the pipeline fill)
            "throughput": 1.0 / max(1, round(ii)), "cycles_per_fragment": ii}


def m_generic(ctx, variant, cfg, design, tmp):
    g = lambda n: os.path.join(tmp, n)  # noqa: E731
    out = run(["yosys", "-q", "-p",
               f"{read_core(params_of(variant, cfg))}; synth -flatten -top sc_specular -run :fine; "
               f"tee -q -o {g('mem.txt')} dump t:$mem_v2; "
               f"synth -flatten -top sc_specular -run fine:; abc; opt_clean; tee -q -o {g('gen.json')} stat -json; "
               f"tee -q -o {g('ltp.txt')} ltp -noff; dffunmap; tee -q -o {g('cmos.json')} stat -json -tech cmos"])
    del out
    gen, cmos = parse_stat_json(open(g("gen.json")).read()), parse_stat_json(open(g("cmos.json")).read())
    if not cmos.get("transistors_exact", False):
        raise Failure(f"stat -tech cmos counted cells without a CMOS cost: {cmos.get('transistors')}+")
    mems = parse_mem_dump(open(g("mem.txt")).read())
    res = {"cells": gen["cells"], "ffs": count(gen["by_type"], r"\$_S?DFFE?_\w+"),
           "depth": parse_ltp(open(g("ltp.txt")).read()), "transistors": cmos["transistors"],
           "ram_bits": sum(s * w for s, w in mems), "memories": [f"{s}x{w}" for s, w in mems]}
    if mems:
        # The same flow with the RAM kept as a black box ($mem_v2: no memory_map): the logic around it.
        # Its synchronous read register, if any, is inside the $mem_v2 and is not counted.
        run(["yosys", "-q", "-p",
             f"{read_core(params_of(variant, cfg))}; synth -flatten -top sc_specular -run :fine; "
             "opt -fast -full; opt -full; techmap; opt -fast; abc -fast; opt -fast; abc; opt_clean; "
             f"tee -q -o {g('nr.json')} stat -json; tee -q -o {g('nrltp.txt')} ltp -noff; dffunmap; "
             f"tee -q -o {g('nrcmos.json')} stat -json -tech cmos"])
        nr, nrc = parse_stat_json(open(g("nr.json")).read()), parse_stat_json(open(g("nrcmos.json")).read())
        res.update(cells_no_ram=nr["cells"] - count(nr["by_type"], r"\$mem(_v2)?"),
                   ffs_no_ram=count(nr["by_type"], r"\$_S?DFFE?_\w+"),
                   depth_no_ram=parse_ltp(open(g("nrltp.txt")).read()),
                   transistors_no_ram=nrc["transistors"])
    return res


def place_ice40(dev, pkg, js, tmp, freq):
    """nextpnr-ice40 + icetime -> (icetime MHz, nextpnr MHz, LCs, critical path through a DSP)."""
    asc, rpt = os.path.join(tmp, f"{dev}.asc"), os.path.join(tmp, f"{dev}.rpt")
    log = subprocess.run(NICE + ["nextpnr-ice40", f"--{dev}", "--package", pkg, "--json", js, "--asc", asc,
                                 "--freq", "12", "--timing-allow-fail", "--pcf-allow-unconstrained", "--seed", "1"],
                         capture_output=True, text=True, timeout=7200)
    if log.returncode != 0:
        raise Failure(f"nextpnr-ice40 --{dev} exited with {log.returncode}: "
                      f"{one_line(' | '.join(log.stderr.strip().splitlines()[-2:]))}")
    run(["icetime", "-d", dev, "-P", pkg, "-m", "-t", "-r", rpt, asc])
    text = open(rpt).read()
    return parse_icetime(text), parse_nextpnr_fmax(log.stderr), parse_nextpnr_lcs(log.stderr), \
        icetime_dsp_on_path(text)


def synth_cells(variant, cfg, synth, tmp, stat_name):
    """Yosys: the core of (variant, cfg), then the `synth` command; its cell counts by type (stat -json)."""
    st = os.path.join(tmp, stat_name)
    run(["yosys", "-q", "-p", f"{read_core(params_of(variant, cfg))}; {synth}; tee -q -o {st} stat -json"])
    return parse_stat_json(open(st).read())["by_type"]


def m_hx8k(ctx, variant, cfg, design, tmp):
    js = os.path.join(tmp, "hx.json")
    s = synth_cells(variant, cfg, f"synth_ice40 -top sc_specular -json {js}", tmp, "hx_stat.json")
    res = {"luts": s.get("SB_LUT4", 0), "dffs": count(s, r"SB_DFF\w*"), "bram_hx8k": s.get("SB_RAM40_4K", 0),
           "fmax_mhz": None, "pnr": "not run"}
    if res["luts"] > HX8K_LCS:
        res["pnr"] = "does not fit an HX8K"
        return res
    fmax, fnp, _, _ = place_ice40("hx8k", "ct256", js, tmp, 12)
    res.update(fmax_mhz=fmax, fmax_hx8k_nextpnr_mhz=fnp, pnr="HX8K ct256")
    return res


def m_up5k(ctx, variant, cfg, design, tmp):
    s = synth_cells(variant, cfg, "synth_ice40 -dsp -top sc_specular", tmp, "up_stat.json")
    res = {"dsp_up5k": s.get("SB_MAC16", 0), "luts_up5k": s.get("SB_LUT4", 0), "dffs_up5k": count(s, r"SB_DFF\w*"),
           "bram_up5k": s.get("SB_RAM40_4K", 0), "fmax_up5k_mhz": None, "fmax_up5k_nextpnr_mhz": None}
    over = [f"{res['dsp_up5k']} SB_MAC16 > {UP5K['dsp']}"] if res["dsp_up5k"] > UP5K["dsp"] else []
    if res["luts_up5k"] > UP5K["lcs"]:
        over.append(f"{res['luts_up5k']} LUT4 > {UP5K['lcs']}")
    if res["bram_up5k"] > UP5K["bram"]:
        over.append(f"{res['bram_up5k']} SB_RAM40_4K > {UP5K['bram']}")
    res["fits_up5k"] = not over
    if over:
        res["pnr_up5k"] = "does not fit: " + ", ".join(over)
        return res
    wv, js, ws = os.path.join(tmp, "sc_wrap.v"), os.path.join(tmp, "up.json"), os.path.join(tmp, "wrap_stat.json")
    with open(wv, "w") as f:
        f.write(wrapper_verilog(design["ports"], params_of(variant, cfg)))
    run(["yosys", "-q", "-p", f"{read_core(params_of(variant, cfg))}; read_verilog {wv}; "
         f"synth_ice40 -dsp -top sc_wrap -json {js}; tee -q -o {ws} stat -json"])
    try:
        fmax, fnp, lcs, crit_dsp = place_ice40("up5k", "sg48", js, tmp, 12)
    except Failure as e:
        res.update(fits_up5k=False, pnr_up5k=f"place and route failed: {one_line(e, 120)}")
        return res
    res.update(fmax_up5k_mhz=fmax, fmax_up5k_nextpnr_mhz=fnp, up5k_lcs=lcs, up5k_crit_dsp=", ".join(sorted(set(crit_dsp))) or None,
               pnr_up5k="UP5K sg48 (serial wrapper)")
    return res


def m_ecp5(ctx, variant, cfg, design, tmp):
    s = synth_cells(variant, cfg, "synth_ecp5 -top sc_specular", tmp, "ecp5.json")
    return {"ecp5_mult18": s.get("MULT18X18D", 0), "ecp5_lut4": s.get("LUT4", 0),
            "ecp5_ff": s.get("TRELLIS_FF", 0), "ecp5_ccu2": s.get("CCU2C", 0), "ecp5_bram": s.get("DP16KD", 0),
            "ecp5_lutram": count(s, r"TRELLIS_DPR16X4")}


def m_xc7(ctx, variant, cfg, design, tmp):
    st = os.path.join(tmp, "xc7.json")
    run(["yosys", "-q", "-p", f"{read_core(params_of(variant, cfg))}; synth_xilinx -family xc7 -flatten -top sc_specular; "
         f"tee -q -o {st} stat -json"])
    s = parse_stat_json(open(st).read())["by_type"]
    return {"x7_dsp48": s.get("DSP48E1", 0), "x7_lut": count(s, r"LUT[1-6]"), "x7_ff": count(s, r"FD[A-Z]*"),
            "x7_carry4": s.get("CARRY4", 0), "x7_bram": count(s, r"RAMB(18|36)E1"),
            "x7_lutram": count(s, r"RAM(32|64|128|256)\w*")}


METRIC_FN = {"sweep": m_sweep, "cosim": m_cosim, "generic": m_generic, "hx8k": m_hx8k, "up5k": m_up5k,
             "ecp5": m_ecp5, "xc7": m_xc7}


# ---------------------------------------------------------------------------------------------------
# Jobs: (variant, config, metric), cached

class Ctx:
    pass


def tool_versions():
    v = []
    for cmd in (["yosys", "-V"], ["nextpnr-ice40", "--version"]):
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
            v.append((p.stdout + p.stderr).strip().splitlines()[0] if (p.stdout + p.stderr).strip() else "?")
        except OSError:
            v.append("missing")
    return v


def job_key(ctx, variant, cfg, metric, design):
    h = hashlib.sha256()
    parts = [metric, FLOW_VERSION[metric], str(cfg["frac"]), str(cfg["guard"]), str(variant["id"])]
    if metric == "sweep":
        parts += [ctx.cli_hash, ctx.n_for.get(cfg["name"], ctx.n)]
    elif metric == "cosim":
        parts += [design["hash"], ctx.cli_hash, ctx.sim_hash.get(cfg["name"], "?"), str(ctx.cosim_count)]
    else:
        parts += [design["hash"]] + ctx.tools
    h.update("\0".join(parts).encode())
    prefix = f"{variant['name']}|{cfg['name']}|{metric}|"
    return prefix + h.hexdigest()[:20], prefix


def designs(ctx, pairs, log):
    """(variant, config) -> {"hash", "ports"}; cached by the hash of every rtl/ source and configs.json."""
    src = source_hash()
    out = {}
    for v, c in pairs:
        key = f"design|{v['name']}|{c['name']}|{src[:20]}"
        e = ctx.cache.get(key)
        if e is None:
            t0 = time.time()
            with tempfile.TemporaryDirectory(prefix="cost_report.") as tmp:
                dh, ports = elaborate(params_of(v, c), tmp)
            e = {"hash": dh, "ports": ports}
            ctx.cache.put(key, e, prefix=f"design|{v['name']}|{c['name']}|")
            log(f"elaborated {v['name']}/{c['name']} in {time.time() - t0:.0f} s")
        out[(v["name"], c["name"])] = e
    return out


def fmt_s(s):
    s = int(round(s))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60}:{s % 60:02d}"


def run_jobs(ctx, jobs, log):
    """jobs: [(variant, cfg, metric, key, prefix)] not in the cache. Returns {key: result or Failure}."""
    done, durations, results = 0, {}, {}
    lock = threading.Lock()
    t_start = time.time()

    def estimate(metric, cfg):
        d = durations.get(metric)
        base = sum(d) / len(d) if d else DEFAULT_SECONDS[metric]
        return base if d else base * (cfg["frac"] / 16.0) ** 1.5

    def one(job):
        v, c, m, key, prefix = job
        t0 = time.time()
        try:
            with tempfile.TemporaryDirectory(prefix="cost_report.") as tmp:
                res = METRIC_FN[m](ctx, v, c, ctx.designs[(v["name"], c["name"])], tmp)
            dt = time.time() - t0
            ctx.cache.put(key, {"result": res, "seconds": round(dt, 1), "date": datetime.date.today().isoformat(),
                                "machine": figures.machine(), "load": round(os.getloadavg()[0], 1)}, prefix=prefix)
            out = res
        except Failure as e:
            dt, out = time.time() - t0, e
        except (OSError, ValueError, KeyError, subprocess.SubprocessError) as e:
            dt, out = time.time() - t0, Failure(f"{type(e).__name__}: {one_line(e)}")
        nonlocal done
        with lock:
            done += 1
            durations.setdefault(m, []).append(dt)
            results[key] = out
            left = [j for j in jobs if j[3] not in results]
            eta = sum(estimate(j[2], j[1]) for j in left) / max(1, ctx.jobs)
            status = f"FAILED: {out}" if isinstance(out, Failure) else f"{dt:.0f} s"
            log(f"[{done}/{len(jobs)}] {v['name']}/{c['name']} {m}: {status} "
                f"(elapsed {fmt_s(time.time() - t_start)}, ETA {fmt_s(eta)})")
        return out

    if jobs:
        eta = sum(estimate(j[2], j[1]) for j in jobs) / max(1, ctx.jobs)
        log(f"{len(jobs)} jobs to run, -j {ctx.jobs}, first estimate {fmt_s(eta)}")
    with cf.ThreadPoolExecutor(max_workers=ctx.jobs) as ex:
        list(ex.map(one, jobs))
    return results


# ---------------------------------------------------------------------------------------------------
# Report

def fmt(v, spec="d"):
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, str):
        return v
    return format(v, spec)


def err_abs(r):
    if r.get("total_max") is None:
        return None
    return max(abs(r["total_max"]), abs(r["total_min"]))


def label(r):
    return f"{r['variant']} F{r['frac']}"


def rate(r):
    t = r.get("throughput")
    if t is None:
        return "—"
    return "1" if t == 1 else f"1/{round(1 / t)}"


def guidance(rows, baseline):
    """The "which unit for which n range and budget" section, derived from the rows."""
    lines = []
    by_cfg = {}
    for r in rows:
        by_cfg.setdefault((r["frac"], r["config"]), []).append(r)
    for (frac, cname), rs in sorted(by_cfg.items()):
        have = [r for r in rs if r.get("err_by_n") and r.get("cells") is not None]
        if not have:
            continue
        lines += [f"**{cname} (F = {frac})** — sweep n {', '.join(sorted({r['sweep_n'] for r in have}))}. For each n "
                  "band: the Pareto front of generic cells against the worst |cos^n − output| in the band, among "
                  "units that take one fragment per clock (cheapest first: each next unit costs more and is more "
                  "accurate), and the cheapest unit of any rate.", "",
                  "| n band | one per clock: cells → max error (cheapest first) | cheapest with error ≤ 1/255 "
                  "| cheapest of any rate |", "|---|---|---|---|"]
        for k, (lo, hi) in enumerate(N_BANDS):
            pts = [(r["cells"], r["err_by_n"][k], r) for r in have if r["err_by_n"][k] is not None]
            if not pts:
                continue
            full = [p for p in pts if p[2].get("throughput") == 1]
            front = pareto(full)
            ok = sorted((p for p in full if p[1] <= 1 / 255), key=lambda p: p[0])
            cheapest = min(pts, key=lambda p: p[0])
            lines.append(
                f"| {lo}..{hi} | " + "; ".join(f"{p[2]['variant']} {p[0]:,} → {p[1]:.2g}" for p in front)
                + f" | {(ok[0][2]['variant'] + f' ({ok[0][0]:,}, {ok[0][1]:.2g})') if ok else 'none'}"
                + f" | {cheapest[2]['variant']} ({cheapest[0]:,} cells, rate {rate(cheapest[2])}, "
                  f"{cheapest[1]:.2g}) |")
        lines.append("")
    if lines:
        lines = ["## Which unit for which n range and budget (derived from the table)", "",
                 "1/255 is one step of an 8-bit display channel. The error is the sweep's total error "
                 "(approximation + quantisation), maximised over every code of every n in the band."
                 + (" Per-n curves of the table units: [table/crossover.png](table/crossover.png)."
                    if os.path.exists(os.path.join(ROOT, "docs", "table", "crossover.png")) else ""), ""] + lines
    return lines


def check_rows(rows):
    for r in rows:
        for k in ("frac", "guard"):
            if not isinstance(r.get(k), int) or isinstance(r.get(k), bool):
                raise Failure(f"row {r.get('variant')}/{r.get('config')}: {k} is {r.get(k)!r}, not an integer")


def check_out_dir(out):
    """--out may be missing (it is created when the report is written), but it must be creatable: the
    nearest existing ancestor is a writable directory. Checked before the long run."""
    d = os.path.abspath(out)
    if os.path.exists(d):
        if not os.path.isdir(d):
            raise Failure(f"--out {out} is not a directory")
    else:
        anc = d
        while not os.path.exists(anc):
            anc = os.path.dirname(anc)
        if not os.path.isdir(anc):
            raise Failure(f"cannot create --out {out}: {anc} is not a directory")
        d = anc
    if not os.access(d, os.W_OK):
        raise Failure(f"cannot write to {d}")


def refresh_sections(md, rows):
    """tradeoffs.md with its standard-cell and lighting sections rewritten from docs/timing.json and
    docs/lighting_cost.json as they are now (inserted before the Pareto plot where an older report lacks them);
    the rest of the report, measured by this script, is kept as it was."""
    head, sep, tail = md.partition("## Pareto plot")
    if not sep:
        raise Failure("tradeoffs.md has no '## Pareto plot' section: rerun the report")
    for title in ("## In a standard-cell library", "## Lighting core: cost against throughput"):
        i = head.find(title)
        if i >= 0:
            j = head.find("\n## ", i + 1)
            head = head[:i] + (head[j + 1:] if j >= 0 else "")
    return head + "\n".join(standard_cell_rows(rows) + lighting_rows()) + sep + tail


def lighting_rows():
    """The lighting core's rows (docs/lighting_cost.json, measured by scripts/lighting_cost.py): the same table
    as docs/lighting.md §8.1, from the same function."""
    path = os.path.join(ROOT, "docs", "lighting_cost.json")
    if not os.path.exists(path):
        return []
    import lighting_cost  # noqa: E402  scripts/lighting_cost.py
    doc = json.load(open(path))
    return ["## Lighting core: cost against throughput", "",
            f"Rows of docs/lighting_cost.json (`scripts/lighting_cost.py`; machine {doc.get('machine', '?')}, each row's "
            "date and RTL source hash in its last column; docs/lighting.md §8.1 reads them):", "",
            lighting_cost.report_markdown(doc), ""]


def standard_cell_rows(rows):
    """What accuracy costs in nanoseconds and picojoules: the OSU 0.18 um sign-off of each unit (docs/timing.json,
    measured by scripts/timing_report.py) beside this report's error of the same unit and width."""
    path = os.path.join(ROOT, "docs", "timing.json")
    if not os.path.exists(path):
        return []
    doc = json.load(open(path))
    err = {(r["variant"], r["config"]): r.get("total_abs_max") for r in rows}
    L = ["## In a standard-cell library: clock, latency, energy (OSU 0.18 µm)", "",
         f"From docs/timing.json (`{doc['command']}`, {doc['machine']}, {doc['date']}; method and meaning: "
         f"docs/signoff.md): typical corner, pre-layout, cell delays ×{doc['derate_late']}, target {doc['target_ns']} ns.",
         "",
         "| unit | width | contract | worst error | period (ns) | meets target | latency (ns) | results/s | area (µm²) "
         "| energy (pJ/result) |", "|---|---|---|---|---|---|---|---|---|---|"]
    for t in doc["rows"]:
        if t["kind"] != "unit":
            continue
        cfg = t["width"].split(" ")[0]
        e = err.get((t["name"].split("+")[0], cfg))  # +mreg: the same outputs as the unit without it
        L.append(f"| {t['name']} | {cfg} | {t['contract']} | {'—' if e is None else f'{e:.3g}'} | {t['period_ns']} | "
                 f"{'yes' if t['met'] else 'no'} | {t.get('latency_ns', '—')} | {t['results_per_s']:,} | "
                 f"{t['area_um2']:,} | {'—' if t.get('energy_pj_per_result') is None else t['energy_pj_per_result']} |")
    return L + ["", "![error against energy and period × area](timing.png)", ""]


def write_report(rows, cmd, out, baseline="schlick_div", run_seconds=None, loads=()):
    """OUT/tradeoffs.md, .json and .png from the rows: all three or none (OUT and missing parents are created
    and removed again when anything fails)."""
    created = []
    d = os.path.abspath(out)
    while not os.path.exists(d):
        created.append(d)
        d = os.path.dirname(d)
    for c in reversed(created):
        os.mkdir(c)
    try:
        check_rows(rows)
        _write_report(rows, cmd, out, baseline, run_seconds, loads)
    except BaseException:
        for c in created:
            if os.path.isdir(c) and not os.listdir(c):
                os.rmdir(c)
        raise


def _write_report(rows, cmd, out, baseline, run_seconds, loads):
    footer = figures.footer(cmd)
    base = {r["config"]: r for r in rows if r["variant"] == baseline}
    ratio = lambda r, k: (r[k] / base[r["config"]][k]) if (r.get(k) is not None and r["config"] in base  # noqa: E731
                                                           and base[r["config"]].get(k)) else None
    L = [
        "# Cost report — every unit, contract and width measured the same way", "",
        "<!-- generated by scripts/cost_report.py, do not edit -->",
        f"Command: `{cmd.strip()}`  ",
        f"Machine: {figures.machine()}; date: {datetime.date.today().isoformat()}; Yosys 0.23, nextpnr-ice40 0.4, "
        "icetime, Verilator 5.006 + SystemC 2.3.4."
        + (f" Computing every row from an empty cache took {fmt_s(sum(run_seconds.values()))} (h:mm:ss or m:ss, the "
           "sum of the measured job times at -j 1: " + ", ".join(f"{m} {fmt_s(t)}" for m, t in run_seconds.items())
           + (f"; the machine was shared, 1-minute load average {min(loads)}–{max(loads)} at the end of the jobs"
              if loads else "") + ")." if run_seconds else ""),
        "",
        "## Error, latency, throughput, simulation speed", "",
        "*contract*: the unit's stated bound (config/configs.json; docs/spec.md §3.3 and §6.4). *quant*: fixed-point "
        "output against the double version of the same function, in output ulps; *total*: cos^n θ − output, over "
        "every input code and every n of *sweep n* (`shadecore sweep`). Latency: documented pipeline latency, checked "
        "by the co-simulation; *rate*: fragments per clock, measured (co-simulation cycles per fragment with a fragment "
        "offered every cycle). *sim*: vectors checked per second by one SystemC co-simulation process (random "
        "stimulus, 0 mismatches required), including start-up.", "",
        "| variant | contract | F | G | sweep n | quant max / min (ulp) | total max | total min | latency | rate | sim vectors/s |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        L.append(f"| {r['variant']} | {r.get('contract', '—')} | {r['frac']} | {r['guard'] if r['variant'].startswith('cs16') else '—'} "
                 f"| {r.get('sweep_n', '—')} | {fmt(r.get('quant_max'), '+.3f')} / {fmt(r.get('quant_min'), '+.3f')} "
                 f"| {fmt(r.get('total_max'), '.3e')} | {fmt(r.get('total_min'), '.3e')} | {fmt(r.get('latency'))} "
                 f"| {rate(r)} | {fmt(r.get('vectors_per_s'), ',.0f')} |")
    L += ["", "## Area and depth (technology independent)", "",
          "Yosys `synth -flatten; abc` on `sc_specular` (`-run :fine` stops before `memory_map`): *cells* are gates "
          "and flip-flops, *FFs* the flip-flops, *depth* the longest path in gates (`ltp -noff`). *transistors*: "
          "`dffunmap; stat -tech cmos` after the same synthesis (every flip-flop counted, enable/reset turned into "
          "gates; the run fails if any cell has no CMOS cost). RAM/ROM: bits of the inferred memories (a case-statement table such as schlick_nr's reciprocal seed is a ROM); the generic figures "
          "map them to flip-flops (`memory_map`), the *without RAM* figures keep each as a black box "
          f"(the logic around it). *÷ {baseline}*: ratio to {baseline} at the same width.", "",
          f"| variant | F | cells | ÷ {baseline} | FFs | depth | transistors | ÷ {baseline} | RAM/ROM bits | cells w/o RAM | transistors w/o RAM |",
          "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        L.append(f"| {r['variant']} | {r['frac']} | {fmt(r.get('cells'), ',')} | {fmt(ratio(r, 'cells'), '.2f')} "
                 f"| {fmt(r.get('ffs'), ',')} | {fmt(r.get('depth'))} | {fmt(r.get('transistors'), ',')} "
                 f"| {fmt(ratio(r, 'transistors'), '.2f')} | {fmt(r.get('ram_bits'), ',')} "
                 f"| {fmt(r.get('cells_no_ram'), ',')} | {fmt(r.get('transistors_no_ram'), ',')} |")
    L += ["", "## FPGA", "",
          "*HX8K*: `synth_ice40` (no DSP blocks: multipliers in LUT4), nextpnr-ice40 HX8K ct256, Fmax from icetime. "
          "*UP5K*: `synth_ice40 -dsp` (SB_MAC16; the UP5K has 8, 5,280 LUT4, 30 SB_RAM40_4K); where the unit fits, "
          "place and route of a generated serial wrapper (every core input from a shift register fed by one pin, "
          "every output captured into a shift register read out on one pin: 4 pins, the sg48 package has too few "
          "for the ports) with nextpnr-ice40 --up5k --package sg48; Fmax from icetime (`icetime -d up5k -P sg48 -mtr`); "
          "nextpnr's own figure in brackets. "
          "ECP5: `synth_ecp5` (MULT18X18D, LUT4, TRELLIS_FF); 7-series: `synth_xilinx -family xc7 -flatten` (DSP48E1, "
          "LUT1..6, FD*). ECP5 and 7-series are cell counts only (no place and route).", "",
          "| variant | F | HX8K LUT4 | HX8K DFF | HX8K Fmax (MHz) | UP5K MAC16 | UP5K LUT4 | fits UP5K | UP5K Fmax icetime (nextpnr) | DSP on path | ECP5 MULT18 | ECP5 LUT4 | ECP5 FF | 7s DSP48 | 7s LUT | 7s FF |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        hx = fmt(r.get("fmax_mhz"), ".1f") if r.get("fmax_mhz") else r.get("pnr", "—")
        if r.get("fmax_up5k_mhz"):
            up = f"{r['fmax_up5k_mhz']:.1f} ({fmt(r.get('fmax_up5k_nextpnr_mhz'), '.1f')})"
        else:
            up = r.get("pnr_up5k", "—")
        L.append(f"| {r['variant']} | {r['frac']} | {fmt(r.get('luts'), ',')} | {fmt(r.get('dffs'), ',')} | {hx} "
                 f"| {fmt(r.get('dsp_up5k'))} | {fmt(r.get('luts_up5k'), ',')} | {fmt(r.get('fits_up5k'))} | {up} "
                 f"| {fmt(r.get('up5k_crit_dsp'))} | {fmt(r.get('ecp5_mult18'))} | {fmt(r.get('ecp5_lut4'), ',')} "
                 f"| {fmt(r.get('ecp5_ff'), ',')} | {fmt(r.get('x7_dsp48'))} | {fmt(r.get('x7_lut'), ',')} "
                 f"| {fmt(r.get('x7_ff'), ',')} |")
    rams = [r for r in rows if r.get("ram_bits")]
    if rams:
        L += ["", "RAM blocks: " + "; ".join(
            f"{r['variant']} F{r['frac']}: {', '.join(r.get('memories', []))} = {r['ram_bits']:,} bits, "
            f"HX8K {fmt(r.get('bram_hx8k'))} / UP5K {fmt(r.get('bram_up5k'))} SB_RAM40_4K, ECP5 "
            f"{fmt(r.get('ecp5_bram'))} DP16KD, 7-series {fmt(r.get('x7_bram'))} RAMB" for r in rams) + "."]
    L += ["", timing_note(rows), ""]
    errs = [f"- {r['variant']}/{r['config']}: {k[:-6]}: {r[k]}" for r in rows for k in sorted(r)
            if k.endswith("_error") and r[k] != "not run"]
    if errs:
        L += ["Steps that failed (reported, not hidden):", ""] + errs + [""]
    missing = {}
    for r in rows:
        for k in sorted(r):
            if k.endswith("_error") and r[k] == "not run":
                missing.setdefault(k[:-6], []).append(f"{r['variant']}/{r['config']}")
    if missing:
        L += ["Not measured yet (no result in the cache; a dash in the tables): "
              + "; ".join(f"{m}: {', '.join(v) if len(v) < len(rows) else 'every row'}" for m, v in missing.items())
              + ".", ""]
    L += guidance(rows, baseline)
    L += standard_cell_rows(rows)
    L += lighting_rows()
    L += ["## Pareto plot", "",
          "![error against area](tradeoffs.png)", "",
          "One point per unit × contract × width; y: the worst |cos^n − output| over the swept n range; x: generic "
          "cells, CMOS transistors, iCE40 LUT4 (no DSP). The grey staircase is the Pareto front (no other point is "
          "both cheaper and more accurate); lower left is better. Hollow markers take fewer than one fragment per clock.",
          "", RERUN_NOTE]
    # All three or none: temporary files in OUT, renamed together at the end.
    tmps = {n: os.path.join(out, f".{n}.tmp.{os.getpid()}") for n in ("tradeoffs.md", "tradeoffs.json", "tradeoffs.png")}
    try:
        with open(tmps["tradeoffs.md"], "w") as f:
            f.write("\n".join(L) + "\n")
        with open(tmps["tradeoffs.json"], "w") as f:
            f.write(json.dumps(rows, indent=2) + "\n")
        plot(rows, tmps["tradeoffs.png"], footer)
    except BaseException:
        for t in tmps.values():
            if os.path.exists(t):
                os.unlink(t)
        raise
    for n, t in tmps.items():
        os.replace(t, os.path.join(out, n))


def timing_note(rows):
    """Which timing numbers to trust, with the agreement of the two tools measured on these rows."""
    def spread(a, b):
        d = [abs(r[a] / r[b] - 1) for r in rows if r.get(a) and r.get(b)]
        return f"{100 * max(d):.1f} % ({len(d)} row{'s' if len(d) != 1 else ''})" if d else "not measured"
    on_dsp = sorted({f"{r['variant']} F{r['frac']}" for r in rows if r.get("up5k_crit_dsp")})
    return (
        "Which timing numbers to trust. *HX8K* (LUT logic only): icetime and nextpnr model the same LUT and "
        f"routing delays; largest difference between them here: {spread('fmax_mhz', 'fmax_hx8k_nextpnr_mhz')}. "
        "*UP5K* with SB_MAC16: nextpnr-ice40 0.4 has no delay for paths through an SB_MAC16 (TOOLCHAIN: 181 MHz "
        "reported where icetime gives 18), and icetime, in the SB_MAC16 modes Yosys produced here, ends a path "
        "at the SB_MAC16 input with a 0.000 ns setup and starts the next one at its output, so neither includes "
        "the multiplier array's own delay when the DSP is used without its internal registers. Handling: the "
        "reported UP5K Fmax is icetime's (nextpnr's in brackets, largest difference here: "
        f"{spread('fmax_up5k_mhz', 'fmax_up5k_nextpnr_mhz')}), and *DSP on path* names the SB_MAC16 mode where "
        "icetime's critical path starts or ends at one — there the figure is an upper bound"
        + (f" ({', '.join(on_dsp)})" if on_dsp else "") + "; where it is empty the critical path is fabric "
        "logic, but a shorter-looking DSP path may still be the real limit, so every UP5K Fmax of a unit with "
        "SB_MAC16 is an upper bound, and the HX8K figure (multipliers in LUTs, fully modelled) is the "
        "trustworthy one. ECP5 and 7-series: cell counts only, no timing.")


RERUN_NOTE = (
    "## Rerunning\n\n"
    "`scripts/cost_report.py --n-for wide=1016..1024` (the wide sweep's n range is a choice: every n at F = 24 is 1.7·10¹⁰ evaluations; build first: `scripts/build.sh`; the iCE40 tools are "
    "installed by `scripts/setup.sh nextpnr-ice40 fpga-icestorm fpga-icestorm-chipdb`). Every result is cached in "
    "docs/tradeoffs.cache.json: synthesis and place-and-route by a hash of the elaborated design of that row, "
    "sweep and co-simulation also by the SHA-256 of the shadecore binary (and of the co-simulator), so a rerun "
    "after adding a unit computes the new rows only, and a rebuilt binary reruns the sweeps and co-simulations. "
    "`--only VARIANT[,..]`, `--configs NAME[,..]`, `--metrics sweep,cosim,generic,hx8k,up5k,ecp5,xc7`, `-j N` "
    "(default 1; synthesis runs under `nice -n 5`), `--dry-run` (list the jobs and what is cached), `--cached-only` (report what the cache holds), `--replot` "
    "(redraw from docs/tradeoffs.json). Progress with an ETA goes to stderr.")


def plot(rows, path, footer):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    panels = (("cells", "generic cells (Yosys synth; abc)"), ("transistors", "CMOS transistors (stat -tech cmos)"),
              ("luts", "iCE40 LUT4 (synth_ice40, no DSP)"))
    variants = sorted({r["variant"] for r in rows})
    contract = {r["variant"]: r.get("contract", "?") for r in rows}
    markers = "osD^vP*Xhp<>"
    cfgs = sorted({(r["frac"], r["config"]) for r in rows})
    colours = plt.get_cmap("viridis")(list(i / max(1, len(cfgs) - 1) * 0.85 for i in range(len(cfgs))))
    colour = {c[1]: colours[i] for i, c in enumerate(cfgs)}
    fig, axes = plt.subplots(1, 4, figsize=(18, 6.4), gridspec_kw={"width_ratios": [1, 1, 1, 0.34]})
    key_ax, axes = axes[3], axes[:3]
    labels = []
    for ax, (key, xlabel) in zip(axes, panels):
        pts = []
        for r in rows:
            x, y = r.get(key), err_abs(r)
            if x is None or y is None:
                continue
            pts.append((x, y, r))
            full = r.get("throughput", 1) == 1
            m = markers[variants.index(r["variant"]) % len(markers)]
            ax.scatter([x], [y], marker=m, s=46, edgecolors=colour[r["config"]],
                       facecolors=colour[r["config"]] if full else "none", linewidths=1.4, zorder=3)
        front = pareto(pts)
        xmax = max(p[0] for p in pts) * 1.5 if pts else 1
        if front:
            xs, ys = [front[0][0]], [front[0][1]]
            for p in front[1:]:
                xs += [p[0], p[0]]
                ys += [ys[-1], p[1]]
            ax.plot(xs + [xmax], ys + [ys[-1]], color="0.55", lw=1.2, zorder=2)
        ax.set_xscale("log")
        ax.set_yscale("log")
        if pts:  # room around the points for their labels
            ax.set_xlim(min(p[0] for p in pts) / 2.2, xmax * 1.6)
            ax.set_ylim(min(p[1] for p in pts) / 2.2, max(p[1] for p in pts) * 2.2)
        ax.set_xlabel(xlabel)
        ax.grid(alpha=0.3, which="both")
        labels.append((ax, pts))
    axes[0].set_ylabel("max |cos^n θ − output| over the swept n (lower is better)")
    handles = [Line2D([], [], marker=markers[i % len(markers)], ls="", color="0.3", label=f"{v} ({contract[v]})")
               for i, v in enumerate(variants)]
    handles += [Line2D([], [], marker="s", ls="", color=colour[c], label=f"{c} (F = {f})") for f, c in cfgs]
    handles += [Line2D([], [], marker="o", ls="", mfc="none", color="0.3", label="< 1 fragment per clock"),
                Line2D([], [], color="0.55", label="Pareto front")]
    key_ax.axis("off")
    key_ax.legend(handles=handles, fontsize=7, loc="center left", title="unit (contract), width", title_fontsize=7)
    fig.suptitle("Error against area: every unit × contract × width (lower left is better); "
                 "labels: unit and fraction bits F", fontsize=11)
    figures.layout(fig)
    for ax, pts in labels:  # after the layout: each label at the nearest free place, leader lines when far
        figures.place_labels(ax, [(x, y, f"{r['variant']} F{r['frac']}") for x, y, r in sorted(pts, key=lambda p: p[:2])])
    figures.save(fig, path, footer, dpi=120)


# ---------------------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="CMake build directory")
    ap.add_argument("--only", "--variants", dest="only", default="", help="comma-separated variant names (default: all)")
    ap.add_argument("--configs", default="", help="comma-separated config names (default: all)")
    ap.add_argument("--metrics", default=",".join(METRICS), help=f"comma-separated subset of {','.join(METRICS)}")
    ap.add_argument("--n", default="16..1024", help="sweep n range")
    ap.add_argument("--n-for", action="append", default=[], metavar="CONFIG=RANGE",
                    help="sweep n range for one config (e.g. wide=1000..1024: the full wide sweep is 17 G evaluations)")
    ap.add_argument("--cosim-count", type=int, default=1000000, help="random co-simulation transactions")
    ap.add_argument("--sweep-threads", type=int, default=1, help="threads of each sweep")
    ap.add_argument("-j", "--jobs", type=int, default=1, help="parallel jobs (default 1: the speed figures stay clean)")
    ap.add_argument("--baseline", default="schlick_div", help="variant the area ratios refer to")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs"), help="directory for tradeoffs.md/.json/.png")
    ap.add_argument("--cache", default=None, help="result cache (default OUT/tradeoffs.cache.json)")
    ap.add_argument("--dry-run", action="store_true", help="list the jobs and which are cached; run nothing")
    ap.add_argument("--cached-only", action="store_true",
                    help="write the report from the cache alone (what is missing shows as not run)")
    ap.add_argument("--replot", action="store_true", help="only redraw OUT/tradeoffs.png from OUT/tradeoffs.json and refresh tradeoffs.md's sections "
                         "read from docs/timing.json and docs/lighting_cost.json")
    a = ap.parse_args()
    log = lambda s: print(f"{PROG}: {s}", file=sys.stderr, flush=True)  # noqa: E731
    figures.require("matplotlib")
    if a.jobs < 1:
        raise Failure("-j must be >= 1")
    if a.replot:
        p = os.path.join(a.out, "tradeoffs.json")
        if not os.path.exists(p):
            raise Failure(f"no {p} to replot (run without --replot first)")
        rows = json.load(open(p))
        import matplotlib  # noqa: F401
        tmp = os.path.join(a.out, f".tradeoffs.png.tmp.{os.getpid()}")
        md = open(os.path.join(a.out, "tradeoffs.md")).read() if os.path.exists(os.path.join(a.out, "tradeoffs.md")) else ""
        m = re.search(r"Command: `([^`]*)`", md)
        w = re.search(r"Machine: (.*?); date: (\d{4}-\d{2}-\d{2})", md)
        if m and w:  # the data's provenance: the report's command, machine and date, then when it was redrawn
            footer = (f"{m.group(1)} | {w.group(1)} | {w.group(2)}; redrawn {datetime.date.today().isoformat()} "
                      "by scripts/cost_report.py --replot")
        else:
            footer = figures.footer(m.group(1) if m else "scripts/cost_report.py")
        plot(rows, tmp, footer)
        if md:  # the sections read from other reports (docs/timing.json, docs/lighting_cost.json) are refreshed too
            refreshed = refresh_sections(md, rows)
            mtmp = os.path.join(a.out, f".tradeoffs.md.tmp.{os.getpid()}")
            with open(mtmp, "w") as f:
                f.write(refreshed)
            os.replace(mtmp, os.path.join(a.out, "tradeoffs.md"))
        os.replace(tmp, os.path.join(a.out, "tradeoffs.png"))
        return 0
    cfgs = json.load(open(os.path.join(ROOT, "config", "configs.json")))
    only = [s for s in a.only.split(",") if s]
    cnames = [s for s in a.configs.split(",") if s]
    metrics = [s for s in a.metrics.split(",") if s]
    for name, given, known in (("variant", only, [v["name"] for v in cfgs["variants"]]),
                               ("config", cnames, [c["name"] for c in cfgs["configs"]]), ("metric", metrics, METRICS)):
        bad = [g for g in given if g not in known]
        if bad:
            raise Failure(f"unknown {name} '{bad[0]}' (known: {', '.join(known)})")
    variants = [v for v in cfgs["variants"] if not only or v["name"] in only]
    configs = [c for c in cfgs["configs"] if not cnames or c["name"] in cnames]
    missing = [v["name"] for v in variants if not v.get("contract")]
    if missing:
        raise Failure(f"variant '{missing[0]}' has no \"contract\" in config/configs.json")
    check_out_dir(a.out)
    ctx = Ctx()
    ctx.n, ctx.cosim_count, ctx.sweep_threads, ctx.jobs = a.n, a.cosim_count, a.sweep_threads, a.jobs
    ctx.n_for = {}
    try:
        parse_n_range(a.n)
        for item in a.n_for:
            name, sep, rng = item.partition("=")
            if not sep:
                raise ValueError(f"malformed --n-for '{item}' (expected CONFIG=LO..HI)")
            parse_n_range(rng)
            ctx.n_for[name] = rng
    except ValueError as e:
        raise Failure(str(e))
    ctx.cli = os.path.join(a.build, "cli", "shadecore")
    if any(m in SIM_METRICS for m in metrics):
        if not os.access(ctx.cli, os.X_OK):
            raise Failure(f"{ctx.cli} is not an executable (build first: scripts/build.sh)")
        ctx.cli_hash = sha_files([ctx.cli])
        ctx.sim_hash = {c["name"]: sha_files([p]) for c in configs
                        for p in [os.path.join(a.build, "sim", f"shadecore_cosim_{c['name']}")] if os.path.exists(p)}
    else:
        ctx.cli_hash, ctx.sim_hash = "", {}
    need = {"generic": ["yosys"], "ecp5": ["yosys"], "xc7": ["yosys"], "hx8k": ["yosys", "nextpnr-ice40", "icetime"],
            "up5k": ["yosys", "nextpnr-ice40", "icetime"]}
    for m in metrics:
        for tool in need.get(m, []):
            if not shutil.which(tool):
                raise Failure(f"{tool} is not installed (scripts/setup.sh nextpnr-ice40 fpga-icestorm "
                              "fpga-icestorm-chipdb yosys)")
    if not shutil.which("yosys"):
        raise Failure("yosys is not installed (scripts/setup.sh)")
    ctx.tools = tool_versions()
    ctx.cache = Cache(a.cache or os.path.join(a.out, "tradeoffs.cache.json"))
    pairs = [(v, c) for v in variants for c in configs]
    t0 = time.time()
    ctx.designs = designs(ctx, pairs, log)
    jobs, cached = [], {}
    for v, c in pairs:
        for m in metrics:
            key, prefix = job_key(ctx, v, c, m, ctx.designs[(v["name"], c["name"])])
            e = ctx.cache.get(key)
            if e is not None:
                cached[key] = e["result"]
            else:
                jobs.append((v, c, m, key, prefix))
    log(f"{len(pairs)} rows x {len(metrics)} metrics: {len(cached)} cached, {len(jobs)} to run")
    if a.dry_run:
        for v, c, m, key, _ in jobs:
            print(f"run    {v['name']}/{c['name']} {m}")
        for k in cached:
            print(f"cached {k.split('|')[0]}/{k.split('|')[1]} {k.split('|')[2]}")
        return 0
    results = dict(cached)
    if not a.cached_only:
        results.update(run_jobs(ctx, jobs, log))
    # Rows: every variant x config of configs.json with whatever the cache holds (the report always lists all
    # rows; --only/--configs choose what is computed).
    rows, failed, seconds, loads = [], 0, {}, []
    for v in cfgs["variants"]:
        for c in cfgs["configs"]:
            r = {"variant": v["name"], "config": c["name"], "frac": c["frac"], "guard": c["guard"],
                 "contract": v.get("contract")}
            d = ctx.designs.get((v["name"], c["name"]))
            if d is None:
                try:
                    d = designs(ctx, [(v, c)], log)[(v["name"], c["name"])]
                except Failure as e:
                    r["elaborate_error"] = str(e)
            for m in METRICS:
                if d is None or (m in SIM_METRICS and not ctx.cli_hash):
                    r[f"{m}_error"] = "not run"
                    continue
                key, _ = job_key(ctx, v, c, m, d)
                res = results.get(key)
                if res is None:
                    e = ctx.cache.get(key)
                    res = e["result"] if e else None
                if isinstance(res, Failure):
                    r[f"{m}_error"] = str(res)
                    failed += 1
                elif res is None:
                    r[f"{m}_error"] = "not run"
                else:
                    r.update(res)
                    e = ctx.cache.get(key)
                    if e:
                        seconds[m] = seconds.get(m, 0) + e.get("seconds", 0)
                        if "load" in e:
                            loads.append(e["load"])
            r["total_abs_max"] = err_abs(r)
            rows.append(r)
    cmd = "scripts/cost_report.py " + " ".join(sys.argv[1:])
    write_report(rows, cmd, a.out, a.baseline, seconds, loads)
    log(f"wrote {a.out}/tradeoffs.md, .json, .png in {fmt_s(time.time() - t0)}")
    if a.cached_only and jobs:
        log(f"{len(jobs)} results were not in the cache (shown as not run)")
    if failed:
        raise Failure(f"{failed} step(s) failed (listed in {a.out}/tradeoffs.md)")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Failure as e:
        sys.exit(f"{PROG}: error: {e}")
    except KeyboardInterrupt:
        sys.exit(f"{PROG}: interrupted (finished results are in the cache)")
