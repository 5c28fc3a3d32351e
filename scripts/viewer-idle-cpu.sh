#!/usr/bin/env bash
# Measures the CPU the idle viewer uses: `gonio view` in a
# real window under Xvfb (lavapipe), no input; after a settling time, the
# process's utime + stime from /proc/PID/stat over a measuring window.
# Not a test (tests/viewer.rs asserts the idle loop by its frame counter).
#
#   scripts/viewer-idle-cpu.sh [GONIO] [SETTLE_S] [MEASURE_S] [-- VIEW ARGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
gonio="${1:-target/release/gonio}"
settle="${2:-10}"
measure="${3:-10}"
shift $(( $# < 3 ? $# : 3 ))
[ "${1:-}" = "--" ] && shift
display=":$(( 90 + RANDOM % 400 ))"
Xvfb "$display" -screen 0 1280x720x24 >/dev/null 2>&1 &
xvfb=$!
trap 'kill "$xvfb" 2>/dev/null || true' EXIT
sleep 1
DISPLAY="$display" "$gonio" view "$@" >/dev/null 2>&1 &
viewer=$!
sleep "$settle"
ticks() { awk '{print $14 + $15}' "/proc/$viewer/stat"; }
a=$(ticks)
sleep "$measure"
b=$(ticks)
kill "$viewer"
wait "$viewer" 2>/dev/null || true
hz=$(getconf CLK_TCK)
awk -v a="$a" -v b="$b" -v hz="$hz" -v s="$measure" 'BEGIN {
    printf "idle CPU over %d s: %.1f %% of a core (%d ticks of 1/%d s)\n", s, 100 * (b - a) / hz / s, b - a, hz }'
