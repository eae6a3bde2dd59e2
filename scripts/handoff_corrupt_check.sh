#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# One corrupted expected value must make both of a bundle's delivered simulator runs FAIL naming it
# (docs/handoff.md). Works on a copy; the bundle is not modified.
#
#   scripts/handoff_corrupt_check.sh BUNDLE_DIR [VECTOR_FILE]     (default vectors/random.hex)
#
# The first non-zero expected word of VECTOR_FILE is zeroed: EXPECTED of a specular-unit vector (five
# words a line) or R of a lighting-core fragment record (ten words, T = 1 + 16·latency: hex ending in 1). Its index among the data
# lines is the vector both run_icarus.sh and run_verilator.sh must name ("FAIL vector <index>:") while
# exiting non-zero. Prints "corrupt_check: PASS ..." and exits 0, or "corrupt_check: FAIL ..." and 1.
set -u
b=${1:?usage: handoff_corrupt_check.sh BUNDLE_DIR [VECTOR_FILE]}
vf=${2:-vectors/random.hex}
[ -f "$b/$vf" ] || { echo "corrupt_check: FAIL: no $b/$vf"; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/shadecore_corrupt.XXXXXX") || exit 1
trap 'rm -rf "$work"' EXIT
cp -r "$b" "$work/bundle" || exit 1
awk 'BEGIN{d=0; i=-1} $0 !~ /^\/\// {i++}
     !d && $0 !~ /^\/\// && NF==5 && $5 !~ /^0+$/ {gsub(/./,"0",$5); d=1; print i > "/dev/stderr"}
     !d && $0 !~ /^\/\// && NF==16 && $1 ~ /1$/ && $8 !~ /^0+$/ {gsub(/./,"0",$8); d=1; print i > "/dev/stderr"}
     {print}' "$b/$vf" > "$work/bundle/$vf" 2> "$work/idx"
idx=$(cat "$work/idx")
[ -n "$idx" ] || { echo "corrupt_check: FAIL: no non-zero expected value in $vf"; exit 1; }
status=0
for s in run_icarus.sh run_verilator.sh; do
  "$work/bundle/$s" > "$work/$s.log" 2>&1; rc=$?
  line=$(grep -m 1 '^FAIL' "$work/$s.log")
  if [ $rc -eq 0 ] || ! grep -q "^FAIL vector $idx:" "$work/$s.log"; then
    echo "corrupt_check: FAIL: $s exit $rc did not name vector $idx: ${line:-$(tail -n 1 "$work/$s.log")}"
    status=1
  else
    echo "corrupt_check: $s exit $rc: $(echo "$line" | cut -c1-160)"
  fi
done
[ $status -eq 0 ] && echo "corrupt_check: PASS: vector $idx of $vf corrupted; run_icarus.sh and run_verilator.sh both FAIL naming it"
exit $status
