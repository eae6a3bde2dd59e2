# SPDX-License-Identifier: Apache-2.0
# LightCore from Python against the CLI: `shadecore vectors --core lighting` writes register writes, fragments and the
# expected colours of LightCore::eval (the co-simulation's model); replayed here record by record through
# LightCore.write and LightCore.eval, every colour must be equal. The GL-like state dict and eval_double are checked
# against the same model's register writes and its fixed-point result.
import numpy as np
import pytest

import shadecore
from conftest import signed


def read_records(path):
    rows = [line.split() for line in path.read_text().splitlines() if line and not line.startswith("//")]
    return np.array([[int(w, 16) for w in r] for r in rows], dtype=np.int64)


def replay(core, rec, frac):
    """Apply the records in order: runs of writes, then runs of fragments through eval. Returns (got, expected)."""
    got, want = [], []
    is_frag = rec[:, 0] != 0
    start = 0
    while start < len(rec):
        end = start
        while end < len(rec) and is_frag[end] == is_frag[start]:
            end += 1
        r = rec[start:end]
        if not is_frag[start]:
            core.write(r[:, 1], r[:, 2])
        else:
            n = signed(r[:, 1:4], frac + 2)
            p = signed(r[:, 4:7], frac + 8)
            back = (r[:, 0] >> 1) & 1
            out = core.eval(n, p, colour=r[:, 13:16], back=back)
            got.append(np.hstack([out["colour"], out["secondary"]]))
            want.append(r[:, 7:13])
        start = end
    return np.vstack(got), np.vstack(want)


@pytest.mark.parametrize("features,mode", [("full", "random"), ("diffuse", "random"), ("gl_default", "random"),
                                           ("mono_spec", "random"), ("full", "hard"), ("phong_point", "hard")])
def test_eval_matches_cli_vectors(cli, tmp_path, features, mode):
    out = tmp_path / "l.hex"
    extra = ["--count", 1500, "--seed", 38] if mode == "random" else []
    cli.run("vectors", "--core", "lighting", "--features", features, "--mode", mode, *extra, "--out", out)
    core = shadecore.LightCore(features)
    assert core.name == features
    got, want = replay(core, read_records(out), core.frac)
    assert len(got) > 100
    # mono cores drive 0 on g and b
    assert np.array_equal(got, want), f"{np.count_nonzero(np.any(got != want, axis=1))} of {len(got)} fragments differ"


def test_program_from_state_and_eval_double():
    core = shadecore.LightCore("gl_default")
    a, d = core.program({
        "global_ambient": [0.1, 0.1, 0.1],
        "material": {"diffuse": [0.7, 0.5, 0.3], "specular": [0.5, 0.5, 0.5], "shininess": 64},
        "lights": [{"position": [0.3, 0.4, 1.0, 0.0], "diffuse": [1, 1, 1], "specular": [1, 1, 1]}],
    })
    assert len(a) == len(d) > 10
    # the same writes through write() on a fresh core give the same colours
    other = shadecore.LightCore("gl_default")
    other.write(a, d)
    rng = np.random.default_rng(1)
    normals = rng.normal(size=(4000, 3))
    normals[:, 2] = np.abs(normals[:, 2])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    n, p = core.fragment_codes(normals, np.zeros_like(normals) + [0.0, 0.0, -5.0])
    fixed = core.eval(n, p)["colour"]
    assert np.array_equal(fixed, other.eval(n, p)["colour"])
    # against the unit's own function in double: the core's quantisation, within ±128 LSB at F = 16
    # (docs/lighting.md §7); against cos^n the cs16 approximation adds up to 1.7e-2 times the specular colour
    err = np.abs(fixed / 2.0 ** core.frac - core.eval_double(n, p, reference="variant")["colour"])
    assert 0 < err.max() <= 128 * 2.0 ** -core.frac
    exact = np.abs(fixed / 2.0 ** core.frac - core.eval_double(n, p)["colour"])
    assert err.max() < exact.max() <= 0.5 * 1.7e-2 + 128 * 2.0 ** -core.frac
    assert np.all(fixed[:, 0] >= fixed[:, 2])  # a warm material under a white light


def test_light_errors():
    with pytest.raises(ValueError, match=r"unknown feature set 'difuse' \(did you mean 'diffuse'\?\)"):
        shadecore.LightCore("difuse")
    with pytest.raises(ValueError, match="No such file"):
        shadecore.LightCore("nope.json")
    core = shadecore.LightCore("diffuse")
    with pytest.raises(ValueError, match="unknown key 'colour' in material"):
        core.program({"material": {"colour": [1, 1, 1]}})
    with pytest.raises(ValueError, match="out of range"):
        core.program({"material": {"diffuse": [3, 0, 0]}})
    with pytest.raises(ValueError, match="shape"):
        core.eval(np.zeros((4, 2), np.int64), np.zeros((4, 2), np.int64))
    with pytest.raises(ValueError, match="normal code"):
        core.eval([[1 << 20, 0, 0]], [[0, 0, 0]])
    custom = shadecore.LightCore({"config": "narrow", "lights": ["directional", "point"], "ambient": True,
                                  "diffuse": True, "specular": "none"})
    assert custom.name == "custom" and custom.frac == 8 and custom.num_lights == 2
    with pytest.raises(ValueError, match="'lights' must be a list"):
        shadecore.LightCore({"lights": 1})
