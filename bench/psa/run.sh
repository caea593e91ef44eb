#!/usr/bin/env bash
# Side-by-side speed of a PSA in vsrlab and on Box2D (pybox2d 2.3.10 from PyPI), one session.
#
#   bash bench/psa/run.sh [SIZE]      # SIZE: small, medium (default) or large
#
# Box2D side: bench/psa/box2d_ring.py (the ring, pressure and a random controller in Python,
# and world.Step alone). vsrlab side: `vsrlab bench --robots psa:SIZE` (full episodes: physics,
# pressure, sensors and the heads brain), single-threaded, steps per CPU-second. The original
# PSA code's own figure (flat, MLP controller, psa-model.md) is printed by `vsrlab bench`.
set -euo pipefail
size="${1:-medium}"
root="$(cd "$(dirname "$0")/../.." && pwd)"
venv="${VENV:-$root/target/psa-bench-venv}"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q -r "$root/bench/psa/requirements.txt"
fi
cargo build --release -q -p vsrlab-cli --manifest-path "$root/Cargo.toml"
box2d="$("$venv/bin/python" "$root/bench/psa/box2d_ring.py" speed "$size" --steps 18000)"
echo "$box2d"
ours="$("$root/target/release/vsrlab" bench --robots "psa:$size" --single-only --json)"
python3 - "$ours" "$box2d" <<'PY'
import json, re, sys
row = json.loads(sys.argv[1])["rows"][0]
b2 = {m.group(1): float(m.group(2)) for m in re.finditer(r"^(\S+) \S+: .* = (\d+) steps/s", sys.argv[2], re.M)}
print(f"vsrlab {row['robot']}: {row['steps_per_s']:.0f} steps/s (full episodes, one core)")
for name, rate in b2.items():
    print(f"  {row['steps_per_s'] / rate:.1f}x {name} ({rate:.0f} steps/s)")
print(f"  {row['ratio_to_original']:.1f}x the original PSA code ({row['original_steps_per_s']:.0f} steps/s, psa-model.md)")
PY
