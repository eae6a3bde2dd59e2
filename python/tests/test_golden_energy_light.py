# SPDX-License-Identifier: Apache-2.0
# The golden references, the energy coefficients and sc_energy against `shadecore eval --norm`; normalize3 and recip
# (no CLI command evaluates them alone) against their stated bounds from exact arithmetic.
import math

import numpy as np
import pytest

import shadecore


@pytest.mark.parametrize("model", ["phong", "phong_mod", "blinn", "blinn_mod", "blinn_ndf", "blinn_hf"])
@pytest.mark.parametrize("kind", ["fitted", "classical"])
def test_energy_against_eval_norm(cli, model, kind):
    n, code = 200 + len(model), 65000
    j = cli.eval_json("--norm", model, "--coef", kind, "--n", n, "--code", code)
    assert shadecore.coef_value(model, [n], kind)[0] == j["norm"]["coef"]
    k = shadecore.coef_code(model, [n], kind)
    assert k[0] == j["material"]["coef"]
    unit_out = j["trace"]["out"]  # the cs16 output before sc_energy
    assert shadecore.energy_eval([unit_out], k)[0] == j["out"] == j["trace"]["norm"]["out"]
    assert shadecore.cs16([code], n, norm=model, coef=kind)[0] == j["out"]


def test_models_and_coef_shapes():
    assert shadecore.models() == ["phong", "phong_mod", "blinn", "blinn_mod", "blinn_ndf", "blinn_hf"]
    n = np.arange(16, 1025)
    v = shadecore.coef_value("phong", n, "classical")
    assert np.allclose(v, (n + 1) / (2 * np.pi), rtol=1e-15, atol=0)
    k = shadecore.coef_code("phong", n, "classical")
    assert np.array_equal(k, np.floor(np.ldexp(v, 16) + 0.5).astype(np.int64))


def test_golden_functions():
    c = np.linspace(0, 1, 1001)
    for n in (16, 100, 1024):
        assert np.array_equal(shadecore.golden.cos_pow(c, n), np.array([math.pow(x, n) for x in c]))
        b = (n / 16) * (c - 1) + 1
        cs = np.where(c < math.cos(6 / math.sqrt(n)), 0.0, ((b * b) ** 2) ** 2 * ((b * b) ** 2) ** 2)
        assert np.allclose(shadecore.golden.cs16(c, n), cs, rtol=1e-14, atol=0)
        sc = np.where(b <= 0, 0.0, ((b * b) ** 2) ** 2 * ((b * b) ** 2) ** 2)
        assert np.allclose(shadecore.golden.cs16(c, n, "sign_clamp"), sc, rtol=1e-14, atol=0)
        assert np.allclose(shadecore.golden.schlick(c, n), c / (n - n * c + c), rtol=1e-15, atol=0)
    assert np.allclose(shadecore.golden.theta_cr([16, 64]), [1.5, 0.75])
    # the table lerp: exact at the table's knots
    knots = np.arange(256) / 255
    assert np.allclose(shadecore.golden.variant("table256", knots, 8 * 16), knots ** 128, rtol=1e-13, atol=1e-300)


@pytest.mark.parametrize("frac", [8, 16, 21, 24])
def test_normalize3_bound(frac):
    rng = np.random.default_rng(frac)
    bits = rng.integers(1, 27, size=(20000, 1))
    v = rng.integers(-(1 << 26), 1 << 26, size=(20000, 3)) >> (27 - bits)
    v = v[np.any(v != 0, axis=1)]
    u = shadecore.normalize3(v, frac)
    exact = v / np.sqrt(np.sum(v.astype(np.float64) ** 2, axis=1, keepdims=True)) * 2.0 ** frac
    err = np.max(np.abs(u - exact))
    assert err <= shadecore.normalize3_bound_ulp(frac)
    assert err > 0.45  # round to nearest: the bound is nearly reached on this many vectors
    assert np.array_equal(shadecore.normalize3(np.array([[0, 0, 0], [5, 0, 0], [0, -7, 0]]), frac),
                          [[0, 0, 0], [1 << frac, 0, 0], [0, -(1 << frac), 0]])
    assert shadecore.normalize3(v.reshape(-1, 2, 3)[:5] if v.shape[0] % 2 == 0 else v[:10].reshape(5, 2, 3),
                                frac).shape == (5, 2, 3)


@pytest.mark.parametrize("frac", [8, 16])
def test_recip_bound(frac):
    q = np.arange(0, 1 << (frac + 9), 7 if frac == 16 else 1, dtype=np.int64)
    att = shadecore.recip(q, frac)
    att_max = (1 << (frac + 8)) - 1
    with np.errstate(divide="ignore"):
        exact = np.where(q > 0, 2.0 ** (2 * frac) / np.maximum(q, 1), np.inf)
    sat = exact >= att_max
    assert np.all(att[sat] == att_max)
    assert np.max(np.abs(att[~sat] - exact[~sat])) <= 1.0
