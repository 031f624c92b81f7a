#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/) in the checked build
# (scripts/checked_build.sh: clang, AddressSanitizer + UndefinedBehaviorSanitizer,
# the directory scripts/sanitize.sh also uses), replays the
# regression inputs, then fuzzes every input format for SECONDS seconds each.
# Usage: scripts/fuzz.sh [SECONDS]   (default 60; `make fuzz FUZZ_SECONDS=N`)
# Environment: FUZZ_BUILD (build-sanitize), JOBS (nproc), FUZZ_ONLY="crdl map"
# (a subset). Exit status 1 when a regression input fails or fuzzing finds
# anything not listed in fuzz/regressions/OPEN. docs/testing.md explains the
# output and what to do with a finding.
set -euo pipefail
seconds=${1:-60}
cd "$(dirname "$0")/.."
root=$(pwd)
build=${FUZZ_BUILD:-build-sanitize}
jobs=${JOBS:-$(nproc)}
formats=(${FUZZ_ONLY:-crdl site_csv grammar model map vary_json graph tokens grade_model
  difficulty_model study api})

source scripts/checked_build.sh
configure_checked_build "$build"
targets=()
for f in "${formats[@]}"; do targets+=("fuzz_$f"); done
cmake --build "$build" -j "$jobs" --target "${targets[@]}"

export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}
export LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

# Seeds: the committed ones, plus inputs made from data/ (never ../shared).
seeds() {  # format dir
  local f=$1 dir=$2
  rm -rf "$dir"
  mkdir -p "$dir"
  if [[ -d fuzz/seeds/$f ]]; then cp fuzz/seeds/"$f"/* "$dir"/; fi
  case $f in
    crdl) cp data/examples/*.crdl "$dir"/ ;;
    model) cp data/models/*.sbm "$dir"/ ;;
    graph) cp data/models/default.sbg "$dir"/ ;;
    grade_model) cp data/models/grades.sbg "$dir"/ ;;
    difficulty_model) cp data/models/difficulty.sbd "$dir"/ ;;
    study)  # first byte: 1 = instrument JSON, 0 = responses CSV (pilot)
      for i in data/instruments/*.json; do
        { printf '\x01'; cat "$i"; } >"$dir/$(basename "$i")"
      done
      ;;
    grammar)
      {
        cat data/grammar/climbing.gra
        printf '%%%%\n'
        cat data/grammar/frames
        printf '%%%%\n'
        sed -n 's/^[RL] //p' data/examples/*.crdl
      } >"$dir/project-grammar.txt"
      ;;
  esac
}

# Open findings: "file | owner | message" lines of fuzz/regressions/OPEN.
open_files=() open_owner=() open_msg=()
while IFS= read -r line; do
  [[ -z "$line" || "$line" == \#* ]] && continue
  open_files+=("$(echo "${line%% | *}" | xargs)")
  rest=${line#* | }
  open_owner+=("$(echo "${rest%% | *}" | xargs)")
  open_msg+=("${rest#* | }")
done <fuzz/regressions/OPEN

# The line that identifies a finding: the broken invariant, the sanitizer's
# summary, or libFuzzer's error.
identify() {  # harness input
  "$1" -timeout=20 "$2" 2>&1 | grep -a -m1 -E 'invariant broken:|SUMMARY: |ERROR: libFuzzer' || true
}

status=0
summary=()
for f in "${formats[@]}"; do
  bin="$build/fuzz/fuzz_$f"
  # 1. Regression inputs (except open findings) must pass.
  regs=()
  if [[ -d fuzz/regressions/$f ]]; then
    for r in fuzz/regressions/"$f"/*; do
      skip=0
      for o in "${open_files[@]}"; do [[ "fuzz/regressions/$o" == "$r" ]] && skip=1; done
      ((skip)) || regs+=("$r")
    done
  fi
  if ((${#regs[@]})); then
    if ! "$bin" -timeout=20 "${regs[@]}" >"$build/regressions-$f.log" 2>&1; then
      echo "fuzz: $f: a regression input fails again: $(identify "$bin" "${regs[0]}")" >&2
      echo "      log: $build/regressions-$f.log" >&2
      status=1
    fi
  fi
  # 2. Fuzz (fork mode keeps going after a finding; every finding is kept).
  seeds "$f" "$build/seeds/$f"
  mkdir -p "$build/corpus/$f"
  art="$build/findings/$f"
  rm -rf "$art"
  mkdir -p "$art"
  dict=()
  [[ -f fuzz/dicts/$f.dict ]] && dict=(-dict="fuzz/dicts/$f.dict")
  log="$build/fuzz-$f.log"
  set +e
  "$bin" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$art/" "${dict[@]}" \
    "$build/corpus/$f" "$build/seeds/$f" >"$log" 2>&1
  set -e
  execs=$(grep -a -oE '^#[0-9]+' "$log" | tail -1 | tr -d '#')
  new=0 known=0
  for a in "$art"/*; do
    [[ -e "$a" ]] || continue
    what=$(identify "$bin" "$a")
    owner=""
    for i in "${!open_msg[@]}"; do
      [[ "$what" == *"${open_msg[$i]}"* ]] && owner=${open_owner[$i]}
    done
    if [[ -n "$owner" ]]; then
      known=$((known + 1))
    else
      new=$((new + 1))
      echo "fuzz: $f: FINDING $a: ${what:-no message (see $log)}" >&2
      status=1
    fi
  done
  summary+=("$(printf '%-10s %12s executions  %3d new findings  %3d known open  corpus %s' \
    "$f" "${execs:-0}" "$new" "$known" "$(ls "$build/corpus/$f" | wc -l)")")
done

echo "fuzz: ${seconds} s per format ($build, clang, ASan + UBSan)"
printf '  %s\n' "${summary[@]}"
if ((${#open_files[@]})); then
  echo "fuzz: open findings owned by other modules (fuzz/regressions/OPEN):"
  for i in "${!open_files[@]}"; do
    echo "  ${open_owner[$i]}: ${open_msg[$i]} (fuzz/regressions/${open_files[$i]})"
  done
fi
exit $status
