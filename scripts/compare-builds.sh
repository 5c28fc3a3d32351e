#!/usr/bin/env bash
# Compares the speed of two gonio binaries in one interleaved run, for a
# change that must not change speed (a refactoring): the bench's three
# shader ratios and the viewer's frame time, old and new alternating
# round by round so both see the same machine load. Not a test: shared
# machines are noisy; read the medians side by side.
#
#   scripts/compare-builds.sh OLD_GONIO NEW_GONIO [ROUNDS] [FRAMES]
#
# Per round and binary: `gonio bench --quick --no-scale` (the rows
# "specialized scene / hand-minimal shader", "uber / specialized shader"
# and "cold gonio render / minimal triangle-to-PNG" of its report), then
# `gonio view` of assets/scenes/viewer-bench.toml at 1920x1080 under Xvfb
# with the panel hidden, vsync off, the camera orbiting (the median frame
# time after a warm-up, as scripts/viewer-frame-time.sh measures it).
#
# `bench --quick` computes every knob's error against traced truths and
# takes long on a small machine (one run on 2 cores had not finished after
# 43 minutes, 2026-12-05): BENCH=ratios measures the three rows alone
# (`bench --quick --ratios`, both binaries need it), BENCH=0 skips them.
set -euo pipefail
cd "$(dirname "$0")/.."
old="$1"; new="$2"; rounds="${3:-2}"; frames="${4:-200}"
out="$(mktemp -d)"
echo "# interleaved comparison ($(date -u '+%F %H:%M') UTC, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
echo "# old: $old"
echo "# new: $new"
for r in $(seq 1 "$rounds"); do
    for side in old new; do
        bin="$old"; [ "$side" = new ] && bin="$new"
        dir="$out/$side-$r"
        if [ "${BENCH:-1}" = ratios ]; then
            "$bin" bench --quick --ratios 2>/dev/null \
                | grep -E "^\| (specialized scene / hand-minimal|uber / specialized|cold .gonio render)" \
                | sed "s/^/round $r $side bench /"
        elif [ "${BENCH:-1}" != 0 ]; then
            "$bin" bench --quick --no-scale -o "$dir" >/dev/null 2>&1
            grep -E "^\| (specialized scene / hand-minimal|uber / specialized|cold .gonio render)" "$dir/report.md" \
                | sed "s/^/round $r $side bench /"
        fi
        xvfb-run -a -s "-screen 0 1920x1080x24" "$bin" view assets/scenes/viewer-bench.toml \
            --size 1920x1080 --no-vsync --no-panel --frames "$frames" --warmup 30 \
            --frame-times --spin 0.5 2>/dev/null | grep '^frame times' | sed "s/^/round $r $side viewer /"
    done
done
rm -rf "$out"
