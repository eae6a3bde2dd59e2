#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# run_icarus.sh — compile the bundle's RTL (filelist.f) and the self-checking testbench
# (tb/$tb.v: tb_shadecore for the specular unit, tb_shadecore_light for the lighting core)
# with Icarus Verilog as plain Verilog-2005, then run it once per vector file in
# vectors/. Exit status 0 only if every run prints "PASS <n> vectors" for all of its n vectors.
#
#   ./run_icarus.sh                    the recorded seed (tb/tb_config.vh, TB_SEED)
#   SEED=7 ./run_icarus.sh             other random input gaps and output backpressure
#   IN_GAP=0 OUT_STALL=0 ./run_icarus.sh   no gaps, no backpressure (then latency must be exact)
#   RESET_AT=-1 ./run_icarus.sh        no reset in the middle of the stream
#   FILELIST=signoff/gates.f ./run_icarus.sh   another design file list: the mapped netlist and the
#                                      cell library's models (gate-level simulation, signoff/signoff.py)
#   VECTORS=vectors/random.hex VCD=/tmp/a.vcd ./run_icarus.sh   one vector file; a VCD of the design's nets
#                                      ($dumpvars through +vcd=, tb/tb_common.vh); FST when the name ends in .fst
# Needs iverilog and vvp (Icarus Verilog 11 or newer). Works in a temporary directory; the bundle is
# not modified.
set -u
tb=tb_shadecore   # the testbench module, tb/$tb.v (shadecore handoff sets it per core)
cd "$(dirname "$0")" || exit 1
for t in iverilog vvp; do
  command -v "$t" >/dev/null 2>&1 || { echo "run_icarus.sh: FAIL: $t not found (install Icarus Verilog)"; exit 1; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/shadecore_icarus.XXXXXX") || exit 1
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT TERM

plus=""
[ -n "${SEED:-}" ] && plus="$plus +seed=$SEED"
[ -n "${IN_GAP:-}" ] && plus="$plus +in_gap=$IN_GAP"
[ -n "${OUT_STALL:-}" ] && plus="$plus +out_stall=$OUT_STALL"
[ -n "${RESET_AT:-}" ] && plus="$plus +reset_at=$RESET_AT"
[ -n "${VCD:-}" ] && plus="$plus +vcd=$VCD"
fst=""
case "${VCD:-}" in *.fst) fst=-fst ;; esac
filelist=${FILELIST:-filelist.f}
[ -f "$filelist" ] || { echo "run_icarus.sh: FAIL: no such file list: $filelist"; exit 1; }

echo "run_icarus.sh: iverilog -g2005 -Wall -I tb -f $filelist -s $tb tb/$tb.v"
if ! iverilog -g2005 -Wall -I tb -f "$filelist" -s "$tb" -o "$work/tb.vvp" "tb/$tb.v" \
     >"$work/compile.log" 2>&1; then
  cat "$work/compile.log"
  echo "run_icarus.sh: FAIL: compilation failed"
  exit 1
fi
[ -s "$work/compile.log" ] && cat "$work/compile.log"

status=0 ; total=0 ; summary=""
for f in ${VECTORS:-vectors/*.hex}; do
  [ -f "$f" ] || continue
  n=$(grep -c '^[0-9a-fA-F]' "$f")
  echo "run_icarus.sh: vvp -n tb.vvp $fst${fst:+ }+vectors=$f +nvec=$n$plus"
  # shellcheck disable=SC2086
  vvp -n "$work/tb.vvp" $fst "+vectors=$f" "+nvec=$n" $plus >"$work/run.log" 2>&1
  rc=$?
  grep -v -e '^VCD info' -e '^FST info' "$work/run.log"
  if [ $rc -eq 0 ] && grep -q "^PASS $n vectors" "$work/run.log" && ! grep -q '^FAIL' "$work/run.log"; then
    total=$((total + n)) ; summary="$summary $(basename "$f") $n"
  else
    status=1 ; summary="$summary $(basename "$f") FAIL"
  fi
done
if [ -z "$summary" ]; then echo "run_icarus.sh: FAIL: no vector files in vectors/"; exit 1; fi
if [ $status -eq 0 ]; then
  echo "run_icarus.sh: PASS $total vectors ($summary )"
else
  echo "run_icarus.sh: FAIL ($summary )"
fi
exit $status
