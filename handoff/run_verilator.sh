#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# run_verilator.sh — build the bundle's RTL (filelist.f) and the self-checking testbench
# (tb/$tb.v: tb_shadecore for the specular unit, tb_shadecore_light for the lighting core)
# with Verilator (--binary: the testbench's own clock and timing, no C++ to
# write), then run it once per vector file in vectors/. Exit status 0 only if every run prints
# "PASS <n> vectors" for all of its n vectors.
#
#   ./run_verilator.sh                 the recorded seed (tb/tb_config.vh, TB_SEED)
#   SEED=7 ./run_verilator.sh          other random input gaps and output backpressure
#   IN_GAP=0 OUT_STALL=0 ./run_verilator.sh   no gaps, no backpressure (then latency must be exact)
#   RESET_AT=-1 ./run_verilator.sh     no reset in the middle of the stream
#   VERILATOR_OBJ_DIR=dir ./run_verilator.sh  keep the build in dir and reuse it while the sources
#                                      are older than it (default: a temporary directory)
#   FILELIST=signoff/gates_verilator.f ./run_verilator.sh   another design file list: the mapped netlist
#                                      and cell models Verilator reads (gate-level simulation, signoff/signoff.py);
#                                      its lint warnings are shown, not fatal (the netlist is the tools' text);
#                                      a build of its own (dir/gates)
#   VECTORS=vectors/random.hex VCD=/tmp/a.vcd ./run_verilator.sh   one vector file; a waveform of the design's
#                                      nets ($dumpvars through +vcd=, tb/tb_common.vh): VCD, or FST when the
#                                      name ends in .fst; a build of its own (--trace / --trace-fst, in
#                                      dir/trace-vcd or dir/trace-fst), the plain build stays as it is
# Needs Verilator 5 (--binary, --timing) and a C++ compiler.
set -u
tb=tb_shadecore   # the testbench module, tb/$tb.v (shadecore handoff sets it per core)
cd "$(dirname "$0")" || exit 1
command -v verilator >/dev/null 2>&1 || { echo "run_verilator.sh: FAIL: verilator not found"; exit 1; }
log=$(mktemp "${TMPDIR:-/tmp}/shadecore_verilator_log.XXXXXX") || exit 1
if [ -n "${VERILATOR_OBJ_DIR:-}" ]; then
  obj=$VERILATOR_OBJ_DIR
  trap 'rm -f "$log"' EXIT
  mkdir -p "$obj" || exit 1
else
  obj=$(mktemp -d "${TMPDIR:-/tmp}/shadecore_verilator.XXXXXX") || { rm -f "$log"; exit 1; }
  trap 'rm -f "$log"; rm -rf "$obj"' EXIT
fi
trap 'exit 130' INT TERM

plus=""
[ -n "${SEED:-}" ] && plus="$plus +seed=$SEED"
[ -n "${IN_GAP:-}" ] && plus="$plus +in_gap=$IN_GAP"
[ -n "${OUT_STALL:-}" ] && plus="$plus +out_stall=$OUT_STALL"
[ -n "${RESET_AT:-}" ] && plus="$plus +reset_at=$RESET_AT"
filelist=${FILELIST:-filelist.f}
[ -f "$filelist" ] || { echo "run_verilator.sh: FAIL: no such file list: $filelist"; exit 1; }
warn=-Wall ; sub=""
if [ "$filelist" != filelist.f ]; then warn="-Wno-fatal -Wno-lint -Wno-style" ; sub=/gates ; fi
trace="" ; bdir=$obj$sub   # the build used: $obj, or a trace build of its own under it
if [ -n "${VCD:-}" ]; then
  plus="$plus +vcd=$VCD"
  case "$VCD" in
    *.fst) trace=--trace-fst ; bdir="$obj$sub/trace-fst" ;;
    *)     trace=--trace ; bdir="$obj$sub/trace-vcd" ;;
  esac
fi

jobs=$(nproc 2>/dev/null || echo 2)
mkdir -p "$bdir" || exit 1
# shellcheck disable=SC2046
if [ -x "$bdir/Vtb" ] && [ -z "$(find rtl tb "$filelist" $(grep -v '^[+-]' "$filelist") -newer "$bdir/Vtb" 2>/dev/null | head -n 1)" ]; then
  echo "run_verilator.sh: reusing $bdir/Vtb (sources unchanged)"
else
  # -Wall without -Wno-fatal: every warning fails the build (the bundle, testbench included, lints clean).
  echo "run_verilator.sh: verilator --binary $warn $trace${trace:+ }-I tb -f $filelist --top-module $tb tb/$tb.v"
  # shellcheck disable=SC2086
  if ! verilator --binary -j "$jobs" $warn $trace -Itb -f "$filelist" --top-module "$tb" \
       -Mdir "$bdir" -o Vtb "tb/$tb.v" >"$log" 2>&1; then
    tail -n 40 "$log"
    echo "run_verilator.sh: FAIL: build failed"
    exit 1
  fi
fi

status=0 ; total=0 ; summary=""
for f in ${VECTORS:-vectors/*.hex}; do
  [ -f "$f" ] || continue
  n=$(grep -c '^[0-9a-fA-F]' "$f")
  echo "run_verilator.sh: Vtb +vectors=$f +nvec=$n$plus"
  # shellcheck disable=SC2086
  # (in a child shell, so the "Aborted" of a failing run, $stop, lands in the log, not on the terminal)
  sh -c '"$@"; r=$?; exit $r' sh "$bdir/Vtb" "+vectors=$f" "+nvec=$n" $plus >"$log" 2>&1
  rc=$?
  grep -v -e '^- ' -e '^Aborting' -e 'Aborted' -e 'Verilog \$stop' "$log"
  if [ $rc -eq 0 ] && grep -q "^PASS $n vectors" "$log" && ! grep -q '^FAIL' "$log"; then
    total=$((total + n)) ; summary="$summary $(basename "$f") $n"
  else
    status=1 ; summary="$summary $(basename "$f") FAIL"
  fi
done
if [ -z "$summary" ]; then echo "run_verilator.sh: FAIL: no vector files in vectors/"; exit 1; fi
if [ $status -eq 0 ]; then
  echo "run_verilator.sh: PASS $total vectors ($summary )"
else
  echo "run_verilator.sh: FAIL ($summary )"
fi
exit $status
