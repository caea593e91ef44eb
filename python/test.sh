#!/usr/bin/env bash
# The Python half of the test suite (the README's test command runs it after `cargo test`):
# a virtual environment at .venv with python/requirements-test.txt, the extension built into it
# with maturin in the dev profile (optimised, and shared with `cargo test`'s build, so only the
# extension itself compiles here), the CLI it is compared with built exactly as `cargo test
# --workspace` builds it (`cargo test --workspace --no-run`: after `cargo test` nothing compiles;
# `cargo build --workspace --bins` resolved dependency features without the dev-dependencies
# and rebuilt much of the tree, 88 s of CI), then pytest.
# pytest's exit code 5 (no tests collected) is a failure: it means the suite went missing, not
# that it passed.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check -r python/requirements-test.txt
echo "python/test.sh: the virtual environment took $((SECONDS - start)) s" >&2
start=$SECONDS
cargo test --locked --quiet --workspace --no-run
echo "python/test.sh: the binaries took $((SECONDS - start)) s" >&2
start=$SECONDS
.venv/bin/maturin develop --locked --quiet -m python/Cargo.toml
echo "python/test.sh: the extension took $((SECONDS - start)) s" >&2
set +e
VSRLAB_BIN="$PWD/target/debug/vsrlab" .venv/bin/python -m pytest python/tests -q "$@"
status=$?
set -e
if [ "$status" -eq 5 ]; then
  echo "python/test.sh: pytest collected no tests: the Python suite is missing" >&2
  exit 1
fi
exit "$status"
