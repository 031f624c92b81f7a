#!/usr/bin/env bash
# Sourced by scripts/sanitize.sh and scripts/fuzz.sh: configures the one
# checked build both use — clang, AddressSanitizer + UndefinedBehaviorSanitizer,
# errors fatal, -O1 with line tables only (enough for symbolized reports), every
# source also compiled with -fsanitize=fuzzer-no-link so the same objects serve
# the GoogleTest suites and the libFuzzer harnesses (fuzz/, linked with
# -fsanitize=fuzzer). One build instead of two halves the time `make test`
# spends compiling. Benchmarks and the MPI driver are left out (OpenMPI's own
# allocations would drown the leak report). docs/testing.md.
#
#   configure_checked_build DIR

configure_checked_build() {
  local dir=$1
  if ! command -v clang++ >/dev/null; then
    echo "checked build: clang++ not found (scripts/setup.sh installs clang and libclang-rt-dev)" >&2
    return 1
  fi
  # A directory configured by an older script with GCC: start afresh.
  if [[ -f "$dir/CMakeCache.txt" ]] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang++' "$dir/CMakeCache.txt"; then
    rm -rf "$dir"
  fi
  local launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  local flags="-O1 -gline-tables-only -fno-omit-frame-pointer"
  flags+=" -fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=all"
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Checked -DCMAKE_CXX_COMPILER=clang++ \
    "${launcher[@]}" -DSB_BUILD_TESTS=ON -DSB_BUILD_BENCH=OFF -DSB_BUILD_FUZZ=ON \
    -DCMAKE_DISABLE_FIND_PACKAGE_MPI=ON "-DCMAKE_CXX_FLAGS=$flags" \
    "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" >/dev/null
}
