#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The full exhaustive cs16 sweep (every code 0..2^16, n = 16..1024: 66 M evaluations) from Python, for timing
against `shadecore sweep` (docs/performance.md, section "Python").

    PYTHONPATH=build/python /usr/bin/python3 python/bench/sweep_bench.py engine   # shadecore.sweep (run_sweep)
    PYTHONPATH=build/python /usr/bin/python3 python/bench/sweep_bench.py numpy    # the array API + NumPy

engine: the sweep's own engine through the binding (both cores, as the CLI). numpy: the sweep composed from the
array functions — cs16 outputs, the double cs16 and cos^n for every (n, code) — with the error extremes per n
taken by NumPy, 64 exponents per call (one thread); its quantisation columns are checked equal to the engine's.
"""
import sys
import time

import numpy as np

import shadecore


def numpy_sweep(lo=16, hi=1024, chunk=64):
    codes = np.arange(65537)
    c = shadecore.code_to_cos(codes)
    qmax, qmin, amax, amin = [], [], [], []
    for n0 in range(lo, hi + 1, chunk):
        n = np.arange(n0, min(hi, n0 + chunk - 1) + 1)[:, None]
        fixed = shadecore.cs16(codes[None, :], n)
        g = shadecore.golden.cs16(c[None, :], n)
        p = shadecore.golden.cos_pow(c[None, :], n)
        q = fixed - g * 65536.0
        a = p - g
        qmax.append(q.max(axis=1))
        qmin.append(q.min(axis=1))
        amax.append(a.max(axis=1))
        amin.append(a.min(axis=1))
    return {k: np.concatenate(v) for k, v in
            (("quant_max_ulp", qmax), ("quant_min_ulp", qmin), ("approx_max", amax), ("approx_min", amin))}


def main():
    mode = sys.argv[1] if len(sys.argv) > 1 else "engine"
    t0 = time.perf_counter()
    if mode == "engine":
        r = shadecore.sweep("cs16", "16..1024")
        print(f"engine: {r['evaluations']} evaluations in {r['seconds']:.3f} s on {r['threads']} threads; "
              f"quant [{r['quant_ulp']['min']['value']:.5f}, {r['quant_ulp']['max']['value']:.5f}] ulp")
    elif mode == "numpy":
        r = numpy_sweep()
        t = time.perf_counter() - t0
        print(f"numpy: {65537 * (1024 - 16 + 1)} evaluations in {t:.3f} s; quant [{r['quant_min_ulp'].min():.5f}, "
              f"{r['quant_max_ulp'].max():.5f}] ulp")
        if "--check" in sys.argv:
            e = shadecore.sweep("cs16", "16..1024")
            ok = np.array_equal(e["quant_max_ulp"], r["quant_max_ulp"]) and np.array_equal(e["quant_min_ulp"],
                                                                                            r["quant_min_ulp"])
            print("quantisation columns equal to the engine's:", ok)
            return 0 if ok else 1
    else:
        print("usage: sweep_bench.py engine|numpy [--check]", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
