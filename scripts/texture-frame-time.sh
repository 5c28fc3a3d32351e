#!/usr/bin/env bash
# The texture path's frame time: whole textured glTF files in the viewer
# under the default environment (gonio's neutral studio), at 1920x1080,
# vsync off, panel and overlay hidden, the camera orbiting 0.5° per
# frame, against the unlit floor of the same geometry and against Bevy
# 0.19 (bench/bevy-peer) drawing the same file under the same map.
# Every asset's variants run interleaved, round by round, in one Xvfb
# server. Not a test: machines are shared and noisy; compare the ratios
# within a round.
#
#   scripts/texture-frame-time.sh [FRAMES] [WARMUP] [ROUNDS] [BEVY_PEER]
#
# Environment:
# - GONIO: the gonio binary to measure (default: `cargo build --release`
#   and target/release/gonio);
# - HELMET: DamagedHelmet (.gltf or .glb; glTF-Sample-Models, not in the
#   repository; skipped when unset);
# - MANY: many-materials.gltf (default: written by `cargo run --release
#   --example many_materials` into a temporary folder);
# - SHOTS: a folder for one screenshot of each renderer per asset (taken
#   in a separate run after the rounds).
#
# Variants, per asset:
# - gonio: `gonio view FILE` as it opens by default (a glTF without
#   lights: the built-in studio map; specular "auto" = prefiltered for
#   gltf-pbr; MSAA 1; tone map clamp);
# - floor: the same file's geometry with every material replaced by an
#   ambient-only Lambert (k_d = 0, no texture), the directional default
#   light instead of the map (`[gltf] default_light = "directional"`):
#   the same triangles and pixels with next to nothing to shade, as
#   viewer-frame-time.sh's floor;
# - bevy: bench/bevy-peer FILE --environment studio.exr, the studio map
#   written by scripts/studio-map.py (gonio renders byte-identical images
#   with it and with its built-in studio), the camera gonio frames the
#   file with, MSAA off, no tone mapping, exposure 1; the environment
#   filtered by Bevy once (the peer's default; gonio filters once too).
#
# First frame, after the rounds (FIRST_FRAME_RUNS runs of each, default
# 3, alternating): gonio loads the scene before it opens its window and
# prints when its first frame began after the window opened; with
# `--frames 2 --warmup 0` its one frame time is the first frame's own
# (upload, draw, present). The script times the launch to the `adapter:`
# line of `-v` (window opened, GPU device and surface created) and to the
# process's exit after that frame. Launch to the first frame presented
# is then about adapter + first-frame start + first frame (the device
# and surface creation counted twice, tens of ms). The peer prints when
# the scene was framed and when the render world first finished a frame
# after it with no pipeline left compiling, both from its start. Texture
# memory: gonio's first-frame upload total (textures are rgba16float
# with full mip chains; the rest is geometry and the environment) and
# the images Bevy holds as the peer reports them.
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-331}"
warmup="${2:-30}"
rounds="${3:-3}"
bevy="${4:-}"
if [[ -n "${GONIO:-}" ]]; then
    gonio="$GONIO"
else
    cargo build --release --quiet
    gonio=target/release/gonio
fi
tmp=$(mktemp -d)
trap 'kill "$xvfb_pid" 2>/dev/null || true; rm -rf "$tmp"' EXIT
many="${MANY:-}"
if [[ -z "$many" ]]; then
    cargo run --release --quiet --example many_materials -- "$tmp/many" >/dev/null
    many="$tmp/many/many-materials.gltf"
fi
scripts/studio-map.py "$tmp/studio.exr"

assets=()
[[ -n "${HELMET:-}" ]] && assets+=("helmet=$(realpath "$HELMET")")
assets+=("many=$(realpath "$many")")

# One X server for every run: no per-run server start in the timings.
display=":$((90 + RANDOM % 100))"
Xvfb "$display" -screen 0 1920x1080x24 -nolisten tcp >/dev/null 2>&1 &
xvfb_pid=$!
sleep 1
export DISPLAY="$display"

floor_scene() { # FILE -> a scene file: the floor of FILE
    local out="$tmp/floor-$(basename "$1").toml"
    cat >"$out" <<EOF
[[objects]]
gltf = "$1"
material = "floor"

[materials.floor]
model = "lambert"
k_d = [0.0, 0.0, 0.0]
k_a = [0.6, 0.6, 0.6]

[ambient]
radiance = [0.5, 0.5, 0.5]

[gltf]
default_light = "directional"
EOF
    echo "$out"
}

now_ms() { date +%s%3N; }
median() { grep -o 'median [0-9.]* ms' | head -1 | grep -o '[0-9.]*'; }

# gonio FILE OUT [ARGS...]: one viewer run; its stdout in OUT, and the
# time from launch to the `adapter:` line of its stderr.
gonio_run() {
    local file="$1" out="$2"; shift 2
    python3 - "$out" "$gonio" view "$file" --size 1920x1080 --no-vsync --no-panel --no-overlay -v \
        --frames "${run_frames:-$frames}" --warmup "${run_warmup:-$warmup}" --frame-times --spin 0.5 "$@" <<'PY'
import subprocess, sys, time
out = sys.argv[1]
t0 = time.monotonic()
p = subprocess.Popen(sys.argv[2:], stdout=open(out, "w"), stderr=subprocess.PIPE, text=True)
adapter = None
for line in p.stderr:
    if adapter is None and line.startswith("adapter:"):
        adapter = (time.monotonic() - t0) * 1e3
p.wait()
done = (time.monotonic() - t0) * 1e3
with open(out, "a") as f:
    f.write(f"adapter {adapter:.0f}\n" if adapter is not None else "adapter ?\n")
    f.write(f"exit {done:.0f}\n")
PY
}

bevy_run() {
    local file="$1" out="$2"; shift 2
    "$bevy" "$file" --environment "$tmp/studio.exr" --size 1920x1080 \
        --frames "$frames" --warmup "$warmup" --spin 0.5 "$@" >"$out" 2>/dev/null
}

declare -A sum
echo "# texture path frame times ($(date -u '+%F %H:%M') UTC, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
echo "# gonio: $gonio ($("$gonio" --version)); bevy: ${bevy:-none}"
echo "# $((frames - warmup - 1)) frame times after $warmup warm-up, $rounds interleaved rounds, 1920x1080"
for round in $(seq 1 "$rounds"); do
    for a in "${assets[@]}"; do
        name="${a%%=*}" file="${a#*=}"
        gonio_run "$file" "$tmp/g"
        g=$(median <"$tmp/g")
        gonio_run "$(floor_scene "$file")" "$tmp/f"
        f=$(median <"$tmp/f")
        line="round $round $name: gonio $g ms, floor $f ms, gonio/floor $(awk -v g="$g" -v f="$f" 'BEGIN {printf "%.2f", g / f}')"
        sum["$name gonio"]+="$g "
        sum["$name floor"]+="$f "
        if [[ -n "$bevy" ]]; then
            # The peer counts its warm-up from the frame the loaded scene
            # is framed in; gonio loads before its first frame.
            bevy_run "$file" "$tmp/b"
            b=$(median <"$tmp/b")
            line+=", bevy $b ms, gonio/bevy $(awk -v g="$g" -v b="$b" 'BEGIN {printf "%.3f", g / b}')"
            sum["$name bevy"]+="$b "
        fi
        echo "$line (load $(cut -d' ' -f1-3 /proc/loadavg))"
        echo "  gonio: $(grep '^frame times' "$tmp/g" | grep -o 'first frame [0-9.]* ms after the window opened'), launch to $(grep '^adapter' "$tmp/g") ms; $(grep '^uploads' "$tmp/g" | grep -o 'first frame [0-9]* calls, [0-9]* bytes')"
        echo "  floor: $(grep '^frame times' "$tmp/f" | grep -o 'first frame [0-9.]* ms after the window opened')"
        if [[ -n "$bevy" ]]; then
            sed 's/^/  bevy: /' <"$tmp/b" | grep -v 'frame times' || true
        fi
    done
done
if (( rounds > 0 )); then
echo
med() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {m = int((NR+1)/2); printf "%.2f\n", (NR % 2 ? a[m] : (a[m] + a[m+1]) / 2)}'; }
echo "| asset | gonio (median of rounds) | floor | gonio / floor (target <= 4) | bevy | gonio / bevy (target <= 0.2) |"
echo "| --- | --- | --- | --- | --- | --- |"
for a in "${assets[@]}"; do
    name="${a%%=*}"
    g=$(echo "${sum[$name gonio]}" | med)
    f=$(echo "${sum[$name floor]}" | med)
    b=$( [[ -n "${sum[$name bevy]:-}" ]] && echo "${sum[$name bevy]}" | med || echo "")
    rf=$(awk -v g="$g" -v f="$f" 'BEGIN {r = g / f; printf "%.2f %s", r, (r <= 4 ? "met" : "missed")}')
    rb=$( [[ -n "$b" ]] && awk -v g="$g" -v b="$b" 'BEGIN {r = g / b; printf "%.3f %s", r, (r <= 0.2 ? "met" : "missed")}' || echo "–")
    echo "| $name | $g ms | $f ms | $rf | ${b:-–}${b:+ ms} | $rb |"
done
fi
echo "# load at the end of the rounds $(cut -d' ' -f1-3 /proc/loadavg)"

first_runs="${FIRST_FRAME_RUNS:-3}"
if (( first_runs > 0 )); then
    echo
    echo "# first frame, $first_runs runs each (launch = the program's start; ms)"
    for a in "${assets[@]}"; do
        name="${a%%=*}" file="${a#*=}"
        for run in $(seq "$first_runs"); do
            run_frames=2 run_warmup=0 gonio_run "$file" "$tmp/g"
            start=$(grep '^frame times' "$tmp/g" | grep -o 'first frame [0-9.]* ms after' | grep -o '[0-9.]*')
            own=$(median <"$tmp/g")
            ad=$(grep '^adapter' "$tmp/g" | cut -d' ' -f2)
            ex=$(grep '^exit' "$tmp/g" | cut -d' ' -f2)
            echo "$name run $run gonio: launch to adapter $ad, first frame began $start after the window opened and took $own, sum $(awk -v a="$ad" -v s="$start" -v o="$own" 'BEGIN {printf "%.0f", a + s + o}'); exit after it $ex (load $(cut -d' ' -f1 /proc/loadavg))"
            if [[ -n "$bevy" ]]; then
                "$bevy" "$file" --environment "$tmp/studio.exr" --size 1920x1080 \
                    --frames 40 --warmup 10 >"$tmp/b" 2>/dev/null
                echo "$name run $run bevy: $(grep -o 'scene ready [0-9.]* ms' "$tmp/b"), $(grep -o 'first frame with.*' "$tmp/b")"
            fi
        done
    done
fi

if [[ -n "${SHOTS:-}" ]]; then
    mkdir -p "$SHOTS"
    for a in "${assets[@]}"; do
        name="${a%%=*}" file="${a#*=}"
        # No orbit: the framed camera itself, in both.
        "$gonio" view "$file" --size 1920x1080 --no-vsync --no-panel --no-overlay \
            --frames 3 --screenshot "$SHOTS/$name-gonio.png" >/dev/null 2>&1
        "$gonio" view "$(floor_scene "$file")" --size 1920x1080 --no-vsync --no-panel --no-overlay \
            --frames 3 --screenshot "$SHOTS/$name-floor.png" >/dev/null 2>&1
        if [[ -n "$bevy" ]]; then
            "$bevy" "$file" --environment "$tmp/studio.exr" --size 1920x1080 --frames 20 --warmup 10 \
                --screenshot "$SHOTS/$name-bevy.png" >/dev/null 2>&1
        fi
    done
    echo "# screenshots in $SHOTS"
fi
