#!/usr/bin/env bash
# The identity harness: fails when a binary's results differ from reference.txt by one bit.
# A change that alters a result (a model change) updates reference.txt with --update and adds
# its entry to CHANGELOG.md in the same commit (docs/architecture.md, "Same results").
# Usage: check.sh [--update | --quick] [BINARY] (default target/release/vsrlab). --quick runs the
# reduced set (run.sh --quick) and compares it with its lines of reference.txt.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
update=false
quick=()
case "${1:-}" in
--update) update=true && shift ;;
--quick) quick=(--quick) && shift ;;
esac
actual="$(mktemp)"
expected="$(mktemp)"
trap 'rm -f "$actual" "$expected"' EXIT
start=$SECONDS
"$here/run.sh" "${quick[@]}" "$@" >"$actual"
if [ ${#quick[@]} -gt 0 ]; then
  # the reference lines of the cases --quick leaves out: experiment lines not marked quick
  grep -v '^#' "$here/experiments.txt" | grep -v '^$' | grep -v '^quick ' | sed 's/^/run /; s/$/ /' >"$expected.skip"
  grep -v -F -f "$expected.skip" "$here/reference.txt" >"$expected" || true
  rm -f "$expected.skip"
else
  cp "$here/reference.txt" "$expected"
fi
if $update; then
  cp "$actual" "$here/reference.txt"
  echo "identity: reference.txt rewritten ($(wc -l <"$actual") cases, $((SECONDS - start)) s)"
  exit 0
fi
if ! diff -u "$expected" "$actual" >"$actual.diff"; then
  cat "$actual.diff"
  rm -f "$actual.diff"
  echo "identity: results differ from bench/identity/reference.txt (above: - expected, + now)." >&2
  echo "identity: a model change updates the references (check.sh --update) and CHANGELOG.md together." >&2
  exit 1
fi
rm -f "$actual.diff"
echo "identity: $(wc -l <"$actual") cases identical to reference.txt ($((SECONDS - start)) s)"
