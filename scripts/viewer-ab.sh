#!/usr/bin/env bash
# Interleaved frame-time comparison of gonio binaries (e.g. two commits'
# builds, for a bisect): each round runs every binary once on SCENE with
# the command line of scripts/viewer-frame-time.sh (1920x1080 under Xvfb,
# vsync off, panel hidden, camera orbiting), so all see the same machine
# load. Per run: the median / p10 / p90 frame time, the GPU scene pass
# median and the gonio process's CPU time (user + sys over the whole run,
# start-up included), which a loaded machine disturbs less than the wall
# clock. Not a test: read ratios within one run.
#
#   scripts/viewer-ab.sh ROUNDS FRAMES SCENE GONIO...
set -uo pipefail
rounds="$1"; frames="$2"; scene="$3"; shift 3
echo "# $(date -u '+%F %H:%M') UTC, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $scene, $frames frames"
for r in $(seq 1 "$rounds"); do
    for bin in "$@"; do
        times="$(mktemp)"
        line="$(xvfb-run -a -s "-screen 0 1920x1080x24" /usr/bin/time -o "$times" -f "%U %S" \
            "$bin" view "$scene" --size 1920x1080 --no-vsync --no-panel --frames "$frames" \
            --warmup 30 --frame-times --spin 0.5 2>/dev/null | grep '^frame times')"
        wall="$(echo "$line" | sed -E 's/.*median ([0-9.]+) ms, p10 ([0-9.]+) ms, p90 ([0-9.]+) ms.*/\1 \2 \3/')"
        pass="$(echo "$line" | grep -oE 'GPU scene pass median [0-9.]+' | grep -oE '[0-9.]+$')"
        cpu="$(awk '{printf "%.2f", $1 + $2}' "$times")"
        rm -f "$times"
        echo "round $r $bin: median p10 p90 $wall ms, scene pass ${pass:-?} ms, CPU $cpu s, load $(cut -d' ' -f1 /proc/loadavg)"
    done
done
