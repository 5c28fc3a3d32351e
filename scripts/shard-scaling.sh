#!/usr/bin/env bash
# scripts/shard-scaling.sh [SCENE_ARGS...]: a reference render in one
# process against N shards in N concurrent processes, and the merge.
#
# For N in $COUNTS (default "1 2 4 8"): N shards of the render started
# together, each with RAYON_NUM_THREADS=$THREADS_PER_SHARD (default 1),
# then `gonio merge`; and the unsharded render with all cores. Prints
# wall time and CPU time (user + system, summed over the processes: the
# work, which sharding adds to by repeating the per-process set-up) and
# checks every merge against the single render with cmp. ROUNDS=3
# repeats the whole set interleaved and prints every round.
# Default scene: the environment-occlusion scene at 80x60 with
# visibility (the expensive reference).
set -euo pipefail
cd "$(dirname "$0")/.."
GONIO=${GONIO:-target/release/gonio}
COUNTS=${COUNTS:-1 2 4 8}
ROUNDS=${ROUNDS:-3}
THREADS_PER_SHARD=${THREADS_PER_SHARD:-1}
if (($# == 0)); then
    set -- assets/scenes/environment_occlusion.toml --width 80 --height 60 \
        --set environment.visibility=true
fi
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# Runs "$@" under /usr/bin/time; appends "wall user sys" to $T/times.
timed() { /usr/bin/time -f '%e %U %S' -a -o "$T/times" "$@"; }
sum() { awk '{w = $1 > w ? $1 : w; c += $2 + $3} END {printf "%.2f %.2f\n", w, c}' "$T/times"; }

echo "# $(date -u '+%F %T') UTC, $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
printf 'round\tprocesses\tthreads each\twall s\tCPU s\tmerge wall s\n'
for round in $(seq "$ROUNDS"); do
    : >"$T/times"
    s0=$(date +%s.%N)
    timed "$GONIO" render --reference "$@" -o "$T/single.exr"
    s1=$(date +%s.%N)
    read -r _ cpu < <(sum)
    printf '%s\t1\tall (%s)\t%.2f\t%s\t-\n' "$round" "$(nproc)" "$(awk -v a="$s0" -v b="$s1" 'BEGIN{print b-a}')" "$cpu"
    for n in $COUNTS; do
        rm -rf "$T/parts" && mkdir "$T/parts"
        : >"$T/times"
        t0=$(date +%s.%N)
        for i in $(seq "$n"); do
            RAYON_NUM_THREADS=$THREADS_PER_SHARD timed "$GONIO" render --reference "$@" \
                --shard "$i/$n" -o "$T/parts/part-{shard}.exr" 2>/dev/null &
        done
        wait
        echo "#   load average $(cut -d' ' -f1-3 /proc/loadavg)" >&2
        t1=$(date +%s.%N)
        read -r _ cpu < <(sum)
        "$GONIO" merge -o "$T/merged.exr" "$T"/parts/part-*.exr
        t2=$(date +%s.%N)
        cmp -s "$T/single.exr" "$T/merged.exr" || { echo "merge of $n shards differs" >&2; exit 1; }
        awk -v r="$round" -v n="$n" -v th="$THREADS_PER_SHARD" -v a="$t0" -v b="$t1" -v c="$t2" -v cpu="$cpu" \
            'BEGIN{printf "%s\t%s\t%s\t%.2f\t%s\t%.3f\n", r, n, th, b-a, cpu, c-b}'
    done
done
