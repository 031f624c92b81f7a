#!/usr/bin/env bash
# Runs every test suite: the GoogleTest binaries through ctest, then the
# command-line and browser tests. Usage: scripts/test.sh BUILD_DIR
set -euo pipefail
build=${1:-build}
cd "$(dirname "$0")/.."
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 600
for t in tests/*.sh; do
  [[ -e "$t" ]] || continue
  echo "== $t"
  bash "$t" "$build"
done
