#!/usr/bin/env bash
# scripts/slurm-test.sh [SHARDS]: a sharded reference render on a real Slurm.
#
# Starts a single-node Slurm (Debian's slurm-wlm and munge, installed with
# apt if missing) configured in a temporary folder, submits
# `sbatch --array=1-SHARDS` (default 4) whose tasks run
# `gonio render --reference --shard auto`, waits (bounded), merges the
# parts with `gonio merge`, and compares the EXR and the PNG with a
# single-process render byte for byte (cmp). Then submits the same array
# again: every task finds its part complete and skips it (restart).
#
# Needs root (apt, and the daemons run as root); nothing outside the
# temporary folder is configured: slurm.conf and the munge key live there,
# the daemons listen on their own socket and ports, and all of them are
# killed (by pid) and the folder removed on exit. No cgroups (proctrack
# linuxproc, task/none), so it runs in containers and chroots too.
#
# GONIO=path/to/gonio picks the binary (default target/release/gonio,
# built if missing); KEEP=1 keeps the folder; SIZE=WxH the image
# (default 160x120); TIMEOUT=seconds bounds the wait (default 150).
# Exit 0: the merged images equal the single render; 1: they differ or a
# job failed; 2: the set-up failed (message says which step).
set -euo pipefail
cd "$(dirname "$0")/.."

SHARDS=${1:-4}
SIZE=${SIZE:-160x120}
TIMEOUT=${TIMEOUT:-150}
WIDTH=${SIZE%x*}
HEIGHT=${SIZE#*x}
started=$(date +%s.%N)
say() { printf '[slurm-test] %s\n' "$*"; }
die() { say "error: $*"; exit 2; }
elapsed() { awk -v a="$started" -v b="$(date +%s.%N)" 'BEGIN{printf "%.1f", b-a}'; }

[[ $(id -u) == 0 ]] || die "run as root: it installs packages and starts slurmctld, slurmd and munged"

# 1. Packages (idempotent: apt only runs when a program is missing).
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null ||
    ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
    say "installing slurm-wlm and munge (apt)"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq || die "apt-get update failed"
    apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null ||
        die "apt-get install slurm-wlm munge failed"
fi

# 2. gonio.
GONIO=${GONIO:-target/release/gonio}
if [[ ! -x $GONIO ]]; then
    say "building $GONIO"
    cargo build --release --quiet || die "cargo build --release failed"
fi
GONIO=$(realpath "$GONIO")

# 3. A temporary cluster: munge key, slurm.conf, daemons.
T=$(mktemp -d /tmp/gonio-slurm.XXXXXX)
chmod 755 "$T"
pids=()
cleanup() {
    local rc=$?
    for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
    for p in "${pids[@]}"; do
        for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
        kill -9 "$p" 2>/dev/null || true
    done
    if [[ ${KEEP:-0} == 1 ]]; then say "kept $T"; else rm -rf "$T"; fi
    exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM
mkdir -p "$T"/{munge,state,spool,log,parts,out}
chmod 700 "$T/munge"

mungekey --create --keyfile="$T/munge/munge.key" 2>/dev/null ||
    { dd if=/dev/urandom of="$T/munge/munge.key" bs=1024 count=1 status=none; }
chmod 400 "$T/munge/munge.key"
SOCKET=$T/munge/munge.socket
munged --foreground --force --socket="$SOCKET" --key-file="$T/munge/munge.key" \
    --pid-file="$T/munge/munged.pid" --seed-file="$T/munge/munged.seed" \
    --log-file="$T/log/munged.log" >"$T/log/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 50); do [[ -S $SOCKET ]] && break; sleep 0.1; done
[[ -S $SOCKET ]] || die "munged did not start: $(cat "$T/log/munged.log" 2>/dev/null)"

# Two free TCP ports for slurmctld and slurmd (not the defaults, so that a
# Slurm already on the machine is left alone).
free_port() {
    local p
    while :; do
        p=$((20000 + RANDOM % 40000))
        # A connection that succeeds means the port is taken.
        (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null || { echo "$p"; return; }
    done
}
CTLD_PORT=$(free_port)
SLURMD_PORT=$(free_port)
while [[ $SLURMD_PORT == "$CTLD_PORT" ]]; do SLURMD_PORT=$(free_port); done
HOST=$(uname -n)
HOST=${HOST%%.*}
NODE=$(slurmd -C | head -1)
[[ $NODE == NodeName=* ]] || die "slurmd -C did not describe this machine: $NODE"
export SLURM_CONF=$T/slurm.conf
cat >"$SLURM_CONF" <<CONF
ClusterName=gonio-test
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
AuthType=auth/munge
AuthInfo=socket=$SOCKET
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
MinJobAge=600
$NODE NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=gonio Nodes=$HOST Default=YES MaxTime=10 State=UP
CONF
slurmctld -D -i -f "$SLURM_CONF" >"$T/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >"$T/log/slurmd.out" 2>&1 &
pids+=($!)
up=0
for _ in $(seq 100); do
    if sinfo -h -o '%T' 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; then up=1; break; fi
    sleep 0.2
done
if [[ $up != 1 ]]; then
    tail -5 "$T/log/slurmctld.log" "$T/log/slurmd.log" "$T/log/"*.out 2>/dev/null
    die "the Slurm node did not come up (logs above)"
fi
say "Slurm $(sinfo -V | awk '{print $2}') up on $HOST in $(elapsed) s: $(sinfo -h -o '%P %D node, %c CPUs, %T')"

# 4. The job: one array task per shard, one core each.
cat >"$T/render.sbatch" <<JOB
#!/bin/bash
#SBATCH --job-name=gonio-shards
#SBATCH --cpus-per-task=1
#SBATCH --output=$T/log/task-%a.out
#SBATCH --time=5
export RAYON_NUM_THREADS=\$SLURM_CPUS_PER_TASK
exec "$GONIO" render --reference --width $WIDTH --height $HEIGHT --shard auto -o "$T/parts/part-{shard}.exr"
JOB

# Submits the array and waits for every task to leave the queue; then
# checks that each one completed.
run_array() {
    local job
    job=$(sbatch --parsable --array=1-"$SHARDS" "$T/render.sbatch") || die "sbatch failed"
    job=${job%%;*}
    local deadline=$(($(date +%s) + TIMEOUT))
    while [[ -n $(squeue -h -j "$job" 2>/dev/null) ]]; do
        if (($(date +%s) > deadline)); then
            scancel "$job" || true
            say "error: job $job still queued or running after ${TIMEOUT} s"
            exit 1
        fi
        sleep 0.5
    done
    local states
    states=$(scontrol -o show job "$job" | grep -o 'JobState=[A-Z_]*' | sort | uniq -c | tr -s ' ')
    if [[ $(scontrol -o show job "$job" | grep -c 'JobState=COMPLETED') != "$SHARDS" ]]; then
        say "error: job $job:$states"
        tail -n 5 "$T"/log/task-*.out
        exit 1
    fi
    say "job $job: $SHARDS tasks completed in $(elapsed) s since start"
}

t0=$(date +%s.%N)
run_array
t1=$(date +%s.%N)
"$GONIO" merge -o "$T/out/merged.exr" "$T"/parts/part-*.exr
"$GONIO" merge -o "$T/out/merged.png" "$T"/parts/part-*.exr
t2=$(date +%s.%N)
"$GONIO" render --reference --width "$WIDTH" --height "$HEIGHT" -o "$T/out/single.exr"
"$GONIO" render --reference --width "$WIDTH" --height "$HEIGHT" -o "$T/out/single.png"
same=1
for ext in exr png; do
    if cmp "$T/out/single.$ext" "$T/out/merged.$ext"; then
        say "merged.$ext = single.$ext ($(stat -c %s "$T/out/merged.$ext") bytes, cmp)"
    else
        same=0
    fi
done

# 5. Restart: the same array again finds every part complete.
before=$(stat -c %Y "$T"/parts/part-*.exr | md5sum)
run_array
skipped=$(grep -l 'skipped' "$T"/log/task-*.out | wc -l)
after=$(stat -c %Y "$T"/parts/part-*.exr | md5sum)
if [[ $skipped != "$SHARDS" || $before != "$after" ]]; then
    say "error: the resubmitted array re-rendered ($skipped of $SHARDS tasks said skipped)"
    same=0
else
    say "resubmitted: all $SHARDS tasks skipped their complete parts"
fi
awk -v a="$t0" -v b="$t1" -v c="$t2" -v n="$SHARDS" -v s="$SIZE" \
    'BEGIN{printf "[slurm-test] %s shards of %s: array %.1f s (submit to last task done), merge of EXR+PNG %.2f s\n", n, s, b-a, c-b}'
if [[ $same == 1 ]]; then
    say "passed in $(elapsed) s"
else
    say "FAILED: the merged image differs from the single render"
    exit 1
fi
