#!/usr/bin/env bash
# EvoGym's own PPO (stable-baselines3, as EvoGym 2.0's examples) beside vsrlab's on one body:
# creates (or reuses) bench/evogym/.venv-ppo with CPython 3.10 and requirements-ppo.txt (torch
# from PyPI pulls its CUDA libraries: about 3 GB to download, 5 GB installed; nothing uses a GPU),
# then runs ppo.py with your arguments. One thread for torch, as `RAYON_NUM_THREADS=1` for vsrlab.
#
#   bench/evogym/ppo.sh --task BridgeWalker-v0 --iterations 20
#   RAYON_NUM_THREADS=1 cargo run --release -p vsrlab-experiment --example ppo_evogym -- BridgeWalker-v0 20
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
EVOGYM_VENV="$HERE/.venv-ppo" EVOGYM_REQUIREMENTS="$HERE/requirements-ppo.txt" EVOGYM_SCRIPT="$HERE/ppo.py" \
    exec "$HERE/run.sh" "$@"
