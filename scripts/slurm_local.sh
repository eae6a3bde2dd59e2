#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A single-node Slurm cluster for the tests (ctest -L slurm) and for trying `shadecore regress --slurm`:
#
#   scripts/slurm_local.sh start [DIR]   # prints: export SLURM_CONF=DIR/slurm.conf
#   scripts/slurm_local.sh stop  [DIR]   # cancels what runs there, stops the three daemons, removes DIR
#   scripts/slurm_local.sh status [DIR]
#
# Everything lives in DIR (default $SLURM_LOCAL_DIR or /tmp/shadecore-slurm-$UID): munged with its own key
# and socket, slurmctld and slurmd with a slurm.conf there, state, spool, logs and pid files; the ports are
# on the loopback (SLURM_LOCAL_PORT, default 26817, and the next one: not Slurm's 6817/6818, so a real
# cluster's daemons on this host do not clash); no cgroups (proctrack/linuxproc, task/none), no accounting
# (poll squeue; there is no sacct). Needs root (slurmd starts jobs as their user) and the Debian packages
# slurm-wlm and munge (scripts/setup.sh installs them). Only the daemons whose pid files are in DIR are
# stopped.
set -euo pipefail

cmd=${1:-}
dir=${2:-${SLURM_LOCAL_DIR:-/tmp/shadecore-slurm-$(id -u)}}
port=${SLURM_LOCAL_PORT:-26817}
max_array=${SLURM_LOCAL_MAX_ARRAY:-1001}   # Slurm's default; the tests lower it to exercise the split
die() { echo "slurm_local: error: $*" >&2; exit 1; }

case "$cmd" in
  start|stop|status) ;;
  *) die "usage: $0 start|stop|status [DIR]" ;;
esac
case "$port" in ''|*[!0-9]*) die "SLURM_LOCAL_PORT must be a number" ;; esac
case "$max_array" in ''|*[!0-9]*) die "SLURM_LOCAL_MAX_ARRAY must be a number" ;; esac

find_tool() {
  local t
  for t in "/usr/sbin/$1" "/usr/bin/$1" "$(command -v "$1" 2>/dev/null || true)"; do
    [ -n "$t" ] && [ -x "$t" ] && { echo "$t"; return 0; }
  done
  die "$1 not found (scripts/setup.sh installs slurm-wlm and munge)"
}

alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

stop_pid() {  # pid file, name
  local pf=$1 i
  alive "$pf" || { rm -f "$pf"; return 0; }
  local pid
  pid=$(cat "$pf")
  kill "$pid" 2>/dev/null || true
  for i in $(seq 1 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  kill -0 "$pid" 2>/dev/null && kill -9 "$pid" 2>/dev/null || true
  rm -f "$pf"
}

if [ "$cmd" = status ]; then
  for d in munged slurmctld slurmd; do
    if alive "$dir/$d.pid"; then echo "$d: running (pid $(cat "$dir/$d.pid"))"; else echo "$d: not running"; fi
  done
  exit 0
fi

if [ "$cmd" = stop ]; then
  [ -d "$dir" ] || exit 0
  [ -f "$dir/slurm.conf" ] || die "$dir is not a slurm_local directory (no slurm.conf)"
  if alive "$dir/slurmctld.pid"; then
    SLURM_CONF="$dir/slurm.conf" scancel --quiet --full --signal=KILL --state=RUNNING "--user=$(id -un)" 2>/dev/null || true
    SLURM_CONF="$dir/slurm.conf" scancel --quiet "--user=$(id -un)" 2>/dev/null || true
  fi
  stop_pid "$dir/slurmd.pid"
  stop_pid "$dir/slurmctld.pid"
  stop_pid "$dir/munged.pid"
  rm -rf "$dir"
  echo "slurm_local: stopped ($dir removed)" >&2
  exit 0
fi

# ---- start
[ "$(id -u)" -eq 0 ] || die "start needs root (slurmd runs the jobs)"
munged=$(find_tool munged)
slurmctld=$(find_tool slurmctld)
slurmd=$(find_tool slurmd)
find_tool sinfo >/dev/null
if alive "$dir/slurmctld.pid"; then
  echo "slurm_local: already running in $dir" >&2
  echo "export SLURM_CONF=$dir/slurm.conf"
  exit 0
fi
for p in "$port" "$((port + 1))"; do
  if (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null; then die "port $p on the loopback is in use (set SLURM_LOCAL_PORT)"; fi
done
mkdir -p "$dir/state" "$dir/spool" "$dir/log"
chmod 700 "$dir"
host=$(hostname -s)
cpus=$(nproc)

# munge: its own key, socket, log, pid and seed files (the default paths need the munge user's directories).
if [ ! -f "$dir/munge.key" ]; then
  head -c 1024 /dev/urandom > "$dir/munge.key"
  chmod 600 "$dir/munge.key"
fi
"$munged" --force -S "$dir/munge.sock" --key-file="$dir/munge.key" --log-file="$dir/log/munged.log" \
  --pid-file="$dir/munged.pid" --seed-file="$dir/munge.seed" || die "munged did not start (see $dir/log/munged.log)"

cat > "$dir/slurm.conf" <<EOF
# Written by shadecore scripts/slurm_local.sh: a single-node test cluster, everything under $dir.
ClusterName=shadecore-local
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge.sock
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
ReturnToService=2
MaxArraySize=$max_array
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF

export SLURM_CONF="$dir/slurm.conf"
"$slurmctld" || { stop_pid "$dir/munged.pid"; die "slurmctld did not start (see $dir/log/slurmctld.log)"; }
"$slurmd" -N "$host" || { stop_pid "$dir/slurmctld.pid"; stop_pid "$dir/munged.pid"; die "slurmd did not start (see $dir/log/slurmd.log)"; }
for i in $(seq 1 100); do
  state=$(sinfo -h -N -o '%t' 2>/dev/null | head -n 1 || true)
  case "$state" in idle*|mix*|alloc*) break ;; esac
  sleep 0.2
done
case "$state" in
  idle*|mix*|alloc*) ;;
  *) "$0" stop "$dir" >/dev/null 2>&1 || true; die "the node did not come up (state '${state:-none}'); logs were in $dir/log" ;;
esac
echo "slurm_local: node $host ($cpus CPUs) $state, slurmctld on 127.0.0.1:$port, in $dir" >&2
echo "export SLURM_CONF=$dir/slurm.conf"
