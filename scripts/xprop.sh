#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# X-propagation runs of one specular unit or of the lighting core (issue 21, docs/formal.md §5, §7.5), on its
# handoff bundle:
#
#   scripts/xprop.sh SHADECORE WORKDIR [--seeds "1 2 3"] -- HANDOFF-ARGS...     (e.g. --variant cs16 --config narrow,
#                                                                               or --core lighting --features diffuse)
#
# 1. `shadecore handoff HANDOFF-ARGS` writes the bundle (RTL, self-checking testbench, vectors from the C model).
# 2. Icarus (4-state): the bundle's testbench with every register of the unit X until the reset (Icarus starts
#    every reg at X and the RTL resets only the valid bits); the testbench fails on an X on out_valid_o /
#    in_ready_o after the reset and on any output word or tag that is not bit-identical (!==) to the C model's.
# 3. Verilator 2-state with the X's made random: built with --x-assign unique --x-initial unique, run with
#    +verilator+rand+reset+2 (every flop a random value at time 0; a seed alone gives zeros) and
#    +verilator+seed+S for each seed: every run must pass every vector (0 mismatches).
# 4. Both checks can fail: a copy of the bundle whose control does not clear its valid bits in reset must FAIL
#    the Icarus run (X after reset) and at least one Verilator seed (random valid bits = spurious results).
# Prints "xprop: PASS" and removes WORKDIR on success; exit 1 otherwise.
set -u
exe=$1; work=$2; shift 2
seeds="1 2 3"
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  case "$1" in
    --seeds) seeds=$2; shift ;;
    *) echo "xprop: bad option $1"; exit 2 ;;
  esac
  shift
done
[ "${1:-}" = "--" ] && shift
fail() { echo "xprop: FAIL: $*"; exit 1; }

b="$work/bundle"
if [ -n "${XPROP_REUSE:-}" ] && [ -f "$b/filelist.f" ]; then
  rm -rf "$work/run" "$work/mut"; echo "xprop: reusing $b (XPROP_REUSE)"
else
  rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
  out=$("$exe" handoff "$@" --no-ice40 --signoff off --out "$b" 2>&1); rc=$?
  echo "$out" | tail -n 3
  [ $rc -eq 0 ] || fail "handoff exited $rc"
fi
top=tb_shadecore
# the lighting core's bundle has its own testbench (tb/tb_shadecore_light.v: register writes, fragments, colours)
light=0
if [ -f "$b/tb/tb_shadecore_light.v" ] && grep -q "sc_light.v" "$b/filelist.f"; then top=tb_shadecore_light; light=1; fi

# icarus DIR -> 0 when every vector file passes; prints the testbench's lines
icarus() {
  local d=$1 st=0 f n
  (cd "$d" && iverilog -g2005 -Wall -I tb -f filelist.f -s $top -o x.vvp "tb/$top.v") >"$d/icarus_compile.log" 2>&1 ||
    { cat "$d/icarus_compile.log"; return 2; }
  for f in "$d"/vectors/*.hex; do
    n=$(grep -c '^[0-9a-fA-F]' "$f")
    (cd "$d" && vvp -n x.vvp "+vectors=vectors/$(basename "$f")" "+nvec=$n") >"$d/icarus_run.log" 2>&1
    if grep -q "^PASS $n vectors" "$d/icarus_run.log" && ! grep -q '^FAIL' "$d/icarus_run.log"; then
      echo "xprop: icarus $(basename "$f"): PASS $n vectors"
    else
      echo "xprop: icarus $(basename "$f"): $(grep -m1 '^FAIL' "$d/icarus_run.log")"; st=1
    fi
  done
  return $st
}
# verilator DIR -> 0 when every seed passes every vector file
verilator_x() {
  local d=$1 st=0 f n s t0=$SECONDS
  (cd "$d" && verilator --binary -j 2 -Wno-fatal -Wno-lint -Wno-style --x-assign unique --x-initial unique -Itb \
      -f filelist.f --top-module $top -Mdir obj_x -o Vtb "tb/$top.v") >"$d/verilator_build.log" 2>&1 ||
    { tail -n 20 "$d/verilator_build.log"; return 2; }
  echo "xprop: verilator --x-assign unique --x-initial unique build of $top: $((SECONDS - t0)) s"
  for s in $seeds; do
    for f in "$d"/vectors/*.hex; do
      n=$(grep -c '^[0-9a-fA-F]' "$f")
      (cd "$d" && sh -c '"$@"; exit $?' sh ./obj_x/Vtb "+vectors=vectors/$(basename "$f")" "+nvec=$n" +verilator+rand+reset+2 \
          "+verilator+seed+$s") >"$d/verilator_run.log" 2>&1
      if grep -q "^PASS $n vectors" "$d/verilator_run.log" && ! grep -q '^FAIL' "$d/verilator_run.log"; then
        echo "xprop: verilator seed $s $(basename "$f"): PASS $n vectors"
      else
        echo "xprop: verilator seed $s $(basename "$f"): $(grep -m1 '^FAIL' "$d/verilator_run.log")"; st=1
      fi
    done
  done
  return $st
}

cp -r "$b" "$work/run" || fail "copy"
icarus "$work/run" || fail "Icarus 4-state run (registers X before reset)"
verilator_x "$work/run" || fail "Verilator --x-assign unique --x-initial unique +verilator+rand+reset+2"

# 4. the checks can fail: the valid bits are not cleared in reset
cp -r "$b" "$work/mut" || fail "copy"
ctl="$work/mut/rtl/sc_pipe_ctrl.v"
old="v_q <= {DEPTH{1'b0}};"
new=""
if [ $light -eq 1 ]; then
  # the lighting core: its back's valid bits (the output stage among them) are not cleared in reset
  ctl="$work/mut/rtl/sc_light.v"; old="vb_q <= {NB{1'b0}};"; new="vb_q <= vb_q;"
elif [ -f "$work/mut/rtl/sc_schlick_iter.v" ] && grep -q "sc_schlick_iter" "$work/mut/filelist.f" &&
   ! grep -q "sc_pipe_ctrl" "$work/mut/filelist.f"; then
  ctl="$work/mut/rtl/sc_schlick_iter.v"; old="out_valid_q <= 1'b0;"
fi
[ "$(grep -cF "$old" "$ctl")" -ge 1 ] || fail "mutation text not found in $ctl"
python3 - "$ctl" "$old" "$new" <<'EOF' || fail "mutation"
import sys
p, old, new = sys.argv[1], sys.argv[2], sys.argv[3]
s = open(p).read()
i = s.index(old)
s = s[:i] + new + "// mutated: valid not cleared in reset" + s[i + len(old):]
open(p, "w").write(s)
EOF
if icarus "$work/mut" >/dev/null; then fail "a control that keeps X valid bits through reset passed the Icarus run"; fi
grep -q "X after reset\|^FAIL" "$work/mut/icarus_run.log" || fail "the Icarus run of the mutant failed without a FAIL line"
echo "xprop: mutant (valid bits not reset) fails the Icarus run: $(grep -m1 '^FAIL' "$work/mut/icarus_run.log")"
if verilator_x "$work/mut" >/dev/null; then fail "a control with random valid bits after reset passed every Verilator seed"; fi
echo "xprop: mutant fails Verilator with random initial values"
rm -rf "$work"
echo "xprop: PASS"
