#!/usr/bin/env bash
# Builds and runs the matrix-code benchmark (single thread) into target/bench-learning.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
CARGO_TARGET_DIR="$here/../../target/bench-learning" RAYON_NUM_THREADS=1 \
    cargo run --release --manifest-path "$here/Cargo.toml" -- "$@"
