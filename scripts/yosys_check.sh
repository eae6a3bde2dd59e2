#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Synthesis sanity check of an RTL top with Yosys (generic cells, technology independent).
#
#   scripts/yosys_check.sh --top MODULE [-I DIR]... [-P NAME=VALUE]... [--log FILE] FILE.v...
#
# Reads the files, sets the top's parameters, then
#   1. hierarchy -check                      (missing modules, elaboration $error of bad parameters)
#   2. proc; no $dlatch/$adlatch/$dlatchsr   (latches inferred from always blocks)
#   3. synth -flatten -top MODULE
#   4. check -assert                         (multiple drivers, logic loops, undriven inputs)
#   5. no $_DLATCH_*/$_SR_* cells after synthesis
# and prints the cell statistics. Exit 0 and "yosys_check: PASS ..." when everything holds; exit 1
# and one line "yosys_check: FAIL: <reason> ..." otherwise (the full log is in --log or a temp file).
set -euo pipefail

top="" ; log="" ; incs=() ; params=() ; files=()
while [ $# -gt 0 ]; do
  case "$1" in
    --top) top="$2"; shift 2 ;;
    -I) incs+=("-I$2"); shift 2 ;;
    -P) params+=("$2"); shift 2 ;;
    --log) log="$2"; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    -*) echo "yosys_check: error: unknown option $1" >&2; exit 2 ;;
    *) files+=("$1"); shift ;;
  esac
done
if [ -z "$top" ] || [ ${#files[@]} -eq 0 ]; then
  echo "yosys_check: error: need --top MODULE and at least one Verilog file" >&2; exit 2
fi
command -v yosys >/dev/null || { echo "yosys_check: error: yosys not found (scripts/setup.sh)" >&2; exit 2; }
if [ -z "$log" ]; then log=$(mktemp /tmp/yosys_check.XXXXXX.log); fi

chparams=""
for p in "${params[@]+"${params[@]}"}"; do chparams+=" -chparam ${p%%=*} ${p#*=}"; done

# Each step logs a marker first (helps to read the log); the failure reason comes from the messages.
script="read_verilog ${incs[*]+"${incs[*]}"} ${files[*]};
log STEP hierarchy; hierarchy -check -top ${top}${chparams};
log STEP proc; proc;
log STEP latch; select -assert-none t:\$dlatch t:\$adlatch t:\$dlatchsr;
log STEP synth; synth -flatten -top ${top};
log STEP check; check -assert;
log STEP latch; select -assert-none t:\$_DLATCH_* t:\$_DLATCHSR_* t:\$_SR_* t:\$dlatch t:\$adlatch;
log STEP stat; stat;
log STEP done"

desc="top=${top}${chparams}"
if yosys -p "$script" >"$log" 2>&1; then
  cells=$(grep -E '^ +Number of cells:' "$log" | tail -1 | awk '{print $4}')
  echo "yosys_check: PASS ${desc}: no latches, no multiple drivers, no logic loops (${cells:-?} cells; log ${log})"
  exit 0
fi
step=$(grep -E '^STEP ' "$log" | tail -1 | awk '{print $2}')
err=$(grep -m1 -E 'ERROR' "$log" || true)
if grep -q -E 'Assertion failed: selection is not empty: t:.*(DLATCH|dlatch)' "$log"; then
  reason="latch inferred: ${err}"
elif grep -q -i 'logic loop' "$log"; then
  reason="combinational logic loop"
elif grep -q -i 'multiple conflicting drivers' "$log"; then
  reason="multiple drivers"
elif [ "$step" = "hierarchy" ]; then
  reason="elaboration failed: ${err}"
else
  reason="yosys failed after step '${step:-read}': ${err}"
fi
echo "yosys_check: FAIL: ${reason} (${desc}; log ${log})"
exit 1
