#!/usr/bin/env bash
# The unit and API test suites (every GoogleTest binary and the CTest CLI
# checks) built with AddressSanitizer + UndefinedBehaviorSanitizer in the
# checked build (scripts/checked_build.sh: clang, -O1, errors fatal, leaks
# checked), which also holds the fuzzing harnesses that scripts/fuzz.sh runs.
# Usage: scripts/sanitize.sh   (`make test-sanitize`); SANITIZE_BUILD
# (build-sanitize) and JOBS (nproc) override; SANITIZE_CTEST_EXCLUDE, a ctest -E
# regex, leaves tests out (`make test` leaves out the documentation commands and
# the kill -9 durability test, which the normal build runs: docs/testing.md).
# docs/testing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${SANITIZE_BUILD:-build-sanitize}
jobs=${JOBS:-$(nproc)}
source scripts/checked_build.sh
configure_checked_build "$build"
cmake --build "$build" -j "$jobs"

export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1}
export LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
exclude=()
if [[ -n "${SANITIZE_CTEST_EXCLUDE:-}" ]]; then
  exclude=(-E "$SANITIZE_CTEST_EXCLUDE")
  echo "sanitize: leaving out tests matching $SANITIZE_CTEST_EXCLUDE (run by the normal suite)"
fi
ctest --test-dir "$build" --output-on-failure -j "$jobs" --timeout 1200 "${exclude[@]}"
echo "sanitize: every test passed under AddressSanitizer + UndefinedBehaviorSanitizer ($build)"
