#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# ctest python.install: `cmake --install BUILD --prefix PREFIX` gives an importable package (PREFIX/SITE/shadecore)
# whose outputs are the CLI's. Usage: install_check.sh CMAKE BUILD PREFIX SITE PYTHON SHADECORE_CLI
set -eu
cmake=$1 build=$2 prefix=$3 site=$4 python=$5 cli=$6
rm -rf "$prefix"
"$cmake" --install "$build" --prefix "$prefix" >/dev/null
cd /
PYTHONPATH="$prefix/$site" "$python" - "$prefix" "$cli" <<'PY'
import json, os, subprocess, sys
import numpy as np
import shadecore
prefix, cli = sys.argv[1], sys.argv[2]
assert os.path.realpath(shadecore.__file__).startswith(os.path.realpath(prefix)), shadecore.__file__
got = shadecore.cs16(np.arange(65532, 65537), n=128)
want = [json.loads(subprocess.run([cli, "eval", "--n", "128", "--code", str(c), "--json", "-"], check=True,
                                  capture_output=True, text=True).stdout)["out"] for c in range(65532, 65537)]
assert list(got) == want, (got, want)
print("install_check: PASS", shadecore.__file__, list(got))
PY
