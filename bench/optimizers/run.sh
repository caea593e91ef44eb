#!/usr/bin/env bash
# Side-by-side benchmark of vsrlab-evolution's CMA-ES and NSGA-II against pycma and pymoo.
#
# Creates (or reuses) bench/optimizers/.venv, installs the pinned requirements, then runs
# compare.py, which measures pycma/pymoo, runs
#   cargo run --release -p vsrlab-evolution --example optimizer_bench -- --json --seeds N
# and prints one table with ratios. All arguments are passed to compare.py:
#
#   bench/optimizers/run.sh                 # 15 seeds per benchmark
#   bench/optimizers/run.sh --seeds 5       # quicker
#   bench/optimizers/run.sh --json          # machine-readable output
#
# Environment: OPTIMIZERS_BENCH_PYTHON = interpreter for the venv (default python3, >= 3.10).
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
VENV="$HERE/.venv"
REQ="$HERE/requirements.txt"
PY="${OPTIMIZERS_BENCH_PYTHON:-python3}"

log() { echo "[run.sh] $*" >&2; }

if [[ ! -x "$VENV/bin/python" ]]; then
    log "creating venv $VENV with $PY"
    "$PY" -m venv "$VENV"
fi

# Reinstall only when requirements.txt changed since the last successful install.
# shellcheck source=../venv.sh
source "$(dirname "$0")/../venv.sh"
install_requirements

# One thread for numpy, so timings compare single-threaded work.
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
cd "$HERE/../.."
exec "$VENV/bin/python" "$HERE/compare.py" "$@"
