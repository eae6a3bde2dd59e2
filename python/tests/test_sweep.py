# SPDX-License-Identifier: Apache-2.0
# shadecore.sweep (the table as NumPy arrays) against `shadecore sweep --json/--csv`, value for value; the version.
import csv
import json

import numpy as np
import pytest

import shadecore


@pytest.mark.parametrize("variant,args,kw", [
    ("cs16", ["--config", "narrow"], {"config": "narrow", "n": "16..1024"}),
    ("cs16", ["--n", "120..136", "--cutoff", "sign_clamp"], {"n": (120, 136), "cutoff": "sign_clamp"}),
    ("cs16_compact", ["--frac", "12", "--guard", "6", "--n", "16..300"], {"frac": 12, "guard": 6, "n": "16..300"}),
    ("schlick_nr", ["--config", "narrow"], {"config": "narrow", "n": "16..1024"}),
    ("table256", ["--n", "500"], {"n": 500}),
])
def test_sweep_matches_cli(cli, tmp_path, variant, args, kw):
    js, cs = tmp_path / "s.json", tmp_path / "s.csv"
    cli.run("sweep", "--variant", variant, *args, "--json", js, "--csv", cs, "--threads", 2)
    j = json.loads(js.read_text())
    r = shadecore.sweep(variant, threads=2, **kw)
    assert r["evaluations"] == j["evaluations"]
    assert list(r["n"]) == [row["n"] for row in j["per_n"]]
    for key in ("approx_max", "approx_min", "quant_max_ulp", "quant_min_ulp", "total_max", "total_min"):
        assert np.array_equal(r[key], [row[key] for row in j["per_n"]]), key
    for key in ("approx", "quant_ulp", "total"):
        for side in ("max", "min"):
            for field in ("value", "n", "code"):
                assert r[key][side][field] == j[key][side][field], (key, side, field)
    with open(cs) as f:
        rows = list(csv.DictReader(f))
    for key in ("approx_max_code", "approx_min_code", "quant_max_code", "quant_min_code", "total_max_code",
                "total_min_code", "nonzero_codes"):
        assert np.array_equal(r[key], [int(row[key]) for row in rows]), key
    assert list(r.keys())[:14] == list(rows[0].keys())  # the columns, named and ordered as the CSV's


def test_sweep_variants_match_cli_help(cli):
    assert set(shadecore.sweep_variants()) == set(shadecore.variants())


def test_sweep_lobe_from_unit_outputs():
    """nonzero_codes per n equals the count from the array API on every code: two paths, one model."""
    r = shadecore.sweep("schlick_iter", "16..40", config="narrow")
    codes = np.arange(257)
    grid = shadecore.schlick_iter(codes[None, :], np.arange(16, 41)[:, None], config="narrow")
    assert np.array_equal(r["nonzero_codes"], np.count_nonzero(grid, axis=1))


def test_version_is_the_cli_version(cli):
    assert shadecore.__version__ in cli.run("--version").stdout
