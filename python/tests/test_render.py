# SPDX-License-Identifier: Apache-2.0
# shadecore.render against `shadecore render SCENE --out DIR --json FILE`: the C-model and exact images, pixel for
# pixel (the 8-bit PNGs the CLI writes), and the cores it derives.
import json
import os

import matplotlib.image
import numpy as np
import pytest

import shadecore

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "scenes")


@pytest.mark.parametrize("scene,size,extra", [
    ("spheres.json", "64x48", []), ("shading_modes.json", "72x48", []), ("gl_two_side.json", "64x40", []),
    ("gl_colour_material.json", "60x40", []), ("gl_shininess.json", "70x20", []),
    ("diffuse.json", "48x36", ["--full-core"]), ("spheres.json", "48x36", ["--full-core", "--share", "4"]),
])
def test_render_matches_cli(cli, tmp_path, scene, size, extra):
    path = os.path.join(SCENES, scene)
    cli.run("render", path, "--size", size, *extra, "--out", tmp_path / "r", "--json", tmp_path / "r.json")
    j = json.loads((tmp_path / "r.json").read_text())
    share = int(extra[extra.index("--share") + 1]) if "--share" in extra else 1
    r = shadecore.render(path, size, full_core="--full-core" in extra, share=share)
    w, h = map(int, size.split("x"))
    assert r["image"].shape == (h, w, 3) and r["covered"].shape == (h, w)
    for key, png in (("rgb8", "cmodel.png"), ("exact_rgb8", "exact.png")):
        img = matplotlib.image.imread(tmp_path / "r" / png)[:, :, :3]
        want = np.rint(img * 255).astype(np.uint8)
        assert np.array_equal(r[key], want), f"{png}: {np.count_nonzero(np.any(r[key] != want, axis=2))} pixels differ"
    assert r["cores"] == [f["summary"] for f in j["features"]]
    assert r["covered"].any() and not r["covered"].all()
    # the codes behind the 8-bit image: GL's colour sum, at most 1.0
    assert r["image"].max() <= 1 << r["frac"] and r["image"][r["covered"]].max() > 0
    assert np.all(np.abs(r["exact"] - r["unit_double"]) <= 1.0)


def test_render_errors(cli, tmp_path):
    with pytest.raises(ValueError, match="malformed"):
        shadecore.render(os.path.join(SCENES, "spheres.json"), "64*48")
    bad = tmp_path / "bad.json"
    bad.write_text('{"camera": 5}')
    for scene in (tmp_path / "nope.json", bad):
        with pytest.raises(ValueError) as e:
            shadecore.render(scene)
        assert str(e.value) == cli.error("render", scene, "--out", tmp_path / "out")
