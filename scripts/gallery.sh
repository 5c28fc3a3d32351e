#!/usr/bin/env bash
# scripts/gallery.sh [I/N] [OUT_DIR]: a gallery of materials × maps,
# one `gonio render` per cell, sharded as gonio's own commands are.
#
# The scene is assets/scenes/environment.toml (three spheres under an
# environment map); each cell gives its middle sphere a Cook-Torrance
# conductor preset and the scene a map, with prefiltered specular so the
# metal reflects it. Cells are numbered k = 0.. (material-major); shard
# I of N renders the cells with k mod N = I - 1, so an array job runs
#
#   sbatch --array=1-8 --wrap 'scripts/gallery.sh $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT gallery'
#
# and a Kubernetes Indexed Job `scripts/gallery.sh $((JOB_COMPLETION_INDEX+1))/8`.
# Without I/N it renders every cell. A cell whose PNG exists is skipped
# (gonio writes atomically: an existing file is complete), so a rerun
# renders only what is missing. GONIO=path picks the binary; REFERENCE=1
# renders with the CPU reference instead of the GPU; SIZE=WxH (240x120).
set -euo pipefail
cd "$(dirname "$0")/.."

SHARD=${1:-1/1}
OUT=${2:-gallery}
GONIO=${GONIO:-target/release/gonio}
SIZE=${SIZE:-240x120}
I=${SHARD%/*}
N=${SHARD#*/}
if ! [[ $I =~ ^[0-9]+$ && $N =~ ^[0-9]+$ ]] || ((I < 1 || I > N)); then
    echo "gallery.sh: expected I/N with 1 <= I <= N, got \`$SHARD'" >&2
    exit 2
fi

materials=(gold-rgb copper silver steel)
maps=(sky ../environment/blobs.hdr)
flags=(--width "${SIZE%x*}" --height "${SIZE#*x}")
[[ ${REFERENCE:-0} == 1 ]] && flags+=(--reference)
mkdir -p "$OUT"

k=0
done_here=0
for material in "${materials[@]}"; do
    for map in "${maps[@]}"; do
        if ((k % N == I - 1)); then
            name=$(basename "${map%.*}")
            png="$OUT/$material--$name.png"
            if [[ -e $png ]]; then
                echo "gallery.sh: $png exists: skipped"
            else
                "$GONIO" render assets/scenes/environment.toml -o "$png" "${flags[@]}" \
                    --set "materials.gold.preset=\"$material\"" \
                    --set "environment.map=\"$map\"" \
                    --set 'environment.specular="prefiltered"'
                echo "gallery.sh: wrote $png"
            fi
            done_here=$((done_here + 1))
        fi
        k=$((k + 1))
    done
done
echo "gallery.sh: shard $I/$N: $done_here of $k cells"
