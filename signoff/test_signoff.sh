#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ctest driver of the OSU 0.18 um sign-off (label timing; docs/signoff.md):
#
#   signoff/test_signoff.sh SHADECORE WORKDIR -- HANDOFF-ARGS...
#
# 1. `shadecore handoff HANDOFF-ARGS --signoff on` writes a bundle whose constraints.sdc carries the measured
#    clock (no placeholder; CLK_PERIOD = signoff.json's period), whose signoff/ holds the netlist and the
#    timing, area, power and gate-level reports, and whose summary has the sign-off line;
# 2. re-timing the bundle's netlist with its own constraints.sdc (`signoff.py . --retime`) gives the slack
#    signoff.json reports;
# 3. the same netlist with a chain of 40 buffers spliced in front of the critical path's end register
#    misses the target (`--steps sta`: met false, WNS more than 1 ns worse);
#    signoff/stages.py on it: the spliced register needs more pieces than the bundle's worst register, and on the bundle itself its
#    worst endpoint is the WNS signoff.json reports (no register misses exactly when the target is met);
# 4. the same netlist with one XOR cell of the datapath turned into an XNOR fails the gate-level
#    simulation (`--steps gatesim`: exit 2, passed false, mismatches > 0);
# 5. the Verilator gate-level route (`--gatesim verilator`: the cell models Yosys writes from the Liberty functions),
#    which auto takes for the largest runs: the bundle's netlist passes with the vectors Icarus counted, the mutant
#    of 4 fails.
# Exit 77 (ctest: skipped) with a note when yosys, sta, iverilog or qflow-tech-osu018 are missing.
# Prints "test_signoff: PASS" and removes WORKDIR on success.
set -u
exe=$1; work=$2; shift 2
[ "${1:-}" = "--" ] && shift
fail() { echo "test_signoff: FAIL: $*"; exit 1; }
for t in yosys sta iverilog vvp /usr/bin/python3; do
  command -v "$t" >/dev/null 2>&1 || { echo "test_signoff: SKIP: $t not installed (scripts/setup.sh installs it)"; exit 77; }
done
[ -f /usr/share/qflow/tech/osu018/osu018_stdcells.lib ] ||
  { echo "test_signoff: SKIP: qflow-tech-osu018 not installed (scripts/setup.sh installs it)"; exit 77; }
py=/usr/bin/python3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
b="$work/bundle"
jget() { "$py" -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2], {'d': d}))" "$1" "$2"; }

# 1. the bundle with the sign-off
out=$("$exe" handoff "$@" --no-ice40 --synth skip --signoff on --out "$b" 2>&1); rc=$?
echo "$out"
[ $rc -eq 0 ] || fail "handoff --signoff on exited $rc"
j="$b/signoff/signoff.json"
for f in signoff/signoff.json signoff/netlist.v signoff/timing.rpt signoff/area.rpt signoff/power.rpt \
         signoff/gatesim_icarus.log signoff/lib/osu018_stdcells.lib reports/signoff.log; do
  [ -s "$b/$f" ] || fail "the bundle has no $f"
done
grep -q placeholder "$b/constraints.sdc" && fail "constraints.sdc still has the placeholder"
period=$(jget "$j" "d['sta']['period_ns']")
grep -q "^set CLK_PERIOD $(printf '%.3f' "$period")\$" "$b/constraints.sdc" ||
  fail "constraints.sdc's CLK_PERIOD is not the measured $period ns: $(grep CLK_PERIOD "$b/constraints.sdc" | head -1)"
grep -q "set_timing_derate -late 1.15" "$b/constraints.sdc" || fail "constraints.sdc has no derate"
[ "$(jget "$j" "d['gatesim']['passed'] and d['gatesim']['mismatches'] == 0 and d['gatesim']['vectors'] > 0")" = True ] ||
  fail "the gate-level simulation did not pass: $(jget "$j" "d['gatesim']")"
[ "$(jget "$j" "d['power']['energy_pj_per_result'] > 0")" = True ] || fail "no energy per result"
# the netlist's own toggles reached OpenSTA: every net's activity taken, and the power differs from OpenSTA's
# propagation from the input ports alone (what the flow reported while OpenSTA 2.0.17 rejected every -pins line)
grep -q "^Error" "$b/signoff/power.rpt" && fail "OpenSTA reported errors in power.rpt: $(grep -m1 '^Error' "$b/signoff/power.rpt")"
[ "$(jget "$j" "d['power']['nets_annotated'] > 100 and d['power']['power_mw'] != d['power']['propagated_mw']")" = True ] ||
  fail "the gate-level activities did not change OpenSTA's power: $(jget "$j" "d['power']")"
grep -q "OSU 0.18 µm sign-off" "$b/reports/summary.md" || fail "summary.md has no sign-off line"
(cd "$b" && sha256sum -c --quiet MANIFEST.sha256) || fail "MANIFEST.sha256 does not cover the sign-off files"

# 2. re-timing with the bundle's own SDC gives the reported slack
rt=$("$py" "$b/signoff/signoff.py" "$b" --retime) || fail "re-timing failed: $rt"
echo "$rt"
want=$(jget "$j" "'%.3f' % d['sta']['critical_path']['sdc_wns_ns']")
echo "$rt" | grep -q "^wns $want ns" || fail "re-timing gave '$rt', signoff.json says $want ns"

# 3. a deliberately slow path misses the target
s="$work/slow"; cp -r "$b" "$s"
end=$(jget "$j" "d['sta']['critical_path']['end']")
"$py" - "$s/signoff/netlist.v" "$end" <<'EOF' || fail "could not splice the slow chain"
import re, sys
path, inst = sys.argv[1], sys.argv[2]
t = open(path).read()
m = re.search(r"(DFF\w+\s+%s\s*\(.*?\.D\()([^)]*)(\))" % re.escape(inst), t, re.S)
assert m, inst
d = m.group(2).strip()
chain = "".join(f"  BUFX2 slow_b{i} (.A({d if i == 0 else f'slow_{i - 1}'}), .Y(slow_{i}));\n" for i in range(40))
wires = "".join(f"  wire slow_{i};\n" for i in range(40))
t = t[:m.start(2)] + "slow_39" + t[m.end(2):]
t = t.replace("endmodule", wires + chain + "endmodule", 1)
open(path, "w").write(t)
EOF
"$py" "$s/signoff/signoff.py" "$s" --steps sta >"$work/slow.log" 2>&1 || { cat "$work/slow.log"; fail "sta on the slow netlist failed"; }
cat "$work/slow.log"
[ "$(jget "$s/signoff/signoff.json" "(not d['sta']['met']) and d['sta']['wns_ns'] < $(jget "$j" "d['sta']['wns_ns']") - 1.0")" = True ] ||
  fail "the slow path did not miss the target: $(jget "$s/signoff/signoff.json" "d['sta']['wns_ns']")"

# 3b. what closing would take (signoff/stages.py): every endpoint's slack, grouped into RTL registers
st=$("$py" "$here/stages.py" "$b") || fail "stages.py failed: $st"
echo "$st" | head -3
[ "$(jget "$b/signoff/stages.json" "abs(min([r['worst_slack_ns'] for r in d['missing']] or [$(jget "$j" "d['sta']['wns_ns']")]) - $(jget "$j" "d['sta']['wns_ns']")) < 0.002 and (d['missing_registers'] == 0) == $(jget "$j" "d['sta']['met']")")" = True ] ||
  fail "stages.json disagrees with signoff.json's WNS $(jget "$j" "d['sta']['wns_ns']") at the target"
"$py" "$here/stages.py" "$s" >/dev/null || fail "stages.py on the slow netlist failed"
slowreg=$(jget "$s/signoff/stages.json" "d['missing'][0]['register']")
[ "$(jget "$s/signoff/stages.json" "d['missing'][0]['pieces'] > max(1, $(jget "$b/signoff/stages.json" "d['max_pieces']")) and d['missing_endpoints'] > 0")" = True ] ||
  fail "stages.py did not find the slow register needing more pieces than the bundle's worst: $(jget "$s/signoff/stages.json" "d['missing'][:1]")"
echo "stages on the slow netlist: worst register $slowreg"

# 4. a wrong cell in the netlist fails the gate-level simulation
m="$work/mutant"; cp -r "$b" "$m"
"$py" - "$m/signoff/netlist.v" "$b/signoff/timing.rpt" <<'EOF' || fail "could not mutate the netlist"
import re, sys
path, rpt = sys.argv[1], sys.argv[2]
t = open(path).read()
# an XOR on the worst path (the datapath), else the first XOR of the netlist
cand = re.findall(r"(\S+)/Y \(XOR2X1\)", open(rpt).read()) + re.findall(r"XOR2X1\s+(\S+)\s*\(", t)
inst = cand[0]
t, n = re.subn(r"XOR2X1(\s+%s\s*\()" % re.escape(inst), r"XNOR2X1\1", t, count=1)
assert n == 1
open(path, "w").write(t)
EOF
"$py" "$m/signoff/signoff.py" "$m" --steps gatesim >"$work/mutant.log" 2>&1; rc=$?
cat "$work/mutant.log"
[ $rc -eq 2 ] || fail "the mutated netlist's gate-level run exited $rc, expected 2"
[ "$(jget "$m/signoff/signoff.json" "(not d['gatesim']['passed']) and d['gatesim']['mismatches'] > 0")" = True ] ||
  fail "the mutated netlist was not reported as failing: $(jget "$m/signoff/signoff.json" "d['gatesim']")"

# 5. the same two netlists through Verilator (a small run: auto chose Icarus above)
[ "$(jget "$j" "d['gatesim']['simulator']")" = icarus ] || fail "auto did not choose Icarus for a small run"
if command -v verilator >/dev/null 2>&1; then
  v="$work/vl"; cp -r "$b" "$v"
  "$py" "$v/signoff/signoff.py" "$v" --steps gatesim --gatesim verilator >"$work/vl.log" 2>&1 ||
    { cat "$work/vl.log"; fail "the netlist failed its Verilator gate-level run"; }
  cat "$work/vl.log"
  [ "$(jget "$v/signoff/signoff.json" "d['gatesim']['passed'] and d['gatesim']['simulator'] == 'verilator' and d['gatesim']['vectors'] == $(jget "$j" "d['gatesim']['vectors']")")" = True ] ||
    fail "the Verilator gate-level run does not match Icarus's: $(jget "$v/signoff/signoff.json" "d['gatesim']")"
  "$py" "$m/signoff/signoff.py" "$m" --steps gatesim --gatesim verilator >"$work/mutant_vl.log" 2>&1; rc=$?
  cat "$work/mutant_vl.log"
  [ $rc -eq 2 ] && [ "$(jget "$m/signoff/signoff.json" "d['gatesim']['mismatches'] > 0")" = True ] ||
    fail "the mutated netlist passed in Verilator (exit $rc)"
else
  echo "test_signoff: note: verilator not installed, the Verilator gate-level route not tried"
fi

rm -rf "$work"
echo "test_signoff: PASS"
