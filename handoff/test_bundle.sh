#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ctest driver for `shadecore handoff` (rtl/CMakeLists.txt, label icarus;handoff):
#
#   handoff/test_bundle.sh SHADECORE WORKDIR [--verilator-corrupt] [--failed-run] -- HANDOFF-ARGS...
#
# 1. shadecore handoff HANDOFF-ARGS --out WORKDIR/bundle exits 0 after both simulators passed;
# 2. the tarball holds the directory; `sha256sum -c MANIFEST.sha256` passes;
# 3. the delivered run_icarus.sh passes again (and prints PASS);
# 4. a second handoff into the now non-empty directory is refused (one-line error) without --force and
#    leaves the bundle as it was;
# 5. a copy with ONE corrupted expected value fails run_icarus.sh (and, with --verilator-corrupt,
#    run_verilator.sh), and fails the manifest check;
# 6. with --failed-run: a handoff whose testbench template does not compile (a copy of the source tree
#    via SHADECORE_ROOT) fails and leaves no directory, no tarball and no staging directory.
# Prints "test_bundle: PASS" and removes WORKDIR on success.
set -u
exe=$1; work=$2; shift 2
vcorrupt=0; failed_run=0
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  case "$1" in
    --verilator-corrupt) vcorrupt=1 ;;
    --failed-run) failed_run=1 ;;
    *) echo "test_bundle: bad option $1"; exit 2 ;;
  esac
  shift
done
[ "${1:-}" = "--" ] && shift
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)

fail() { echo "test_bundle: FAIL: $*"; exit 1; }

rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
b="$work/bundle"

# 1. the handoff itself (it runs both simulators before reporting success)
out=$("$exe" handoff "$@" --no-ice40 --signoff off --out "$b" 2>&1); rc=$?
echo "$out"
[ $rc -eq 0 ] || fail "handoff exited $rc"
echo "$out" | grep -q "run_icarus.sh: PASS" || fail "handoff did not report the Icarus PASS"
echo "$out" | grep -q "run_verilator.sh: PASS" || fail "handoff did not report the Verilator PASS"
for f in filelist.f constraints.sdc interface.md tb/tb_shadecore.v run_icarus.sh run_verilator.sh \
         vectors/hard.hex vectors/random.hex reports/verilator_lint.log reports/yosys_synth.log \
         reports/sim_icarus.log reports/sim_verilator.log MANIFEST.sha256; do
  [ -f "$b/$f" ] || fail "bundle has no $f"
done
ls -a "$work" | grep -q handoff-tmp && fail "staging directory left behind"
grep -q '%Warning' "$b/reports/sim_verilator.log" && fail "Verilator warns about the bundle (reports/sim_verilator.log)"
grep -qi 'warning' "$b/reports/sim_icarus.log" && fail "Icarus warns about the bundle (reports/sim_icarus.log)"

# 2. tarball and manifest
[ -f "$b.tar.gz" ] || fail "no tarball $b.tar.gz"
tar -tzf "$b.tar.gz" | grep -q '^bundle/MANIFEST.sha256$' || fail "tarball does not hold bundle/MANIFEST.sha256"
n_man=$(wc -l < "$b/MANIFEST.sha256")
n_files=$(cd "$b" && find . -type f ! -name MANIFEST.sha256 | wc -l)
[ "$n_man" -eq "$n_files" ] || fail "MANIFEST.sha256 lists $n_man files, the bundle has $n_files"
(cd "$b" && sha256sum -c --quiet MANIFEST.sha256) || fail "manifest check failed on a fresh bundle"

# 3. the delivered Icarus script on its own
out=$("$b/run_icarus.sh" 2>&1); rc=$?
echo "$out" | tail -n 1
[ $rc -eq 0 ] && echo "$out" | tail -n 1 | grep -q "^run_icarus.sh: PASS" || fail "run_icarus.sh did not pass on the bundle"

# 4. non-empty directory without --force
out=$("$exe" handoff "$@" --no-ice40 --signoff off --out "$b" 2>&1); rc=$?
[ $rc -ne 0 ] || fail "handoff into a non-empty directory without --force succeeded"
[ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] || fail "refusal is not one line: $out"
echo "$out" | grep -q "not empty" || fail "refusal does not say why: $out"
(cd "$b" && sha256sum -c --quiet MANIFEST.sha256) || fail "the refused run changed the bundle"

# 5. one corrupted expected value must fail the simulations and the manifest
c="$work/corrupt"
cp -r "$b" "$c"
awk 'BEGIN { done = 0 }
     !done && $0 !~ /^\/\// && NF == 5 && $5 !~ /^0+$/ { gsub(/./, "0", $5); done = 1 }
     { print }' "$b/vectors/hard.hex" > "$c/vectors/hard.hex"
cmp -s "$b/vectors/hard.hex" "$c/vectors/hard.hex" && fail "could not corrupt vectors/hard.hex"
out=$("$c/run_icarus.sh" 2>&1); rc=$?
echo "$out" | grep -E '^FAIL|run_icarus.sh: FAIL'
[ $rc -ne 0 ] || fail "run_icarus.sh passed with a corrupted expected value"
echo "$out" | grep -q '^FAIL vector' || fail "run_icarus.sh did not name the failing vector"
(cd "$c" && sha256sum -c --quiet MANIFEST.sha256 >/dev/null 2>&1) && fail "manifest check passed on a corrupted bundle"
if [ $vcorrupt -eq 1 ]; then
  out=$(VERILATOR_OBJ_DIR="$work/vobj" "$c/run_verilator.sh" 2>&1); rc=$?
  echo "$out" | grep -E '^FAIL|run_verilator.sh: FAIL'
  [ $rc -ne 0 ] || fail "run_verilator.sh passed with a corrupted expected value"
  echo "$out" | grep -q '^FAIL vector' || fail "run_verilator.sh did not name the failing vector"
fi

# 6. a run that fails part-way leaves nothing behind
if [ $failed_run -eq 1 ]; then
  fr="$work/root"
  mkdir -p "$fr/docs"
  cp -r "$root/rtl" "$root/handoff" "$root/config" "$root/LICENSE" "$fr/"
  echo "this is not Verilog" >> "$fr/handoff/tb/tb_shadecore.v"
  out=$(SHADECORE_ROOT="$fr" "$exe" handoff "$@" --no-ice40 --signoff off --out "$work/sub/failed" 2>&1); rc=$?
  [ $rc -ne 0 ] || fail "handoff with a broken testbench template succeeded"
  echo "$out" | tail -n 1
  echo "$out" | tail -n 1 | grep -q "run_icarus.sh did not pass" || fail "the failure is not the Icarus run: $(echo "$out" | tail -n 1)"
  [ ! -e "$work/sub" ] || fail "a failed run left $work/sub behind: $(ls -a "$work/sub")"
fi

rm -rf "$work"
echo "test_bundle: PASS"
