#!/usr/bin/env bash
# Runs every test suite: the GoogleTest binaries through ctest, then the
# command-line and browser tests, then the sanitizer suite (scripts/sanitize.sh)
# and bounded fuzzing of every input format (scripts/fuzz.sh).
# Usage: scripts/test.sh BUILD_DIR
# SB_TEST_SANITIZE=0 skips the sanitizer suite; SB_TEST_FUZZ_SECONDS (6)
# sets the fuzzing time per format, 0 skips it. docs/testing.md.
# Under the sanitizers `make test` leaves out what only repeats the normal
# suite's checks at several times the cost: the documentation commands (docs_*,
# the same CLI paths the unit tests run under the sanitizers), the app and web
# suites' second run on PostgreSQL (the same app and web code; the store's
# suite, which runs the SQL layer on both backends, stays) and the kill -9
# durability test (it checks what the database keeps, not memory);
# `make test-sanitize` runs every test.
set -euo pipefail
build=${1:-build}
cd "$(dirname "$0")/.."
stage() { echo "== $1 (at ${SECONDS} s)"; }
stage "ctest $build"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 600
for t in tests/*.sh; do
  [[ -e "$t" ]] || continue
  stage "$t"
  bash "$t" "$build"
done
status=0
if [[ "${SB_TEST_SANITIZE:-1}" != 0 ]]; then
  stage scripts/sanitize.sh
  SANITIZE_CTEST_EXCLUDE=${SANITIZE_CTEST_EXCLUDE-'^docs_|^durability$|^load$|^[A-Za-z0-9_]+\.[A-Za-z0-9_]+/postgresql$'} \
    bash scripts/sanitize.sh || status=1
fi
fuzz_seconds=${SB_TEST_FUZZ_SECONDS:-6}
if [[ "$fuzz_seconds" != 0 ]]; then
  stage "scripts/fuzz.sh $fuzz_seconds"
  bash scripts/fuzz.sh "$fuzz_seconds" || status=1
fi
stage "done, status $status"
exit $status
