#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ctest regress.slurm (label slurm, issue 22): `shadecore regress --plan smoke` through a real single-node
# Slurm cluster (scripts/slurm_local.sh) and through --local, on the same build:
#   1. --slurm with at most one task at once per array, on a cluster whose MaxArraySize (8) is below the
#      plan's shard count: one sbatch --array per MaxArraySize tasks; one pending task is cancelled
#      (scancel JOB_TASK): the run must retry exactly that shard once and pass;
#   2. --local -j 2: the two merged reports must be equal (byte for byte: merged.json holds no times,
#      hosts or paths);
#   3. the merged report equals one-process runs: the random job against `shadecore cosim --shards 1`
#      (vectors, mismatches, stimulus digest), the bare exhaustive job against one bare harness process;
#   4. resume: the finished directory run again runs nothing; with one shard's result removed it runs
#      exactly that shard; another plan in the same directory is refused (exit 1, one line);
#   5. Ctrl-C (SIGINT) of a --slurm run cancels its array (nothing of it left in squeue), exit 130.
# Exits 77 (ctest: skipped) when Slurm or munge is not installed or this is not root.
# usage: regress_slurm_check.sh SHADECORE SOURCE_DIR BARE_DEFAULT
set -uo pipefail
cli=$1
src=$2
bare=$3
command -v slurmctld >/dev/null 2>&1 || [ -x /usr/sbin/slurmctld ] || { echo "SKIP: slurm-wlm not installed (scripts/setup.sh)"; exit 77; }
[ -x /usr/sbin/munged ] || command -v munged >/dev/null 2>&1 || { echo "SKIP: munge not installed"; exit 77; }
[ "$(id -u)" -eq 0 ] || { echo "SKIP: needs root (slurmd)"; exit 77; }

tmp=$(mktemp -d /tmp/shadecore-regress-test.XXXXXX)
export SLURM_LOCAL_DIR=$tmp/cluster
export SLURM_LOCAL_PORT=${SHADECORE_TEST_SLURM_PORT:-27817}
export SLURM_LOCAL_MAX_ARRAY=8   # below the smoke plan's shard count: the plan must be split into several arrays
cleanup() {
  "$src/scripts/slurm_local.sh" stop "$SLURM_LOCAL_DIR" >/dev/null 2>&1 || true
  rm -rf "$tmp"
}
trap cleanup EXIT
fail=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; fi; }
jq_get() { /usr/bin/python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

eval "$("$src/scripts/slurm_local.sh" start "$SLURM_LOCAL_DIR")" || { echo "FAIL: the test cluster did not start"; exit 1; }
[ -n "${SLURM_CONF:-}" ] || { echo "FAIL: slurm_local.sh start printed no SLURM_CONF"; exit 1; }

# ---- 1. --slurm, one task cancelled while pending
"$cli" regress --plan smoke --slurm --max-running 1 --poll 300 --out "$tmp/slurm" > "$tmp/slurm.out" 2>&1 &
rpid=$!
job=""
for _ in $(seq 1 200); do
  job=$(sed -n 's/^regress: round 1: Slurm array job \([0-9]*\) .*/\1/p' "$tmp/slurm.out" | head -n 1)
  [ -n "$job" ] && break
  sleep 0.1
done
ntasks=$(wc -l < "$tmp/slurm/slurm/round1-0.tasks" 2>/dev/null || echo 0)
victim=$((ntasks - 1))
victim_id=$(sed -n "$((victim + 1))p" "$tmp/slurm/slurm/round1-0.tasks" 2>/dev/null)
if [ -n "$job" ] && [ "$ntasks" -gt 2 ]; then scancel "${job}_${victim}"; fi
wait $rpid
st=$?
cat "$tmp/slurm.out"
check "--slurm smoke exits 0 (got $st)" '[ $st -eq 0 ]'
nshards=$(jq_get "$tmp/slurm/shards.json" "len(d)")
arrays=$(grep -c '^regress: round 1: Slurm array job' "$tmp/slurm.out")
check "$nshards shards in $arrays arrays of at most 8 tasks" '[ "$arrays" -eq $(( (nshards + 7) / 8 )) ] && [ "$arrays" -gt 1 ]'
check "an array job was submitted and task $victim ($victim_id) cancelled" '[ -n "$job" ] && [ -n "$victim_id" ]'
check "the cancelled shard was retried, and only it" \
  '[ "$(jq_get "$tmp/slurm/run.json" "d[\"invocations\"][-1][\"retried\"]")" = "['"'"$victim_id"'"']" ]'
check "the retry named the shard" 'grep -q "retrying 1 shard(s) once (lost or failed to run): $victim_id" "$tmp/slurm.out"'
check "its log exists" '[ -s "$tmp/slurm/logs/$victim_id.log" ]'

# ---- 2. --local: the same merged report
"$cli" regress --plan smoke --local -j 2 --out "$tmp/local" > "$tmp/local.out" 2>&1
st=$?
cat "$tmp/local.out"
check "--local smoke exits 0 (got $st)" '[ $st -eq 0 ]'
check "merged.json of --slurm and --local are equal" 'cmp -s "$tmp/slurm/merged.json" "$tmp/local/merged.json"'
check "merged report passed with vectors > 0" \
  '[ "$(jq_get "$tmp/local/merged.json" "d[\"ok\"] and d[\"totals\"][\"vectors\"] > 0")" = True ]'
check "summary.md written" 'grep -q "^| job | kind | shards" "$tmp/local/summary.md"'

# ---- 3. merged = one process
job_field() { jq_get "$tmp/local/merged.json" "[j for j in d[\"jobs\"] if j[\"name\"]==\"$1\"][0][\"$2\"]"; }
args=$(jq_get "$src/regress/plans/smoke.json" \
  "' '.join(['--variant',[j for j in d['jobs'] if j['name']=='rand_cs16_default'][0]['variant'],'--config','default','--count',str([j for j in d['jobs'] if j['name']=='rand_cs16_default'][0]['count']),'--seed',str([j for j in d['jobs'] if j['name']=='rand_cs16_default'][0]['seed']),'--in-stall','0.2','--out-stall','0.3'])")
"$cli" cosim --mode random $args --shards 1 --json "$tmp/one.json" > /dev/null 2>&1
for k in vectors mismatches stimulus_digest; do
  one=$(jq_get "$tmp/one.json" "d[\"$k\"]")
  check "rand_cs16_default: merged $k = one process ($one)" '[ "$(job_field rand_cs16_default $k)" = "$one" ]'
done
n=$(jq_get "$src/regress/plans/smoke.json" "[j for j in d['jobs'] if j['name']=='exh_cs16_default_bare'][0]['n']")
one=$("$bare" --n "$n" --no-progress | sed -n 's/.*: [0-9]* sent, \([0-9]*\) out, \([0-9]*\) mismatches.*/\1 \2/p')
check "exh_cs16_default_bare: merged vectors and mismatches = one bare process ($one)" \
  '[ "$(job_field exh_cs16_default_bare vectors) $(job_field exh_cs16_default_bare mismatches)" = "$one" ]'

# ---- 4. resume
before=$(stat -c %Y "$tmp"/slurm/shards/*.json | md5sum)
"$cli" regress --plan smoke --slurm --poll 300 --out "$tmp/slurm" > "$tmp/resume.out" 2>&1
st=$?
check "resume of a finished run exits 0 and runs nothing" \
  '[ $st -eq 0 ] && [ "$(jq_get "$tmp/slurm/run.json" "len(d[\"invocations\"][-1][\"ran\"])")" = 0 ]'
check "no shard result was rewritten" '[ "$(stat -c %Y "$tmp"/slurm/shards/*.json | md5sum)" = "$before" ]'
gone=$(jq_get "$tmp/local/shards.json" "d[2][\"id\"]")
rm -f "$tmp/local/shards/$gone.json"
"$cli" regress --plan smoke --local --out "$tmp/local" > "$tmp/resume2.out" 2>&1
st=$?
check "resume with one result removed runs exactly that shard ($gone)" \
  '[ $st -eq 0 ] && [ "$(jq_get "$tmp/local/run.json" "d[\"invocations\"][-1][\"ran\"]")" = "['"'"$gone"'"']" ]'
check "and the merged report is unchanged" 'cmp -s "$tmp/slurm/merged.json" "$tmp/local/merged.json"'
printf '{"name":"other","jobs":[{"name":"d","kind":"cosim","mode":"directed"}]}\n' > "$tmp/other.json"
"$cli" regress --plan "$tmp/other.json" --local --out "$tmp/local" > "$tmp/other.out" 2>&1
st=$?
check "another plan in the same directory is refused with one line (exit $st)" \
  '[ $st -eq 1 ] && [ "$(wc -l < "$tmp/other.out")" = 1 ] && grep -q "holds a run of another plan" "$tmp/other.out"'

# ---- 5. Ctrl-C cancels the array
"$cli" regress --plan smoke --slurm --max-running 1 --poll 300 --out "$tmp/int" > "$tmp/int.out" 2>&1 &
rpid=$!
job=""
for _ in $(seq 1 200); do
  job=$(sed -n 's/^regress: round 1: Slurm array job \([0-9]*\) .*/\1/p' "$tmp/int.out" | tr '\n' ',')
  [ "$(grep -c '^regress: round 1: Slurm array job' "$tmp/int.out")" -ge 3 ] && break
  sleep 0.1
done
job=${job%,}
kill -INT $rpid
wait $rpid
st=$?
left=1
for _ in $(seq 1 50); do
  left=$(squeue -h -j "$job" 2>/dev/null | wc -l)
  [ "$left" = 0 ] && break
  sleep 0.2
done
check "SIGINT: exit 130 (got $st), array $job cancelled ($left task(s) left)" '[ $st -eq 130 ] && [ -n "$job" ] && [ "$left" = 0 ]'

[ $fail -eq 0 ] && echo "regress.slurm: PASS"
exit $fail
