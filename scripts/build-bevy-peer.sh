#!/usr/bin/env bash
# Builds bench/bevy-peer, the Bevy 0.19 program gonio's viewer is measured
# against, and prints its binary's path for
# scripts/viewer-frame-time.sh. Not part of gonio's build or tests: Bevy
# takes 20–40 min to build on 2 cores. Its target directory is kept apart
# (BEVY_TARGET_DIR, default target/bevy-peer) so it never touches gonio's.
set -euo pipefail
cd "$(dirname "$0")/.."
target="${BEVY_TARGET_DIR:-$PWD/target/bevy-peer}"
(cd bench/bevy-peer && CARGO_TARGET_DIR="$target" cargo build --release --quiet)
echo "$target/release/bevy-peer"
