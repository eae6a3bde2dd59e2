#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Checks of the RTL coverage machinery (issue 36, docs/coverage.md), counted by hand here, independently of
cli/coverage.cpp.

--quick (ctest coverage.summary, a second or two): Verilator databases written here by hand (two runs of two
  modules: line, branch and toggle points, two parameterisations of one module) through `shadecore coverage`:
  the merge sums the runs, the per-module hit / total / waived / percent equal the hand count, a waiver applies
  to what it names (by source text, file, signal glob); a waiver that matches nothing, a waived point that was
  hit, a malformed waiver file and a file that is no database are each a one-line error with exit 1 and nothing
  written; so is a report directory that is a file or under /proc or /sys (cosim --coverage, coverage --out).
--run (ctest coverage.regress, label long: builds the coverage model of cs16 once, ~2 min, then cached):
  `shadecore regress --plan tests/data/coverage/tiny.json --local --coverage` — every co-simulation shard writes
  its database, the merge after the run equals the hand-made union of the shards' databases module by module,
  merged.json carries that summary, the HTML report is there, and a rerun of the same --out (resume) runs nothing
  and writes the same merged.json; `--until-coverage` adds closure rounds of new seeds until a target is met or
  --max-rounds stops it (exit 2, what is below target and its holes named), resumes them, and stops at once when
  the targets are met.
--params-run (ctest coverage.params, label long: two lighting coverage cores, then cached): the parameterisation of
  real coverage builds — diffuse at share 1 and at share 2 — and the project's share-1 waiver of mp_fld applying to
  the share-1 pool only (the share-2 one is hit).
The quick mode also checks the parameterisations (params_quick): verilator --xml-only maps, canonical module names
  independent of Verilator's __piN numbers, and waivers keyed to parameters ("params").
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from collections import defaultdict

FAILS = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        FAILS.append(what)


def key(**kv):
    order = ["f", "l", "n", "page", "o", "S", "h"]
    return "".join("\x01%s\x02%s" % (k, kv[k]) for k in order if k in kv)


def write_dat(path, points):
    with open(path, "w") as f:
        f.write("# SystemC::Coverage-3\n")
        for k, c in points:
            f.write("C '%s' %d\n" % (k, c))


def parse_dat(path):
    pts = {}
    with open(path, encoding="utf-8", errors="surrogateescape") as f:
        assert f.readline().startswith("# SystemC::Coverage")
        for line in f:
            if not line.startswith("C '"):
                continue
            q2 = line.rindex("'")
            pts[line[3:q2]] = pts.get(line[3:q2], 0) + int(line[q2 + 1:])
    return pts


def fields(k):
    out = {}
    for part in k.split("\x01")[1:]:
        a, b = part.split("\x02", 1)
        out[a] = b
    return out


KIND = {"v_line": "line", "v_branch": "branch", "v_toggle": "toggle", "v_func": "functional"}


def hand_summary(points):
    """module -> kind -> [hit, total] (no waivers); a point reached through both harnesses (hierarchy under "dut."
    or "TOP.") is one point."""
    same = {}
    for k, c in points.items():
        fl = fields(k)
        fl["h"] = fl.get("h", "").split(".", 1)[-1]
        ident = tuple(sorted(fl.items()))
        same[ident] = same.get(ident, 0) + c
    s = defaultdict(lambda: defaultdict(lambda: [0, 0]))
    for ident, c in same.items():
        fl = dict(ident)
        typ, mod = fl["page"].split("/", 1)
        kind = KIND.get(typ, typ)
        if kind != "functional" and "__" in mod:
            mod = mod[:mod.index("__")]
        s[mod][kind][1] += 1
        if c > 0:
            s[mod][kind][0] += 1
    return s


def run(cmd, **kw):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def quick(sc, work):
    src = os.path.join(work, "rtl_a.v")
    with open(src, "w") as f:
        f.write("module a;\n  always @(posedge clk) q <= d;\n  default: y = 0;  // defensive\n  if (x) z = 1;\n"
                "  function integer fsize(input integer x);\n    fsize = x + 1;\n  endfunction\n")
    A = dict(f=src, h="TOP.a")
    run1 = [
        (key(l=2, n=3, page="v_line/a", o="block", **A), 7),
        (key(l=3, n=5, page="v_line/a", o="case", **A), 0),       # the defensive default: never hit
        (key(l=6, n=5, page="v_line/a", o="block", **A), 0),      # inside the constant function fsize
        (key(l=4, n=3, page="v_branch/a", o="if", **A), 0),
        (key(l=4, n=4, page="v_branch/a", o="else", **A), 3),
        (key(l=1, n=9, page="v_toggle/a", o="tag[0]", **A), 4),
        (key(l=1, n=9, page="v_toggle/a", o="tag[31]", **A), 0),  # a constant-tied bit: waived by signal glob
        (key(l=1, n=9, page="v_toggle/b__W8", o="q[0]", f=src, h="TOP.a.u_b8"), 0),
        (key(l=1, n=9, page="v_toggle/b__W4", o="q[0]", f=src, h="TOP.a.u_b4"), 2),
    ]
    run2 = [
        (key(l=4, n=3, page="v_branch/a", o="if", **A), 5),       # the second run reaches the if
        (key(l=1, n=9, page="v_toggle/b__W8", o="q[0]", f=src, h="TOP.a.u_b8"), 0),
        (key(l=1, n=9, page="v_toggle/b__W8", o="q[1]", f=src, h="TOP.a.u_b8"), 1),
        (key(l=2, n=3, page="v_line/a", o="block", f=src, h="dut.a"), 0),  # the same point through the SystemC harness
    ]
    d1, d2 = os.path.join(work, "r1.dat"), os.path.join(work, "r2.dat")
    write_dat(d1, run1)
    write_dat(d2, run2)
    good = os.path.join(work, "good.json")
    with open(good, "w") as f:
        json.dump({"waivers": [
            {"id": "a-default", "module": "a", "kind": "line", "source": "default: y = 0;",
             "reason": "defensive default of a case whose selector takes only listed values"},
            {"id": "a-elab-function", "module": "a", "kind": "line", "function": "fsize",
             "reason": "a constant function evaluated at elaboration only"},
            {"id": "a-tag-msb", "module": "a", "kind": "toggle", "signal": "tag[3?]",
             "reason": "tag bits above the testbench's tag width are tied low"},
            {"id": "zz-absent", "module": "zz_*", "kind": "toggle", "signal": "*",
             "reason": "a module this database does not hold: not applicable, no error"},
        ]}, f)
    out = os.path.join(work, "out")
    r = run([sc, "coverage", d1, d2, "--out", out, "--waivers", good, "--no-html"])
    check(r.returncode == 0, "shadecore coverage on two hand-made runs exits 0 (%s)" % r.stderr.strip())
    if r.returncode != 0:
        return
    merged = parse_dat(os.path.join(out, "coverage.dat"))
    union = parse_dat(d1)
    for k, c in parse_dat(d2).items():
        union[k] = union.get(k, 0) + c
    check(merged == union, "the merged database is the sum of the two runs (%d keys)" % len(union))
    s = json.load(open(os.path.join(out, "summary.json")))
    mods = {m["module"]: m for m in s["modules"]}
    # By hand: module a: line 1 hit of 3 (2 waived: the default by source, fsize's line by function; "dut.a" and
    # "TOP.a" are one point) -> 1/1 = 100 %; branch 2/2; toggle tag[0] hit, tag[31] waived -> 1/1.
    # Module b (two parameterisations, W8 and W4): toggle W8 q[0] 0, W8 q[1] 1, W4 q[0] 2 -> 2 of 3.
    expect = {"a": {"line": (1, 3, 2, 100.0), "branch": (2, 2, 0, 100.0), "toggle": (1, 2, 1, 100.0)},
              "b": {"toggle": (2, 3, 0, 66.66)}}
    for m, kinds in expect.items():
        for k, (hit, tot, wv, pc) in kinds.items():
            got = mods.get(m, {}).get(k, {})
            check((got.get("hit"), got.get("total"), got.get("waived"), got.get("percent")) == (hit, tot, wv, pc),
                  "%s %s: hit %d, total %d, waived %d, %.2f %% (summary: %s)" % (m, k, hit, tot, wv, pc, got))
    check(s["totals"]["toggle"]["hit"] == 3 and s["totals"]["toggle"]["total"] == 5, "totals add the modules")
    check([a["id"] for a in s["waivers"]["applied"]] == ["a-default", "a-elab-function", "a-tag-msb"] and
          s["waivers"]["not_applicable"] == ["zz-absent"], "applied and not-applicable waivers are listed")
    check(s["holes"].get("b") == ["toggle q[0] (rtl_a.v:1 a.u_b8)"], "the one hole of b is named: %s" % s["holes"].get("b"))
    hand = hand_summary(union)
    check(hand["b"]["toggle"] == [2, 3] and hand["a"]["branch"] == [2, 2], "the hand count agrees with itself")

    def refused(waivers, needle, what, dats=(d1, d2)):
        wf = os.path.join(work, "w_%d.json" % len(os.listdir(work)))
        with open(wf, "w") as f:
            f.write(waivers if isinstance(waivers, str) else json.dumps({"waivers": waivers}))
        o = os.path.join(work, "refused_%d" % len(os.listdir(work)))
        r = run([sc, "coverage", *dats, "--out", o, "--waivers", wf, "--no-html"])
        lines = [x for x in r.stderr.splitlines() if x.strip()]
        check(r.returncode == 1 and len(lines) == 1 and needle in lines[0] and not os.path.exists(o) and
              not any(x.startswith(os.path.basename(o)) for x in os.listdir(work)),
              "%s: exit 1, one line naming it, nothing written (%r)" % (what, lines[-1] if lines else ""))

    refused([{"id": "stale", "module": "a", "kind": "line", "source": "no such text", "reason": "a waiver for code that is gone"}],
            "waiver 'stale' (a line) matches nothing", "a waiver that matches nothing")
    refused([{"id": "wrong", "module": "a", "kind": "toggle", "signal": "tag[0]", "reason": "claims a bit that toggles"}],
            "waiver 'wrong' claims toggle tag[0]", "a waived point that was hit")
    refused([{"id": "noreason", "module": "a", "kind": "toggle", "signal": "x"}], "a reason is required", "a waiver without a reason")
    refused([{"id": "k", "module": "a", "kind": "fsm", "signal": "x", "reason": "an unknown kind of point"}], "kind 'fsm'",
            "an unknown kind")
    refused("{not json", "not valid JSON", "a waiver file that is not JSON")
    bogus = os.path.join(work, "bogus.dat")
    with open(bogus, "w") as f:
        f.write("hello\n")
    refused([], "is not a Verilator coverage database", "a file that is no database", dats=(d1, bogus))
    # --coverage DIR / --out DIR that cannot be a report directory: one line, exit 1, before anything runs or builds.
    for cmd, needle in (([sc, "cosim", "--mode", "directed", "--coverage", bogus], "exists and is not a directory"),
                        ([sc, "cosim", "--mode", "directed", "--coverage", "/proc/h36/x"], "is under /proc"),
                        ([sc, "coverage", d1, "--out", "/sys/x"], "is under /sys")):
        r = run(cmd)
        lines = [x for x in r.stderr.splitlines() if x.strip()]
        check(r.returncode == 1 and len(lines) == 1 and needle in lines[0] and "building" not in r.stderr,
              "%s: refused with one line (%r)" % (" ".join(cmd[1:3] + cmd[-2:]), lines[-1] if lines else ""))


POOL_TOP = """module cov_params_top (input wire [7:0] a, input wire [7:0] b, input wire [1:0] s, output wire [31:0] p);
%s
endmodule
"""
POOL_INST = {
    1: "  sc_mul_pool #(.NOP(2), .SH(1), .ON(3), .ST(64'h0100), .AW(64'h0404), .BW(64'h0404), .AMX(4), .BMX(4))\n"
       "    u_one (.a_i(a), .b_i(b), .sel_i(s), .p_o(p[15:0]));",
    2: "  sc_mul_pool #(.NOP(2), .SH(2), .ON(3), .ST(64'h0100), .AW(64'h0404), .BW(64'h0404), .AMX(4), .BMX(4))\n"
       "    u_two (.a_i(a), .b_i(b), .sel_i(s), .p_o(p[31:16]));",
}
CANON = "sc_mul_pool__{AMX=4,AW=1028,BMX=4,BW=1028,LAT=0,NOP=2,ON=3,SH=%d,SIGNED=0,ST=256}"


def pool_lines(pool_v):
    """The lines of rtl/sc_mul_pool.v the parameterisation checks name, found by their text (not hard-coded numbers:
    the file grows): mp_fld's function line, mp_on's, and `if (mp_on(j) != 0)` in mp_inst."""
    text = open(pool_v).read().splitlines()

    def find(needle):
        hits = [i + 1 for i, ln in enumerate(text) if needle in ln]
        if len(hits) != 1:
            raise SystemExit("coverage_check: %r is on %d lines of %s, expected 1" % (needle, len(hits), pool_v))
        return hits[0]
    return find("function integer mp_fld("), find("function integer mp_on("), find("if (mp_on(j) != 0)")


def params_quick(sc, root, work):
    """Waivers keyed to a parameterisation (docs/coverage.md "Parameterisations"). A design holding rtl/sc_mul_pool.v
    at share 1 (u_one) and share 2 (u_two) through `verilator --xml-only` (the map a coverage build keeps), twice with
    the instances in the other order so Verilator's __piN numbers swap; hand-made databases of each build's points
    (mp_fld's line: dead at SH = 1, hit at SH = 2; the `else` of mp_inst's `if (mp_on(j) != 0)`, dead while every op is on)
    through `shadecore coverage --params-map`."""
    verilator = shutil.which("verilator")
    if not verilator:
        check(False, "verilator is on PATH (the parameterisation map is its --xml-only output)")
        return
    rtl = os.path.join(root, "rtl")
    pool_v = os.path.join(rtl, "sc_mul_pool.v")
    xml, pi = {}, {}
    for tag, order in (("a", (1, 2)), ("b", (2, 1))):
        d = os.path.join(work, "xml_" + tag)
        os.makedirs(d)
        top = os.path.join(d, "cov_params_top.v")
        with open(top, "w") as f:
            f.write(POOL_TOP % "\n".join(POOL_INST[k] for k in order))
        xml[tag] = os.path.join(d, "verilated_params.xml")
        r = run([verilator, "--xml-only", "--xml-output", xml[tag], "--Mdir", os.path.join(d, "obj"), "--top", "cov_params_top",
                 "-Wall", "-Wno-fatal", "-I" + rtl, top, pool_v])
        check(r.returncode == 0 and os.path.exists(xml[tag]), "verilator --xml-only of the share-1/share-2 design (%s)" % tag)
        if r.returncode != 0:
            return
        text = open(xml[tag]).read()
        # instance -> Verilator's name of its module in this build
        pi[tag] = {inst: mod for inst, mod in
                   __import__("re").findall(r'<cell [^>]*name="(u_one|u_two)" submodname="([^"]+)"', text)}
    check(pi["a"]["u_one"] == pi["b"]["u_two"] and pi["a"]["u_two"] == pi["b"]["u_one"] and "__pi" in pi["a"]["u_one"],
          "Verilator numbers the parameterisations per build: %s in one, %s in the other" % (pi["a"], pi["b"]))

    lf, lo, li = pool_lines(pool_v)

    def pool_points(tag, inst, counts):
        mod = pi[tag][inst]
        h = "TOP.cov_params_top." + inst
        return [(key(f=pool_v, l=lf, n=20, page="v_line/" + mod, o="block", S="%d-%d" % (lf, lf + 1), h=h), counts[0]),  # mp_fld
                (key(f=pool_v, l=lo, n=20, page="v_line/" + mod, o="block", S="%d-%d" % (lo, lo + 1), h=h), counts[1]),  # mp_on
                (key(f=pool_v, l=li, n=9, page="v_branch/" + mod, o="if", S="%d-%d,%d" % (li, li + 3, li + 6), h=h), counts[2]),
                (key(f=pool_v, l=li, n=10, page="v_branch/" + mod, o="else", h=h), counts[3])]
    # share 1: mp_fld never runs; share 2: it does; the else of `if (mp_on(j) != 0)` never (ON = 3 = both ops on)
    da, db = os.path.join(work, "pa.dat"), os.path.join(work, "pb.dat")
    write_dat(da, pool_points("a", "u_one", (0, 10, 10, 0)) + pool_points("a", "u_two", (7, 10, 10, 0)))
    write_dat(db, pool_points("b", "u_one", (0, 4, 4, 0)) + pool_points("b", "u_two", (3, 4, 4, 0)))
    wf = os.path.join(work, "pw.json")
    good = [
        {"id": "pool-mp_fld-share1", "module": "sc_mul_pool", "kind": "line", "function": "mp_fld", "params": {"SH": 1},
         "reason": "mp_fld runs only in the SH > 1 arm of mp_inst, constant-folded away at share 1"},
        {"id": "pool-all-on-else", "module": "sc_mul_pool", "kind": "branch", "source": "if (mp_on(j) != 0)",
         "comment": "else", "params": {"NOP": 2, "ON": "32'h3"},
         "reason": "every op of a two-op pool with ON = 3 is on: the implicit else is never taken"},
        {"id": "pool-share3", "module": "sc_mul_pool", "kind": "line", "function": "mp_fld", "params": {"SH": 3},
         "reason": "a parameterisation these databases do not hold: not applicable, no error"},
    ]
    with open(wf, "w") as f:
        json.dump({"waivers": good}, f)
    outs = {}
    for tag, dat in (("a", da), ("b", db)):
        o = os.path.join(work, "pout_" + tag)
        r = run([sc, "coverage", dat, "--params-map", xml[tag], "--waivers", wf, "--out", o, "--no-html"])
        check(r.returncode == 0, "coverage --params-map of build %s exits 0 (%s)" % (tag, r.stderr.strip()))
        if r.returncode != 0:
            return
        outs[tag] = o
    merged = parse_dat(os.path.join(outs["a"], "coverage.dat"))
    pages = sorted({fields(k)["page"].split("/", 1)[1] for k in merged})
    check(pages == sorted([CANON % 1, CANON % 2]), "the merged database names each parameterisation canonically: %s" % pages)
    s = json.load(open(os.path.join(outs["a"], "summary.json")))
    pool = {m["module"]: m for m in s["modules"]}.get("sc_mul_pool", {})
    # By hand: line — mp_fld at SH=1 waived, at SH=2 hit (7), mp_on hit twice: 3/3 +1w; branch — both ifs hit, both
    # elses waived (NOP=2, ON=3 in both): 2/2 +2w.
    got = {k: (pool.get(k, {}).get("hit"), pool.get(k, {}).get("total"), pool.get(k, {}).get("waived")) for k in ("line", "branch")}
    check(got == {"line": (3, 4, 1), "branch": (2, 4, 2)},
          "sc_mul_pool: line 3 hit of 4, 1 waived (mp_fld at SH=1 only); branch 2 of 4, 2 waived: %s" % got)
    applied = {x["id"]: x["points"] for x in s["waivers"]["applied"]}
    check(applied == {"pool-mp_fld-share1": 1, "pool-all-on-else": 2} and s["waivers"]["not_applicable"] == ["pool-share3"],
          "the share-1 waiver takes one point (not the share-2 one), the SH=3 waiver is not applicable: %s %s" %
          (applied, s["waivers"]["not_applicable"]))
    check(not s["holes"], "no hole left: the share-2 mp_fld point is hit, not waived (%s)" % s["holes"])
    # The two builds' databases, canonical, merge point for point although their __piN numbers are swapped.
    oab = os.path.join(work, "pout_ab")
    r = run([sc, "coverage", os.path.join(outs["a"], "coverage.dat"), os.path.join(outs["b"], "coverage.dat"), "--waivers", wf,
             "--out", oab, "--no-html"])
    ab = parse_dat(os.path.join(oab, "coverage.dat")) if r.returncode == 0 else {}
    line_fld = {fields(k)["page"]: c for k, c in ab.items() if fields(k).get("l") == str(lf)}
    check(r.returncode == 0 and len(ab) == 8 and line_fld == {"v_line/" + CANON % 1: 0, "v_line/" + CANON % 2: 10},
          "two builds with swapped __piN numbers merge into the same 8 points (mp_fld at SH=2: 7 + 3): %s" % line_fld)

    def refused(waivers, needle, what, dats=(da,), extra=("--params-map", xml["a"])):
        w2 = os.path.join(work, "pw_%d.json" % len(os.listdir(work)))
        with open(w2, "w") as f:
            json.dump({"waivers": waivers}, f)
        o = os.path.join(work, "prefused_%d" % len(os.listdir(work)))
        r = run([sc, "coverage", *dats, *extra, "--out", o, "--waivers", w2, "--no-html"])
        lines = [x for x in r.stderr.splitlines() if x.strip()]
        check(r.returncode == 1 and len(lines) == 1 and needle in lines[0] and not os.path.exists(o) and
              not any(x.startswith(os.path.basename(o)) for x in os.listdir(work)),
              "%s: exit 1, one line naming it, nothing written (%r)" % (what, lines[-1] if lines else ""))

    base = dict(good[0])
    refused([dict(base, id="share2", params={"SH": 2})], "waiver 'share2' claims line sc_mul_pool.v:%d" % lf,
            "the same point waived at share 2, where it is hit")
    refused([dict(base, id="stale-p", function="mp_gone")], "waiver 'stale-p' (sc_mul_pool line, SH=1) matches nothing",
            "a params waiver whose parameterisation is there but which matches none of its points")
    refused([dict(base, id="typo", params={"SHARE": 1})], "waiver 'typo': params: sc_mul_pool has no parameter 'SHARE' (its "
            "parameters: AMX, AW, BMX, BW, LAT, NOP, ON, SH, SIGNED, ST)", "an unknown parameter name")
    refused([dict(base, id="raw")], "waiver 'raw' is keyed to parameters (SH=1), but the database's sc_mul_pool points carry "
            "no parameterisation", "a params waiver on a database without parameterisations", extra=())
    for bad, needle in (([1], '"params" must be an object'), ({}, '"params" must be an object'),
                        ({"SH": 1.5}, "params: SH must be an integer or a string"), ({"S H": 1}, "is not a parameter name")):
        refused([dict(base, id="bad", params=bad)], needle, "params %s refused" % json.dumps(bad))
    other = os.path.join(work, "pother.dat")
    write_dat(other, [(key(f=pool_v, l=lo, n=20, page="v_line/sc_mul_pool__pi9", o="block", h="TOP.cov_params_top.u_one"), 1)])
    refused([], "module sc_mul_pool__pi9 is not in the parameterisation map", "a database of another build", dats=(other,))
    wrong = os.path.join(work, "pwrong.dat")
    write_dat(wrong, [(key(f=pool_v, l=lo, n=20, page="v_line/" + pi["a"]["u_one"], o="block", h="TOP.cov_params_top.u_two"), 1)])
    refused([], "has no instance u_two of %s" % pi["a"]["u_one"], "a point the map places in another module", dats=(wrong,))
    # A point Verilator merged over a generate loop's instances ends in a wildcard index ("...u_shade.g_ch[*", as the
    # lighting core's per-channel multipliers): no single instance to check, so it is taken, not refused.
    wild = os.path.join(work, "pwild.dat")
    write_dat(wild, [(key(f=pool_v, l=lo, n=20, page="v_line/" + pi["a"]["u_one"], o="block", h="TOP.cov_params_top.g_ch[*"), 1)])
    ow, ww = os.path.join(work, "pout_wild"), os.path.join(work, "pw_wild.json")
    with open(ww, "w") as f:
        json.dump({"waivers": []}, f)
    r = run([sc, "coverage", wild, "--params-map", xml["a"], "--waivers", ww, "--out", ow, "--no-html"])
    check(r.returncode == 0, "a point whose hierarchy ends in a wildcard index is taken (%s)" % r.stderr.strip())


def params_run(sc, root, work):
    """The share-tied waiver on real coverage builds (ctest coverage.params, label long: two lighting coverage cores,
    ~2 min each the first time, then cached): `cosim --core lighting --coverage` of `diffuse` (share 1) and of the same
    set at share 2 write canonical databases (the map beside each build); merged with the project's waivers, mp_fld
    (its line in sc_mul_pool.v) is waived at SH = 1 and counted — hit — at SH = 2."""
    lf = pool_lines(os.path.join(root, "rtl", "sc_mul_pool.v"))[0]
    base = json.load(open(os.path.join(root, "config", "configs.json")))
    s2 = dict(next(f for f in base["feature_sets"] if f["name"] == "diffuse"), name="diffuse_share2", share=2)
    s2f = os.path.join(work, "diffuse_share2.json")
    with open(s2f, "w") as f:
        json.dump(s2, f)
    dats = []
    for tag, feat in (("s1", "diffuse"), ("s2", s2f)):
        o, js = os.path.join(work, "cov_" + tag), os.path.join(work, tag + ".json")
        r = run([sc, "cosim", "--core", "lighting", "--features", feat, "--harness", "bare", "--mode", "random", "--count", "2000",
                 "--seed", "3", "--in-stall", "0.2", "--out-stall", "0.2", "--coverage", o, "--json", js])
        check(r.returncode == 0, "cosim --core lighting --features %s --coverage passes (%s)" % (tag, r.stderr.strip()[-300:]))
        if r.returncode != 0:
            return
        bdir = json.load(open(js))["build_dir"]
        check(os.path.exists(os.path.join(bdir, "verilated_params.xml")) and os.path.exists(os.path.join(bdir, "params.json")),
              "the coverage build %s keeps its parameterisation map (verilated_params.xml, params.json)" % os.path.basename(bdir))
        dats.append(os.path.join(o, "coverage.dat"))
    for d in dats:
        pages = {fields(k)["page"] for k in parse_dat(d)}
        raw = sorted(p for p in pages if not p.startswith("v_func/") and not p.endswith("}"))
        check(not raw, "every code point of %s names its parameterisation canonically (%s)" % (d, raw[:3]))
    o = os.path.join(work, "merged")
    r = run([sc, "coverage", *dats, "--out", o, "--no-html"])
    check(r.returncode == 0, "the two databases merge with the project's waivers (%s)" % r.stderr.strip())
    if r.returncode != 0:
        return
    fld = {}
    for k, c in parse_dat(os.path.join(o, "coverage.dat")).items():
        fl = fields(k)
        if fl["page"].startswith("v_line/sc_mul_pool__") and fl.get("l") == str(lf):
            sh = [x.split("=")[1] for x in fl["page"][fl["page"].index("{") + 1:-1].split(",") if x.startswith("SH=")][0]
            fld[sh] = fld.get(sh, 0) + c
    check(set(fld) == {"1", "2"} and fld["1"] == 0 and fld["2"] > 0,
          "mp_fld (sc_mul_pool.v:%d): never run" % lf + " at SH=1, run %s time(s) at SH=2" % fld.get("2"))
    s = json.load(open(os.path.join(o, "summary.json")))
    applied = {x["id"]: x["points"] for x in s["waivers"]["applied"]}
    holes = [h for h in s["holes"].get("sc_mul_pool", []) if "sc_mul_pool.v:%d " % lf in h]
    check(applied.get("mul-pool-mp_fld-share1") == 1 and not holes,
          "the share-1 waiver takes the one SH=1 point; the SH=2 point is counted (hit), neither waived nor a hole (%s, %s)" %
          (applied.get("mul-pool-mp_fld-share1"), holes))


def full(sc, root, work):
    plan = os.path.join(root, "tests", "data", "coverage", "tiny.json")
    out = os.path.join(work, "run")
    shutil.rmtree(out, ignore_errors=True)
    r = run([sc, "regress", "--plan", plan, "--local", "-j", "2", "--coverage", "--out", out, "--no-progress"])
    print(r.stdout[-3000:])
    check(r.returncode == 0, "regress --coverage on the tiny plan passes (%s)" % r.stderr.strip()[-300:])
    if r.returncode != 0:
        return
    merged = json.load(open(os.path.join(out, "merged.json")))
    shards = json.load(open(os.path.join(out, "shards.json")))
    dats = [os.path.join(out, "coverage", "shards", s["id"], "coverage.dat") for s in shards
            if any("{cov}" in a for a in s["argv"])]
    check(len(dats) >= 3 and all(os.path.exists(d) for d in dats), "every co-simulation shard wrote its database (%d)" % len(dats))
    union = {}
    for d in dats:
        for k, c in parse_dat(d).items():
            union[k] = union.get(k, 0) + c
    check(parse_dat(os.path.join(out, "coverage", "merged.dat")) == union, "merged.dat is the sum of the shards' databases")
    hand = hand_summary(union)
    cov = merged.get("coverage", {})
    got = {m["module"]: m for m in cov.get("modules", [])}
    check(set(got) == set(hand), "merged.json summarises every module of the databases: %s" % sorted(hand))
    for m, kinds in hand.items():
        for k, (hit, tot) in kinds.items():
            g = got.get(m, {}).get(k, {})
            # a waived point counts neither as hit nor as a hole (and is never hit: that is an error)
            check(g.get("total") == tot and g.get("hit") == hit, "%s %s: total %d, hit %d by hand; summary %s" % (m, k, tot, hit, g))
    check(os.path.exists(os.path.join(out, "coverage", "html", "index.html")), "the HTML report is written")
    # A stale waiver: the merge is refused, the report still written with the error named, exit 1.
    bad = os.path.join(work, "stale.json")
    with open(bad, "w") as f:
        json.dump({"waivers": [{"id": "stale", "module": "sc_cs16", "kind": "line", "source": "no such RTL text",
                                "reason": "a waiver whose code is gone"}]}, f)
    r3 = run([sc, "regress", "--plan", plan, "--merge-only", "--coverage", "--waivers", bad, "--out", out, "--no-progress"])
    m3 = json.load(open(os.path.join(out, "merged.json")))
    check(r3.returncode == 1 and "waiver 'stale'" in r3.stderr and "waiver 'stale'" in m3.get("coverage", {}).get("error", ""),
          "regress --coverage with a stale waiver: exit 1, the error in merged.json (%s)" % r3.stderr.strip()[-200:])
    r4 = run([sc, "regress", "--plan", plan, "--merge-only", "--coverage", "--out", out, "--no-progress"])
    check(r4.returncode == 0, "--merge-only --coverage with the project's waivers passes again")
    before = open(os.path.join(out, "merged.json")).read()
    r2 = run([sc, "regress", "--plan", plan, "--local", "-j", "2", "--coverage", "--out", out, "--no-progress"])
    check(r2.returncode == 0 and "to run" in r2.stdout and open(os.path.join(out, "merged.json")).read() == before,
          "a rerun of the same --out (resume) runs nothing and writes the same merged.json")
    closure(sc, plan, work)


def closure(sc, plan, work):
    """--until-coverage: a target the tiny plan cannot reach (toggle 100 %) adds --max-rounds closure rounds, each one
    shard of the random job under a new seed, then stops with exit 2 naming what is below target and its holes; a
    rerun of the same --out resumes them and adds none; targets it reaches stop at once with exit 0."""
    out = os.path.join(work, "closure")
    args = [sc, "regress", "--plan", plan, "--local", "-j", "2", "--coverage", "--until-coverage", "--max-rounds", "2",
            "--coverage-target", "line=0,branch=0,functional=0,toggle=100", "--out", out, "--no-progress"]
    r = run(args)
    print(r.stdout[-2000:])
    m = json.load(open(os.path.join(out, "merged.json"))) if os.path.exists(os.path.join(out, "merged.json")) else {}
    c = m.get("closure", {})
    check(r.returncode == 2 and "coverage targets not met after 2 closure round(s)" in r.stderr,
          "an unreachable target: exit 2 after --max-rounds 2 rounds (%d: %s)" % (r.returncode, r.stderr.strip()[-200:]))
    check(c.get("met") is False and c.get("rounds") == 2 and c.get("stopped") == "--max-rounds 2 reached",
          "merged.json closure: not met, 2 rounds, stopped by --max-rounds (%s)" % {k: c.get(k) for k in ("met", "rounds", "stopped")})
    below = c.get("below_target", [])
    check(below and all(" toggle " in b for b in below), "only toggle is below target (%s)" % below[:3])
    check(sum(len(v) for v in c.get("holes", {}).values()) > 0, "the holes of the modules below target are named")
    rec = json.load(open(os.path.join(out, "closure.json")))
    tiny = json.load(open(plan))
    rand = [j for j in tiny["jobs"] if j.get("mode") == "random"]
    for k, rnd in enumerate(rec["rounds"], 1):
        for j, c_job in zip(rand, rnd["jobs"]):
            check(c_job["name"] == "%s-c%d" % (j["name"], k) and c_job["seed"] == j["seed"] + k * 1000003 and
                  c_job["shards"] == 1 and c_job["count"] == j["count"] // j.get("shards", 1),
                  "closure round %d adds %s-c%d: seed %d, one shard of %d" % (k, j["name"], k, j["seed"] + k * 1000003,
                                                                              j["count"] // j.get("shards", 1)))
    ids = [s["id"] for s in json.load(open(os.path.join(out, "shards.json")))]
    done = [i for i in ids if json.load(open(os.path.join(out, "shards", i + ".json"))).get("completed")]
    check(len(done) == len(ids) and any(i.startswith("rand_cs16-c2.") for i in ids),
          "every shard of the plan and of both rounds completed (%d of %d)" % (len(done), len(ids)))
    totals = [h["totals"]["toggle"]["hit"] for h in c.get("history", [])]
    check(len(totals) == 3 and totals == sorted(totals), "toggle hits never fall from round to round (%s)" % totals)
    r2 = run(args)
    check(r2.returncode == 2 and "resume" in r2.stdout and json.load(open(os.path.join(out, "closure.json"))) == rec,
          "a rerun of the same --out resumes: no new round (%d)" % r2.returncode)
    r3 = run([sc, "regress", "--plan", plan, "--local", "-j", "2", "--coverage", "--out", out, "--no-progress"])
    check(r3.returncode == 1 and "--until-coverage" in r3.stderr, "the closure's --out without --until-coverage is refused")
    out2 = os.path.join(work, "closure_met")
    r4 = run(args[:-4] + ["line=0,branch=0,functional=0,toggle=0", "--out", out2, "--no-progress"])
    m4 = json.load(open(os.path.join(out2, "merged.json")))
    check(r4.returncode == 0 and m4["closure"]["met"] and m4["closure"]["rounds"] == 0 and
          not os.path.exists(os.path.join(out2, "closure.json")), "targets already met: no round, exit 0")
    r5 = run(args[:-4] + ["toggle=101", "--out", os.path.join(work, "bad"), "--no-progress"])
    check(r5.returncode == 1 and len(r5.stderr.strip().splitlines()) == 1 and "0..100" in r5.stderr and
          not os.path.exists(os.path.join(work, "bad")), "a target above 100 %: one line, exit 1, nothing written")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", required=True)
    ap.add_argument("--work", required=True)
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--quick", action="store_true")
    g.add_argument("--run", action="store_true")
    g.add_argument("--params-run", action="store_true")
    a = ap.parse_args()
    sc = os.path.join(a.build, "cli", "shadecore")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    os.makedirs(a.work, exist_ok=True)
    work = tempfile.mkdtemp(dir=a.work)
    try:
        if a.quick:
            quick(sc, work)
            params_quick(sc, root, work)
        elif a.params_run:
            params_run(sc, root, work)
        else:
            full(sc, root, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print("coverage_check: %s" % ("PASS" if not FAILS else "FAIL (%d)" % len(FAILS)))
    return 0 if not FAILS else 1


if __name__ == "__main__":
    sys.exit(main())
