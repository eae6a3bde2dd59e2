#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The full handoff matrix (issue 11): `shadecore handoff` for every variant at every named width, each
# also with energy normalisation (--norm all), and cs16 with the sign_clamp cut-off — each bundle is
# simulated by its own testbench on Icarus and Verilator before the command succeeds; then one expected
# value is corrupted in a copy and both run_icarus.sh and run_verilator.sh must FAIL. The default ctest
# suite runs a subset (rtl/CMakeLists.txt, handoff.*). Results: one line per bundle and a summary;
# docs/handoff.md records one. With CORES=lighting: the lighting core's bundle for the named feature sets
# of config/configs.json (`--core lighting --features NAME`; `full` only with FULL=1: its Yosys synthesis
# is skipped by default, but its simulations are long).
#
#   scripts/handoff_matrix.sh [OUT_DIR]          default out/handoff-matrix; ~30-60 min on 2 cores
#   ICE40=1 scripts/handoff_matrix.sh            also iCE40 place and route where the tools are installed
#   CORES=lighting scripts/handoff_matrix.sh     the lighting core's feature sets (CORES=all: both)
#   SHADECORE=build-h11/cli/shadecore scripts/handoff_matrix.sh
set -u
cd "$(dirname "$0")/.."
exe=${SHADECORE:-build/cli/shadecore}
out=${1:-out/handoff-matrix}
[ -x "$exe" ] || { echo "handoff_matrix: $exe not built (scripts/build.sh)"; exit 1; }
mkdir -p "$out" || exit 1
ice=--no-ice40; [ "${ICE40:-0}" = 1 ] && ice=
# The table units (contract "table") have no bundle yet: handoff refuses them (their testbench would need a
# table-load phase); VARIANTS="a b" restricts the list.
variants=${VARIANTS:-$(/usr/bin/python3 -c 'import json; print(" ".join(v["name"] for v in json.load(open("config/configs.json"))["variants"] if v.get("contract") != "table"))')}
configs=$(/usr/bin/python3 -c 'import json; print(" ".join(c["name"] for c in json.load(open("config/configs.json"))["configs"]))')
pass=0; fail=0; t0=$(date +%s)
run() {  # name, handoff options...
  local name=$1; shift
  local b="$out/$name" s e
  rm -rf "$b" "$b.tar.gz"
  s=$(date +%s)
  if "$exe" handoff "$@" $ice --signoff off --seed 1 --out "$b" > "$out/$name.log" 2>&1; then
    # one corrupted expected value must make both delivered simulator runs fail, naming it
    if ! scripts/handoff_corrupt_check.sh "$b" > "$out/$name.corrupt.log" 2>&1; then
      e="FAIL ($(grep -m 1 'corrupt_check: FAIL' "$out/$name.corrupt.log"))"; fail=$((fail + 1))
    else
      e="PASS  $(grep -o 'run_icarus.sh: PASS [0-9]* vectors' "$out/$name.log") / $(grep -o 'run_verilator.sh: PASS [0-9]* vectors' "$out/$name.log" | sed 's/run_verilator.sh: //'); $(grep -o 'vector [0-9]* of' "$out/$name.corrupt.log" | head -n 1 | sed 's/ of//') corrupted: both FAIL naming it; $(grep -o 'Yosys: .*' "$out/$name.log")"
      pass=$((pass + 1))
    fi
  else
    e="FAIL  $(tail -n 1 "$out/$name.log")"; fail=$((fail + 1))
  fi
  printf '%-28s %4ss  %s\n' "$name" "$(( $(date +%s) - s ))" "$e"
}
cores=${CORES:-specular}
if [ "$cores" = specular ] || [ "$cores" = all ]; then
  for v in $variants; do
    for c in $configs; do
      run "$v.$c" --variant "$v" --config "$c"
      run "$v.$c.norm" --variant "$v" --config "$c" --norm all
      [ "$v" = cs16 ] && run "$v.$c.sign_clamp" --variant "$v" --config "$c" --cutoff sign_clamp
    done
  done
fi
if [ "$cores" = lighting ] || [ "$cores" = all ]; then
  sets=$(/usr/bin/python3 -c 'import json; print(" ".join(s["name"] for s in json.load(open("config/configs.json"))["feature_sets"]))')
  for f in $sets; do
    [ "$f" = full ] && [ "${FULL:-0}" != 1 ] && continue
    run "light.$f" --core lighting --features "$f"
  done
fi
echo "handoff_matrix: $pass passed, $fail failed ($(( $(date +%s) - t0 )) s; $exe; $(date -u '+%Y-%m-%d %H:%M UTC'))"
[ $fail -eq 0 ]
