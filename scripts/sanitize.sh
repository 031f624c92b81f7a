#!/usr/bin/env bash
# The unit and API test suites (every GoogleTest binary and the CTest CLI
# checks) built with AddressSanitizer + UndefinedBehaviorSanitizer in their own
# build directory, -O1, errors fatal (-fno-sanitize-recover=all), leaks
# checked. Benchmarks and the MPI driver are not built (OpenMPI's own
# allocations would drown the leak report).
# Usage: scripts/sanitize.sh   (`make test-sanitize`); SANITIZE_BUILD
# (build-sanitize) and JOBS (nproc) override. docs/testing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${SANITIZE_BUILD:-build-sanitize}
jobs=${JOBS:-$(nproc)}
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
flags="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize "${launcher[@]}" \
  -DSB_BUILD_BENCH=OFF -DCMAKE_DISABLE_FIND_PACKAGE_MPI=ON \
  "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" >/dev/null
cmake --build "$build" -j "$jobs"

export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1}
export LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir "$build" --output-on-failure -j "$jobs" --timeout 1200
echo "sanitize: every test passed under AddressSanitizer + UndefinedBehaviorSanitizer ($build)"
