#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""ctest coverage.mutation (issue 36, docs/mutation.md): scripts/mutation.py refuses bad arguments with one line
on stderr and a non-zero exit, and one mutant of cs16 known to be killed (the first of `mutate -list 300 -seed 1`
that ties or inverts a bit of the result register out_spec_o; at the time of writing m012, bit 4 tied to 1) is
killed by the handoff bench again (a fresh bundle, no cache; ~40 s); a schlick_nr mutant equivalent for every input
is proved so; a cs16 datapath mutant is killed by the exhaustive stage alone, its witness named (~1 min).
--part quick (ctest coverage.mutation, the default suite): the refusals, the killed mutant and the CPU-bounded proofs;
--part stages (ctest coverage.mutation_stages, label long: ~5 CPU min): the equivalence proof and the exhaustive stage.

  tests/mutation_check.py --build BUILD_DIR [--work DIR] [--part quick|stages|all]"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(os.path.dirname(HERE), "scripts", "mutation.py")
# A tied or inverted bit of the result register (out_spec_o): every bench must kill it (the directed vectors
# hold 0, 1.0 and values between); the first such mutant of the list, so the check survives RTL changes.
PICK = r"-mode (const0|const1|inv) .*-wire out_spec_o "
EQUIV_PICK = r"-mode const0 -module sc_schlick_nr -cell \$logic_not\$rtl/sc_schlick_front\.vh:22\S* -port A "
# A bit of a squaring's register tied (cs16's x1 = x0^2): the exhaustive stage alone must kill it and name a witness.
EXH_PICK = r"-mode (const0|const1) .*-wire g_ref\.sq1 "


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", required=True)
    ap.add_argument("--work", default=None)
    ap.add_argument("--part", choices=("quick", "stages", "all"), default="all")
    a = ap.parse_args()
    quick, stages = a.part in ("quick", "all"), a.part in ("stages", "all")
    cli = os.path.join(a.build, "cli", "shadecore")
    work = a.work or os.path.join(a.build, "tests", "mutation_check")
    fails = 0
    bad = [["--design", "nosuch"], ["--design", "table256"], ["--count", "0"], ["--jobs", "0"],
           ["--stages", "hard,bogus"], ["--expect", "killed"], ["--mutant", "3"], ["--design", "cs16", "--pick", "("],
           ["--design", "cs16", "--cli", "/nonexistent/shadecore"], ["--frobnicate"],
           ["--design", "cs16", "--mutant", "100000", "--cli", cli, "--work", work]]
    for args in bad if quick else []:
        p = subprocess.run([sys.executable, SCRIPT] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           universal_newlines=True, timeout=120)
        lines = p.stderr.strip().splitlines()
        ok = p.returncode != 0 and len(lines) == 1 and lines[0].startswith("mutation.py: error:")
        print("%s refused %-60s rc %d: %s" % ("ok  " if ok else "FAIL", " ".join(args)[:60], p.returncode,
                                              lines[-1] if lines else "(no message)"))
        fails += not ok
    if quick:
        fails += killed_mutant(cli, work)
        fails += no_one_sided_proof(work)
    if stages:
        fails += stage_mutants(cli, work)
    if quick:
        fails += cpu_bounds()
    print("mutation_check: %s" % ("PASS" if not fails else "FAIL (%d)" % fails))
    return 1 if fails else 0


def killed_mutant(cli, work):
    """The first cs16 mutant of the result register is killed by the handoff bench (a fresh bundle, no cache)."""
    p = subprocess.run([sys.executable, SCRIPT, "--design", "cs16", "--pick", PICK, "--expect", "killed",
                        "--no-cache", "--cli", cli, "--work", work], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True, timeout=600)
    print(p.stdout.strip())
    if p.returncode != 0:
        print("FAIL: the cs16 mutant matching %s is not killed" % PICK)
        return 1
    return 0


def no_one_sided_proof(work):
    """The equivalence proofs do not prove mutants the bench kills (both were "proved" before EQ_METHOD 8):
    a bit of the result register out_spec_o tied to 1 (equiv_make left the mutated wire, the port itself, unpaired:
    a gold and a gate copy, compared nowhere), and a bit of cs16's |base| tied to 1 where it feeds a register
    (the combinational miter read without its x constant modelled compared only the bits where the original is 1,
    and a tie to 1 only raises bits). Run on the design and mutant list killed_mutant() has just prepared."""
    sys.path.insert(0, os.path.dirname(SCRIPT))
    import mutation  # noqa: E402
    import re
    import tempfile
    wdir = os.path.join(work, "cs16")
    muts = [ln.strip() for ln in open(os.path.join(wdir, "mutations.txt")) if ln.strip()]
    ctx = {"mutations": muts, "unit": "sc_cs16", "design_il": os.path.join(wdir, "design.il"), "eq_timeout": 12,
           "eq_steps": 8}
    fails = 0
    for what, pat in (("a result register bit tied to 1", r"-mode const1 .*-port Q .*-wire out_spec_o "),
                      ("a bit of |base| tied to 1", r"-mode const1 .*-port Y .*-wire g_ref\.mag ")):
        pick = [i for i, m in enumerate(muts, 1) if re.search(pat, m)]
        if not pick:
            print("FAIL: no cs16 mutant matches %s (%s)" % (pat, what))
            fails += 1
            continue
        with tempfile.TemporaryDirectory(prefix="proof_", dir=wdir) as mdir:
            eq, why = mutation.equivalence(ctx, pick[0], mdir)
        ok = eq != "equivalent"
        print("%s m%03d (%s) not proved equivalent: %s" % ("ok  " if ok else "FAIL", pick[0], what, why))
        fails += not ok
    return fails


def stage_mutants(cli, work):
    """A schlick_nr mutant proved equivalent; a cs16 mutant killed by the exhaustive stage alone, with a witness."""
    fails = 0
    # A survivor that is equivalent for every input, in a design with a memory (schlick_nr's seed ROM): the ! of
    # cos_neg in the clamp tied off (cos_neg's priority masks it). Proved only once memories are mapped to logic
    # before the proofs (SAT cannot import a memory port; method 6, docs/mutation.md).
    p = subprocess.run([sys.executable, SCRIPT, "--design", "schlick_nr", "--pick", EQUIV_PICK, "--expect",
                        "equivalent", "--no-cache", "--cli", cli, "--work", work], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True, timeout=600)
    print(p.stdout.strip())
    if p.returncode != 0:
        print("FAIL: the schlick_nr mutant matching %s is not proved equivalent" % EQUIV_PICK)
        fails += 1
    # The exhaustive stage by itself (the bare harness on every input code of every n): a datapath mutant is killed
    # with its first mismatch named.
    p = subprocess.run([sys.executable, SCRIPT, "--design", "cs16", "--pick", EXH_PICK, "--stages", "exhaustive",
                        "--eq-timeout", "0", "--expect", "killed", "--no-cache", "--cli", cli, "--work", work],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=600)
    print(p.stdout.strip())
    if p.returncode != 0 or "exhaustive: first mismatch: n " not in p.stdout:
        print("FAIL: the cs16 mutant matching %s is not killed by the exhaustive stage with a witness" % EXH_PICK)
        fails += 1
    return fails


def cpu_bounds():
    """The proofs' bound is CPU time, and the re-proof rule."""
    # The proofs' bound is CPU time (a busy child stopped at its CPU limit counts as a timeout, however loaded the
    # machine), and a survivor is proved again when its proof was wall-clock bounded or had a smaller bound.
    sys.path.insert(0, os.path.dirname(SCRIPT))
    import mutation  # noqa: E402
    rc, _, secs = mutation.run(["sh", "-c", "while :; do :; done"], timeout=60, cpu=1)
    ok = rc is None and secs < 30
    rc2, out2, _ = mutation.run(["sh", "-c", "echo done"], timeout=60, cpu=1)
    ok = ok and rc2 == 0 and out2.strip() == "done"
    base = {"eq_method": mutation.EQ_METHOD, "eq_bound": mutation.EQ_BOUND, "eq_timeout": 30}
    ok = ok and not mutation.needs_proof(base, 30) and mutation.needs_proof(base, 60) \
        and mutation.needs_proof(dict(base, eq_bound=None), 30) and mutation.needs_proof(dict(base, eq_method=5), 30)
    print("%s CPU-bounded proofs: a busy child stopped after %.1f s (1 CPU s), re-proof rule" % ("ok  " if ok else "FAIL", secs))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
