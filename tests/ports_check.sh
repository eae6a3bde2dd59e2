#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# The unit beyond the host's values (ctest handoff.ports.*; docs/spec.md §3.1 "Beyond the host's values"): a
# handoff bundle of VARIANT at the default width, then `shadecore vectors --mode ports` (n in 1..1024, 0..1024 for
# the dividers schlick_div and schlick_iter, the ends first; thr over its port, codes around it) through the bundle's
# own Icarus bench: the RTL must give the C model's bits on every vector. n > 1024, and n = 0 but for the dividers,
# are left out: there the RTL, sized for the host's values, and the C model differ (docs/spec.md §3.1).
# Usage: ports_check.sh SHADECORE WORKDIR VARIANT
set -eu
sc=$1 work=$2 variant=$3
rm -rf "$work"
mkdir -p "$work"
"$sc" handoff --variant "$variant" --config default --seed 5 --count 2000 --no-ice40 --synth skip --signoff off \
  --out "$work/bundle" >"$work/handoff.log" 2>&1 || { tail -5 "$work/handoff.log"; echo "ports_check: FAIL (handoff)"; exit 1; }
vecs=""
for s in 21 22 23; do
  "$sc" vectors --variant "$variant" --config default --mode ports --count 2000 --seed $s \
    --out "$work/bundle/vectors/ports$s.hex" >/dev/null
  vecs="$vecs vectors/ports$s.hex"
done
grep -q "^// mode ports, seed 21: n in [01]..1024" "$work/bundle/vectors/ports21.hex" || { echo "ports_check: FAIL (header)"; exit 1; }
if (cd "$work/bundle" && VECTORS="${vecs# }" ./run_icarus.sh >"$work/icarus.log" 2>&1); then
  tail -1 "$work/icarus.log"
  echo "ports_check: PASS ($variant)"
else
  grep "FAIL" "$work/icarus.log" | head -3
  echo "ports_check: FAIL ($variant)"
  exit 1
fi
