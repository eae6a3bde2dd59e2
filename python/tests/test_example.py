# SPDX-License-Identifier: Apache-2.0
# The example script of docs/python.md runs and writes its figure.
import os
import subprocess
import sys

EXAMPLE = os.path.join(os.path.dirname(__file__), "..", "examples", "cs16_vs_cos.py")


def test_example_draws_its_figure(tmp_path):
    out = tmp_path / "fig.png"
    p = subprocess.run([sys.executable, EXAMPLE, "--out", str(out), "--sphere-n", "100"], capture_output=True,
                       text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 20000
    assert "wrote" in p.stdout
