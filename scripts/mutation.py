#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Mutation score of the handoff benches (issue 36, docs/mutation.md).

For each design point: a handoff bundle from the CLI (`shadecore handoff ... --synth skip --signoff off`),
the unit's module elaborated with the bundle's own parameters (Yosys: read the bundle's RTL, `hierarchy
-top <bundle top>`, the derived unit module renamed to its plain name, then `hierarchy -top <unit>; proc;
flatten; opt`, as MCY prepares a design), `mutate -list N -seed S` (fixed seed) and, per mutant, `mutate`
applied and `write_verilog` under the module's own name (its parameter list kept, unused, so the wrapper's
`#(...)` still binds). The bundle's run_icarus.sh then runs with FILELIST= a copy of filelist.f in which the
unit's file is that mutant (every other module unchanged), cheapest check first:

  hard     vectors/hard*.hex (the directed vectors), the recorded seed
  random   vectors/random*.hex
  nogap    every vector file, IN_GAP=0 OUT_STALL=0 (no gaps or backpressure: exact latency)
  seed2    every vector file, SEED=2 RESET_AT=5 (other gaps / backpressure, an early reset)
  extra    more vectors from the CLI (`shadecore vectors ... --mode random`, no C++ change): units, three
           files with n in 16..31, 32..127 and 128..1024 (seeds 11, 12, 13); lighting, one file of seed 11
  ports    units: material port values beyond what the host writes (`shadecore vectors --mode ports`, three
           files, seeds 21, 22, 23): n in 1..1024 (0..1024 for the dividers), thr over its F+1-bit port with codes around it (reference
           cs16: thr from |base| = 1 up), so a change confined to the host's thr(n) window or to n in 1..15
           shows; the lighting core has no such stage
  exhaustive  units that take a fragment every clock (not schlick_iter): the mutant Verilated with the bare
           harness sim/bare_main.cpp (sc_specular around it, no SystemC) and run on EVERY input code of every
           n = 16..1024 (`--all-codes`: 1009 x 2^(F+2) fragments), each output and its latency compared with
           the C model; the first mismatch (n, code) is the witness. A survivor of it computes the same function
           as the C model on the unit's whole input domain (recorded; not counted as equivalent, which needs a
           proof of every state and input)

each bounded in time (timeout = max(--min-timeout, --timeout-factor x the unmutated design's time)).
A bench failure kills the mutant; a stage that runs out of time makes it "timeout" (counted apart).
A survivor is "equivalent" only when Yosys proves it (each proof bounded by --eq-timeout seconds of CPU time, not of
the wall clock, so that the machine's load does not decide it; see equivalence()):
(0) a tied bit that is that constant already, (a) combinational SAT of a miter with every flip-flop exposed as a port pair, else (b) equiv_make of the
original and the mutant (same-named nets paired, the mutated wire left out), equiv_simple -seq N,
equiv_induct -seq N, `equiv_status -assert`. --eq-timeout 0 skips it; a later run with a bound adds it to
the cached survivors.
Every other survivor needs a reason: scripts/mutation_reasons.json, keyed "<design>:<mutant id>".

Results are cached per mutant (WORK/<design>/cache.json, written after each mutant, keyed by a fingerprint
of the prepared design, the mutation list and the bench), so an interrupted run resumes where it stopped.
The equivalence proofs depend on the prepared design and the mutation alone, not on the bench: they are kept
apart in the cache ("proofs", keyed by the design, the mutation list, --eq-steps and the proof method), so new
vectors re-run every mutant's simulations but reuse each survivor's proof or failed proof (a failed one only
when it had at least the current --eq-timeout).

  scripts/mutation.py [--design D ...] [--count 300] [--seed 1] [--jobs 2]   all listed designs; docs/
  scripts/mutation.py --design cs16 --mutant 3 --expect killed               one mutant (ctest)
  scripts/mutation.py --list                                                 the designs

Exit status: 0 done (with --expect: the mutant had the expected result), 1 failure, 2 bad arguments.
"""
import argparse
import datetime
import hashlib
import json
import multiprocessing
import os
import platform
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REASONS = os.path.join(ROOT, "scripts", "mutation_reasons.json")

# Design points, in the order of the report. "handoff": the CLI's arguments; "unit": the mutated module
# (None: from config/configs.json variants[].rtl[0]).
DESIGNS = [
    ("cs16", ["--variant", "cs16", "--config", "default"], None),
    ("cs16_compact", ["--variant", "cs16_compact", "--config", "default"], None),
    ("schlick_div", ["--variant", "schlick_div", "--config", "default"], None),
    ("schlick_nr", ["--variant", "schlick_nr", "--config", "default"], None),
    ("schlick_iter", ["--variant", "schlick_iter", "--config", "default"], None),
    ("cs16_faithful", ["--variant", "cs16_faithful", "--config", "default"], None),
    ("light_gl_default", ["--core", "lighting", "--features", "gl_default"], "sc_light"),
    ("light_full_shared", ["--core", "lighting", "--features", "full_shared"], "sc_light"),
]
# Units that cannot be run: the handoff bundle has no bench for the table RAM.
NO_BENCH = {
    "table256": "no handoff bench for the table RAM (the bundle cannot be made for a table unit)",
    "table1024": "no handoff bench for the table RAM (the bundle cannot be made for a table unit)",
}
STAGES = ["hard", "random", "nogap", "seed2", "extra", "ports", "exhaustive"]
# Units the exhaustive stage cannot take: the bare harness presents a fragment every clock.
NO_EXHAUSTIVE = {"schlick_iter": "takes one fragment per F+4 clocks; the bare harness presents one every clock"}
EQ_METHOD = 8  # equivalence(): 8 = 7 with the combinational SAT made sound (undef modelled: 7 and older, without
#                it, compared only the bits where gold is 1, see equivalence()) and exposing the flip-flops only.
#                7 = constant bit, combinational SAT, equiv_*, with memories mapped to logic first and,
#                for the combinational SAT, every wire split to bits before the flip-flops are exposed (`splitnets`:
#                `expose -evert-dff` takes only a flip-flop that drives a whole wire; one driving a slice stayed a
#                flip-flop, which SAT cannot import: "rc 1" for every schlick_div survivor of 2026-12-07); an
#                older method's survivor is tried again. 4 and 5 (a one-step `sat -seq 1` in (a)) proved a mutant the
#                bench kills (schlick_div m115 of 2026-12-06): their "equivalent" results are void and re-run.
VOID_METHODS = (4, 5)

# What bounds a proof: "cpu" = --eq-timeout seconds of the prover's CPU time (RLIMIT_CPU; a wall-clock guard of ten
# times that plus a minute beside it), so that a loaded machine does not turn a proof into "not proved". Proofs made
# under the earlier wall-clock bound (no "eq_bound") that did not succeed are tried again, and so is a survivor
# whose proof had a smaller bound than this run's; successes stand.
EQ_BOUND = "cpu"


def void_proof(r):
    """An "equivalent" result whose proof does not stand: a void method's, or a combinational SAT proof made before
    EQ_METHOD 8 (one-sided through the miter's x constant)."""
    return r.get("status") == "equivalent" and (r.get("eq_method") in VOID_METHODS or (
        r.get("eq_method", 0) < 8 and r.get("equivalence", "").startswith("combinational SAT")))


class ArgError(Exception):
    pass


class OneLineParser(argparse.ArgumentParser):
    def error(self, message):
        sys.stderr.write("mutation.py: error: %s\n" % message)
        sys.exit(2)


def die(msg, code=1):
    sys.stderr.write("mutation.py: error: %s\n" % msg)
    sys.exit(code)


def log(msg):
    sys.stdout.write(msg + "\n")
    sys.stdout.flush()


def sha(*parts):
    h = hashlib.sha256()
    for p in parts:
        h.update(p if isinstance(p, bytes) else str(p).encode())
        h.update(b"\0")
    return h.hexdigest()[:16]


CHILD = [None]  # the running child's process group (killed when a worker is terminated)


def run(cmd, cwd=None, env=None, timeout=None, cpu=None):
    """Run cmd in its own process group; returns (rc or None on timeout, output, seconds). With cpu, the child gets
    that many seconds of CPU time (RLIMIT_CPU) and running past it counts as a timeout too."""
    t0 = time.time()

    def limit():
        resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 5))
    p = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         start_new_session=True, preexec_fn=limit if cpu else None)
    CHILD[0] = p.pid
    try:
        out, _ = p.communicate(timeout=timeout)
        CHILD[0] = None
        if cpu and p.returncode in (-signal.SIGXCPU, -signal.SIGKILL):
            return None, out.decode(errors="replace"), time.time() - t0
        return p.returncode, out.decode(errors="replace"), time.time() - t0
    except subprocess.TimeoutExpired:
        try:
            os.killpg(p.pid, signal.SIGTERM)
            out, _ = p.communicate(timeout=10)
        except (subprocess.TimeoutExpired, ProcessLookupError):
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            out, _ = p.communicate()
        return None, out.decode(errors="replace"), time.time() - t0


def unit_module(design_args, unit):
    if unit:
        return unit
    variant = design_args[design_args.index("--variant") + 1]
    cfg = json.load(open(os.path.join(ROOT, "config", "configs.json")))
    for v in cfg["variants"]:
        if v["name"] == variant:
            return os.path.splitext(v["rtl"][0])[0]
    raise ArgError("unknown variant %s" % variant)


# ----------------------------------------------------------------------------------------------------
# preparation: bundle, elaborated unit, mutation list


def snapshot(opts):
    """The sources at --source (a commit) as a tree for SHADECORE_ROOT: the bundle's RTL, configs and templates
    come from a commit, not from a working tree that someone may be editing."""
    rc, out, _ = run(["git", "-C", ROOT, "rev-parse", "--verify", opts.source + "^{commit}"])
    if rc != 0:
        raise ArgError("--source %s: not a commit" % opts.source)
    commit = out.strip()
    dest = os.path.join(opts.work, "src", commit[:12])
    if not os.path.isfile(os.path.join(dest, ".complete")):
        shutil.rmtree(dest, ignore_errors=True)
        os.makedirs(dest)
        rc, out, _ = run(["sh", "-c", "git -C '%s' archive %s | tar -x -C '%s'" % (ROOT, commit, dest)])
        if rc != 0:
            raise RuntimeError("git archive failed: " + out[-500:])
        open(os.path.join(dest, ".complete"), "w").close()
    return commit, dest


def cli_env(opts):
    return dict(os.environ, SHADECORE_ROOT=opts.src_dir)


def make_bundle(opts, name, handoff_args, bundle, dry=False):
    cli, vec_seed, vec_count = opts.cli, opts.vec_seed, opts.vec_count
    cmd = [cli, "handoff"] + handoff_args + ["--seed", str(vec_seed), "--count", str(vec_count),
                                             "--no-ice40", "--synth", "skip", "--signoff", "off",
                                             "--out", bundle, "--force"]
    if dry:  # the command only
        return cmd
    stamp = os.path.join(bundle, ".mutation_cmd")
    key = " ".join(cmd[1:]) + " @" + opts.commit
    if os.path.isfile(stamp) and open(stamp).read() == key and \
            os.path.isfile(os.path.join(bundle, "run_icarus.sh")):
        return cmd
    log("[%s] %s (sources of %s)" % (name, " ".join(["shadecore"] + cmd[1:]), opts.commit[:12]))
    rc, out, secs = run(["nice", "-n", "10"] + cmd, env=cli_env(opts))
    if rc != 0:
        raise RuntimeError("handoff failed (%s):\n%s" % (rc, out[-3000:]))
    with open(stamp, "w") as f:
        f.write(key)
    log("[%s] bundle made in %.0f s" % (name, secs))
    return cmd


def read_filelist(bundle):
    incdirs, files = [], []
    for line in open(os.path.join(bundle, "filelist.f")):
        line = line.strip()
        if not line or line.startswith("//") or line.startswith("#"):
            continue
        if line.startswith("+incdir+"):
            incdirs.append(line[len("+incdir+"):])
        else:
            files.append(line)
    return incdirs, files


def bundle_top(bundle):
    m = re.search(r"^\s*(\w+)\s+dut\s*\(", open(os.path.join(bundle, "tb", "tb_dut.vh")).read(), re.M)
    if not m:
        raise RuntimeError("cannot find the design under test in tb/tb_dut.vh")
    return m.group(1)


def prepare(name, bundle, unit, count, seed, wdir):
    """design.il (the unit elaborated with the bundle's parameters, flattened) and mutations.txt."""
    incdirs, files = read_filelist(bundle)
    unit_file = [f for f in files if os.path.basename(f) == unit + ".v"]
    if len(unit_file) != 1:
        raise RuntimeError("%s.v is not in the bundle's filelist.f" % unit)
    top = bundle_top(bundle)
    inc = " ".join("-I" + d for d in incdirs)
    ys = os.path.join(wdir, "elab.ys")
    with open(ys, "w") as f:
        f.write("read_verilog %s %s\nhierarchy -top %s\nls\n" % (inc, " ".join(files), top))
    rc, out, _ = run(["yosys", "-q", "-l", os.path.join(wdir, "elab.log"), ys], cwd=bundle)
    if rc != 0:
        raise RuntimeError("yosys elaboration failed:\n" + out[-3000:])
    elab = open(os.path.join(wdir, "elab.log")).read()
    # the parameters the wrapper passes to the unit (for the report; the derived module carries them)
    derived = [ln.strip() for ln in elab.splitlines()
               if re.fullmatch(r"\s+(\$paramod\S*\\%s|%s)" % (re.escape(unit), re.escape(unit)), ln)]
    if len(derived) != 1:
        raise RuntimeError("expected one instance of %s below %s, found %s" % (unit, top, derived))
    # the parameters the wrapper passes to the unit (for the report): the derive step of that very module
    params = {}
    m = re.search(r"derive mode using pre-parsed AST for module `\\%s'\.\n((?:Parameter .*\n)*)"
                  r"Generating RTLIL representation for module `%s'" % (re.escape(unit), re.escape(derived[0])), elab)
    if m:
        for pl in m.group(1).splitlines():
            k, v = pl[len("Parameter \\"):].split(" = ", 1)
            if re.fullmatch(r"32'[01]{32}", v):  # a negative integer, printed as bits
                v = str(int(v[3:], 2) - (1 << 32) if v[3] == "1" else int(v[3:], 2))
            params[k] = v
    ren = "" if derived[0] == unit else "rename %s %s\n" % (derived[0], unit)
    with open(ys, "w") as f:
        f.write("read_verilog %s %s\nhierarchy -top %s\n%shierarchy -check -top %s\n"
                "proc\nflatten\nopt\nstat\nwrite_rtlil %s\nmutate -list %d -seed %d -o %s\n"
                % (inc, " ".join(files), top, ren, unit, os.path.join(wdir, "design.il"), count, seed,
                   os.path.join(wdir, "mutations.txt")))
    rc, out, _ = run(["yosys", "-q", "-l", os.path.join(wdir, "prep.log"), ys], cwd=bundle)
    if rc != 0:
        raise RuntimeError("yosys preparation failed:\n" + out[-3000:])
    muts = [ln.strip() for ln in open(os.path.join(wdir, "mutations.txt")) if ln.strip()]
    # the unit's own parameter names: declared again (unused) in every mutant so the wrapper's #(...) binds
    src = open(os.path.join(bundle, unit_file[0])).read()
    hm = re.search(r"module\s+%s\s*#\s*\((.*?)\)\s*\(" % re.escape(unit), src, re.S)
    pnames = re.findall(r"\bparameter\s+(?:integer\s+|signed\s+|\[[^\]]*\]\s*)*(\w+)", hm.group(1)) if hm else []
    return {"unit_file": unit_file[0], "top": top, "params": params, "pnames": pnames, "mutations": muts}


# ----------------------------------------------------------------------------------------------------
# one mutant


def write_mutant(ctx, idx, mdir):
    mut = ctx["mutations"][idx - 1] if idx > 0 else None
    vfile = os.path.join(mdir, "%s.v" % ctx["unit"])
    ys = os.path.join(mdir, "mutate.ys")
    with open(ys, "w") as f:
        f.write("read_rtlil %s\n%s\nwrite_verilog -noattr %s\n" % (ctx["design_il"], mut or "", vfile))
    rc, out, _ = run(["yosys", "-q", ys], cwd=mdir, timeout=300)
    if rc != 0:
        raise RuntimeError("yosys mutate failed:\n" + out[-2000:])
    text = open(vfile).read()
    if ctx["pnames"]:
        decl = "#(" + ", ".join("parameter %s = 0" % p for p in ctx["pnames"]) + ") "
        text, n = re.subn(r"^module %s\(" % re.escape(ctx["unit"]), "module %s %s(" % (ctx["unit"], decl),
                          text, count=1, flags=re.M)
        if n != 1:
            raise RuntimeError("cannot find the module header in the mutant")
    with open(vfile, "w") as f:
        f.write(text)
    fl = os.path.join(mdir, "filelist.f")
    with open(os.path.join(ctx["bundle"], "filelist.f")) as src, open(fl, "w") as dst:
        for line in src:
            dst.write(vfile + "\n" if line.strip() == ctx["unit_file"] else line)
    return fl


def stage_env(ctx, stage, fl):
    env = dict(os.environ, FILELIST=fl, TMPDIR=os.path.dirname(fl))
    if stage == "hard":
        env["VECTORS"] = " ".join(ctx["hard"])
    elif stage == "random":
        env["VECTORS"] = " ".join(ctx["random"])
    elif stage == "nogap":
        env.update(IN_GAP="0", OUT_STALL="0")
    elif stage == "seed2":
        env.update(SEED="2", RESET_AT="5")
    elif stage == "extra":
        env["VECTORS"] = " ".join(ctx["extra"])
    elif stage == "ports":
        env["VECTORS"] = " ".join(ctx["ports"])
    return env


def exhaustive(ctx, fl, timeout):
    """The exhaustive stage: the design of filelist `fl` (the mutant in place of the unit) Verilated with the bare
    harness, every input code of every n = 16..1024. Returns (rc, line, seconds) as simulate(): rc None on a
    timeout, 0 when every output equals the C model's, else the harness's first-mismatch (witness) line."""
    b = ctx["bare"]
    mdir = os.path.join(os.path.dirname(fl), "bare")
    incdirs, files = [], []
    for line in open(fl):
        line = line.strip()
        if line.startswith("+incdir+"):
            incdirs.append(os.path.join(ctx["bundle"], line[len("+incdir+"):]))
        elif line and not line.startswith(("//", "#")):
            files.append(line if os.path.isabs(line) else os.path.join(ctx["bundle"], line))
    build = b["build"]
    cflags = " ".join(["-O2", "-std=c++17", '-DSHADECORE_BARE_CONFIG=\\"%s\\"' % b["config"],
                       "-DSHADECORE_BARE_MREG=0", "-DSHADECORE_BARE_VARIANT=%d" % b["variant"]] +
                      ["-I" + os.path.join(ROOT, d) for d in ("cmodel/include", "stimulus/include", "common/include")] +
                      ["-I" + os.path.join(build, "generated")])
    libs = " ".join(os.path.join(build, l) for l in ("cmodel/libshadecore_cmodel.a", "common/libshadecore_common.a"))
    cmd = (["verilator", "--cc", "--exe", "--build", "-j", "1", "-O3", "--x-assign", "fast", "--x-initial", "fast",
            "-Wno-fatal", "-Wno-lint", "-Wno-style", "--top-module", "sc_specular", "--prefix", "Vbare_cs16",
            "-Mdir", mdir, "-o", "bare", "-GVARIANT=%d" % b["variant"], "-GFRAC=%d" % b["frac"],
            "-GGUARD=%d" % b["guard"], "-GCUTOFF=0", "-GTAGW=%d" % b["tagw"], "-GMREG=0"] +
           ["-I" + d for d in incdirs] + files + [os.path.join(ROOT, "sim", "bare_main.cpp"),
                                                   "-CFLAGS", cflags, "-LDFLAGS", libs])
    t0 = time.time()
    rc, out, _ = run(cmd, cwd=os.path.dirname(fl), timeout=timeout)
    if rc is None:
        return None, "", time.time() - t0
    if rc != 0:
        raise RuntimeError("the exhaustive stage's Verilator build failed:\n" + out[-2000:])
    rc, out, _ = run([os.path.join(mdir, "bare"), "--n", "16..1024", "--all-codes", "--no-progress"],
                     cwd=os.path.dirname(fl), timeout=max(1, timeout - (time.time() - t0)))
    lines = [ln for ln in (out or "").splitlines() if ln.startswith("bare:")]
    first = [ln for ln in lines if "first mismatch" in ln]
    stats = [ln for ln in lines if " sent, " in ln]
    line = "exhaustive: " + (first[0][len("bare: "):] if first else stats[0][len("bare: "):] if stats else "no result")
    return rc, line, time.time() - t0


def simulate(ctx, stage, fl, timeout):
    if stage == "exhaustive":
        return exhaustive(ctx, fl, timeout)
    rc, out, secs = run(["sh", "./run_icarus.sh"], cwd=ctx["bundle"], env=stage_env(ctx, stage, fl),
                        timeout=timeout)
    fail = [ln for ln in out.splitlines() if ln.startswith("FAIL")]
    return rc, (fail[0] if fail else out.strip().splitlines()[-1] if out.strip() else ""), secs


def equivalence(ctx, idx, mdir):
    """'equivalent' (proved) or 'unknown' (not proved within the time bounds), with a one-line account.

    Yosys proofs, each bounded by --eq-timeout, the first that succeeds counts:
    (0) a tie (const0/const1) of a bit that is that constant already: `sat -seq 1 -prove WIRE[BIT] VALUE` on
        the original, every flip-flop free (any state, reachable or not): the mutant is the same circuit.
    (a) combinational: every flip-flop of the original (gold) and the mutant (gate) turned into a port pair
        (`dffunmap; splitnets; expose -dff -evert-dff`: its Q an input, its D an output, same names on both sides;
        `-dff` exposes the flip-flops only, not every internal wire as well), a miter of the two (`miter -equiv
        -make_outputs -ignore_gold_x`: a gold output that is x, the RTL's don't-care, is not compared), the shared
        logic merged (`opt_merge`), `sat -enable_undef -set-def-inputs -prove trigger 0`: the same next state and
        outputs from every state, reachable or not — sequential equivalence follows. The undef model is needed:
        without it SAT reads the miter's x constant as 0, and `-ignore_gold_x` then skips every bit where gold is 0
        (only gate >= gold was checked: cs16 m074, which the hard vectors kill, was "proved" so; of the 48 such proofs
        in 2026-12-07's caches, 47 hold under this proof and schlick_iter m073 does not).
        Where a flip-flop is left (SAT cannot import it) this fails with an error and (b) decides. A model here is
        no counter-example (the state may be unreachable), so (b) is tried next. (A `sat -seq 1` variant that
        took the left flip-flops as free states proved a mutant the bench kills: not used.)
    Memories (a ROM such as schlick_nr's seed table) are mapped to logic first (`memory_map`): SAT cannot import
    a memory port.
    (b) Yosys's equivalence flow: equiv_make pairs every net of the same name except the mutated wire itself
        (its value may differ where the difference is masked further on) unless that wire is a port (every port is
        paired: a port left out would be compared nowhere, EQ_METHOD 8), equiv_simple -seq N and
        equiv_induct -seq N (every pair, with the others as assumptions); `equiv_status -assert` (every pair
        proved, the output ports among them) counts as equivalent."""
    mut = ctx["mutations"][idx - 1]
    unit = ctx["unit"]
    tries = []
    f = dict(re.findall(r"-(mode|wire|wirebit) (\S+)", mut))
    if f.get("mode") in ("const0", "const1") and "wire" in f and "wirebit" in f:
        ys = os.path.join(mdir, "const.ys")
        with open(ys, "w") as fh:
            fh.write("read_rtlil %s\nmemory_map\ncd %s\nrename %s mutation_check_w\n"
                     "sat -verify -seq 1 -prove mutation_check_w[%s] 1'b%s\n"
                     % (ctx["design_il"], unit, f["wire"], f["wirebit"], f["mode"][-1]))
        logf = os.path.join(mdir, "const.log")
        rc, out, secs = run(["yosys", "-q", "-l", logf, ys], cwd=mdir, **proof_bound(ctx))
        logtxt = open(logf).read() if os.path.isfile(logf) else ""
        if rc == 0 and "no model found: SUCCESS!" in logtxt:
            return "equivalent", "the tied bit %s[%s] is %s in every state already (sat -seq 1 -prove, %.0f s)" % (
                f["wire"], f["wirebit"], f["mode"][-1], secs)
        tries.append("constant bit: %s" % ("timed out" if rc is None else "not constant"
                                           if "model found: FAIL" in logtxt else "rc %s" % rc))
    ys = os.path.join(mdir, "comb.ys")
    with open(ys, "w") as f:
        f.write("read_rtlil %s\ncopy %s gold\n%s\nrename %s gate\nmemory_map\ndffunmap\nsplitnets\n"
                "expose -dff -evert-dff gold gate\nmiter -equiv -flatten -make_outputs -ignore_gold_x gold gate miter\n"
                "hierarchy -top miter\nopt -fast\nopt_merge -share_all\nopt_clean\n"
                "sat -verify -enable_undef -set-def-inputs -prove trigger 0 miter\n"
                % (ctx["design_il"], unit, mut, unit))
    logf = os.path.join(mdir, "comb.log")
    rc, out, secs = run(["yosys", "-q", "-l", logf, ys], cwd=mdir, **proof_bound(ctx))
    logtxt = open(logf).read() if os.path.isfile(logf) else ""
    if rc == 0 and "no model found: SUCCESS!" in logtxt:
        return "equivalent", "combinational SAT with the flip-flops as ports: proved (%.0f s)" % secs
    tries.append("combinational SAT: %s" % ("timed out" if rc is None else "a model from some state"
                                            if "model found: FAIL" in logtxt else "rc %s" % rc))
    wire = re.search(r"-wire (\S+)", mut)
    bl = os.path.join(mdir, "blacklist.txt")
    with open(bl, "w") as f:
        # a port is never left out: equiv_make would give it a gold and a gate copy and compare neither (the
        # output tie m012 of cs16 was "proved" so); the select below refuses any port left unpaired
        f.write((wire.group(1) + "\n") if wire and wire.group(1) not in unit_ports(ctx) else "")
    ys = os.path.join(mdir, "equiv.ys")
    n = ctx["eq_steps"]
    with open(ys, "w") as f:
        f.write("read_rtlil %s\ncopy %s gold\n%s\nrename %s gate\nmemory_map\n"
                "equiv_make -blacklist %s gold gate equiv\nhierarchy -top equiv\n"
                "select -assert-none equiv/o:*_gold equiv/o:*_gate equiv/i:*_gold equiv/i:*_gate\nflatten\nopt_clean\n"
                "equiv_simple -seq %d\nequiv_induct -seq %d\nequiv_status -assert\n"
                % (ctx["design_il"], unit, mut, unit, bl, n, n))
    logf = os.path.join(mdir, "equiv.log")
    rc, out, secs = run(["yosys", "-q", "-l", logf, ys], cwd=mdir, **proof_bound(ctx))
    logtxt = open(logf).read() if os.path.isfile(logf) else ""
    if rc == 0 and "Equivalence successfully proven!" in logtxt:
        return "equivalent", "equiv_simple/equiv_induct -seq %d: every pair proved (%.0f s)" % (n, secs)
    m = re.search(r"Of those cells (\d+) are proven and (\d+) are unproven", logtxt)
    tries.append("equiv_*: %s" % ("timed out" if rc is None else "%s of %d pairs unproven"
                                  % (m.group(2), int(m.group(1)) + int(m.group(2))) if m else "rc %s" % rc))
    return "unknown", "not proved within %d CPU s each (%s)" % (ctx["eq_timeout"], "; ".join(tries))


def unit_ports(ctx):
    """The unit's port names, from design.il."""
    if "ports" not in ctx:
        text = open(ctx["design_il"]).read()
        body = re.search(r"^module \\%s\n(.*?)^end$" % re.escape(ctx["unit"]), text, re.S | re.M)
        ctx["ports"] = set(re.findall(r"^\s*wire (?:width \d+ )?(?:upto )?(?:signed )?(?:input|output|inout) \d+ \\(\S+)$",
                                      body.group(1) if body else "", re.M))
    return ctx["ports"]


def needs_proof(r, eq_timeout):
    """A survivor's proof is (re)tried when it was made by another method, under the old wall-clock bound, or with a
    smaller bound than eq_timeout."""
    return r.get("eq_method") != EQ_METHOD or r.get("eq_bound") != EQ_BOUND or r.get("eq_timeout", 0) < eq_timeout


def proof_bound(ctx):
    """The bound of one proof (EQ_BOUND): CPU seconds, and a wall-clock guard."""
    return {"cpu": ctx["eq_timeout"], "timeout": 10 * ctx["eq_timeout"] + 60}


def run_mutant(args):
    ctx, idx, prev = args
    mdir = tempfile.mkdtemp(prefix="m%d_" % idx, dir=ctx["tmp"])
    res = {"id": idx, "mutation": ctx["mutations"][idx - 1] if idx > 0 else "none"}
    done = []
    if prev and prev.get("status") == "survived":  # a survivor of fewer stages: only the new ones
        res = dict(prev)
        done = prev.get("stages", [])
    t0 = time.time() - (prev or {}).get("seconds", 0) if done else time.time()
    try:
        fl = write_mutant(ctx, idx, mdir)
        res["status"] = "survived"
        res["stages"] = ctx["stages"]
        for stage in ctx["stages"]:
            if stage in done:
                continue
            rc, line, secs = simulate(ctx, stage, fl, ctx["timeouts"][stage])
            if rc is None:
                res.update(status="timeout", stage=stage, detail="no result in %.0f s" % secs)
                break
            if rc != 0:
                res.update(status="killed", stage=stage, detail=line[:300])
                break
        if res["status"] == "survived" and idx > 0 and ctx["eq_timeout"] > 0 and needs_proof(res, ctx["eq_timeout"]):
            known = ctx.get("proofs", {}).get(str(idx))
            if known and (known["equivalent"] or (known["eq_timeout"] >= ctx["eq_timeout"]
                                                  and known.get("eq_bound") == EQ_BOUND)):
                eq = "equivalent" if known["equivalent"] else "unknown"
                why = known["why"] if known["why"].endswith("(proof reused)") else known["why"] + " (proof reused)"
                res["eq_timeout"] = known["eq_timeout"]
            else:
                eq, why = equivalence(ctx, idx, mdir)
                res["eq_timeout"] = ctx["eq_timeout"]
            res["equivalence"] = why
            res["eq_method"] = EQ_METHOD
            res["eq_bound"] = EQ_BOUND
            if eq == "equivalent":
                res["status"] = "equivalent"
        if res["status"] == "survived" and idx > 0:
            keep = os.path.join(ctx["wdir"], "survivors")
            os.makedirs(keep, exist_ok=True)
            shutil.copy(os.path.join(mdir, "%s.v" % ctx["unit"]), os.path.join(keep, "m%03d_%s.v" % (idx, ctx["unit"])))
    except Exception as e:  # noqa: BLE001 - reported as an error result, the run goes on
        res.update(status="error", detail=str(e)[-500:])
    finally:
        shutil.rmtree(mdir, ignore_errors=True)
    res["seconds"] = round(time.time() - t0, 2)
    return res


def on_term(signum, frame):
    if CHILD[0]:
        try:
            os.killpg(CHILD[0], signal.SIGTERM)
        except OSError:
            pass
    os._exit(1)


def nice_init():
    try:
        os.nice(10)
    except OSError:
        pass
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, on_term)


# ----------------------------------------------------------------------------------------------------
# one design


def load_cache(path, fp, proof_key=None, harvested=None):
    """The cache of a design: its results when the fingerprint matches, else empty results; the proofs when
    their key matches (or `harvested`, proofs taken from an older cache that predates the proofs section)."""
    c = None
    try:
        c = json.load(open(path))
    except (OSError, ValueError):
        pass
    out = c if c is not None and c.get("fingerprint") == fp else {"fingerprint": fp, "results": {}}
    proofs = (c or {}).get("proofs")
    if not (proofs and proofs.get("key") == proof_key):
        proofs = {"key": proof_key, "results": dict(harvested or {})}
    out["proofs"] = proofs
    return out


def proof_of(r, eq_timeout):
    """What a result says about its mutant's equivalence proof (None when no proof was tried)."""
    if r.get("eq_method") != EQ_METHOD or "equivalence" not in r:
        return None
    return {"equivalent": r["status"] == "equivalent", "why": r["equivalence"],
            "eq_timeout": r.get("eq_timeout", eq_timeout), "eq_bound": r.get("eq_bound")}


def vector_files(bundle):
    """A bundle's vector files (paths relative to it): the directed ones (hard*.hex) and the others."""
    vecs = sorted(f for f in os.listdir(os.path.join(bundle, "vectors")) if f.endswith(".hex"))
    return (["vectors/" + f for f in vecs if f.startswith("hard")],
            ["vectors/" + f for f in vecs if not f.startswith("hard")])


def fingerprint(design_il, mutations, cmd, eq_steps, bundle, vectors):
    """What a cached result depends on: the prepared design, the mutation list, the handoff command, --eq-steps,
    the bench's vector files and the bench itself (every file of the bundle's tb/: a check added to the bench must
    run the mutants again; a new stage re-runs the survivors in it only)."""
    tb = os.path.join(bundle, "tb")
    benches = sorted(os.path.relpath(os.path.join(d, f), tb) for d, _, fs in os.walk(tb) for f in fs)
    return sha(design_il, "\n".join(mutations), " ".join(cmd[1:]), eq_steps,
               *[open(os.path.join(bundle, v), "rb").read() for v in vectors],
               *[b.encode() + b"\0" + open(os.path.join(tb, b), "rb").read() for b in benches])


def harvest_proofs(wdir, cmd, eq_steps):
    """The proofs of a cache written before the proofs section, when its results are verified to belong to the
    files still in wdir (its fingerprint recomputed from the old design.il, mutation list and vectors): read
    before the bundle and design.il are rewritten. Returns (design.il bytes, mutation list, {id: proof})."""
    try:
        c = json.load(open(os.path.join(wdir, "cache.json")))
        il = open(os.path.join(wdir, "design.il"), "rb").read()
        muts = [x.strip() for x in open(os.path.join(wdir, "mutations.txt")) if x.strip()]
        hard, rand = vector_files(os.path.join(wdir, "bundle"))
        fp = fingerprint(il, muts, cmd, eq_steps, os.path.join(wdir, "bundle"), hard + rand)
    except (OSError, ValueError):
        return None
    if c.get("fingerprint") != fp or c.get("proofs"):
        return None
    eq_t = (c.get("meta") or {}).get("eq_timeout", 0)
    got = {k: proof_of(r, eq_t) for k, r in c.get("results", {}).items()}
    return il, muts, {k: v for k, v in got.items() if v}


def save_cache(path, cache):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(cache, f, indent=1, sort_keys=True)
    os.replace(tmp, path)


def make_extra(opts, name, handoff_args, wdir, mode="random"):
    """The extra stage's vector files (shadecore vectors, random mode): n bands for a unit, a seed for lighting; the
    ports stage's (mode "ports", units only: three seeds, n and thr over their whole ports)."""
    edir = os.path.join(wdir, "extra" if mode == "random" else mode)
    os.makedirs(edir, exist_ok=True)
    if mode == "ports":
        jobs = [] if "lighting" in handoff_args else [(None, 21), (None, 22), (None, 23)]
    else:
        jobs = [(None, 11)] if "lighting" in handoff_args else [("16..31", 11), ("32..127", 12), ("128..1024", 13)]
    files = []
    for band, seed in jobs:
        out = os.path.join(edir, "%s_n%s_seed%d.hex" % (mode, (band or "all").replace("..", "-"), seed))
        cmd = [opts.cli, "vectors"] + handoff_args + ["--mode", mode, "--count", str(opts.vec_count),
                                                      "--seed", str(seed), "--out", out]
        if band:
            cmd[-2:-2] = ["--n", band]
        stamp = out + ".cmd"
        key = " ".join(cmd[1:]) + " @" + opts.commit
        if not (os.path.isfile(out) and os.path.isfile(stamp) and open(stamp).read() == key):
            rc, txt, _ = run(["nice", "-n", "10"] + cmd, env=cli_env(opts))
            if rc != 0:
                raise RuntimeError("shadecore vectors failed:\n" + txt[-2000:])
            with open(stamp, "w") as f:
                f.write(key)
        files.append(out)
    return files


def bare_params(opts, handoff_args, bundle):
    """What the exhaustive stage builds for a unit design (variant id, width, the bundle's TAGW, the build tree), or
    None: a lighting design, or a unit the bare harness cannot feed (NO_EXHAUSTIVE)."""
    if "--variant" not in handoff_args:
        return None
    variant = handoff_args[handoff_args.index("--variant") + 1]
    config = handoff_args[handoff_args.index("--config") + 1] if "--config" in handoff_args else "default"
    if variant in NO_EXHAUSTIVE:
        return None
    cj = json.load(open(os.path.join(ROOT, "config", "configs.json")))
    v = [x for x in cj["variants"] if x["name"] == variant]
    c = [x for x in cj["configs"] if x["name"] == config]
    m = re.search(r"TAGW\s*=\s*(\d+)", open(os.path.join(bundle, "tb", "tb_config.vh")).read())
    if not v or not c or not m:
        raise RuntimeError("exhaustive stage: cannot find variant %s, config %s or TAGW in the bundle" % (variant, config))
    return {"variant": v[0]["id"], "config": config, "frac": c[0]["frac"], "guard": c[0]["guard"],
            "tagw": int(m.group(1)), "build": os.path.dirname(os.path.dirname(os.path.abspath(opts.cli)))}


def run_design(opts, name, handoff_args, unit_opt, only=None):
    unit = unit_module(handoff_args, unit_opt)
    wdir = os.path.join(opts.work, name)
    os.makedirs(wdir, exist_ok=True)
    bundle = os.path.join(wdir, "bundle")
    # an older cache's proofs, read before make_bundle and prepare rewrite the files they were made from
    old = harvest_proofs(wdir, make_bundle(opts, name, handoff_args, bundle, dry=True), opts.eq_steps)
    cmd = make_bundle(opts, name, handoff_args, bundle)
    prep = prepare(name, bundle, unit, opts.count, opts.seed, wdir)
    hard, rand = vector_files(bundle)
    extra = make_extra(opts, name, handoff_args, wdir) if "extra" in opts.stages else []
    ports = make_extra(opts, name, handoff_args, wdir, "ports") if "ports" in opts.stages else []
    bare = bare_params(opts, handoff_args, bundle) if "exhaustive" in opts.stages else None
    stages = [s for s in STAGES if s in opts.stages and not (s == "hard" and not hard)
              and not (s == "random" and not rand) and not (s == "extra" and not extra)
              and not (s == "ports" and not ports)
              and not (s == "exhaustive" and not bare)]
    ctx = dict(prep, unit=unit, bundle=bundle, wdir=wdir, design_il=os.path.join(wdir, "design.il"),
               hard=hard, random=rand, extra=extra, ports=ports, bare=bare, stages=stages, eq_timeout=opts.eq_timeout,
               eq_steps=opts.eq_steps, tmp=os.path.join(wdir, "tmp"), timeouts={})
    os.makedirs(ctx["tmp"], exist_ok=True)
    # the fingerprint: what a cached result depends on (a new stage re-runs the survivors in it only)
    fp = fingerprint(open(ctx["design_il"], "rb").read(), prep["mutations"], cmd, opts.eq_steps, bundle, hard + rand)
    if getattr(opts, "pick", None):
        hit = [i for i, m in enumerate(prep["mutations"], 1) if re.search(opts.pick, m)]
        if not hit:
            raise ArgError("--pick %s: no mutant of %s matches" % (opts.pick, name))
        only = (only or []) + hit[:1]
    ids = only if only else list(range(1, len(prep["mutations"]) + 1))
    for i in ids:
        if not 1 <= i <= len(prep["mutations"]):
            raise ArgError("--mutant %d: %s has %d mutants" % (i, name, len(prep["mutations"])))
    cache_path = os.path.join(wdir, "cache.json")
    design_il = open(ctx["design_il"], "rb").read()
    proof_key = sha(design_il, "\n".join(prep["mutations"]), opts.eq_steps, EQ_METHOD)
    harvested = old[2] if old and old[0] == design_il and old[1] == prep["mutations"] else None
    cache = load_cache(cache_path, fp, proof_key, harvested)
    ctx["proofs"] = cache["proofs"]["results"]
    if opts.no_cache:
        cache.pop("baseline", None)
        for i in ids:
            cache["results"].pop(str(i), None)
    # the unmutated design through the same flow: must pass every stage; its times set the time bounds
    base = cache.setdefault("baseline", {})
    if any(st not in base for st in stages):
        fl = write_mutant(ctx, 0, tempfile.mkdtemp(prefix="m0_", dir=ctx["tmp"]))
        for stage in stages:
            if stage in base:
                continue
            rc, line, secs = simulate(ctx, stage, fl, 3600)
            if rc != 0:
                raise RuntimeError("the unmutated design (Yosys round trip) fails stage %s: %s" % (stage, line))
            base[stage] = round(secs, 2)
        shutil.rmtree(os.path.dirname(fl), ignore_errors=True)
        save_cache(cache_path, cache)
    for stage in stages:
        ctx["timeouts"][stage] = max(opts.min_timeout, opts.timeout_factor * cache["baseline"][stage])
    log("[%s] unit %s (%s), %d mutants (seed %d), stages %s, baseline %s s" % (
        name, unit, ", ".join("%s=%s" % kv for kv in prep["params"].items()) or "no parameters",
        len(prep["mutations"]), opts.seed, "/".join(stages),
        " ".join("%s %.1f" % (s, cache["baseline"][s]) for s in stages)))


    def stale(r):
        if void_proof(r):
            return True
        return r["status"] == "error" or (r["status"] == "survived" and (
            any(st not in r.get("stages", STAGES[:4]) for st in stages) or
            (opts.eq_timeout > 0 and needs_proof(r, opts.eq_timeout))))
    todo = [i for i in ids if str(i) not in cache["results"] or stale(cache["results"][str(i)])]
    done = len(ids) - len(todo)
    if done:
        log("[%s] %d of %d mutants from the cache" % (name, done, len(ids)))
    counts = {}
    for i in ids:
        if str(i) in cache["results"] and i not in todo:
            s = cache["results"][str(i)]["status"]
            counts[s] = counts.get(s, 0) + 1
    t0 = time.time()
    meta = {"name": name, "unit": unit, "handoff": "shadecore " + " ".join(cmd[1:]).replace(bundle, "DIR"),
            "params": prep["params"], "stages": stages, "timeouts": ctx["timeouts"],
            "baseline": cache["baseline"], "eq_timeout": opts.eq_timeout, "eq_steps": opts.eq_steps,
            "count": opts.count, "seed": opts.seed, "source": opts.commit}
    if not only:
        cache["meta"] = dict(meta, complete=False)
        save_cache(cache_path, cache)
    if todo:
        pool = multiprocessing.Pool(opts.jobs, initializer=nice_init)
        try:
            for r in pool.imap_unordered(run_mutant, [(ctx, i, cache["results"].get(str(i))) for i in todo]):
                cache["results"][str(r["id"])] = r
                if proof_of(r, opts.eq_timeout):
                    cache["proofs"]["results"][str(r["id"])] = proof_of(r, opts.eq_timeout)
                save_cache(cache_path, cache)
                if r["status"] != "survived":
                    stale_v = os.path.join(wdir, "survivors", "m%03d_%s.v" % (r["id"], unit))
                    if os.path.exists(stale_v):
                        os.remove(stale_v)
                done += 1
                counts[r["status"]] = counts.get(r["status"], 0) + 1
                log("[%s] %3d/%d  m%03d %-10s %-7s %5.1f s  | %s" % (
                    name, done, len(ids), r["id"], r["status"], r.get("stage", ""), r["seconds"],
                    " ".join("%s %d" % kv for kv in sorted(counts.items()))))
            pool.close()
        except BaseException:
            pool.terminate()
            raise
        finally:
            pool.join()
    shutil.rmtree(ctx["tmp"], ignore_errors=True)
    if not only:
        cache["meta"] = dict(meta, complete=True)
        save_cache(cache_path, cache)
    return dict(meta, results=[cache["results"][str(i)] for i in ids], wall_seconds=round(time.time() - t0, 1))


def unvoid(results):
    """A proof that does not stand is not reported as one: its mutant counts as a survivor until it is run again."""
    return [dict(r, status="survived", equivalence=r["equivalence"] + " (void: proof made before EQ_METHOD 8)")
            if r is not None and void_proof(r) else r for r in results]


def cached_design(opts, name):
    """A finished design's results from its cache (--report-only), or None."""
    try:
        c = json.load(open(os.path.join(opts.work, name, "cache.json")))
    except (OSError, ValueError):
        return None
    meta = c.get("meta")
    if not meta or meta["count"] != opts.count or meta["seed"] != opts.seed:
        return None
    res = [c["results"].get(str(i)) for i in range(1, meta["count"] + 1)]
    res = unvoid(res)
    done = [r for r in res if r is not None]
    if not done:
        return None
    if len(done) < len(res) or meta.get("complete") is False:
        return dict(meta, results=done, partial=True)
    return dict(meta, results=res)


# ----------------------------------------------------------------------------------------------------
# report


def reason_class(why):
    """A written reason's class: 'all' (equivalent for every input, shown by hand), 'contract' (no input that obeys
    the unit's contract shows it), 'other' (a real gap, or no reason yet)."""
    if not why:
        return "other"
    if "for every input" in why.lower():
        return "all"
    if "contract" in why.lower() or "THRWIN" in why:
        return "contract"
    return "other"


def summarise(d, reasons=None):
    c = {k: 0 for k in ("killed", "survived", "timeout", "equivalent", "error")}
    by_stage = {}
    cls = {"all": 0, "contract": 0, "other": 0}
    exh = 0   # survivors of the exhaustive stage: the C model's function on the whole input domain
    for r in d["results"]:
        exh += r["status"] == "survived" and "exhaustive" in r.get("stages", [])
        c[r["status"]] = c.get(r["status"], 0) + 1
        if r["status"] == "killed":
            by_stage[r["stage"]] = by_stage.get(r["stage"], 0) + 1
        if r["status"] == "survived":
            cls[reason_class((reasons or {}).get("%s:%d" % (d["name"], r["id"])))] += 1
    total = len(d["results"])
    denom = total - c["equivalent"]
    denom2 = denom - cls["all"] - cls["contract"]
    return dict(c, total=total, killed_by_stage=by_stage, survivors_by_reason=cls, survived_exhaustive=exh,
                score=round(100.0 * c["killed"] / denom, 2) if denom else None,
                score_reasoned=round(100.0 * c["killed"] / denom2, 2) if denom2 else None)


def tool_versions():
    def first(cmd):
        try:
            return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                  timeout=30).stdout.decode().strip().splitlines()[0]
        except (OSError, IndexError, subprocess.SubprocessError):
            return "?"
    return {"yosys": first(["yosys", "-V"]), "icarus": first(["iverilog", "-V"]),
            "python": platform.python_version()}


def describe(mut):
    """A short reading of a mutate command: mode, wire[bit], source lines."""
    f = dict(re.findall(r"-(mode|wire|wirebit|cell|port|portbit|ctrlbit) (\S+)", mut))
    srcs = re.findall(r"-src (\S+)", mut)
    what = {"inv": "inverted", "const0": "tied to 0", "const1": "tied to 1",
            "cnot0": "XOR-ed with bit %s of the same signal, inverted when it is 0" % f.get("ctrlbit"),
            "cnot1": "XOR-ed with bit %s of the same signal, inverted when it is 1" % f.get("ctrlbit")}
    where = "%s[%s]" % (f["wire"], f.get("wirebit", "?")) if "wire" in f else \
        "port %s[%s] of %s" % (f.get("port", "?"), f.get("portbit", "?"), f.get("cell", "?"))
    return "%s %s (%s)" % (where, what.get(f.get("mode"), f.get("mode")), ", ".join(srcs))


def previous_design(opts, name):
    """--report-only, a design whose cache no longer holds a finished campaign (a single-mutant run such as the ctest
    overwrites it when the fingerprint changed): its complete entry of the report being replaced (--json), carried over
    as it was, with the commit of its sources, and marked so; a partial entry (a campaign stopped for time) is carried
    over as partial. None when that report has no entry of it."""
    try:
        prev = json.load(open(opts.json))
    except (OSError, ValueError):
        return None
    if prev.get("count") != opts.count or prev.get("seed") != opts.seed:
        return None
    for d in prev.get("designs", []):
        if d.get("name") == name and d.get("results"):
            keep = {k: d[k] for k in ("name", "unit", "handoff", "params", "stages", "timeouts", "source", "results")
                    if k in d}
            keep["results"] = unvoid(keep["results"])
            if len(d["results"]) < opts.count:  # a campaign stopped for time: carried as the partial run it was
                keep["partial"] = True
            return dict(keep, count=opts.count, seed=opts.seed, baseline=d.get("baseline_seconds"),
                        eq_timeout=d.get("equivalence_bound_seconds"),
                        carried=d.get("carried") or prev.get("date", "an earlier report"))
    return None


def write_report(opts, designs, md_path, json_path):
    reasons = json.load(open(REASONS)) if os.path.isfile(REASONS) else {}
    now = datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    machine = "%s, %d cores, %s" % (platform.node(), os.cpu_count() or 0, platform.platform())
    tools = tool_versions()
    regen = "scripts/mutation.py --count %d --seed %d --jobs %d" % (opts.count, opts.seed, opts.jobs) + \
        "".join(" --design %s" % d["name"] for d in designs)
    out = {"command": regen, "date": now, "machine": machine, "tools": tools, "count": opts.count,
           "seed": opts.seed, "vector_seed": opts.vec_seed, "vector_count": opts.vec_count,
           "not_run": NO_BENCH, "designs": []}
    L = ["<!-- SPDX-License-Identifier: Apache-2.0 -->",
         "# Mutation score of the handoff benches",
         "",
         "How many injected bugs the self-checking handoff bench kills (issue 36). Generated by "
         "`scripts/mutation.py` (its header has the method); the JSON beside it is docs/mutation.json.",
         "",
         "Method, in short: the unit's module is elaborated by Yosys with the parameters the bundle's wrapper "
         "gives it, flattened (its sub-modules are mutated too, inside this instance), and `mutate -list N "
         "-seed S` picks N mutations (invert a bit, tie it to 0 or 1, XOR it with another bit of its signal). "
         "Each mutant is written back as the module's own file and the bundle's `run_icarus.sh` runs with it, "
         "cheapest first: `hard` (the directed vectors), `random`, `nogap` (every vector, no input gaps and no "
         "backpressure: exact latency), `seed2` (other gaps and backpressure, a reset after 5 vectors), `extra` "
         "(more random vectors from `shadecore vectors`: for a unit 3 × %d with n in 16..31, 32..127, "
         "128..1024, seeds 11, 12, 13; for the lighting core one file of seed 11), `ports` (units: `shadecore vectors "
         "--mode ports`, seeds 21, 22, 23: n in 1..1024 (0..1024 for the dividers), thr over its F+1-bit port with codes around it — for the "
         "reference cs16 from |base| = 1 up, where its squarings stay in range — so a change seen only with a thr "
         "other than the host's thr(n) or an n in 1..15 shows), `exhaustive` "
         "(units that take a fragment every clock: the mutant Verilated with the bare harness `sim/bare_main.cpp` "
         "and run on every F+2-bit input code of every n = 16..1024 against the C model, its first mismatch the "
         "witness; a survivor of it computes the C model's function on the unit's whole input domain, which is "
         "recorded but is not a proof of equivalence); each "
         "stage is time-bounded (max(%d s, %g × the unmutated time)). A survivor counts as *equivalent* only "
         "when Yosys proves it, each proof bounded by the design's equivalence bound in CPU seconds (since 2026-12-07; "
         "wall-clock before, which a loaded machine could turn into 'not proved'): (0) for a tie to 0 or 1, the "
         "bit is that constant in the original from every state (`sat -seq 1 -prove`), else (a) a miter of original and "
         "mutant with every flip-flop exposed as a port pair (`dffunmap; splitnets; expose -dff -evert-dff; miter "
         "-equiv -ignore_gold_x; opt_merge; sat -enable_undef -set-def-inputs -prove trigger 0`: the same next state "
         "and outputs from every state; the undef model since EQ_METHOD 8, without which the miter compared only the "
         "bits where the original is 1), else (b) "
         "`equiv_make` (same-named nets paired, the mutated wire left out unless it is a port; a port left unpaired "
         "is refused), `equiv_simple -seq 8`, "
         "`equiv_induct -seq 8`, `equiv_status -assert`; memories mapped to logic first (`memory_map`); "
         "every other survivor is listed with its reason. Score = killed / (total − equivalent) (issue 36's "
         "figure, target >= 98 %%); the last column also leaves out the survivors whose written reason shows them "
         "equivalent for every input (by hand, where the 30 s Yosys bound did not reach) or under the unit's "
         "documented contract — a reading aid, not the score."
         % (opts.vec_count, opts.min_timeout, opts.timeout_factor),
         "",
         "Regenerate: `%s` (about %s min on this machine; cached per mutant in %s/, so a rerun resumes)."
         % (regen, "?", os.path.relpath(opts.work, ROOT) if opts.work.startswith(ROOT) else opts.work),
         "",
         "Machine: %s. Date: %s. Tools: %s; %s; Python %s. Mutation seed %d, vectors seed %d (%d random)."
         % (machine, now, tools["yosys"], tools["icarus"], tools["python"], opts.seed, opts.vec_seed,
            opts.vec_count),
         "",
         "| design | unit | mutants | killed (%s) | survived (by hand: all inputs / contract / other) | timed out "
         "| equivalent (proved) | score | score without the reasoned equivalents |" % " / ".join(STAGES),
         "|---|---|---:|---|---|---:|---:|---:|---:|"]
    total_min = 0.0
    for d in designs:
        s = summarise(d, reasons)
        total_min += sum(r.get("seconds", 0) for r in d["results"]) / 60.0 / max(1, opts.jobs)
        ks = s["killed_by_stage"]
        sc = s["survivors_by_reason"]
        L.append("| %s | %s | %d | %d (%s) | %d (%d / %d / %d) | %d | %d | %s | %s |" % (
            d["name"] + (" (partial: %d of %d run)" % (len(d["results"]), d["count"]) if d.get("partial") else "")
            + (" (carried over from the report of %s)" % d["carried"] if d.get("carried") else ""),
            d["unit"], s["total"], s["killed"], " / ".join(str(ks.get(st, 0)) for st in STAGES),
            s["survived"], sc["all"], sc["contract"], sc["other"], s["timeout"], s["equivalent"],
            "%.2f %%" % s["score"] if s["score"] is not None else "-",
            "%.2f %%" % s["score_reasoned"] if s["score_reasoned"] is not None else "-"))
        out["designs"].append({"name": d["name"], "unit": d["unit"], "handoff": d["handoff"],
                               "params": d["params"], "stages": d["stages"], "timeouts": d["timeouts"],
                               "baseline_seconds": d["baseline"], "summary": s,
                               "equivalence_bound_seconds": d.get("eq_timeout"), "source": d.get("source"),
                               **({"carried": d["carried"]} if d.get("carried") else {}),
                               # killed: id, stage and the first failure line; the others in full
                               "results": [{k: v for k, v in r.items() if k in ("id", "status", "stage", "detail")}
                                           if r["status"] == "killed" else r for r in d["results"]]})
    for n in getattr(opts, "pending", []):
        L.append("| %s | | - | not run yet (time) | | | | | |" % n)
    for n, why in NO_BENCH.items():
        L.append("| %s | sc_table | - | not run: %s | | | | | |" % (n, why))
    L[L.index("Regenerate: `%s` (about %s min on this machine; cached per mutant in %s/, so a rerun resumes)."
              % (regen, "?", os.path.relpath(opts.work, ROOT) if opts.work.startswith(ROOT) else opts.work))] = \
        "Regenerate: `%s` (about %.0f min of wall time on this machine for the mutants; cached per mutant in " \
        "%s/, so a rerun resumes)." % (regen, max(total_min, 1),
                                      os.path.relpath(opts.work, ROOT) if opts.work.startswith(ROOT) else opts.work)
    L += ["", "Bundles: `shadecore handoff <args> --seed %d --count %d --no-ice40 --synth skip --signoff off "
          "--out DIR`, per design:" % (opts.vec_seed, opts.vec_count), ""]
    for d in designs:
        L.append("- %s: `%s` (sources of commit %s); unit %s with %s; stage time limits %s s; equivalence "
                 "bound %s s" % (
                     d["name"], d["handoff"], d.get("source", "?")[:12], d["unit"],
                     ", ".join("%s=%s" % kv for kv in d["params"].items()) or "no parameters",
                     " / ".join("%s %.0f" % (st, t) for st, t in d["timeouts"].items()), d.get("eq_timeout", "?")))
    L += ["", "## Survivors", "",
          "Each survivor that is not proved equivalent, with what the mutation does and why the bench misses it "
          "(scripts/mutation_reasons.json). \"Equivalent under the contract\" means no input that obeys the unit's "
          "documented contract can show the change; \"equivalent for every input\" means the reason is a proof by "
          "hand that the Yosys bound did not reach. Terms:", ""]
    for term, text in sorted(reasons.get("_definitions", {}).items()):
        L.append("- **%s**: %s" % (term, text))
    L.append("")
    missing = 0
    for d in designs:
        surv = [r for r in d["results"] if r["status"] in ("survived", "timeout", "error")]
        L.append("### %s" % d["name"])
        L.append("")
        note = reasons.get("_notes", {}).get(d["name"])
        if note:
            L += ["Review note (not a per-mutant reason): " + note, ""]
        if not surv:
            L.append("None: every non-equivalent mutant is killed.")
        for r in surv:
            key = "%s:%d" % (d["name"], r["id"])
            why = reasons.get(key)
            if why is None and r["status"] == "survived":
                missing += 1
            exh = ("; exhaustive stage: equal to the C model on every input code of every n = 16..1024"
                   if r["status"] == "survived" and "exhaustive" in r.get("stages", []) else "")
            L.append("- m%03d %s — %s%s%s%s" % (
                r["id"], r["status"], describe(r["mutation"]),
                ("; " + r["equivalence"]) if r.get("equivalence") else
                ("; equivalence not attempted yet" if r["status"] == "survived" else ""), exh,
                ("; " + r["detail"]) if r["status"] != "survived" and r.get("detail") else ""))
            L.append("  - reason: %s" % (why or "(none written yet)"))
            L.append("  - `%s`" % r["mutation"])
        eqs = [r for r in d["results"] if r["status"] == "equivalent"]
        if eqs:
            L.append("")
            L.append("Proved equivalent (%d): %s." % (len(eqs), ", ".join("m%03d %s" % (r["id"], describe(r["mutation"]))
                                                                         for r in eqs)))
        L.append("")
    L += ["Table units (table256, table1024): not run — %s." % NO_BENCH["table256"], ""]
    if reasons.get("_findings"):
        L += ["## Findings and what is left", ""] + ["- " + t for t in reasons["_findings"]] + [""]
    with open(md_path, "w") as f:
        f.write("\n".join(L))
    with open(json_path, "w") as f:
        json.dump(out, f, indent=1)
    return missing


# ----------------------------------------------------------------------------------------------------


def main(argv):
    names = [d[0] for d in DESIGNS]
    ap = OneLineParser(description="Mutation score of the handoff benches (docs/mutation.md).")
    ap.add_argument("--design", action="append", help="design point (repeatable; default all): " + ", ".join(names))
    ap.add_argument("--count", type=int, default=300, help="mutants per design (mutate -list N), default 300")
    ap.add_argument("--seed", type=int, default=1, help="mutate -seed, default 1")
    ap.add_argument("--jobs", type=int, default=2, help="parallel simulations (1..2 on this machine), default 2")
    ap.add_argument("--mutant", type=int, action="append", help="run only this mutant id (repeatable; no report)")
    ap.add_argument("--pick", metavar="REGEX",
                    help="run the first mutant whose mutate command matches REGEX (as --mutant; no report)")
    ap.add_argument("--expect", choices=["killed", "survived", "timeout", "equivalent"],
                    help="with --mutant: exit 0 only if every chosen mutant has this result")
    ap.add_argument("--stages", default=",".join(STAGES), help="checks in order (default %s)" % ",".join(STAGES))
    ap.add_argument("--cli", default=os.path.join(ROOT, "build", "cli", "shadecore"), help="the shadecore CLI")
    ap.add_argument("--work", default=os.path.join(ROOT, "build-mutation"), help="work and cache directory")
    ap.add_argument("--source", default="HEAD", help="the commit whose RTL the bundles take (default HEAD)")
    ap.add_argument("--vec-seed", type=int, default=1, help="handoff --seed (vectors, gaps), default 1")
    ap.add_argument("--vec-count", type=int, default=2000, help="handoff --count, default 2000")
    ap.add_argument("--min-timeout", type=float, default=20.0, help="seconds, lower bound of a stage's time limit")
    ap.add_argument("--timeout-factor", type=float, default=5.0, help="stage time limit / unmutated time, default 5")
    ap.add_argument("--eq-timeout", type=int, default=30, help="CPU seconds for each equivalence proof (0: skip)")
    ap.add_argument("--eq-steps", type=int, default=8, help="equiv_simple/equiv_induct -seq N, default 8")
    ap.add_argument("--md", default=os.path.join(ROOT, "docs", "mutation.md"))
    ap.add_argument("--json", default=os.path.join(ROOT, "docs", "mutation.json"))
    ap.add_argument("--no-report", action="store_true", help="do not write docs/mutation.md and .json")
    ap.add_argument("--no-cache", action="store_true", help="run every chosen mutant again (the cache is rewritten)")
    ap.add_argument("--list", action="store_true", help="print the design points and exit")
    ap.add_argument("--report-only", action="store_true",
                    help="write docs/mutation.md and .json from the finished designs' caches, run nothing")
    opts = ap.parse_args(argv)
    if opts.list:
        for n, a, u in DESIGNS:
            log("%-18s %s" % (n, " ".join(a)))
        for n, why in NO_BENCH.items():
            log("%-18s not run: %s" % (n, why))
        return 0
    for d in opts.design or []:
        if d in NO_BENCH:
            ap.error("--design %s: %s" % (d, NO_BENCH[d]))
        if d not in names:
            ap.error("--design %s: unknown (one of %s)" % (d, ", ".join(names)))
    if not 1 <= opts.count <= 100000:
        ap.error("--count must be 1..100000")
    cores = os.cpu_count() or 1
    if not 1 <= opts.jobs <= max(2, cores):
        ap.error("--jobs must be 1..%d" % max(2, cores))
    opts.stages = [s.strip() for s in opts.stages.split(",") if s.strip()]
    bad = [s for s in opts.stages if s not in STAGES]
    if bad or not opts.stages:
        ap.error("--stages: unknown stage %s (of %s)" % (",".join(bad) or "(none)", ",".join(STAGES)))
    if opts.pick:
        try:
            re.compile(opts.pick)
        except re.error as e:
            ap.error("--pick: bad regular expression (%s)" % e)
    single = opts.mutant or opts.pick
    if opts.expect and not single:
        ap.error("--expect needs --mutant or --pick")
    if opts.report_only and single:
        ap.error("--report-only takes no --mutant or --pick")
    if single and (not opts.design or len(opts.design) != 1):
        ap.error("--mutant and --pick need exactly one --design")
    if opts.min_timeout <= 0 or opts.timeout_factor <= 0 or opts.eq_timeout < 0 or opts.eq_steps < 1:
        ap.error("time limits must be positive")
    if not (os.path.isfile(opts.cli) and os.access(opts.cli, os.X_OK)):
        ap.error("no shadecore CLI at %s (build it, or --cli)" % opts.cli)
    for tool in ("yosys", "iverilog", "vvp"):
        if not shutil.which(tool):
            ap.error("%s not found" % tool)
    opts.work = os.path.abspath(opts.work)
    chosen = [d for d in DESIGNS if not opts.design or d[0] in opts.design]
    results = []
    if opts.report_only:
        results = [r for r in (cached_design(opts, d[0]) or previous_design(opts, d[0]) for d in chosen) if r]
        missing = [d[0] for d in chosen if d[0] not in [r["name"] for r in results]]
        opts.pending = missing
        write_report(opts, results, opts.md, opts.json)
        log("wrote %s and %s from %d finished design(s)%s" % (opts.md, opts.json, len(results),
                                                         "; not finished: " + ", ".join(missing) if missing else ""))
        return 0
    try:
        opts.commit, opts.src_dir = snapshot(opts)
    except ArgError as e:
        die(str(e), 2)
    except RuntimeError as e:
        die(str(e))
    failed = []
    for name, hargs, unit in chosen:
        try:
            results.append(run_design(opts, name, hargs, unit, only=list(opts.mutant or [])))
        except ArgError as e:
            die(str(e), 2)
        except RuntimeError as e:
            if len(chosen) == 1:
                die("%s: %s" % (name, e))
            log("[%s] not run: %s" % (name, str(e).replace("\n", " | ")[:400]))
            failed.append(name)
            continue
        s = summarise(results[-1])
        log("[%s] mutants %d killed %d survived %d timeout %d equivalent %d error %d score %s %%" % (
            name, s["total"], s["killed"], s["survived"], s["timeout"], s["equivalent"], s["error"], s["score"]))
    if single:
        bad = [r for d in results for r in d["results"] if opts.expect and r["status"] != opts.expect]
        for d in results:
            for r in d["results"]:
                log("%s m%03d %s %s %s" % (d["name"], r["id"], r["status"], r.get("stage", ""), r.get("detail", "")))
        if bad:
            die("%d mutant(s) not %s" % (len(bad), opts.expect))
        return 0
    opts.pending = failed
    if not opts.no_report:
        missing = write_report(opts, results, opts.md, opts.json)
        log("wrote %s and %s%s" % (opts.md, opts.json,
                                   " (%d survivors without a reason)" % missing if missing else ""))
    return 1 if failed else 0


def main_term(signum, frame):
    raise KeyboardInterrupt


if __name__ == "__main__":
    signal.signal(signal.SIGTERM, main_term)  # kill PID: the workers and their simulations stop too
    signal.signal(signal.SIGINT, signal.default_int_handler)  # also when started in the background
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:
        die("interrupted (finished mutants are in the cache; run again to resume)", 130)
