#!/usr/bin/env bash
# Runs the reduced co-design campaign (reduced-direct.toml and reduced-cppn.toml: 3 tasks × 2
# encodings) as six processes side by side, each with its share of the cores: BridgeWalker and
# CaveCrawler cost about twice BeamToppler's per evaluation. A many-core machine finishes in
# about a tenth of the CPU time (docs/ch5.2.md).
#
#   experiments/ch5.2/reduced-parallel.sh OUT [VSRLAB]
#
# OUT gets one folder per setting (OUT/reduced-direct-bridge-walker, …) and a log per setting.
# VSRLAB: the vsrlab binary (default: vsrlab on PATH). Threads per setting: THREADS_HEAVY (3) for
# BridgeWalker and CaveCrawler, THREADS_LIGHT (2) for BeamToppler. For a smoke test,
# ITERATIONS and EVALUATIONS replace the files' PPO iterations and evaluation budget.
set -euo pipefail
out=${1:?usage: reduced-parallel.sh OUT [VSRLAB]}
vsrlab=${2:-vsrlab}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
pids=()
for enc in direct cppn; do
    for setting in bridge-walker:BridgeWalker-v0:${THREADS_HEAVY:-3} \
                   beam-toppler:BeamToppler-v0:${THREADS_LIGHT:-2} \
                   cave-crawler:CaveCrawler-v0:${THREADS_HEAVY:-3}; do
        IFS=: read -r slug env threads <<< "$setting"
        name="reduced-$enc-$slug"
        file="$out/$name.toml"
        # the sweep's setting as a file of its own
        sed -e '/^\[sweep\]/,$d' -e "s/^env = \".*\"/env = \"$env\"/" -e "s/^name = .*/name = \"$name\"/" \
            "$here/reduced-$enc.toml" > "$file"
        if [[ -n "${ITERATIONS:-}" ]]; then sed -i "s/^iterations = .*/iterations = $ITERATIONS/" "$file"; fi
        if [[ -n "${EVALUATIONS:-}" ]]; then sed -i "s/^evaluations = .*/evaluations = $EVALUATIONS/" "$file"; fi
        "$vsrlab" run "$file" --out "$out/$name" --threads "$threads" --log-every 30 > "$out/$name.log" 2>&1 &
        pids+=($!)
    done
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
exit $status
