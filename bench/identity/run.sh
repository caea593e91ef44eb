#!/usr/bin/env bash
# Prints, for every line of configs.txt, the outcome of `vsrlab simulate --json` without its
# wall-clock field. Compare two binaries with: diff <(run.sh A) <(run.sh B)
set -euo pipefail
bin="${1:-target/release/vsrlab}"
here="$(dirname "$0")"
grep -v '^#' "$here/configs.txt" | while read -r line; do
  # shellcheck disable=SC2086
  out="$("$bin" simulate $line --json | grep -v wall_seconds | tr -d ' \n')"
  echo "$line => $out"
done
