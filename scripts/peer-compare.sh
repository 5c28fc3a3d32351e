#!/bin/bash
# Renders glTF files with gonio and with three.js, Babylon.js and Filament (the web-peers harness:
# headless Chromium, same camera, lat-long map in gonio's orientation, Khronos PBR Neutral), then
# measures gonio against them and writes the side-by-side pictures (scripts/peer-compare.py).
# Method and results: docs/peers.md.
#
#   scripts/peer-compare.sh                 # every file of the default list below
#   scripts/peer-compare.sh FILE.gltf ...   # only these files (their rows of the table are replaced)
#   FORCE=1 scripts/peer-compare.sh ...     # render again even where a render (or a failed one's log) exists
#   ONLY=gonio scripts/peer-compare.sh ...  # re-render one renderer (e.g. gonio after a change)
#
# "gonio-sampled" is gonio with environment.specular = "sampled", 1024 directions (the whole BRDF
# against the map by multiple importance sampling, close to gonio's integrated truth): it is
# measured beside gonio's default (the prefiltered split sum) but not pictured.
#
# Environment (defaults in brackets):
#   WEB_PEERS  the installed web-peers harness, see its README.md [~/web-peers]
#   GONIO      gonio binary [target/release/gonio]
#   MAP        lat-long .hdr [$WEB_PEERS/out/env/chinese_garden_nosun_512.hdr, made here from
#              Poly Haven's chinese_garden_1k.hdr (CC0): every texel whose largest channel exceeds 16
#              scaled down to 16 (the sun), then averaged 2 x 2 to 512 x 256 (Babylon.js prefilters
#              the map on SwiftShader: about 65 s a render at 1k, 25 s at 512)]
#   PYTHON     a python3 with numpy and Pillow [/usr/bin/python3: apt-get install python3-numpy python3-pil]
#   SAMPLES    folder of the Khronos glTF sample models [/work/samples/Models]
#   PEER_ASSETS folder of the newer-extension samples [/work/shared/assets/gltf-pbr-next]
#   OUT        renders and logs [target/peers]
#   DOCS       pictures and results.csv [docs/peers]
#
# Camera (all four renderers, not the file's own): up +Y, target the centre of the file's world
# AABB (accessor bounds through the node transforms of the default scene), position on +Z at
# r / sin(fov_y / 2) (r: half the AABB diagonal), fov_y 45 deg, 480 x 360; the peers' far plane
# 50 (d + r) (Babylon.js's skybox hides geometry under a closer far plane). A file's own lights
# are kept by all four, unshadowed.
set -u
cd "$(dirname "$0")/.."
ROOT=$PWD
WEB_PEERS=${WEB_PEERS:-$HOME/web-peers}
GONIO=${GONIO:-$ROOT/target/release/gonio}
SAMPLES=${SAMPLES:-/work/samples/Models}
PEER_ASSETS=${PEER_ASSETS:-/work/shared/assets/gltf-pbr-next}
OUT=${OUT:-$ROOT/target/peers}
DOCS=${DOCS:-$ROOT/docs/peers}
FORCE=${FORCE:-0}
PYTHON=${PYTHON:-/usr/bin/python3}
ONLY=${ONLY:-gonio gonio-sampled three babylon filament}
W=480
H=360
FOV=45

[ -x "$WEB_PEERS/render.sh" ] || { echo "peer-compare: no web-peers harness at $WEB_PEERS (WEB_PEERS=...; install it as its README.md says)" >&2; exit 2; }
[ -x "$GONIO" ] || { echo "peer-compare: no gonio binary at $GONIO (cargo build --release, or GONIO=...)" >&2; exit 2; }

if [ -z "${MAP:-}" ]; then
  MAP=$WEB_PEERS/out/env/chinese_garden_nosun_512.hdr
  if [ ! -f "$MAP" ]; then
    SRC=$WEB_PEERS/out/env/chinese_garden_1k.hdr
    [ -f "$SRC" ] || { echo "peer-compare: $SRC missing: run the harness's tools/get_maps.sh" >&2; exit 2; }
    # The garden's sun (73 texels up to 68,000) is resampled differently by every renderer
    # (web-peers README, "Diffuse IBL"): scale every texel whose largest channel exceeds 16 to 16,
    # then average 2 x 2 texels.
    node --input-type=module -e "
      import { readHDR, writeHDR } from '$WEB_PEERS/lib/hdr.mjs';
      const m = readHDR('$SRC'), C = 16, W = m.width / 2, H = m.height / 2;
      for (let i = 0; i < m.width * m.height; i++) {
        const mx = Math.max(m.data[3 * i], m.data[3 * i + 1], m.data[3 * i + 2]);
        if (mx > C) for (let k = 0; k < 3; k++) m.data[3 * i + k] *= C / mx;
      }
      const o = new Float32Array(W * H * 3), at = (x, y, k) => m.data[(y * m.width + x) * 3 + k];
      for (let y = 0; y < H; y++) for (let x = 0; x < W; x++) for (let k = 0; k < 3; k++)
        o[(y * W + x) * 3 + k] = 0.25 * (at(2 * x, 2 * y, k) + at(2 * x + 1, 2 * y, k) + at(2 * x, 2 * y + 1, k) + at(2 * x + 1, 2 * y + 1, k));
      writeHDR('$MAP', W, H, o);" || exit 1
  fi
fi

default_files() {
  local f
  for f in Box/Box.gltf BoxInterleaved/BoxInterleaved.gltf BoxTextured/BoxTextured.gltf \
    Avocado/Avocado.gltf Cameras/Cameras.gltf MultipleScenes/MultipleScenes.gltf \
    NormalTangentTest/NormalTangentTest.glb ShadowsDirectional/shadows-directional.gltf \
    SimpleMeshes/SimpleMeshes.gltf Suzanne/Suzanne.gltf Triangle/Triangle.gltf \
    TriangleWithoutIndices/TriangleWithoutIndices.gltf AlphaBlendModeTest/AlphaBlendModeTest.glb \
    MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb \
    MetalRoughSpheresTextured/MetalRoughSpheresTextured.gltf \
    MetalRoughSpheresTextured/MetalRoughSpheresTexelFactors.gltf \
    TextureCoordinateTest/TextureCoordinateTest.glb TextureEncodingTest/TextureEncodingTest.glb \
    TextureLinearInterpolationTest/TextureLinearInterpolationTest.glb \
    TextureSettingsTest/TextureSettingsTest.glb TextureTransformTest/TextureTransformTest.gltf \
    VertexColorTest/VertexColorTest.glb; do
    echo "assets/gltf/$f"
  done
  for f in Box-Draco/Box.gltf Suzanne-Draco/Suzanne-Draco.glb \
    MetalRoughSpheres-Meshopt/MetalRoughSpheres-EXT-Meshopt.glb \
    BoxTextured-KTX2/BoxTextured-UASTC.gltf BoxTextured-WebP/BoxTextured-WebP-lossless.gltf; do
    echo "assets/gltf-compressed/$f"
  done
  for f in AnisotropyStrengthTest/AnisotropyStrengthTest.glb AttenuationTest/AttenuationTest.glb \
    ClearCoatTest/ClearCoatTest.glb IridescenceSuzanne/IridescenceSuzanne.glb \
    SheenCloth/SheenCloth.gltf SpecularTest/SpecularTest.glb \
    TransmissionTest/TransmissionTest.glb UnlitTest/UnlitTest.glb; do
    echo "$PEER_ASSETS/$f"
  done
  for f in DamagedHelmet/glTF-Binary/DamagedHelmet.glb WaterBottle/glTF/WaterBottle.gltf \
    WaterBottle/glTF-Draco/WaterBottle.gltf StainedGlassLamp/glTF-KTX-BasisU/StainedGlassLamp.gltf \
    AnisotropyBarnLamp/glTF-KTX2-Basisu/AnisotropyBarnLamp.gltf; do
    echo "$SAMPLES/$f"
  done
}

# A name per file: the file's base name, with its folder's when that adds something
# (WaterBottle/glTF-Draco/WaterBottle.gltf -> WaterBottle-glTF-Draco, Box-Draco/Box.gltf -> Box-Draco).
name_of() {
  local base dir
  base=$(basename "$1"); base=${base%.*}
  dir=$(basename "$(dirname "$1")")
  case "$dir" in
    glTF) echo "$base" ;;
    glTF-*) echo "$base-$dir" ;;
    "$base"-*) echo "$dir" ;;
    *) echo "$base" ;;
  esac
}

# Prints "px,py,pz tx,ty,tz near far" from the file's bounds (the harness's own framing code).
camera_of() {
  node --input-type=module -e "
    import { gltfBounds } from '$WEB_PEERS/lib/gltfbox.mjs';
    let b = null; try { b = gltfBounds(process.argv[1]); } catch (e) {}
    const c = b ? b.center : [0, 0, 0], r = b ? Math.max(b.radius, 1e-6) : 1;
    const d = r / Math.sin($FOV * Math.PI / 360);
    const near = d - r > 0 ? Math.max((d - r) * 0.5, d * 1e-3) : Math.max(d * 1e-3, 1e-3);
    const f = (x) => Number(x.toPrecision(7));
    console.log([f(c[0]), f(c[1]), f(c[2] + d)].join(',') + ' ' + c.map(f).join(',') + ' ' + f(near) + ' ' + f(50 * (d + r)));
  " "$1"
}

if [ $# -gt 0 ]; then FILES=("$@"); else mapfile -t FILES < <(default_files); fi
mkdir -p "$OUT/renders" "$DOCS"
NAMES=()
for file in "${FILES[@]}"; do
  [ -f "$file" ] || { echo "peer-compare: $file: no such file (skipped)" >&2; continue; }
  name=$(name_of "$file")
  NAMES+=("$name")
  dir=$OUT/renders/$name
  mkdir -p "$dir"
  read -r pos target near far < <(camera_of "$file")
  printf '{"file": "%s", "position": [%s], "target": [%s], "fov_y_deg": %s, "width": %s, "height": %s, "map": "%s"}\n' \
    "$file" "$pos" "$target" "$FOV" "$W" "$H" "$MAP" > "$dir/camera.json"
  for r in $ONLY; do
    png=$dir/$r.png
    # Done before (or failed before: its log stays, e.g. a refused extension or a timeout).
    if [ "$FORCE" != 1 ] && { [ -s "$png" ] || [ -s "$dir/$r.log" ]; }; then continue; fi
    rm -f "$png"
    start=$(date +%s.%N)
    if [ "$r" = gonio ] || [ "$r" = gonio-sampled ]; then
      extra=()
      [ "$r" = gonio-sampled ] && extra=(--set 'environment.specular="sampled"' --set environment.samples=1024)
      "$GONIO" render "$file" -o "$png" --width $W --height $H \
        --set "environment.map=\"$MAP\"" --set 'image.tone_map="pbr-neutral"' \
        --set "camera.position=[$pos]" --set "camera.target=[$target]" --set "camera.fov_y_deg=$FOV" --set "camera.up=[0,1,0]" \
        --set shadows.imported_lights=false "${extra[@]}" > "$dir/$r.log" 2>&1
    else
      "$WEB_PEERS/render.sh" "$r" "$file" "$png" --width $W --height $H --env "$MAP" --tone-map neutral \
        --position="$pos" --target="$target" --fov-y $FOV --near "$near" --far "$far" \
        --json "$dir/$r.json" > "$dir/$r.log" 2>&1
    fi
    rc=$?
    printf '%-40s %-9s exit %d  %5.1f s\n' "$name" "$r" $rc "$(echo "$(date +%s.%N) - $start" | bc)"
    [ $rc -eq 0 ] || { tail -3 "$dir/$r.log" | sed 's/^/    /'; rm -f "$png"; }
  done
done

"$PYTHON" scripts/peer-compare.py --renders "$OUT/renders" --map "$MAP" --docs "$DOCS" "${NAMES[@]}"
