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
        data = out.read_bytes()
        start = 0
        while data.startswith(b"//", start):  # the // header, then fixed-width records
            start = data.index(b"\n", start) + 1
        first = data[start:data.index(b"\n", start)].decode()
        widths = [len(w) for w in first.split()]
        width = len(first) + 1
        body = data[start:]
        assert len(widths) == 5 and len(body) % width == 0, "fixed-width hex columns"
        rows = np.frombuffer(body, dtype=np.uint8).reshape(-1, width)
        assert np.all(rows[:, -1] == ord("\n")), "fixed-width hex columns"
        chars = rows.astype(np.int64)
        digits = np.where(chars >= ord("a"), chars - ord("a") + 10, chars - ord("0"))
        cols, pos = [], 0
        for w in widths:  # vectorised hex parsing (the files have ~10^5..10^6 words)
            value = np.zeros(len(rows), dtype=np.int64)
            for k in range(w):
                value = value * 16 + digits[:, pos + k]
            cols.append(value)
            pos += w + 1
        return tuple(cols)


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("SHADECORE_CLI")
    assert path and os.access(path, os.X_OK), "SHADECORE_CLI must name the built shadecore executable"
    return Cli(path)


def signed(words, bits):
    """Two's-complement words of `bits` bits as signed integers."""
    words = np.asarray(words, dtype=np.int64)
    return np.where(words >= (1 << (bits - 1)), words - (1 << bits), words)
