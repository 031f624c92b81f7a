#!/bin/sh
# The ascent fit at scale against the numpy Rasch fit of the same ticks
# (docs/BENCHMARKS.md, "Grades from ascents at scale"): for 1M and 5M ticks,
# writes a synthetic gym, then times `strangebeta ratings fit` and
# bench/ratings_rasch_numpy.py whole-process with /usr/bin/time -v (wall,
# CPU, peak resident memory).
# Usage: bench/ratings_scale.sh [BUILD_DIR] [WORK_DIR]   (needs Debian's python3-numpy/scipy)
set -e
build=${1:-build}
work=${2:-/tmp/sb_ratings_scale}
mkdir -p "$work"
for size in 1m 5m; do
  case $size in
    1m) c=10000; r=50000 ;;
    5m) c=50000; r=250000 ;;
  esac
  dir=$work/gym$size
  [ -f "$dir/TICKS.csv" ] || "$build/strangebeta" ratings synth --climbers $c --routes $r --ticks-per-route 20 --seed 1 --out "$dir" >/dev/null
  ticks=$(($(wc -l < "$dir/TICKS.csv") - 1))
  for who in strangebeta numpy; do
    if [ $who = strangebeta ]; then
      /usr/bin/time -v "$build/strangebeta" ratings fit --ticks "$dir/TICKS.csv" --routes "$dir/ROUTES.csv" --format json --drift off -o "$dir/fit.json" 2> "$dir/time.$who" >/dev/null
    else
      /usr/bin/time -v /usr/bin/python3 "$(dirname "$0")/ratings_rasch_numpy.py" "$dir/TICKS.csv" 2> "$dir/time.$who" > "$dir/out.$who"
    fi
    wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$dir/time.$who")
    user=$(sed -n 's/.*User time (seconds): //p' "$dir/time.$who")
    sys=$(sed -n 's/.*System time (seconds): //p' "$dir/time.$who")
    kb=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$dir/time.$who")
    echo "$size $who: $ticks ticks, wall $wall, user $user s, sys $sys s, peak $((kb / 1024)) MB, $((kb * 1024 / ticks)) bytes/tick"
  done
done
