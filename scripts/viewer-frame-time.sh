#!/usr/bin/env bash
# Measures the viewer's frame time in a real window under Xvfb (lavapipe),
# vsync off, as issue 6 asks: the median over a few hundred frames after a
# warm-up, present/copy overhead included. Not a test: machines are shared
# and noisy; run it on a quiet machine and compare ratios within one run.
#
#   scripts/viewer-frame-time.sh [FRAMES] [WARMUP]
#
# Scenes: assets/scenes/viewer-bench.toml (16 128-triangle sphere on a plane,
# one shadowed directional light) at 1920x1080, and the default scene at
# 1280x720; each with the panel shown and hidden, the camera orbiting
# 0.5° per frame (so nothing is cached between frames except the shadow map,
# which does not depend on the camera).
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-300}"
warmup="${2:-30}"
cargo build --release --quiet
gonio=target/release/gonio
run() {
    local size="$1"; shift
    xvfb-run -a -s "-screen 0 ${size}x24" "$gonio" view --size "$size" --no-vsync \
        --frames "$frames" --warmup "$warmup" --frame-times --spin 0.5 "$@" 2>/dev/null \
        | grep '^frame times'
}
echo "# gonio view frame times ($(date -u +%F), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
for panel in "" "--no-panel"; do
    echo "viewer-bench 1920x1080 ${panel:-with panel}:"
    run 1920x1080 assets/scenes/viewer-bench.toml $panel
    echo "default scene 1280x720 ${panel:-with panel}:"
    run 1280x720 $panel
done
