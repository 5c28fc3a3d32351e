#!/usr/bin/env bash
# Measures the viewer's frame time in a real window under Xvfb (lavapipe),
# vsync off: the median over a few hundred frames
# after a warm-up, present/copy overhead included. Not a test: machines are
# shared and noisy; run it on a quiet machine and compare ratios within one
# run (every scene's variants run interleaved, round by round).
#
#   scripts/viewer-frame-time.sh [FRAMES] [WARMUP] [ROUNDS] [BEVY_PEER]
#
# With GONIO_BEFORE=PATH (another build's gonio binary, e.g. the commit
# before a change), that binary draws each viewer-bevy-match variant too,
# in the same rounds, for a before/after column measured interleaved.
#
# Scenes:
# - assets/scenes/viewer-bench.toml (16 128-triangle sphere on a plane, one
#   shadowed directional light) at 1920x1080, and the default scene at
#   1280x720, each with the panel shown and hidden, the camera orbiting
#   0.5° per frame (nothing is cached between frames but the shadow map,
#   which does not depend on the camera);
# - assets/scenes/viewer-bevy-match.toml at 1920x1080, panel hidden, the
#   camera orbiting: its unlit floor (no lights, ambient materials: the
#   same geometry and pixels with nothing to shade), one and four shadowed
#   point lights, each static (gonio draws the maps once) and with the
#   lights orbiting 1° per frame (`--spin-lights`: maps drawn anew every
#   frame, as Bevy always does). With BEVY_PEER (the binary
#   scripts/build-bevy-peer.sh builds) Bevy draws the same scene in each
#   round beside gonio.
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-300}"
warmup="${2:-30}"
rounds="${3:-3}"
bevy="${4:-}"
cargo build --release --quiet
gonio=target/release/gonio
median() { grep -o 'median [0-9.]* ms' | head -1 | grep -o '[0-9.]*'; }
before="${GONIO_BEFORE:-}"
run_with() {
    local exe="$1" size="$2"; shift 2
    xvfb-run -a -s "-screen 0 ${size}x24" "$exe" view --size "$size" --no-vsync \
        --frames "$frames" --warmup "$warmup" --frame-times --spin 0.5 "$@" 2>/dev/null \
        | grep '^frame times'
}
run() { run_with "$gonio" "$@"; }
echo "# gonio view frame times ($(date -u +%F), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
for panel in "" "--no-panel"; do
    echo "viewer-bench 1920x1080 ${panel:-with panel}:"
    run 1920x1080 assets/scenes/viewer-bench.toml $panel
    echo "default scene 1280x720 ${panel:-with panel}:"
    run 1280x720 $panel
done

match=assets/scenes/viewer-bevy-match.toml
one_light=$(awk '/^\[\[lights\]\]/{n++} n==1' "$match" | tr '\n' ' ' \
    | sed -E 's/\[\[lights\]\] *kind = "point" *position = (\[[^]]*\]) *intensity = (\[[^]]*\]) *shadows = true */{kind="point", position=\1, intensity=\2, shadows=true}/')
unlit=(--set 'lights=[]' --set 'materials.suzanne={model="lambert", k_d=0, k_a=[0.8, 0.35, 0.15]}'
       --set 'materials.floor={model="lambert", k_d=0, k_a=[0.6, 0.6, 0.6]}' --set 'ambient.radiance=[0.5, 0.5, 0.5]')
declare -A sum
variants=("unlit floor" "1 light" "1 light, moving" "4 lights" "4 lights, moving")
args_of() {
    case "$1" in
        "unlit floor") echo unlit ;;
        "1 light") echo one ;;
        "1 light, moving") echo one spin ;;
        "4 lights") echo four ;;
        "4 lights, moving") echo four spin ;;
    esac
}
echo
echo "viewer-bevy-match 1920x1080, panel hidden, $rounds interleaved rounds (median of each run, ms):"
for round in $(seq "$rounds"); do
    for v in "${variants[@]}"; do
        a=($(args_of "$v"))
        extra=()
        case "${a[0]}" in
            unlit) extra=("${unlit[@]}") ;;
            one) extra=(--set "lights=[$one_light]") ;;
        esac
        [[ "${a[1]:-}" == spin ]] && extra+=(--spin-lights 1)
        m=$(run 1920x1080 "$match" --no-panel --no-overlay "${extra[@]}" | median)
        echo "  round $round gonio $v: $m"
        sum["gonio $v"]+="$m "
        if [[ -n "$before" ]]; then
            m=$(run_with "$before" 1920x1080 "$match" --no-panel --no-overlay "${extra[@]}" | median)
            echo "  round $round before $v: $m"
            sum["before $v"]+="$m "
        fi
        if [[ -n "$bevy" && "${a[0]}" != unlit ]]; then
            lights=4; [[ "${a[0]}" == one ]] && lights=1
            spin=(); [[ "${a[1]:-}" == spin ]] && spin=(--spin-lights 1)
            m=$(xvfb-run -a -s "-screen 0 1920x1080x24" "$bevy" "$match" --frames "$frames" \
                --warmup "$warmup" --spin 0.5 --lights "$lights" "${spin[@]}" 2>/dev/null \
                | grep '^frame times' | median)
            echo "  round $round bevy  $v: $m"
            sum["bevy $v"]+="$m "
        fi
    done
done
echo
# The targets beside each figure: the shadowed frame at most 4x the
# unlit floor, and at most 0.2 of Bevy's frame (static and moving lights).
echo "| variant | gonio (median of rounds) | / unlit floor (target <= 4) | bevy | gonio / bevy (target <= 0.2) |"
echo "| --- | --- | --- | --- | --- |"
med() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {m = int((NR+1)/2); printf "%.2f\n", (NR % 2 ? a[m] : (a[m] + a[m+1]) / 2)}'; }
floor=$(echo "${sum[gonio unlit floor]}" | med)
for v in "${variants[@]}"; do
    g=$(echo "${sum[gonio $v]}" | med)
    b=$( [[ -n "${sum[bevy $v]:-}" ]] && echo "${sum[bevy $v]}" | med || echo "")
    ratio=$(awk -v g="$g" -v f="$floor" -v v="$v" 'BEGIN {
        r = g / f; printf "%.2f", r; if (v != "unlit floor") printf (r <= 4 ? " met" : " missed")}')
    vs=$( [[ -n "$b" ]] && awk -v g="$g" -v b="$b" 'BEGIN {
        r = g / b; printf "%.3f %s", r, (r <= 0.2 ? "met" : "missed")}' || echo "–")
    echo "| $v | $g ms | $ratio | ${b:-–}${b:+ ms} | $vs |"
done
if [[ -n "$before" ]]; then
    echo
    echo "Before ($before) and after, interleaved in the same rounds:"
    echo "| variant | before | after | after / before |"
    echo "| --- | --- | --- | --- |"
    for v in "${variants[@]}"; do
        a=$(echo "${sum[gonio $v]}" | med)
        b=$(echo "${sum[before $v]}" | med)
        echo "| $v | $b ms | $a ms | $(awk -v a="$a" -v b="$b" 'BEGIN {printf "%.2f", a / b}') |"
    done
fi
