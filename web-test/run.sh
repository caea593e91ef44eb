#!/usr/bin/env bash
# The browser part of the test suite (the README's test command runs it after python/test.sh):
# Debian's chromium (installed with apt-get when missing and running as root), playwright-core from
# web-test/package-lock.json (never `npx playwright install`: it would download a browser), the CLI
# in the dev profile (shared with `cargo test`; built with --workspace, as python/test.sh explains),
# then web-test/viewer.test.mjs, which serves replays with `vsrlab view`, drives the page headless
# and checks its pixels (docs/viewer.md).
set -euo pipefail
cd "$(dirname "$0")/.."
CHROMIUM="${CHROMIUM:-/usr/bin/chromium}"
if [ ! -x "$CHROMIUM" ]; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    echo "web-test/run.sh: installing Debian's chromium" >&2
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
  else
    echo "web-test/run.sh: needs Debian's chromium at $CHROMIUM (sudo apt-get install chromium), or CHROMIUM=/path/to/chromium" >&2
    exit 1
  fi
fi
if ! command -v node >/dev/null; then
  echo "web-test/run.sh: needs Node.js 20 or later and npm (sudo apt-get install nodejs npm)" >&2
  exit 1
fi
(cd web-test && npm ci --no-audit --no-fund --silent)
# the CLI as `cargo test --workspace` builds it: nothing compiles after the README's `cargo test`
# (`cargo build --bins` resolves dependency features without the dev-dependencies: a rebuild)
cargo test --locked --quiet --workspace --no-run
VSRLAB_BIN="$PWD/target/debug/vsrlab" CHROMIUM="$CHROMIUM" node web-test/viewer.test.mjs
