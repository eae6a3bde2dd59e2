#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The main job: install what is missing, build, then the default exhaustive sweep (cs16, default
# width, n = 16..1024, every input code) with its table, JSON, CSV and plots under out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
BUILD_DIR=${BUILD_DIR:-build}
OUT=${OUT:-out}
mkdir -p "$OUT"
"$BUILD_DIR/cli/shadecore" sweep --json "$OUT/sweep.json" --csv "$OUT/sweep.csv" --plots "$OUT/plots"
