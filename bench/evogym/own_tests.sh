#!/usr/bin/env bash
# EvoGym's own screen-free tests (tests/screen_free of an EvoGym checkout) run on vsrlab: the
# folder bench/evogym/shim stands in for EvoGym's package, so the tests run unchanged.
#
#   bash bench/evogym/own_tests.sh PATH/TO/evogym [pytest options]
#
# Needs the project's venv with vsrlab built (`bash python/test.sh` makes it).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
checkout="${1:?usage: own_tests.sh PATH/TO/evogym [pytest options]}"
shift
if [ ! -d "$checkout/tests/screen_free" ]; then
    echo "own_tests.sh: $checkout/tests/screen_free: no such folder (is $checkout an EvoGym checkout?)" >&2
    exit 2
fi
cd "$checkout/tests"
PYTHONPATH="$here/shim" exec "$root/.venv/bin/python" -m pytest -p no:cacheprovider screen_free "$@"
