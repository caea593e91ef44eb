#!/usr/bin/env bash
# Side-by-side speed benchmark: EvoGym (PyPI evogym==2.0.0) vs vsrlab.
#
# Creates (or reuses) bench/evogym/.venv with CPython 3.10, installs the pinned
# requirements, makes sure the system libGL that EvoGym's compiled module links
# against is present, then runs compare.py with all arguments passed through.
#
#   bench/evogym/run.sh                    # EvoGym + vsrlab (cargo run --release)
#   bench/evogym/run.sh --skip-vsrlab      # EvoGym only
#   bench/evogym/run.sh --vsrlab target/release/vsrlab --json
#
# Environment:
#   EVOGYM_PYTHON   python3.10 interpreter to build the venv with (optional)
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# EVOGYM_VENV, EVOGYM_REQUIREMENTS and EVOGYM_SCRIPT let ppo.sh reuse this set-up for its own
# venv (torch and stable-baselines3 beside EvoGym) and script.
VENV="${EVOGYM_VENV:-$HERE/.venv}"
REQ="${EVOGYM_REQUIREMENTS:-$HERE/requirements.txt}"
SCRIPT="${EVOGYM_SCRIPT:-$HERE/compare.py}"

log() { echo "[run.sh] $*" >&2; }

is_py310() {
    "$1" -c 'import sys; sys.exit(0 if sys.version_info[:2] == (3, 10) else 1)' >/dev/null 2>&1
}

find_python310() {
    local cands=() root cand
    [[ -n "${EVOGYM_PYTHON:-}" ]] && cands+=("$EVOGYM_PYTHON")
    command -v python3.10 >/dev/null 2>&1 && cands+=("$(command -v python3.10)")  # may be a pyenv shim
    for root in "$(pyenv root 2>/dev/null || true)" "${PYENV_ROOT:-$HOME/.pyenv}"; do
        [[ -n "$root" ]] || continue
        # highest 3.10.x first
        for cand in $(ls -d "$root"/versions/3.10.* 2>/dev/null | sort -V -r); do
            cands+=("$cand/bin/python3.10")
        done
    done
    cands+=(/usr/bin/python3.10 /usr/local/bin/python3.10)
    for cand in "${cands[@]}"; do
        if [[ -x "$cand" ]] && is_py310 "$cand"; then
            echo "$cand"; return 0
        fi
    done
    return 1
}

venv_ok() {
    [[ -x "$VENV/bin/python" ]] && is_py310 "$VENV/bin/python"
}

setup_start=$(date +%s)

if ! venv_ok; then
    PY="$(find_python310)" || {
        log "ERROR: no CPython 3.10 found (EvoGym 2.0.0 only has cp310 wheels)."
        log "       Install one (e.g. 'pyenv install 3.10') or set EVOGYM_PYTHON=/path/to/python3.10."
        exit 2
    }
    log "creating venv $VENV with $PY"
    rm -rf "$VENV"
    "$PY" -m venv "$VENV"
fi

# Reinstall only when requirements.txt changed since the last successful install.
# shellcheck source=../venv.sh
source "$(dirname "$0")/../venv.sh"
install_requirements

# evogym's compiled module (simulator_cpp) links against the system libGL.so.1
# (and through it libX11) even though we never render. Debian: package libgl1.
if ! "$VENV/bin/python" -c 'import evogym.simulator_cpp' 2>/dev/null; then
    err="$("$VENV/bin/python" -c 'import evogym.simulator_cpp' 2>&1 || true)"
    log "importing evogym failed: ${err##*$'\n'}"
    if [[ "$err" == *libGL* || "$err" == *libX11* || "$err" == *libGLX* ]]; then
        if [[ "$(id -u)" == 0 ]] && command -v apt-get >/dev/null 2>&1; then
            log "installing Debian package libgl1 (runtime library only; no display is used)"
            apt-get update -qq >&2 && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libgl1 >&2
        else
            log "ERROR: need the system library libGL.so.1 (Debian/Ubuntu: apt-get install libgl1)."
            exit 2
        fi
    fi
    "$VENV/bin/python" -c 'import evogym.simulator_cpp' || {
        log "ERROR: evogym still cannot be imported."
        exit 2
    }
fi

log "setup took $(( $(date +%s) - setup_start )) s"

# One thread for everything numeric, so process_time() measures a single thread.
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
exec "$VENV/bin/python" "$SCRIPT" "$@"
