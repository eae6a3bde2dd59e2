# SPDX-License-Identifier: Apache-2.0
# Fixtures of the Python package's tests (ctest -L python): the CLI they compare against. ctest sets
# SHADECORE_CLI (the build's shadecore) and PYTHONPATH (<build>/python).
import json
import os
import subprocess

import numpy as np
import pytest


class Cli:
    def __init__(self, path):
        self.path = path

    def run(self, *args, check=True):
        p = subprocess.run([self.path, *map(str, args)], capture_output=True, text=True, timeout=120)
        if check and p.returncode != 0:
            raise AssertionError(f"shadecore {' '.join(map(str, args))} exited {p.returncode}: {p.stderr}")
        return p

    def eval_json(self, *args):
        return json.loads(self.run("eval", *args, "--json", "-").stdout)

    def error(self, *args):
        """The one-line message of a refused command, without 'shadecore: error: ' and the help pointer."""
        p = self.run(*args, check=False)
        assert p.returncode == 1, p
        line = p.stderr.strip()
        assert "\n" not in line, line
        assert line.startswith("shadecore: error: "), line
        line = line[len("shadecore: error: "):]
        return line.split(" (see shadecore")[0]

    def vectors(self, tmp_path, *args):
        """`shadecore vectors ... --out FILE` as arrays n, thr, coef, code (signed), expected."""
        out = tmp_path / "v.hex"
        self.run("vectors", *args, "--out", out)
        rows = [line.split() for line in out.read_text().splitlines() if line and not line.startswith("//")]
        a = np.array([[int(w, 16) for w in r] for r in rows], dtype=np.int64)
        return a[:, 0], a[:, 1], a[:, 2], a[:, 3], a[:, 4]


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("SHADECORE_CLI")
    assert path and os.access(path, os.X_OK), "SHADECORE_CLI must name the built shadecore executable"
    return Cli(path)


def signed(words, bits):
    """Two's-complement words of `bits` bits as signed integers."""
    words = np.asarray(words, dtype=np.int64)
    return np.where(words >= (1 << (bits - 1)), words - (1 << bits), words)
