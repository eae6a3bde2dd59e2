#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Gappa proofs of the units' quantisation contracts (issue 21, docs/bounds.md §3).

The Gappa scripts are generated from config/configs.json (widths F, G of every named configuration; the
cs16 forms' "squarer" entries: rel_guard, stage_frac, keep, compensate, turned into the stage widths,
dropped columns and constants by the rule of docs/spec.md §3.4, the same rule as rtl/sc_cs16.v's
localparams). For each unit × width the script states the contract as a Gappa goal; Gappa either proves
it (exit 0) or prints the best enclosure it found (then the contract is "not closed" and the report says
which hypothesis is missing). A second query `in ?` prints the enclosure Gappa proves.

  scripts/gappa_bounds.py run [--json out/bounds/gappa.json] [--keep DIR] [--filter RE]
  scripts/gappa_bounds.py show UNIT CONFIG            print one generated script

Exit status 0 when every contract that is expected to close did close (and none expected open closed
unexpectedly: a tightening must update docs), 1 otherwise.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from fractions import Fraction as Q

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load_config():
    with open(os.path.join(ROOT, "config", "configs.json")) as f:
        return json.load(f)


def clog2(v):
    r = 0
    while (1 << r) < v:
        r += 1
    return r


def b(q):
    """A rational with a power-of-two denominator in Gappa's binary notation (mb e)."""
    q = Q(q)
    if q == 0:
        return "0"
    e = 0
    while q.denominator != 1:
        q *= 2
        e -= 1
    m = q.numerator
    while m % 2 == 0:
        m //= 2
        e += 1
    return "%db%d" % (m, e)


def squarer_stages(F, G, sq):
    """Stage widths and squarer constants of a cs16 form (docs/spec.md §3.4; rtl/sc_cs16.v FORM = 1)."""
    WB = F + (G if sq["rel_guard"] else 0)
    W = [F + 4] + [WB + a for a in sq["stage_frac"]]          # W0..W4 (W4 places stage 4's truncation)
    shifts = [2 * W[0] - W[1], 2 * W[1] - W[2], 2 * W[2] - W[3], 2 * W[3] - F]
    out_w = [W[1], W[2], W[3], F]
    st = []
    for k in range(4):
        N = W[k]
        d = 2 * W[k] - W[k + 1] - (clog2(N) + sq["keep"][k])
        d = max(0, min(d, shifts[k]))
        comp = 1 if sq["compensate"] else 0
        rnd = comp if k < 3 else 1
        # dropped bits: diagonal x_i at column 2i, off-diagonal x_i x_j (i < j) at column i+j+1
        dmax = 0
        e4 = 0
        for i in range(N):
            if 2 * i < d:
                dmax += 1 << (2 * i)
                e4 += 1 << (2 * i + 1)
            for j in range(i + 1, N):
                if i + j + 1 < d:
                    dmax += 1 << (i + j + 1)
                    e4 += 1 << (i + j + 1)
        c = ((e4 + 2) >> 2) if comp else 0
        if rnd:
            c += 1 << (shifts[k] - 1)
        st.append(dict(N=N, SHIFT=shifts[k], DROP=d, RND=rnd, ECOMP=comp, C=c, DMAX=dmax, WOUT=out_w[k]))
    return W, st


def contract(kind, F, G):
    """(lo, hi) of out − 2^F·y in ulps, closed (Gappa proves closed intervals)."""
    if kind in ("reference", "faithful"):
        return (-(Q(1, 2) + Q(15, 2 ** G)), Q(1, 2))
    if kind == "compact":
        return (Q(-1), Q(1))
    if kind == "exact":
        return (Q(-1, 2), Q(1, 2))
    raise ValueError(kind)


def script_cs16_ref(F, G):
    W = F + G
    lo, hi = contract("reference", F, G)
    u = Q(1, 2 ** F)
    return """# cs16 reference datapath (docs/spec.md §3.2), F = %(F)d, G = %(G)d, W = %(W)d: x0 = |base| exact with
# F+4 fraction bits, x0 <= 1 (spec §3.2), four squarings truncated to W bits, output rounded half up to F.
@tw = fixed<-%(W)d,dn>;
@to = fixed<-%(F)d,nu>;
@b0 = fixed<-%(F4)d,dn>;
x0 = b0(X);
x1 = tw(x0 * x0);
x2 = tw(x1 * x1);
x3 = tw(x2 * x2);
x4 = tw(x3 * x3);
out = to(x4);
Y1 = x0 * x0;
Y2 = Y1 * Y1;
Y3 = Y2 * Y2;
Y4 = Y3 * Y3;
{ X in [0,1] -> out - Y4 in [%(lo)s, %(hi)s] }
x2 - Y2 -> (x2 - x1 * x1) + (x1 - Y1) * (x1 + Y1);
x3 - Y3 -> (x3 - x2 * x2) + (x2 - Y2) * (x2 + Y2);
x4 - Y4 -> (x4 - x3 * x3) + (x3 - Y3) * (x3 + Y3);
""" % dict(F=F, G=G, W=W, F4=F + 4, lo=b(lo * u), hi=b(hi * u))


def script_cs16_form(F, G, sq, kind):
    W, st = squarer_stages(F, G, sq)
    lo, hi = contract(kind, F, G)
    u = Q(1, 2 ** F)
    L = ["# cs16 form (%s contract, docs/spec.md §3.4), F = %d, G = %d: stage widths W0..W3 = %s, output F bits." %
         (kind, F, G, ", ".join(str(w) for w in W[:4])),
         "# Squaring k: x_k = floor((x_(k-1)^2 - d_k + C_k) / 2^SHIFT_k), d_k the dropped partial-product bits,",
         "# 0 <= d_k <= DMAX_k (every dropped bit 1: a bound, not always reachable), C_k the constant of sc_square.",
         "# x0 < 1 here (x0 = 1.0 passes the integer bit through every stage and is exact: out = 1.0 = y).",
         "@b0 = fixed<-%d,dn>;" % (F + 4),
         "x0 = b0(X);"]
    prev = "x0"
    hyp = []
    for k, s in enumerate(st, 1):
        win = W[k - 1]
        scale = Q(1, 2 ** (2 * win))
        L.append("# k = %d: N = %d, SHIFT = %d, DROP = %d, RND = %d, ECOMP = %d, C = %d, DMAX = %d" %
                 (k, s["N"], s["SHIFT"], s["DROP"], s["RND"], s["ECOMP"], s["C"], s["DMAX"]))
        L.append("@t%d = fixed<-%d,dn>;" % (k, s["WOUT"]))
        L.append("x%d = t%d(%s * %s - d%d + %s);" % (k, k, prev, prev, k, b(s["C"] * scale)))
        hyp.append("d%d in [0, %s]" % (k, b(s["DMAX"] * scale)))
        # the kept bits are a subset of the bits of x^2: 0 <= x^2 - d (the kept sum is not negative)
        hyp.append("%s * %s - d%d in [0, 1]" % (prev, prev, k))
        prev = "x%d" % k
    L += ["Y1 = x0 * x0;", "Y2 = Y1 * Y1;", "Y3 = Y2 * Y2;", "Y4 = Y3 * Y3;"]
    goal = "out - Y4 in [%s, %s]" % (b(lo * u), b(hi * u))
    # no wrap: every x_k (k = 1..3) stays below 1.0 (the squarer's result has no integer bit for x0 < 1)
    nowrap = " /\\ ".join("x%d in [0, %s]" % (k, b(1 - Q(1, 2 ** W[k]))) for k in (1, 2, 3))
    L.append("out = x4;")
    L.append("{ X in [0, %s] /\\ %s -> %s /\\ %s }" % (b(1 - Q(1, 2 ** (F + 4))), " /\\ ".join(hyp), nowrap, goal))
    L.append("x2 - Y2 -> (x2 - (x1 * x1 - d2 + %s)) + (%s - d2) + (x1 - Y1) * (x1 + Y1);" %
             (b(st[1]["C"] * Q(1, 2 ** (2 * W[1]))), b(st[1]["C"] * Q(1, 2 ** (2 * W[1])))))
    L.append("x3 - Y3 -> (x3 - (x2 * x2 - d3 + %s)) + (%s - d3) + (x2 - Y2) * (x2 + Y2);" %
             (b(st[2]["C"] * Q(1, 2 ** (2 * W[2]))), b(st[2]["C"] * Q(1, 2 ** (2 * W[2])))))
    L.append("x4 - Y4 -> (x4 - (x3 * x3 - d4 + %s)) + (%s - d4) + (x3 - Y3) * (x3 + Y3);" %
             (b(st[3]["C"] * Q(1, 2 ** (2 * W[3]))), b(st[3]["C"] * Q(1, 2 ** (2 * W[3])))))
    L.append("x1 - Y1 -> (x1 - (x0 * x0 - d1 + %s)) + (%s - d1);" %
             (b(st[0]["C"] * Q(1, 2 ** (2 * W[0]))), b(st[0]["C"] * Q(1, 2 ** (2 * W[0])))))
    return "\n".join(L) + "\n"


def script_schlick_div(F):
    lo, hi = contract("exact", F, 0)
    u = Q(1, 2 ** F)
    return """# schlick_div / schlick_iter (docs/spec.md §6.3 a, c), F = %(F)d: q = floor(2^(F+1)·c/Dc) exactly (restoring
# division), out = (q + 1) >> 1. For any real y, floor((floor(2y) + 1)/2) = floor(y + 1/2) (nested floor
# division by the integer 2), so out = S rounded half up to F bits, S = c/Dc in [0, 1] (spec §6.2).
@to = fixed<-%(F)d,nu>;
out = to(S);
{ S in [0,1] -> out - S in [%(lo)s, %(hi)s] }
""" % dict(F=F, lo=b(lo * u), hi=b(hi * u))


def units():
    """(unit, config, script, contract kind, expected to close)."""
    cfg = load_config()
    out = []
    for c in cfg["configs"]:
        F, G = c["frac"], c["guard"]
        out.append(("cs16", c["name"], script_cs16_ref(F, G), "reference", True, F, G))
        for v in cfg["variants"]:
            if "squarer" in v:
                out.append((v["name"], c["name"], script_cs16_form(F, G, v["squarer"], v["contract"]), v["contract"],
                            None, F, G))
        out.append(("schlick_div", c["name"], script_schlick_div(F), "exact", True, F, G))
    return out


def run_gappa(text, keep=None, name="x"):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(keep or d, name + ".g")
        if keep:
            os.makedirs(keep, exist_ok=True)
        with open(path, "w") as f:
            f.write(text)
        t0 = time.monotonic()
        p = subprocess.run(["gappa", path], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=600)
        dt = time.monotonic() - t0
        # the enclosure Gappa can prove: the same script with the goal's interval replaced by "?"
        q = re.sub(r"out - Y4 in \[[^\]]*\]|out - S in \[[^\]]*\]",
                   lambda m: m.group(0).split(" in ")[0] + " in ?", text)
        q = re.sub(r"-> x1 in \[[^\]]*\] /\\ x2 in \[[^\]]*\] /\\ x3 in \[[^\]]*\] /\\", "->", q)
        path2 = os.path.join(keep or d, name + ".query.g")
        with open(path2, "w") as f:
            f.write(q)
        p2 = subprocess.run(["gappa", path2], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=600)
    enc = None
    m = re.search(r"in \[\S+ \{([-+0-9.e]+), [^}]*\}, \S+ \{([-+0-9.e]+), [^}]*\}\]", p2.stdout + p2.stderr)
    if m:
        enc = (m.group(1), m.group(2))
    else:
        m = re.search(r"in \[(-?\d+b-?\d+|0) \{([-+0-9.e]+)[^}]*\}, (-?\d+b-?\d+) \{([-+0-9.e]+)", p2.stdout)
        if m:
            enc = (m.group(2), m.group(4))
    best = None
    m = re.search(r"BND\((?:out - Y4|out - S)\), best: \[([^,\]]+), ([^\]]+)\]", p.stderr)
    if m:
        best = (m.group(1), m.group(2))
    return dict(proved=p.returncode == 0, seconds=round(dt, 3), enclosure=enc, best=best,
                stderr=p.stderr.strip().splitlines()[-3:] if p.returncode else [])


def load(path):
    if not os.path.exists(path):
        return None
    return json.load(open(path))


def report_section(g):
    L = ["## 3. Quantisation contracts, proved (Gappa)\n"]
    if not g:
        L.append("Not run (`scripts/gappa_bounds.py run --json out/bounds/gappa.json` before `scripts/bounds.py all`).\n")
        return "\n".join(L)
    L.append("`scripts/gappa_bounds.py run` (Gappa 1.4.1; scripts generated from config/configs.json; `show UNIT CONFIG` prints "
             "one). Error = out − 2^F·y in output ulps, y the real-number value of the same input (cs16: x0^16 with x0 = |base|; "
             "Schlick: S = c/Dc). Gappa proves closed intervals, so a strict bound of the spec is proved in its closed form. "
             "Measured extremes: docs/spec.md §3.3, §3.4 and §6.4 (`shadecore sweep`, exhaustive).\n")
    L.append("| unit | width | contract (ulp) | Gappa | enclosure Gappa proves (ulp) | s |")
    L.append("|---|---|---|---|---|---|")
    for r in g["rows"]:
        enc = "—"
        if r["enclosure"]:
            F = r["F"]
            try:
                lo = float(r["enclosure"][0]) * 2 ** F
                hi = float(r["enclosure"][1]) * 2 ** F
                enc = "[%.6g, %.6g]" % (lo, hi)
            except ValueError:
                enc = "[%s, %s]" % r["enclosure"]
        L.append("| `%s` | %s (F = %d, G = %d) | [%s, %s] | %s | %s | %.2f |" % (
            r["unit"], r["config"], r["F"], r["G"], r["contract"][0], r["contract"][1],
            "**proved**" if r["proved"] else "not closed", enc, r["seconds"]))
    L.append("")
    L.append(g.get("notes", ""))
    return "\n".join(L)


NOTES = """Where a contract is not closed, the missing hypothesis is named rather than the bound widened:

- `cs16_faithful`, `cs16_compact` (not closed where marked): the only fact Gappa gets about a truncated squarer is
  0 ≤ d_k ≤ DMAX_k for the dropped partial-product bits (every dropped bit 1). That bound is reached only by
  inputs whose low bits are all ones, which are not the inputs that drive the other stages' errors to their
  extremes; the contracts hold (exhaustive check over every x0, `shadecore sweep --variant FORM --bases`,
  docs/spec.md §3.4) because of that correlation. The missing hypothesis is a joint bound on (x_(k−1), d_k)
  (d_k as a function of the low bits of x_(k−1)); it is not expressible as an independent interval.
- `schlick_nr`, `normalize3` (sc_normalize), `recip_att` (sc_recip): not attempted in Gappa yet. Their
  bounds rest on the seed tables' worst cases (ε0 = 0.0080872 of `SchlickNr.TableWorstCase`, the rsqrt
  seed rule), which are exhaustive C++ checks; a Gappa proof needs them as hypotheses
  (|1 − md·y0| ≤ ε0 per table interval) plus the truncation chain of spec §6.3 b / §8.
- `schlick_div` uses the integer identity ⌊(⌊2y⌋ + 1)/2⌋ = ⌊y + ½⌋ (the restoring quotient is exact), so
  its Gappa proof is one rounding; the bit-exact check against the integer formula is the exhaustive test of
  docs/spec.md §6.4.
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--json")
    r.add_argument("--keep")
    r.add_argument("--filter", default=".")
    s = sub.add_parser("show")
    s.add_argument("unit")
    s.add_argument("config")
    t = sub.add_parser("tighter", help="the cs16 reference contract with its lower end raised by 2^-G ulp: "
                       "Gappa must not prove it (shows that the check can fail)")
    t.add_argument("unit", choices=["cs16"])
    t.add_argument("config")
    args = ap.parse_args()
    if args.cmd == "tighter":
        cfg = load_config()
        c = [c for c in cfg["configs"] if c["name"] == args.config]
        if not c:
            print("gappa_bounds: unknown config %s" % args.config, file=sys.stderr)
            return 1
        F, G = c[0]["frac"], c[0]["guard"]
        text = script_cs16_ref(F, G)
        lo, hi = contract("reference", F, G)
        tight = (lo + Q(1, 2 ** G)) * Q(1, 2 ** F)
        old = "out - Y4 in [%s," % b(lo * Q(1, 2 ** F))
        if text.count(old) != 1:
            print("gappa_bounds: goal not found in the generated script", file=sys.stderr)
            return 1
        r = run_gappa(text.replace(old, "out - Y4 in [%s," % b(tight)))
        ok = run_gappa(text)["proved"]
        print("gappa: contract %s; tightened to lower end %s ulp: %s" %
              ("proved" if ok else "NOT proved", lo + Q(1, 2 ** G), "proved (unexpected)" if r["proved"] else "not proved"))
        if ok and not r["proved"]:
            print("gappa: tighter contract rejected")
            return 0
        return 1
    if args.cmd == "show":
        for u, c, text, *_ in units():
            if u == args.unit and c == args.config:
                sys.stdout.write(text)
                return 0
        print("gappa_bounds: no script for %s %s" % (args.unit, args.config), file=sys.stderr)
        return 1
    rows, ok = [], True
    for u, c, text, kind, expect, F, G in units():
        if not re.search(args.filter, "%s.%s" % (u, c)):
            continue
        res = run_gappa(text, args.keep, "%s_%s" % (u, c))
        lo, hi = contract(kind, F, G)
        row = dict(unit=u, config=c, F=F, G=G, contract=[str(lo), str(hi)], kind=kind, **res)
        rows.append(row)
        if expect is True and not res["proved"]:
            ok = False
        print("gappa: %-14s %-8s contract [%s, %s] ulp: %s (%.2f s)%s" % (
            u, c, lo, hi, "PROVED" if res["proved"] else "not closed", res["seconds"],
            "" if res["proved"] else "  best %s" % (res["best"],)))
    if args.json:
        os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
        json.dump(dict(rows=rows, notes=NOTES), open(args.json, "w"), indent=1)
    print("gappa: %s" % ("PASS" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
