#!/usr/bin/env bash
# gonio's set-up: installs the system packages gonio needs on Debian 12,
# idempotently (a second run only checks and returns in well under a second).
#   - Mesa lavapipe, the software Vulkan driver gonio renders with when the
#     machine has no GPU: mesa-vulkan-drivers, libvulkan1
#   - for the interactive viewer and its tests under a virtual display:
#     xvfb, xauth and the X11 client libraries winit loads at run time
#   - the font plots are labelled with: fonts-dejavu-core
#   - Mesa's GL through EGL, for WGPU_BACKEND=gl and tests/gl_backend.rs:
#     libegl1, libegl-mesa0, libgles2, libgl1-mesa-dri
#   - a C++ compiler for meshoptimizer (the `meshopt` crate builds its C++
#     sources with `cc`; glTF meshopt decoding): g++
# Rust itself is not installed here: gonio needs rustc/cargo >= 1.95 (rustup.rs).
set -euo pipefail

packages=(
  mesa-vulkan-drivers libvulkan1
  libegl1 libegl-mesa0 libgles2 libgl1-mesa-dri
  fonts-dejavu-core
  g++
  xvfb xauth libxkbcommon-x11-0 libx11-xcb1 libxcursor1 libxi6 libxrandr2
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup.sh: installing ${missing[*]}" >&2
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if ! command -v cargo >/dev/null 2>&1; then
  echo "setup.sh: cargo not found. Install Rust >= 1.95 (https://rustup.rs) and run this again." >&2
  exit 1
fi
if [ ! -e /usr/share/vulkan/icd.d/lvp_icd.x86_64.json ] && ! ls /usr/share/vulkan/icd.d/*.json >/dev/null 2>&1; then
  echo "setup.sh: no Vulkan driver manifest in /usr/share/vulkan/icd.d; is mesa-vulkan-drivers installed?" >&2
  exit 1
fi
