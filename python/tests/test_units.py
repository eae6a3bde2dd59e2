# SPDX-License-Identifier: Apache-2.0
# Every specular unit from Python against the CLI, bit for bit: `shadecore vectors` (the CLI's exhaustive and random
# vector lists, expected outputs from the C model) and `shadecore eval --json` (outputs, material words, double
# references).
import numpy as np
import pytest

import shadecore
from conftest import signed

VARIANTS = ["cs16", "cs16_faithful", "cs16_compact", "schlick_div", "schlick_nr", "schlick_iter", "table256",
            "table1024"]
CS16_LIKE = {"cs16", "cs16_faithful", "cs16_compact"}


def test_every_variant_is_covered():
    assert sorted(shadecore.variants()) == sorted(VARIANTS)


def test_done_when_example(cli):
    """The issue's example: cs16 at n = 128 on codes 0..65536, last five, equal to `shadecore eval`."""
    out = shadecore.cs16(np.arange(65537), n=128)
    assert out.shape == (65537,) and out.dtype == np.int64
    for code in range(65532, 65537):
        assert out[code] == cli.eval_json("--n", 128, "--code", code)["out"]


@pytest.mark.parametrize("variant", VARIANTS)
def test_exhaustive_narrow_every_n(cli, tmp_path, variant):
    """Every code 0..2^F and the four out-of-range extremes, every n 16..1024, narrow width (F = 8)."""
    n, thr, coef, word, expected = cli.vectors(tmp_path, "--variant", variant, "--config", "narrow", "--mode",
                                               "exhaustive", "--n", "16..1024")
    f = shadecore.format("narrow")
    codes = signed(word, f["frac"] + 2)
    got = shadecore.eval_unit(variant, codes, n, config="narrow")
    assert np.array_equal(got, expected), f"{np.count_nonzero(got != expected)} outputs differ"
    s = shadecore.setup(variant, np.arange(16, 1025), config="narrow")
    un, idx = np.unique(n, return_index=True)
    assert np.array_equal(s["thr"][un - 16], thr[idx])


@pytest.mark.parametrize("variant", VARIANTS)
def test_exhaustive_default_width(cli, tmp_path, variant):
    """Every code at F = 16 for two n (one n per call: the scalar-n path, and the block path for cs16)."""
    n, _, _, word, expected = cli.vectors(tmp_path, "--variant", variant, "--mode", "exhaustive", "--n", "128..129")
    codes = signed(word, 18)
    per_n = np.concatenate([shadecore.eval_unit(variant, codes[n == k], k) for k in (128, 129)])
    assert np.array_equal(per_n, expected)
    # the consecutive codes alone (cs16's block fast path), one n
    sel = (n == 128) & (codes >= 0) & (codes <= 65536)
    assert np.array_equal(shadecore.eval_unit(variant, np.arange(65537), 128), expected[sel])


@pytest.mark.parametrize("variant", sorted(CS16_LIKE))
def test_sign_clamp(cli, tmp_path, variant):
    n, _, _, word, expected = cli.vectors(tmp_path, "--variant", variant, "--config", "narrow", "--cutoff",
                                          "sign_clamp", "--mode", "exhaustive", "--n", "16..520")
    got = shadecore.eval_unit(variant, signed(word, 10), n, config="narrow", cutoff="sign_clamp")
    assert np.array_equal(got, expected)


@pytest.mark.parametrize("variant", VARIANTS)
def test_random_wide_and_custom(cli, tmp_path, variant):
    """Random vectors (every n, codes over the whole signed word) at the wide width and at F = 12, G = 6."""
    for width in (["--config", "wide"], ["--frac", "12"] + (["--guard", "6"] if variant in CS16_LIKE else [])):
        n, _, _, word, expected = cli.vectors(tmp_path, "--variant", variant, *width, "--mode", "random", "--count",
                                              3000, "--seed", 38)
        kw = {"config": "wide"} if width[1] == "wide" else {"frac": 12, "guard": 6 if variant in CS16_LIKE else None}
        f = shadecore.format(kw.get("config"), kw.get("frac"))
        assert np.array_equal(shadecore.eval_unit(variant, signed(word, f["frac"] + 2), n, **kw), expected)


def test_norm_all_and_model(cli, tmp_path):
    """The sc_energy stage after the unit (--norm all: model and kind per n; --norm blinn --coef classical)."""
    n, _, coef, word, expected = cli.vectors(tmp_path, "--config", "narrow", "--norm", "all", "--mode", "exhaustive",
                                             "--n", "16..1024")
    got = shadecore.cs16(signed(word, 10), n, config="narrow", norm="all")
    assert np.array_equal(got, expected)
    un, idx = np.unique(n, return_index=True)
    assert np.array_equal(shadecore.setup("cs16", un, config="narrow", norm="all")["coef"], coef[idx])
    n, _, coef, word, expected = cli.vectors(tmp_path, "--variant", "schlick_nr", "--norm", "blinn", "--coef",
                                             "classical", "--mode", "random", "--count", 5000, "--seed", 3)
    got = shadecore.schlick_nr(signed(word, 18), n, norm="blinn", coef="classical")
    assert np.array_equal(got, expected)


@pytest.mark.parametrize("variant,config,n,code", [
    ("cs16", "default", 128, 65000), ("cs16", "narrow", 1000, 255), ("cs16_faithful", "wide", 64, 16000000),
    ("cs16_compact", "default", 16, -5), ("schlick_div", "default", 300, 40000), ("schlick_nr", "narrow", 1000, 0xfe),
    ("schlick_iter", "wide", 17, 9999999), ("table256", "default", 700, 65535), ("table1024", "narrow", 20, 200),
])
def test_eval_json_outputs_and_references(cli, variant, config, n, code):
    """One input through `shadecore eval --json`: the output, material word and every double reference."""
    j = cli.eval_json("--variant", variant, "--config", config, "--n", n, "--code", code)
    assert shadecore.eval_unit(variant, [code], n, config=config)[0] == j["out"]
    assert shadecore.setup(variant, [n], config=config)["thr"][0] == j["material"]["thr"]
    c = shadecore.code_to_cos([code], config)
    assert shadecore.golden.cos_pow(c, n)[0] == j["double"]["cos_pow"]
    ref_name = "cs16" if variant in CS16_LIKE else ("table_lerp" if variant.startswith("table") else "schlick")
    ref = shadecore.golden.variant(variant, c, n)[0]
    assert ref == j["double"][ref_name]
    if ref_name == "cs16":
        assert ref == shadecore.golden.cs16(c, n)[0]
    if ref_name == "schlick":
        assert ref == shadecore.golden.schlick(c, n)[0]
    f = shadecore.format(config)
    assert j["out"] - np.ldexp(ref, f["frac"]) == j["double"]["error_ulp"]


def test_cos_input_matches_eval_cos(cli):
    for x in (0.95, 0.5, -0.25, 1.0, 0.999999):
        j = cli.eval_json("--n", 64, "--cos", x)
        assert shadecore.cos_to_code(x) == j["code"]
        assert shadecore.cs16(cos=[x], n=64)[0] == j["out"]


def test_broadcasting_n_and_shapes():
    codes = np.arange(0, 65537, 97)
    ns = np.array([16, 128, 1024])
    grid = shadecore.cs16(codes[None, :], ns[:, None])
    assert grid.shape == (3, codes.size)
    for i, k in enumerate(ns):
        assert np.array_equal(grid[i], shadecore.cs16(codes, int(k)))
    assert shadecore.cs16(np.int64(65536), 128).shape == ()
    assert shadecore.cs16(codes.reshape(1, -1), 128).shape == (1, codes.size)
    # non-contiguous and other integer dtypes give the same result
    assert np.array_equal(shadecore.cs16(codes[::2].astype(np.int32), 128), shadecore.cs16(codes[::2], 128))


@pytest.mark.parametrize("variant", VARIANTS)
def test_grid_equals_row_by_row(variant):
    """The (n × code) grid path (one row of codes, one column of n: no broadcast copies) equals row-by-row calls and
    the general broadcast path, for the units and the golden functions."""
    f = shadecore.format("narrow")
    codes = np.arange(f["in_min"], f["in_max"] + 1)  # consecutive: cs16's block form per row
    ns = np.array([16, 17, 300, 1024])
    grid = shadecore.eval_unit(variant, codes, ns[:, None], config="narrow")
    assert grid.shape == (4, codes.size)
    for i, k in enumerate(ns):
        assert np.array_equal(grid[i], shadecore.eval_unit(variant, codes, int(k), config="narrow"))
    general = shadecore.eval_unit(variant, np.broadcast_to(codes, (4, codes.size)), np.repeat(ns[:, None], codes.size, 1),
                                  config="narrow")
    assert np.array_equal(grid, general)
    odd = codes[::-3]  # not consecutive
    assert np.array_equal(shadecore.eval_unit(variant, odd, ns[:, None], config="narrow")[2],
                          shadecore.eval_unit(variant, odd, 300, config="narrow"))
    c = shadecore.code_to_cos(codes, "narrow")
    g = shadecore.golden.variant(variant, c, ns[:, None])
    assert np.array_equal(g[3], shadecore.golden.variant(variant, c, 1024))
    assert np.array_equal(shadecore.golden.cos_pow(c, ns[:, None])[1], shadecore.golden.cos_pow(c, 17))
