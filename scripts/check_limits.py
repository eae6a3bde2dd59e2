#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Checks that the RTL's elaboration checks state the legal ranges of config/configs.json "limits" (issue 20).

The C++ side is generated from "limits" (shadecore/limits.hpp, cmake/ShadecoreConfigs.cmake). The RTL side
cannot be: a failing check instantiates an undefined module named after the message, and Verilog-2005
cannot build a module name from a parameter. So, for every entry's "rtl" reference module.PARAM, this finds
the check in rtl/<module>.v (the `if (...)` whose block instantiates <module>_error_illegal_<PARAM>...) and
checks that both its condition and its error-module name state the entry's numbers:
  min/max        PARAM < min || PARAM > max            ..._PARAM_legal_range_is_<min>_to_<max>
  COEFW-FRAC     COEFW < FRAC + min || ... FRAC + max  ..._COEFW_legal_range_is_FRAC_plus_<min>_to_FRAC_plus_<max>
  A+B, sum_max   A + B > sum_max                       ..._A_plus_B_must_be_at_most_<sum_max>
  frac_plus_max  PARAM's check also FRAC + PARAM > N   ..._and_FRAC_plus_PARAM_at_most_<N>, N = limits[frac_plus_max].max
It also fails when a range check of a parameter named in "limits" exists in rtl/*.v without an entry.
Prints one line per check and `check_limits: PASS` or `check_limits: FAIL`; exit status 0 / 1."""
import glob
import json
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def find_check(src, module, param):
    """(condition, error name) of the check of `param` in a module's source, or None."""
    m = re.search(r"if\s*\((?P<cond>[^\n]*)\)\s*begin\s*:\s*\w+\s*\n\s*(?P<name>%s_error_illegal_%s_\w+)"
                  % (re.escape(module), re.escape(param)), src)
    return (m.group("cond"), m.group("name")) if m else None


def expect(ref, lim, limits):
    """(condition regexes, name regex) a reference must match, each with the numbers filled in."""
    module, what = ref.split(".", 1)
    if "+" in what:
        a, b = what.split("+")
        n = lim["sum_max"]
        return module, a, [r"\b%s\s*\+\s*%s\s*>\s*%d\b" % (a, b, n)], r"_%s_plus_%s_must_be_at_most_%d$" % (a, b, n)
    if "-" in what:
        p, base = what.split("-")
        lo, hi = lim["min"], lim["max"]
        return module, p, [r"\b%s\s*<\s*%s\s*\+\s*%d\b" % (p, base, lo), r"\b%s\s*>\s*%s\s*\+\s*%d\b" % (p, base, hi)], \
            r"_%s_legal_range_is_%s_plus_%d_to_%s_plus_%d$" % (p, base, lo, base, hi)
    lo, hi = lim["min"], lim["max"]
    conds = [r"\b%s\s*>\s*%d\b" % (what, hi)]
    conds.append(r"\b%s\s*<\s*%d\b" % (what, lo))
    name = r"_%s_legal_range_is_%d_to_%d" % (what, lo, hi)
    if "frac_plus_max" in lim:
        n = limits[lim["frac_plus_max"]]["max"]
        conds.append(r"\bFRAC\s*\+\s*%s\s*>\s*%d\b" % (what, n))
        name += r"_and_FRAC_plus_%s_at_most_%d" % (what, n)
    return module, what, conds, name + "$"


def main():
    cfg = json.load(open(os.path.join(ROOT, "config", "configs.json")))
    limits = {k: v for k, v in cfg["limits"].items() if not k.startswith("_")}
    srcs = {os.path.basename(f)[:-2]: open(f).read() for f in glob.glob(os.path.join(ROOT, "rtl", "*.v"))}
    bad = 0
    covered = set()
    for key, lim in sorted(limits.items()):
        for ref in lim["rtl"]:
            module, param, conds, name_rx = expect(ref, lim, limits)
            covered.add((module, param))
            token = param if "+" not in ref else ref.split(".", 1)[1].replace("+", "_plus_")
            found = find_check(srcs.get(module, ""), module, token)
            if found is None:
                print("check_limits: %s (limits.%s): no elaboration check of %s in rtl/%s.v" % (ref, key, param, module))
                bad += 1
                continue
            cond, name = found
            wrong = [c for c in conds if not re.search(c, cond)]
            if wrong or not re.search(name_rx, name):
                print("check_limits: %s (limits.%s): rtl/%s.v states `if (%s)` / %s, configs.json %s"
                      % (ref, key, module, cond, name, {k: v for k, v in lim.items() if k not in ("rtl", "cpp")}))
                bad += 1
            else:
                print("check_limits: %s agrees with limits.%s (%s)" % (ref, key, name))
    # every range check of a parameter that "limits" governs has an entry
    params = {r.split(".", 1)[1].split("+")[0].split("-")[0] for lim in limits.values() for r in lim["rtl"]}
    for module, src in sorted(srcs.items()):
        for m in re.finditer(r"\b%s_error_illegal_(%s)_(legal_range|must_be_at_most|plus)" %
                             (re.escape(module), "|".join(sorted(params))), src):
            if (module, m.group(1)) not in covered:
                print("check_limits: rtl/%s.v checks the range of %s, which config/configs.json \"limits\" "
                      "does not list (add %s.%s to an entry's rtl)" % (module, m.group(1), module, m.group(1)))
                bad += 1
    print("check_limits: %s" % ("FAIL" if bad else "PASS"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
