#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Self-test of a lighting-core harness's checks (ctest sim.light.{bare,axi}.selftest_detects_*): builds (or finds) the
# diffuse core of HARNESS (bare | axi) through `shadecore cosim`, then runs its simulator on 3000 random fragments with
# one observed value corrupted (--inject KIND --inject-at AT). Prints the run and "exit N"; exits 0 only when the run
# FAILED as it must (status 2).
#   light_inject_selftest.sh SHADECORE HARNESS KIND AT
set -u
shadecore=$1 harness=$2 kind=$3 at=$4
json=light_${harness}_selftest_${kind}.json
"$shadecore" cosim --core lighting --harness "$harness" --features diffuse --mode directed --count 10 --seed 43 \
  --json "$json" >/dev/null 2>&1 || { echo "light_inject_selftest: building the $harness core failed"; exit 1; }
d=$(sed -n 's/.*"build_dir": "\(.*\)".*/\1/p' "$json")
"$d/shadecore_light_$harness" --mode random --count 3000 --in-stall 0.2 --out-stall 0.3 --seed 43 --reset-at -1 \
  --inject "$kind" --inject-at "$at"
rc=$?
echo "exit $rc"
test $rc -eq 2
