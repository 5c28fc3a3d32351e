#!/usr/bin/env bash
# gonio's checks, fast to slow: the README's test command and CI (.ci/run)
# run exactly this after ./setup.sh. Each step stops the run on failure:
#   1. formatting        cargo fmt --check                      (seconds)
#   2. lints             cargo clippy --all-targets, -D warnings (~1 min cold)
#   3. API docs          cargo doc --no-deps, warnings denied   (~1 min cold)
#   4. every test        cargo test --release                   (GPU tests on lavapipe)
# Clippy and doc use the release profile so they share the dependencies'
# metadata with each other; the tests build the release artefacts.
set -euo pipefail
cd "$(dirname "$0")/.."

step() { echo "==> $*" >&2; }

step "cargo fmt --check"
cargo fmt --all --check

step "cargo clippy --release --all-targets -- -D warnings"
cargo clippy --release --all-targets --quiet -- -D warnings

step "cargo doc --release --no-deps (warnings denied)"
RUSTDOCFLAGS="-D warnings" cargo doc --release --no-deps --quiet

step "cargo test --release"
cargo test --release "$@"
