#!/usr/bin/env bash
# Prints what a vsrlab binary computes for every case of the identity harness, one line per case:
#   - each line of configs.txt: the outcome of `vsrlab simulate ARGS --json` (wall clock left out);
#   - each line of experiments.txt: a shipped experiment file reduced by reduce.py (fewer runs and
#     evaluations) and run, as the SHA-256 of every run's generations.csv and its last row.
# check.sh compares this with reference.txt; two binaries compare with diff <(run.sh A) <(run.sh B).
# Usage: run.sh [--quick] [BINARY] (default target/release/vsrlab), from anywhere. --quick runs
# the simulate cases and the experiment lines marked `quick` only (what `cargo test` checks).
set -euo pipefail
quick=false
if [ "${1:-}" = "--quick" ]; then
  quick=true
  shift
fi
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
bin="$(realpath "${1:-$root/target/release/vsrlab}")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$root"

# simulate cases, two at a time (each is one thread), printed in the file's order
grep -v '^#' "$here/configs.txt" | grep -v '^$' >"$work/simulate.txt"
simulate_one() {
  # shellcheck disable=SC2086
  out="$("$2" simulate $3 --json | grep -v wall_seconds | tr -d ' \n')"
  echo "$3 => $out" >"$1"
}
export -f simulate_one
n=0
while IFS= read -r line; do
  n=$((n + 1))
  printf '%s\0%s\0%s\0' "$work/sim-$(printf %04d $n)" "$bin" "$line"
done <"$work/simulate.txt" | xargs -0 -n 3 -P 2 bash -c 'simulate_one "$@"' _
cat "$work"/sim-*

# experiment cases, one after the other (each uses every core)
k=0
grep -v '^#' "$here/experiments.txt" | grep -v '^$' | while IFS= read -r line; do
  case "$line" in
  "quick "*) line="${line#quick }" ;;
  *) if $quick; then continue; fi ;;
  esac
  # shellcheck disable=SC2086
  set -- $line
  file="$1"
  shift
  k=$((k + 1))
  name="$k-$(basename "$file" .toml)"
  python3 "$here/reduce.py" "$file" "$@" >"$work/$name.toml"
  started=$SECONDS
  "$bin" run "$work/$name.toml" --out "$work/out-$name" >/dev/null 2>"$work/$name.log" || {
    echo "run $line => failed: $(tail -1 "$work/$name.log")"
    continue
  }
  (cd "$work/out-$name" && find . -name generations.csv | sort) | while IFS= read -r csv; do
    sum="$(sha256sum "$work/out-$name/$csv" | cut -c1-16)"
    echo "run $line ${csv#./} => sha256 $sum last $(tail -1 "$work/out-$name/$csv")"
  done
  echo "identity: $file took $((SECONDS - started)) s" >&2
done
