#!/usr/bin/env bash
# Runs the benchmarks recorded in docs/BENCHMARKS.md.
set -euo pipefail
build=${1:-build}
cd "$(dirname "$0")/.."
for b in "$build"/bench/sb_*_bench; do
  [[ -x "$b" ]] || continue
  echo "== $b"
  "$b"
done
