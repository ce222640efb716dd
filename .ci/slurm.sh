#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A real Slurm run of docs/sweeps.md's job array: starts munge, slurmctld and slurmd for a
# one-node cluster on this machine (their configuration, state and logs in a temporary folder),
# submits the job file that docs/sweeps.md shows ("Slurm array") with sbatch, waits for its
# tasks, merges their shards with sweep-merge, and checks that the merged CSV equals the same
# sweep run in one process, row for row and byte for byte. Every daemon it started is stopped on
# the way out, whatever happens. Uses the build of .ci/test.sh (build/app/cli/sonargrid-cli).
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
bash .ci/deps.sh
cmake --build build -j "$(nproc)" --target sonargrid-cli
start=$(date +%s)

work="$(mktemp -d /tmp/sonargrid-slurm.XXXXXX)"
chmod 0700 "$work"
pids=()
cleanup() {
  local status=$?
  # Jobs first (scancel talks to slurmctld), then the daemons, newest first.
  if [ -n "${SLURM_CONF:-}" ]; then scancel --quiet --user="$(id -un)" 2>/dev/null || true; fi
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  # Nothing it started may outlive it: every daemon was given a path inside $work.
  if pgrep -f "$work" >/dev/null; then
    echo "slurm.sh: processes left behind:" >&2
    pgrep -af "$work" >&2
    pkill -9 -f "$work" || true
    status=1
  fi
  if [ $status -ne 0 ]; then
    for log in "$work"/*.log; do [ -f "$log" ] && { echo "== $log"; tail -n 30 "$log"; }; done
  fi
  rm -rf "$work"
  exit $status
}
trap cleanup EXIT

# Fails the script when a daemon it started is not running a moment later.
wait_for() {  # wait_for SECONDS DESCRIPTION COMMAND...
  local seconds=$1 what=$2
  shift 2
  for _ in $(seq $((seconds * 10))); do
    if "$@" >/dev/null 2>&1; then return 0; fi
    sleep 0.1
  done
  echo "slurm.sh: $what did not come up within $seconds s" >&2
  return 1
}

# munge: a key of our own, the socket in our folder (AuthInfo below points Slurm at it).
dd if=/dev/urandom of="$work/munge.key" bs=1024 count=1 status=none
chmod 0400 "$work/munge.key"
munged --force --key-file="$work/munge.key" --socket="$work/munge.socket" \
  --pid-file="$work/munged.pid" --log-file="$work/munged.log" --seed-file="$work/munged.seed"
wait_for 10 munged test -s "$work/munged.pid"
pids+=("$(cat "$work/munged.pid")")
wait_for 10 "munge's socket" munge --socket="$work/munge.socket" --string=ping

# Free TCP ports for slurmctld and slurmd on the loopback interface.
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
node="$(hostname -s)"
cpus="$(nproc)"
mkdir -p "$work/state" "$work/spool"
cat >"$work/slurm.conf" <<EOF
ClusterName=sonargrid-ci
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$(id -un)
AuthType=auth/munge
AuthInfo=socket=$work/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/affinity
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=ci Nodes=$node Default=YES MaxTime=30 State=UP
EOF
export SLURM_CONF="$work/slurm.conf"
slurmctld -i -f "$SLURM_CONF"
wait_for 20 slurmctld test -s "$work/slurmctld.pid"
pids+=("$(cat "$work/slurmctld.pid")")
slurmd -f "$SLURM_CONF"
wait_for 20 slurmd test -s "$work/slurmd.pid"
pids+=("$(cat "$work/slurmd.pid")")
wait_for 30 "the node" bash -c "sinfo -h -N -o %T | grep -qx idle"

# The job file is docs/sweeps.md's own: the bash block under "### Slurm array".
jobs="$work/jobs"
mkdir -p "$jobs"
awk '/^### Slurm array/{s=1} s&&/^```bash$/{b=1;next} b&&/^```$/{exit} b{print}' docs/sweeps.md \
  >"$jobs/sweep-array.sh"
grep -q -- '--array=0-3' "$jobs/sweep-array.sh" || {
  echo "slurm.sh: docs/sweeps.md's Slurm example is not a 4-task array" >&2
  exit 1
}
cp datasets/arafat-room/run-1.sglog datasets/arafat-room/world.json "$jobs/"
export PATH="$root/build/app/cli:$PATH"
job=$(sbatch --parsable --chdir="$jobs" "$jobs/sweep-array.sh")
echo "slurm.sh: submitted job array $job"
for _ in $(seq 1800); do
  [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break
  sleep 1
done
if [ -n "$(squeue -h -j "$job" 2>/dev/null)" ]; then
  echo "slurm.sh: job $job still queued or running after 30 minutes" >&2
  exit 1
fi
# Each task's end as slurmctld recorded it (sacct would need a database; scontrol does not).
states="$(scontrol show job "$job" | grep -o 'JobState=[A-Z_]*' || true)"
if [ "$(grep -c 'JobState=COMPLETED' <<<"$states")" -ne 4 ]; then
  echo "slurm.sh: not every task of job $job completed:" $states >&2
  exit 1
fi
for i in 0 1 2 3; do
  test -s "$jobs/shard-$i.csv" || {
    echo "slurm.sh: task $i wrote no shard-$i.csv" >&2
    cat "$jobs/slurm-${job}_$i.out" 2>/dev/null || true
    exit 1
  }
done

# Merge the shards, then the same sweep in one process (the job file's command without --shard).
(cd "$jobs" && sonargrid-cli sweep-merge shard-0.csv shard-1.csv shard-2.csv shard-3.csv --csv all.csv)
one="$(sed -n '/^sonargrid-cli sweep /,/[^\\]$/p' "$jobs/sweep-array.sh" |
  sed -e 's/--shard "[^"]*" //' -e 's/--csv "[^"]*"/--csv one-process.csv/')"
(cd "$jobs" && eval "$one")
rows=$(grep -vc '^#' "$jobs/all.csv")
if ! diff <(grep -v '^#' "$jobs/one-process.csv") <(grep -v '^#' "$jobs/all.csv") >/dev/null; then
  echo "slurm.sh: the merged CSV's rows differ from the one-process sweep's" >&2
  diff <(grep -v '^#' "$jobs/one-process.csv") <(grep -v '^#' "$jobs/all.csv") | head -n 20 >&2
  exit 1
fi
cmp "$jobs/one-process.csv" "$jobs/all.csv"
echo "slurm.sh: the merged CSV of 4 Slurm tasks equals the one-process sweep, row for row" \
  "($((rows - 1)) sets) and byte for byte; $(($(date +%s) - start)) s"
