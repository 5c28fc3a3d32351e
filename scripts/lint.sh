#!/usr/bin/env bash
# gonio's fast checks, run before the tests: the README's test command and
# CI (.ci/run) are `./setup.sh && scripts/lint.sh && cargo test --release`.
# Each step stops the run on failure:
#   1. formatting        cargo fmt --check                      (seconds)
#   2. import graph      no circle between files or folders of src/,
#                        the README's layer map holds (tests/import_graph.rs;
#                        well under a second once built)
#   3. lints             cargo clippy --all-targets, -D warnings (~1 min cold)
#   4. API docs          cargo doc --no-deps, warnings denied   (~1 min cold)
# Clippy and doc use the release profile so they share the dependencies'
# metadata with each other.
set -euo pipefail
cd "$(dirname "$0")/.."

step() { echo "==> $*" >&2; }

step "cargo fmt --check"
cargo fmt --all --check

step "cargo test --release --test import_graph"
cargo test --release --test import_graph --quiet

step "cargo clippy --release --all-targets -- -D warnings"
cargo clippy --release --all-targets --quiet -- -D warnings

step "cargo doc --release --no-deps (warnings denied)"
RUSTDOCFLAGS="-D warnings" cargo doc --release --no-deps --quiet
