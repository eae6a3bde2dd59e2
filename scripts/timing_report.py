#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Timing and energy sign-off report: every unit and lighting set in OSU 0.18 um (docs/timing.md, .json, .png).

Per row (a unit of config/configs.json "variants" at a width, or a lighting feature set of "feature_sets"):
  1. `shadecore handoff --signoff on` writes the row's bundle (RTL, vectors from the C model, the self-checking
     bench; --synth skip --no-ice40) and signs it off:
  2. signoff/signoff.py (run by the handoff, inside the bundle) maps it to the OSU 0.18 um cells (Dadda/Kogge-Stone multipliers), times it with
     OpenSTA (WNS/TNS at the target, Fmax by bisection, critical path), runs the bench on the netlist
     (gate-level, Icarus) and takes the energy per result from the netlist's own activity.
The table units have no handoff bundle (the plain-Verilog bench cannot load the table RAM): their rows are
synthesised and timed from the RTL (sc_specular with VARIANT set) without a gate-level run, and say so.
Rows are cached in OUT/timing.cache.json by the SHA-256 of what decides them (the row's own RTL files — a unit's,
or all of rtl/ for a lighting set —, config/configs.json, signoff/signoff.py and fastmul.py, handoff/, the sources
that write a bundle, the target, the vector count; a table row, which has no bundle, only its RTL, configs.json,
the flow and the target): a rerun computes only what changed. Each measured row also
gets signoff/stages.py's analysis (what closing the target would take); --add-stages adds it to cached rows.
A row also records what of its bundle decided it (rtl/, tb/, vectors/, the I/O constraints: inputs_sha) and the
flow's hash; --revalidate rewrites the bundle of a row whose key changed and keeps the row when that bundle is
the one it was measured on (a source that does not change bundles, a new field in configs.json). --from-bundle
takes a row from a bundle signed off outside the report (an interrupted run resumed step by step), on the same
condition; with --equiv-from REV also a bundle written from REV's RTL, and with --equiv one written from its own
(an edit after the run started), which signoff/equiv.py proves equivalent to the RTL these sources write (recorded
as carried).
Long (hours from an empty cache on 2 cores; a lighting set with 8 lights takes the longest); run by hand.
"""
import argparse
import datetime
import fcntl
import glob
import hashlib
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figures  # noqa: E402  scripts/figures.py: machine line, footer

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIGNOFF = os.path.join(ROOT, "signoff", "signoff.py")
FIELDS = ["name", "kind", "width", "contract", "latency_cycles", "period_ns", "wns_ns", "fmax_mhz",
          "fo4_per_cycle", "area_um2", "cells", "energy_pj_per_result", "gate_sim_vectors",
          "gate_sim_mismatches", "critical_path"]


# What decides a row's numbers (with the target and the vector count): the cache key. The shadecore binary enters
# through the sources that write a bundle (the C model, the stimulus, the handoff command and its templates), not
# through its own bytes: a rebuild for an unrelated change (the renderer, the replay, coverage) keeps the cache. A binary older
# than one of those sources is refused (rebuild first), so the key never describes sources the binary lacks.
# The RTL enters per row (rtl_of): a unit's row takes its own files, so work on the lighting core keeps the units' rows.
DECIDING = ["config/configs.json", "signoff/signoff.py", "signoff/fastmul.py", "handoff"]
# A table unit's row has no bundle (synthesis and STA of its RTL only): neither handoff/ nor the binary decide it.
TABLE_DECIDING = ["config/configs.json", "signoff/signoff.py", "signoff/fastmul.py"]
LEGACY_DECIDING = ["rtl/*.v", "rtl/*.vh"] + DECIDING  # the key until 2026-12-06 (rows upgraded when it still matches)
BINARY_SOURCES = ["cmodel/include/shadecore/*.hpp", "cmodel/include/shadecore/units", "cmodel/include/shadecore/analysis",
                  "cmodel/src/units", "cmodel/src/analysis", "stimulus", "common", "cli/handoff_*",
                  "cli/cmd_handoff.cpp", "cli/unit_spec.hpp", "cli/output.*", "cli/text_template.*", "cli/templates"]


class Failure(Exception):
    pass


def files_of(paths):
    for base in paths:
        full = os.path.join(ROOT, base)
        yield from sorted(glob.glob(full)) if "*" in base else [full] if os.path.isfile(full) else sorted(
            os.path.join(d, f) for d, _, fs in os.walk(full) for f in fs if not f.endswith(".pyc"))


def sha_tree(paths):
    h = hashlib.sha256()
    for p in files_of(paths):
        h.update(os.path.relpath(p, ROOT).encode())
        h.update(hashlib.sha256(open(p, "rb").read()).digest())
    return h.hexdigest()


def rtl_of(cfg, r):
    """The RTL files a row's bundle is made of (config/configs.json "rtl", the one list): a unit's sc_specular
    files, includes, energy files and its variant's files; a lighting set, every file of rtl/."""
    if r["kind"] != "unit":
        return ["rtl/*.v", "rtl/*.vh"]
    top = cfg["rtl"]["sc_specular"]
    names = top["files"] + top["includes"] + top.get("energy", []) + r["variant"]["rtl"]
    return [os.path.join("rtl", n) for n in sorted(set(names))]


def rows_of(cfg, only, configs):
    rows = []
    for v in cfg["variants"]:
        for c in cfg["configs"]:
            if c["name"] in configs:
                rows.append({"name": v["name"], "kind": "unit", "config": c, "contract": v["contract"],
                             "variant": v, "table": "entries" in v, "mreg": 0})
                if v.get("mreg_stages"):  # the pipelining parameter MREG (rtl/sc_mul_reg.v): a row with it on
                    rows.append({"name": v["name"] + "+mreg", "kind": "unit", "config": c, "contract": v["contract"],
                                 "variant": v, "table": False, "mreg": 1})
    for s in cfg["feature_sets"]:
        rows.append({"name": s["name"], "kind": "lighting", "config": {"name": s.get("config", "default")},
                     "contract": "lighting", "set": s, "table": False, "mreg": 0})
        if s.get("share", 1) == 1:  # the lighting core's pipelining parameter (feature-set key mreg, handoff --mreg)
            rows.append({"name": s["name"] + "+mreg", "kind": "lighting", "config": {"name": s.get("config", "default")},
                         "contract": "lighting", "set": s, "table": False, "mreg": 1})
    if only:
        known = {r["name"] for r in rows}
        bad = [o for o in only if o not in known]
        if bad:
            raise Failure(f"unknown row(s) {', '.join(bad)} (units: variants of config/configs.json, or feature sets)")
        rows = sorted((r for r in rows if r["name"] in only), key=lambda r: only.index(r["name"]))  # in --only's order
    return rows


def row_id(r):
    return f"{r['kind']}:{r['name']}:{r['config']['name']}"  # name carries +mreg


def bundle(a, r, d, signoff="on"):
    """Write the handoff bundle of a row into d (or, for a table unit, a synthesis-only directory); signoff="off"
    writes it without signing it off (what decides the sign-off, for inputs_sha)."""
    if r["table"]:
        os.makedirs(d)
        gen = os.path.join(a.build, "generated", "rtl")
        files = json.load(open(os.path.join(ROOT, "config", "configs.json")))["rtl"]["sc_specular"]["files"]
        files = files + r["variant"]["rtl"]
        with open(os.path.join(d, "filelist.f"), "w") as f:
            f.write(f"+incdir+{os.path.join(ROOT, 'rtl')}\n+incdir+{gen}\n")
            f.write("".join(os.path.join(ROOT, "rtl", x) + "\n" for x in dict.fromkeys(files)))
        return {"top": "sc_specular", "chparam": {"VARIANT": r["variant"]["id"], "FRAC": r["config"]["frac"],
                                                  "GUARD": r["config"]["guard"]}}
    # The handoff signs its own bundle off (--signoff on: the same signoff/signoff.py), so the report's numbers are
    # the bundle's: its constraints.sdc, reports and signoff.json.
    cmd = [a.shadecore, "handoff", "--out", d, "--no-ice40", "--synth", "skip", "--signoff", signoff,
           "--clock-target", str(a.target), "--seed", "1", "--count", str(count_of(a, r))]
    if r["kind"] == "unit":
        cmd += ["--variant", r["variant"]["name"], "--config", r["config"]["name"]]
        if r.get("mreg"):
            cmd += ["--mreg", str(r["mreg"])]
    else:
        cmd += ["--core", "lighting", "--features", r["set"]["name"]]
        if r.get("mreg"):
            cmd += ["--mreg", str(r["mreg"])]
    if signoff == "off":  # the bundle's files only (inputs_sha): its benches ran when the row was measured
        cmd.append("--no-sim")
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=a.timeout)
    if p.returncode:
        raise Failure(f"{' '.join(cmd)} failed: {(p.stderr or p.stdout).strip().splitlines()[-1:]}")
    return {}


def count_of(a, r):
    return a.count if r["kind"] == "unit" else a.light_count


def from_bundle(a, r, d):
    """A row from a bundle already signed off (a kept or resumed run: `signoff.py BUNDLE --steps gatesim,power` after
    an interrupted one). Taken only when a bundle written now from these sources is that bundle (inputs_sha), its
    sign-off ran this flow (signoff.py and fastmul.py byte for byte) at this target, and every step has a result."""
    jp = os.path.join(d, "signoff", "signoff.json")
    if r["table"] or not os.path.isfile(jp):
        raise Failure(f"--from-bundle: {jp} does not exist (a signed-off handoff bundle is needed)")
    s = json.load(open(jp))
    for step in ("synth", "sta", "gatesim", "power"):
        if not s.get(step):
            raise Failure(f"--from-bundle: {d} has no {step} result (signoff/signoff.py {d} --steps {step} first)")
    if not s["gatesim"].get("passed"):
        raise Failure(f"--from-bundle: {d}: its gate-level simulation failed; a failed row is measured, not taken")
    if s["target_ns"] != a.target:
        raise Failure(f"--from-bundle: {d} was signed off at {s['target_ns']} ns, not --target {a.target}")
    for f in FLOW:
        own = os.path.join(d, "signoff", os.path.basename(f))
        if not (os.path.isfile(own) and open(own, "rb").read() == open(os.path.join(ROOT, f), "rb").read()):
            raise Failure(f"--from-bundle: {d} was signed off by another {f} than this checkout's")
    now, carry = None, None
    with tempfile.TemporaryDirectory(prefix="shadecore_revalidate.") as tmp:
        fresh = os.path.join(tmp, "b")
        bundle(a, r, fresh, signoff="off")
        now = inputs_of(a, r, fresh)
        if inputs_sha(d) != now["bundle"] and getattr(a, "equiv_from", None):
            # written by the sources of REV for rtl/: carried as --revalidate --equiv-from carries a cached row
            now, carry = equiv_carry(a, fresh, inputs_sha(d), tmp)
            if now is None:
                raise Failure(f"--from-bundle --equiv-from {a.equiv_from}: {d}: {carry}")
        elif inputs_sha(d) != now["bundle"] and getattr(a, "equiv", False):
            # its own rtl/ is what was mapped (a run started before an edit that was never committed as such)
            now, carry = equiv_carry(a, fresh, inputs_sha(d), tmp, rtl_from=os.path.join(d, "rtl"))
            if now is None:
                raise Failure(f"--from-bundle --equiv: {d}: {carry}")
    if inputs_sha(d) != now["bundle"] and carry is None:
        raise Failure(f"--from-bundle: {d} is not the bundle these sources write for {row_id(r)} "
                      "(rtl/, tb/, vectors/ or the I/O constraints differ): measure the row instead, or name the "
                      "revision whose RTL it was written from (--equiv-from REV)")
    if carry is not None:
        s["carried"] = [carry]
    tbc = os.path.join(d, "tb", "tb_config.vh")
    m = re.search(r"localparam integer LATENCY\s*=\s*(\d+)", open(tbc).read()) if os.path.exists(tbc) else None
    s["latency_cycles"] = int(m.group(1)) if m else None
    s["seconds"] = None  # the interrupted run's time is not known
    s["log"] = f"taken from the signed-off bundle {d} (--from-bundle)"
    s["stages"] = stages_of(d, r)
    s["inputs"] = now
    return s


def measure(a, r):
    with tempfile.TemporaryDirectory(prefix="shadecore_timing.") as tmp:
        d = os.path.join(tmp, "b")
        t_start = time.time()
        extra = bundle(a, r, d)
        log = ""
        if extra:
            cmd = ["/usr/bin/python3", SIGNOFF, d, "--target", str(a.target), "--timeout", str(a.timeout),
                   "--top", extra["top"], "--steps", "synth,sta"]
            cmd += [x for k, v in extra["chparam"].items() for x in ("--chparam", f"{k}={v}")]
            p = subprocess.run(cmd, capture_output=True, text=True)
            if p.returncode:
                raise Failure(f"signoff of {row_id(r)} failed: {(p.stderr or p.stdout).strip().splitlines()[-1:]}")
            log = p.stdout
        s = json.load(open(os.path.join(d, "signoff", "signoff.json")))
        s["seconds"] = round(time.time() - t_start, 1)
        s["log"] = log
        lat = None
        tbc = os.path.join(d, "tb", "tb_config.vh")
        if os.path.exists(tbc):
            m = re.search(r"localparam integer LATENCY\s*=\s*(\d+)", open(tbc).read())
            lat = int(m.group(1)) if m else None
        elif r["table"]:
            lat = None
        s["latency_cycles"] = lat
        s["stages"] = stages_of(d, r)
        s["inputs"] = None if r["table"] else inputs_of(a, r, d)
        if a.keep:  # the signed-off bundle, for a reader who wants its netlist and reports (a handoff bundle as is)
            dest = os.path.join(a.keep, row_id(r).replace(":", "_"))
            if os.path.lexists(dest):
                raise Failure(f"--keep: {dest} exists (choose an empty directory)")
            os.makedirs(a.keep, exist_ok=True)
            shutil.copytree(d, dest, symlinks=True)
        return s


STAGES = os.path.join(ROOT, "signoff", "stages.py")


def stages_of(d, r):
    """signoff/stages.py on a signed-off bundle: the registers that miss the target and the pieces each needs
    (summary kept in the cache; None for a table unit, which has no bundle)."""
    if r["table"] or not os.path.isfile(os.path.join(d, "signoff", "netlist.v")):
        return None
    p = subprocess.run(["/usr/bin/python3", STAGES, d, "--show", "0"], capture_output=True, text=True)
    if p.returncode:
        raise Failure(f"stages.py on {row_id(r)} failed: {(p.stderr or p.stdout).strip().splitlines()[-1:]}")
    j = json.load(open(os.path.join(d, "signoff", "stages.json")))
    keep = ["endpoints", "missing_endpoints", "registers", "missing_registers", "max_pieces", "extra_flops_estimate",
            "pieces_histogram"]
    out = {k: j[k] for k in keep}
    out["worst_instances"] = [{k: i[k] for k in ("instance", "registers", "missing_bits", "worst_slack_ns", "max_pieces")}
                              for i in j["by_instance"][:6]]
    return out


def add_stages(a, r, hit):
    """A cached row without the stage analysis: the bundle again (handoff --signoff off), synthesis and STA only
    (the same ABC script the handoff chooses), the WNS checked against the cached one, then stages.py."""
    with tempfile.TemporaryDirectory(prefix="shadecore_stages.") as tmp:
        d = os.path.join(tmp, "b")
        bundle(a, r, d, signoff="off")
        p = subprocess.run(["/usr/bin/python3", SIGNOFF, d, "--target", str(a.target), "--timeout", str(a.timeout),
                            "--steps", "synth,sta", "--abc",
                            ("keep" if r.get("mreg") else "lean") if r["kind"] == "lighting"
                            else r["variant"].get("signoff_abc", "full")],
                           capture_output=True, text=True)
        if p.returncode:
            raise Failure(f"signoff of {row_id(r)} failed: {(p.stderr or p.stdout).strip().splitlines()[-1:]}")
        again = json.load(open(os.path.join(d, "signoff", "signoff.json")))["sta"]["wns_ns"]
        if abs(again - hit["signoff"]["sta"]["wns_ns"]) > 0.0005:
            raise Failure(f"{row_id(r)}: synthesis again gives WNS {again}, the cache has "
                          f"{hit['signoff']['sta']['wns_ns']}: the flow is not reproducible, rerun the row")
        return stages_of(d, r)


FLOW = ["signoff/signoff.py", "signoff/fastmul.py"]


def inputs_sha(d):
    """What of a bundle decides its sign-off: rtl/, tb/, vectors/, filelist.f and the SDC's I/O assumptions (its
    period is the sign-off's own output), without the files' "made by" comment lines (the command that wrote the
    bundle: its path and options such as --signoff)."""
    h = hashlib.sha256()
    for sub in ("rtl", "tb", "vectors", "filelist.f"):
        p = os.path.join(d, sub)
        files = [p] if os.path.isfile(p) else sorted(os.path.join(x, f) for x, _, fs in os.walk(p) for f in fs)
        for f in files:
            h.update(os.path.relpath(f, d).encode())
            h.update(hashlib.sha256(re.sub(rb"(?im)^.*made by.*$", b"", open(f, "rb").read())).digest())
    sdc = os.path.join(d, "constraints.sdc")
    if os.path.exists(sdc):
        h.update("".join(x for x in open(sdc) if re.match(r"\s*(set IO_FRACTION|set_input_delay|set_output_delay)", x))
                 .encode())
    return h.hexdigest()


def inputs_of(a, r, d):
    return {"bundle": inputs_sha(d), "flow": sha_tree(FLOW), "target": a.target}


def revalidate(a, r, hit):
    """A row whose key no longer matches (a source of the binary, config/configs.json, the RTL changed): the bundle
    again without the sign-off; if it is the one the row was measured on (inputs_sha) under the same flow and
    target, the row still holds. Returns (the entry's "inputs", None) when it does.
    With --equiv-from REV, a bundle whose rtl/ changed is carried when (1) the bundle written now, with each of its
    rtl/ files that git has at REV replaced by that version, is byte for byte the bundle the row was measured on
    (inputs_sha: so tb/, vectors/ and the I/O constraints did not change, and REV's RTL is what was mapped), and
    (2) signoff/equiv.py proves that RTL and the current one equivalent for this configuration. Returns (inputs,
    the carry record) then; (None, why not) otherwise."""
    if r["table"] or not hit["signoff"].get("inputs"):
        return None, "no recorded inputs"
    rec = hit["signoff"]["inputs"]
    with tempfile.TemporaryDirectory(prefix="shadecore_revalidate.") as tmp:
        d = os.path.join(tmp, "b")
        bundle(a, r, d, signoff="off")
        now = inputs_of(a, r, d)
        if now == rec:
            return now, None
        if not a.equiv_from:
            return None, "its bundle changed"
        if now["flow"] != rec["flow"] or now["target"] != rec["target"]:
            return None, "the flow or the target changed"
        return equiv_carry(a, d, rec["bundle"], tmp)


def equiv_carry(a, d, measured, tmp, rtl_from=None):
    """--equiv-from REV: the bundle d written now from these sources, with each of its rtl/ files that git has at REV
    replaced by that version, must hash to `measured` (the bundle a row was measured on), and signoff/equiv.py must
    prove REV's RTL and the current one equivalent for this configuration. Returns (inputs of d, the carry record),
    or (None, why not). With rtl_from (--from-bundle --equiv: the signed-off bundle's own rtl/), that directory's
    files take the place of REV's: the rest of the bundle must be the one written now."""
    now = inputs_of(a, None, d)
    old = os.path.join(tmp, "at_rev")
    shutil.copytree(d, old, symlinks=True)
    if rtl_from:
        rev = None
        shutil.rmtree(os.path.join(old, "rtl"))
        shutil.copytree(rtl_from, os.path.join(old, "rtl"), symlinks=True)
        what = "its own RTL"
    else:
        rev = git("rev-parse", "--verify", a.equiv_from + "^{commit}").strip()
        for f in sorted(os.listdir(os.path.join(old, "rtl"))):
            if git_has(rev, f"rtl/{f}"):
                with open(os.path.join(old, "rtl", f), "w") as out:
                    out.write(git("show", f"{rev}:rtl/{f}"))
        what = f"the RTL of {rev[:10]}"
    if inputs_sha(old) != measured:
        return None, f"the bundle with {what} is not the one measured (another revision, or tb/, " \
                     "vectors/ or the I/O constraints changed too)"
    jp = os.path.join(tmp, "equiv.json")
    p = subprocess.run(["/usr/bin/python3", EQUIV, old, d, "--json", jp, "--timeout", str(a.timeout)],
                       capture_output=True, text=True)
    if not os.path.exists(jp):
        return None, (p.stderr or p.stdout).strip().splitlines()[-1] if (p.stderr or p.stdout).strip() else "equiv.py failed"
    with open(jp) as fj:
        e = json.load(fj)
    if not e["proven"]:
        whose = f"{rev[:10]}'s" if rev else "the bundle's"
        return None, f"its RTL is not proven equivalent to {whose} ({e['unproven']} of {e['equiv_cells']} unproven)"
    carry = {"from_rev": rev or "bundle", "measured_bundle": measured, "equiv_cells": e["equiv_cells"],
             "seconds": e["seconds"], "tool": e["yosys"], "date": datetime.date.today().isoformat()}
    return now, carry


def git(*args):
    p = subprocess.run(["git", "-C", ROOT] + list(args), capture_output=True, text=True)
    if p.returncode:
        raise Failure(f"git {' '.join(args)}: {p.stderr.strip()}")
    return p.stdout


def git_has(rev, path):
    return subprocess.run(["git", "-C", ROOT, "cat-file", "-e", f"{rev}:{path}"], capture_output=True).returncode == 0


EQUIV = os.path.join(ROOT, "signoff", "equiv.py")


def backfill_inputs(a, r):
    """The inputs of a row cached under the current key (so made from these very sources): its bundle again."""
    with tempfile.TemporaryDirectory(prefix="shadecore_revalidate.") as tmp:
        d = os.path.join(tmp, "b")
        bundle(a, r, d, signoff="off")
        return inputs_of(a, r, d)


def to_row(r, s):
    st, sy = s["sta"], s["synth"]
    gs, pw = s.get("gatesim"), s.get("power")
    cp = st["critical_path"]
    c = r["config"]
    width = f"{c['name']} (F={c['frac']}, G={c['guard']})" if "frac" in c else c["name"]
    out = {"name": r["name"], "kind": r["kind"], "width": width, "contract": r["contract"],
           "latency_cycles": s.get("latency_cycles"), "period_ns": st["period_ns"], "wns_ns": st["wns_ns"],
           "tns_ns": st["tns_ns"], "met": st["met"], "fmax_mhz": st["fmax_mhz"],
           "fo4_per_cycle": st.get("fo4_per_cycle"), "area_um2": round(sy["area_um2"]), "cells": sy["cells"],
           "flops": sy["flops"],
           "energy_pj_per_result": pw["energy_pj_per_result"] if pw else None,
           "power_mw": pw["power_mw"] if pw else None,
           "results_per_clock": round(pw["results"] / pw["cycles"], 4) if pw else None,
           "gate_sim_vectors": gs["vectors"] if gs else None,
           "gate_sim_mismatches": gs["mismatches"] if gs else None,
           # the simulator of the gate-level run (signoff.py --gatesim): icarus unless the row says otherwise
           "gate_sim_simulator": gs.get("simulator", "icarus") if gs else None,
           "critical_path": f"{cp['start_reg']} -> {cp['end_reg']} ({cp['levels']} cells, "
                            f"{cp['arrival_ns']} ns derated)",
           "seconds": s["seconds"]}
    if s.get("carried"):
        out["carried"] = s["carried"]
    if out["latency_cycles"] is not None:
        out["latency_ns"] = round(out["latency_cycles"] * out["period_ns"], 2)
    rpc = out["results_per_clock"] if out["results_per_clock"] else 1.0
    out["results_per_s"] = round(rpc * 1e9 / out["period_ns"])
    out["ns_um2"] = round(out["period_ns"] * out["area_um2"])
    if not out["met"]:
        out["reason"] = (f"misses {s['target_ns']} ns by {-out['wns_ns']:.3f} ns: the worst stage is "
                         f"{cp['start_reg']} -> {cp['end_reg']} ({cp['levels']} cells); closing it takes that stage "
                         f"cut into {math.ceil(st['fmax_period_ns'] / s['target_ns'] - 1e-9)} (Fmax period "
                         f"{st['fmax_period_ns']} ns / {s['target_ns']} ns), and every other stage that misses likewise")
        sg = s.get("stages")
        if sg:
            hist = ", ".join(f"{n} into {k}" for k, n in sorted(sg["pieces_histogram"].items(), key=lambda x: int(x[0])))
            worst = "; ".join(f"{i['instance']} {i['registers']} ({i['worst_slack_ns']:+.2f} ns, {i['max_pieces']} pieces)"
                              for i in sg["worst_instances"][:3])
            out["reason"] += (f". signoff/stages.py: {sg['missing_registers']} of {sg['registers']} registers "
                              f"({sg['missing_endpoints']:,} of {sg['endpoints']:,} endpoints) miss; their cones cut "
                              f"{hist} at least, about {sg['extra_flops_estimate']:,} flip-flops more (to "
                              f"{out['flops'] + sg['extra_flops_estimate']:,}); the worst instances: {worst}")
            out["stages"] = sg
        if r["kind"] == "lighting":
            cfg = json.load(open(os.path.join(ROOT, "config", "configs.json")))
            lat = cfg["light"]["latency"]
            out["reason"] += ("; the lighting core's pipelining parameter MREG (row <set>+mreg) registers the "
                              f"normalisers' products ({lat['normalize']} -> {lat['normalize'] + lat['mreg_normalize']} "
                              f"cycles), each dot product ({lat['mreg_dot']} more), each product stage of the back "
                              f"({lat['mreg_back']} more), the lanes' N before the dot products ({lat['mreg_n']} more) "
                              f"and P before the L and V normalisers ({lat['mreg_p']} more), the attenuation's q = kc + "
                              f"kl·d + kq·d² ({lat['mreg_att']} more) and the reciprocal sc_recip's products "
                              f"({lat['mreg_recip']} more), each stage of the spot and low-shininess power chains "
                              f"sc_powi ({lat['mreg_powi']} more each), and passes MREG to the units and the energy "
                              "stage, at every share")
    if gs is None:
        out["reason_gate_sim"] = ("no gate-level run: the handoff bench cannot load a table RAM"
                                  if r["table"] else "not run")
    return out


def closes_with_mreg(rows):
    """A row (a unit or a lighting set) that misses the target but whose pipelining-parameter row (<name>+mreg, the
    same width) meets it: its reason leads with that design point (the same outputs, more cycles), and "closes_with"
    names it. A row whose +mreg row misses too leads with how far the parameter gets it."""
    by = {(r["name"], r["width"]): r for r in rows}
    for r in rows:
        m = by.get((r["name"] + "+mreg", r["width"]))
        if not r["met"] and m and not m["met"]:
            # (a lighting set) the parameter brings it closer but not to the target: say how far, then why not
            r["reason"] = (f"with the pipelining parameter MREG = 1 (row {m['name']}, the same outputs) it closes at "
                           f"{m['period_ns']} ns instead of {r['period_ns']}, at {m['latency_cycles']} cycles instead of "
                           f"{r['latency_cycles']} and {m['flops']:,} flip-flops instead of {r['flops']:,}; that row's "
                           f"reason says what is left. Without it, it " + r["reason"])
            continue
        if r["met"] or not m or not m["met"]:
            continue
        r["closes_with"] = m["name"]
        r["reason"] = (f"closes with the pipelining parameter MREG = 1: row {m['name']} (the same outputs) meets "
                       f"{m['period_ns']} ns with WNS {m['wns_ns']:+.3f} ns, at {m['latency_cycles']} cycles instead of "
                       f"{r['latency_cycles']} and {m['flops']:,} flip-flops instead of {r['flops']:,}. Without it, it "
                       + r["reason"])


def write_md(path, rows, meta, missing=()):
    L = ["<!-- generated by scripts/timing_report.py, do not edit -->", "# Timing and energy sign-off (OSU 0.18 µm)", ""]
    L += [f"Generated by `{meta['command']}` on {meta['machine']}, {meta['date']}. Library: {meta['library']}; "
          f"{meta['tools']['yosys']}, {meta['tools']['opensta']}, {meta['tools']['iverilog']}.", "",
          f"Target: **{meta['target_ns']} ns** (250 MHz at 4.0 ns; the library's FO4 is {meta['fo4_ns']} ns, so the target is "
          f"{meta['target_ns'] / meta['fo4_ns']:.0f} FO4), typical corner, pre-layout, cell delays derated "
          f"×{meta['derate_late']} for wires; inputs arrive and outputs leave {meta['io_fraction']:.0%} of the period "
          f"from the edge, driven by {meta['drive_cell']} and loading four of its inputs. "
          "What these numbers mean and how they were made: docs/signoff.md.", "",
          "| row | width | contract | latency (cycles / ns) | closes at (ns) | WNS at target (ns) | Fmax (MHz) | FO4/cycle "
          "| area (µm²) | cells | flip-flops | energy (pJ/result) | results/s | gate-level sim | critical path |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lat = f"{r['latency_cycles']} / {r['latency_ns']}" if r.get("latency_cycles") is not None else "—"
        gs = figures.gate_sim_text(r, r.get("reason_gate_sim", "—"))
        e = f"{r['energy_pj_per_result']:.1f}" if r.get("energy_pj_per_result") is not None else "—"
        wns = f"{r['wns_ns']:+.3f}" + ("" if r["met"] else " ✗")
        L.append(f"| {r['name']} ({r['kind']}) | {r['width']} | {r['contract']} | {lat} | {r['period_ns']} | {wns} | "
                 f"{r['fmax_mhz']} | {r['fo4_per_cycle']} | {r['area_um2']:,} | {r['cells']:,} | {r['flops']:,} | {e} | "
                 f"{r['results_per_s']:,} | {gs} | `{r['critical_path']}` |")
    miss = [r for r in rows if not r["met"]]
    closes = [r for r in miss if r.get("closes_with")]
    L += ["", f"{len(rows) - len(miss)} of {len(rows)} rows meet {meta['target_ns']} ns"
          + (f"; {len(closes)} more close with MREG = 1 (their +mreg row meets it)." if closes else ".")]
    if miss:
        L += ["", "Rows that miss the target, and what it would take:", ""]
        L += [f"- **{r['name']}**: {r['reason']}." for r in miss]
    carried = [r for r in rows if r.get("carried")]
    if carried:
        L += ["", "Carried by equivalence, not mapped again (`--revalidate --equiv-from REV`, or `--from-bundle DIR "
              "--equiv` for a bundle signed off from RTL edited since): these rows' numbers are "
              "those of the netlist mapped from the RTL of the revision named (or of the bundle), which signoff/equiv.py (Yosys "
              "equiv_make, equiv_struct -icells, equiv_simple, equiv_induct) proved equivalent, for the row's configuration, to "
              "the RTL the current sources write; the bundle is otherwise byte for byte the one measured (tb/, "
              "vectors/, I/O constraints). Mapping the current RTL again may differ in the last digits (the names "
              "Yosys and ABC see changed), not in function.", ""]
        L += [f"- **{r['name']}**: measured on "
              + ("the RTL of the bundle it was signed off in (an edit later)" if r["carried"][0]["from_rev"] == "bundle"
                 else f"the RTL of `{r['carried'][0]['from_rev'][:10]}`")
              + "; carried by proof: " + ", then ".join(
                  ("that RTL" if c["from_rev"] == "bundle" else f"`{c['from_rev'][:10]}`'s RTL")
                  + f" proven equivalent to the then-current one on {c['date']} "
                  f"({c['equiv_cells']:,} paired signals, {c['seconds']} s)" for c in r["carried"]) + "."
              for r in carried]
    if missing:
        L += ["", "Not measured in this report (no current cached result; docs/signoff.md says why): "
              + ", ".join(f"`{m}`" for m in missing) + "."]
    L += ["", "![error against energy and against period × area](timing.png)", ""]
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")


def plot(path, rows, footer):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    trade = {}
    tj = os.path.join(ROOT, "docs", "tradeoffs.json")
    if os.path.exists(tj):
        for t in json.load(open(tj)):
            trade[(t["variant"], t["config"])] = t
    pts = []
    for r in rows:
        if r["kind"] != "unit":
            continue
        cfg = r["width"].split(" ")[0]
        t = trade.get((r["name"].split("+")[0], cfg))  # "<unit>+mreg": the same outputs, so the unit's error
        if t is None or t.get("total_abs_max") is None:
            continue
        pts.append((r, t["total_abs_max"]))
    # one colour per row in both panels (the default cycle would give a row another colour in each)
    colour = {r["name"]: plt.get_cmap("tab10")(i % 10) for i, (r, _) in enumerate(pts)}
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6))
    for ax, key, label in ((axes[0], "energy_pj_per_result", "energy per result (pJ, gate-level activity)"),
                           (axes[1], "ns_um2", "period × area (ns·µm²)")):
        placed = sorted(((r.get(key), err, r) for r, err in pts if r.get(key) is not None), key=lambda p: p[0])
        for x, err, r in placed:
            ax.scatter([x], [err], s=36, marker="o" if r["met"] else "x", color=colour[r["name"]])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.autoscale_view()
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, hi * 3)  # headroom: every label goes above its point (below would leave the axes)
        fig.canvas.draw()
        # labels: the first slot (offset in points, right or left of the point, above or below it) whose box
        # stays inside the axes and clear of the boxes already placed; boxes estimated in pixels (8 pt text)
        scale = fig.dpi / 72.0
        box = ax.bbox
        taken = []
        for x, err, r in placed:
            px, py = ax.transData.transform((x, err))
            w, h = 5.0 * len(r["name"]) * scale, 11 * scale
            slots = [(dx, dy) for dy in list(range(6, 150, 12)) + list(range(-18, -150, -12)) for dx in (4, -4)]
            chosen = slots[0]
            for dx, dy in slots:
                x0 = px + dx * scale - (w if dx < 0 else 0)
                y0 = py + dy * scale
                if x0 < box.x0 or x0 + w > box.x1 or y0 < box.y0 or y0 + h > box.y1:
                    continue
                if all(x0 + w < qx0 or qx0 + qw < x0 or y0 + h < qy0 or qy0 + qh < y0 for qx0, qy0, qw, qh in taken):
                    chosen = (dx, dy)
                    taken.append((x0, y0, w, h))
                    break
            dx, dy = chosen
            ax.annotate(r["name"], (x, err), textcoords="offset points", xytext=(dx, dy), fontsize=8,
                        ha="right" if dx < 0 else "left",
                        arrowprops=None if abs(dy) < 15 else dict(arrowstyle="-", lw=0.5, color="0.4"))
        ax.set_xlabel(label)
        ax.set_ylabel("max |cos^n − unit| over n = 16..1024 (sweep)")
        ax.grid(True, alpha=0.3)
    axes[0].set_title("error against energy (o meets 4.0 ns, x misses)", fontsize=10)
    axes[1].set_title("error against period × area", fontsize=10)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    figures.save(fig, path, footer)


def store(path, rid, entry):
    """Adds one row to the cache file under a lock (other runs may be adding theirs), atomically."""
    d = os.path.dirname(os.path.abspath(path))
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "." + os.path.basename(path) + ".lock"), "w") as lk:
        fcntl.flock(lk, fcntl.LOCK_EX)
        data = json.load(open(path)) if os.path.exists(path) else {"entries": {}}
        data["entries"][rid] = entry
        fd, tmp = tempfile.mkstemp(prefix=".timing.cache.", dir=d)
        with os.fdopen(fd, "w") as f:
            json.dump(data, f, indent=1, sort_keys=True)
            f.write("\n")
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="build directory (default build/)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs"), help="output directory (default docs/)")
    ap.add_argument("--only", default="", help="comma list of rows (unit or feature-set names)")
    ap.add_argument("--configs", default="default", help="comma list of widths for the units (default: default)")
    ap.add_argument("--target", type=float, default=4.0, help="target clock period, ns (default 4.0)")
    ap.add_argument("--count", type=int, default=2000,
                    help="random vectors per unit bundle (default 2000: the pipeline's fill is ~0.4 %% of the power run)")
    ap.add_argument("--light-count", type=int, default=200, help="random fragments per lighting bundle (default 200)")
    ap.add_argument("--timeout", type=int, default=10800, help="seconds per tool run (default 10800)")
    ap.add_argument("--cache", default=None, help="cache file (default OUT/timing.cache.json)")
    ap.add_argument("--keep", default=None,
                    help="copy each measured row's signed-off bundle to KEEP/<kind>_<name>_<width> (not cached rows)")
    ap.add_argument("--add-stages", action="store_true",
                    help="for cached rows without it, add signoff/stages.py's analysis (synthesis and STA again, "
                         "checked to give the cached WNS); measured rows always get it")
    ap.add_argument("--revalidate", action="store_true",
                    help="rows whose key changed: write the bundle again (no sign-off) and keep the row when it is the "
                         "bundle it was measured on (rtl, tb, vectors, I/O constraints) under the same flow; cached "
                         "rows get that record if they lack it")
    ap.add_argument("--equiv-from", default=None, metavar="REV",
                    help="with --revalidate: carry a row whose bundle's RTL changed when the bundle with git REV's "
                         "rtl/ files is the one it was measured on and signoff/equiv.py proves the two RTLs "
                         "equivalent for the row's configuration (the row says so in the report); with "
                         "--from-bundle: take a bundle written from REV's RTL on the same condition")
    ap.add_argument("--equiv", action="store_true",
                    help="with --from-bundle: take a bundle signed off from RTL that differs from what these sources "
                         "write (an edit after the run started) when the rest of the bundle is the one written now and "
                         "signoff/equiv.py proves its rtl/ equivalent to the current (recorded as carried)")
    ap.add_argument("--from-bundle", default=None, metavar="DIR",
                    help="take the one --only row from DIR, a bundle signed off to the end (e.g. resumed with "
                         "signoff/signoff.py DIR --steps gatesim,power), when these sources write that very bundle")
    ap.add_argument("--dry-run", action="store_true", help="list the rows and whether each is cached")
    ap.add_argument("--cached-only", action="store_true",
                    help="write the report from the cached rows only; list the others as not measured")
    a = ap.parse_args()
    if a.equiv_from and not (a.revalidate or a.from_bundle):
        raise Failure("--equiv-from REV goes with --revalidate or --from-bundle")
    if a.equiv and not a.from_bundle:
        raise Failure("--equiv goes with --from-bundle")
    cfg = json.load(open(os.path.join(ROOT, "config", "configs.json")))
    a.shadecore = os.path.join(a.build, "cli", "shadecore")
    if not os.access(a.shadecore, os.X_OK):
        raise Failure(f"no shadecore binary at {a.shadecore}: build first (scripts/build.sh)")
    rows = rows_of(cfg, [o for o in a.only.split(",") if o], a.configs.split(","))
    if a.from_bundle and (len(rows) != 1 or a.cached_only or a.dry_run):
        raise Failure("--from-bundle takes one row (--only NAME) and measures, so not with --cached-only or --dry-run")
    cache_path = a.cache or os.path.join(a.out, "timing.cache.json")
    cache = json.load(open(cache_path)) if os.path.exists(cache_path) else {"entries": {}}
    newer = [p for p in files_of(BINARY_SOURCES) if os.path.getmtime(p) > os.path.getmtime(a.shadecore)]
    if newer and not a.dry_run and not a.cached_only:
        raise Failure(f"{a.shadecore} is older than {os.path.relpath(newer[0], ROOT)} "
                      f"(and {len(newer) - 1} more): rebuild first (scripts/build.sh)")
    common = sha_tree(DECIDING)
    legacy = sha_tree(LEGACY_DECIDING)
    srch = sha_tree(BINARY_SOURCES)
    out_rows, meta, missing = [], None, []
    table_common = sha_tree(TABLE_DECIDING)
    for i, r in enumerate(rows):
        tail = f"src:{srch}|{a.target}|{count_of(a, r)}"
        key = hashlib.sha256(f"{row_id(r)}|{common}|rtl:{sha_tree(rtl_of(cfg, r))}|{tail}".encode()).hexdigest()[:24]
        if r["table"]:  # no bundle, no vectors: synthesis and STA of the RTL under configs.json and the flow alone
            key = hashlib.sha256(f"{row_id(r)}|table:{table_common}|rtl:{sha_tree(rtl_of(cfg, r))}|{a.target}"
                                 .encode()).hexdigest()[:24]
        old = hashlib.sha256(f"{row_id(r)}|{legacy}|{tail}".encode()).hexdigest()[:24]
        if os.path.exists(cache_path):  # another run may have added rows since this one started
            cache = json.load(open(cache_path))
        hit = cache["entries"].get(row_id(r))
        if hit is not None and hit["key"] == old:  # the older key over the same files: the same row
            hit = dict(hit, key=key)
            store(cache_path, row_id(r), hit)
        cached = hit is not None and hit["key"] == key
        if a.revalidate and hit is not None and not r["table"]:
            if not cached:
                inp, why = revalidate(a, r, hit)
                if inp and why:  # carried by equivalence: the new bundle's inputs, and how it got here
                    sg = dict(hit["signoff"], inputs=inp, carried=hit["signoff"].get("carried", []) + [why])
                    hit, cached = dict(hit, key=key, signoff=sg), True
                    store(cache_path, row_id(r), hit)
                elif inp:
                    hit, cached = dict(hit, key=key), True
                    store(cache_path, row_id(r), hit)
                print(f"timing_report: {row_id(r)}: " + (
                      f"the RTL of {why['from_rev'][:10]} it was measured on is proven equivalent to this one "
                      f"({why['equiv_cells']} paired signals, {why['seconds']} s): carried" if inp and why else
                      "the same bundle: re-validated" if inp else f"not re-validated ({why})"), flush=True)
            elif not hit["signoff"].get("inputs"):
                hit = dict(hit, signoff=dict(hit["signoff"], inputs=backfill_inputs(a, r)))
                store(cache_path, row_id(r), hit)
        if a.dry_run:
            print(f"{row_id(r)}: {'cached' if cached else 'to run'}")
            continue
        if a.cached_only and not cached:
            missing.append(row_id(r))
            continue
        if a.from_bundle:
            print(f"timing_report: {row_id(r)}: from {a.from_bundle} ...", flush=True)
            s = from_bundle(a, r, a.from_bundle)
            hit = {"key": key, "signoff": s}
            store(cache_path, row_id(r), hit)
            cached = False
        elif not cached:
            print(f"timing_report: [{i + 1}/{len(rows)}] {row_id(r)} ...", flush=True)
            s = measure(a, r)
            hit = {"key": key, "signoff": s}
            cache["entries"][row_id(r)] = hit
            store(cache_path, row_id(r), hit)
        if a.add_stages and "stages" not in hit["signoff"] and not r["table"] and not hit["signoff"]["sta"]["met"]:
            print(f"timing_report: [{i + 1}/{len(rows)}] {row_id(r)}: adding the stage analysis ...", flush=True)
            hit = dict(hit, signoff=dict(hit["signoff"], stages=add_stages(a, r, hit)))
            store(cache_path, row_id(r), hit)
        s = hit["signoff"]
        row = to_row(r, s)
        out_rows.append(row)
        meta = meta or s
        print(f"timing_report: {row_id(r)}: {row['period_ns']} ns (WNS {row['wns_ns']:+.3f} at {a.target}), "
              f"{row['area_um2']:,} um2, {row.get('energy_pj_per_result')} pJ/result, "
              f"gate sim {row.get('gate_sim_mismatches')} mismatches{' (cached)' if cached else ''}", flush=True)
    if a.dry_run:
        return
    if not out_rows:
        raise Failure("no row to report: none of " + ", ".join(missing) + " has a current cached result "
                      "(nothing written)")
    closes_with_mreg(out_rows)
    cmdline = "scripts/timing_report.py" + "".join(f" {x}" for x in sys.argv[1:])
    info = {"command": cmdline, "machine": figures.machine(), "date": datetime.date.today().isoformat(),
            "library": meta["library"], "tools": meta["tools"], "target_ns": a.target, "fo4_ns": meta["fo4_ns"],
            "derate_late": meta["derate_late"], "io_fraction": meta["io_fraction"], "drive_cell": meta["drive_cell"]}
    doc = dict(info, rows=out_rows, not_measured=missing)
    os.makedirs(a.out, exist_ok=True)
    jp = os.path.join(a.out, "timing.json")
    with open(jp + ".tmp", "w") as f:
        json.dump(doc, f, indent=1)
    os.replace(jp + ".tmp", jp)
    if meta is None:
        raise Failure("no row measured or cached: nothing to report")
    write_md(os.path.join(a.out, "timing.md"), out_rows, info, missing)
    # the figure's footer names the command with a long --only list shortened, so the machine and date still fit
    short = re.sub(r"--only \S+", lambda m: f"--only <{len(m.group(0).split(','))} rows>"
                   if len(m.group(0)) > 60 else m.group(0), cmdline)
    plot(os.path.join(a.out, "timing.png"), out_rows, figures.footer(short))
    print(f"timing_report: wrote {jp}, timing.md, timing.png")


if __name__ == "__main__":
    try:
        main()
    except Failure as e:
        print(f"timing_report: error: {e}", file=sys.stderr)
        sys.exit(1)
