#!/bin/bash
# The time of a new tick with its gym's ascent-grade fit warm, and of the next
# wall pages (docs/BENCHMARKS.md, "A new tick, incrementally"). Run against a
# server on a COPY of a database (it writes ticks):
#   bench/tick_latency.sh PORT ROUTE N WALL... (e.g. 18761 200001 5 1 121)
# Logs in as head-1 (the synthetic chain's password) for the wall pages, then
# N times: a tick on ROUTE from a new device (no cookie) and its own address,
# then each WALL page.
# Prints "HTTP-code seconds what" per request. Each WALL is requested once
# first ("warm-up": a first request fits the gym's grades of its discipline).
set -eu
P=$1; ROUTE=$2; N=$3; shift 3
U=http://127.0.0.1:$P
J=$(mktemp)
B=$(mktemp)
trap 'rm -f "$J" "$B"' EXIT
curl -s -o /dev/null -c "$J" -H 'Content-Type: application/json' \
  -d '{"username":"head-1","password":"synth-chain-password"}' "$U/api/sessions"
for w in "$@"; do
  curl -s -o /dev/null -b "$J" -w "%{http_code} %{time_total}s /walls/$w (warm-up)\n" "$U/walls/$w"
done
for i in $(seq "$N"); do
  # From its own source address (127.0.62.i), so the burst rule holds none.
  t=$(curl -s -o "$B" --interface "127.0.62.$i" -H 'Content-Type: application/json' \
    -w "%{http_code} %{time_total}s" -d '{"outcome":"send","attempts":3}' \
    "$U/api/routes/$ROUTE/ticks")
  echo "$t POST /api/routes/$ROUTE/ticks $(grep -o '"held":[a-z]*' "$B") $(grep -o '"ticks":[0-9]*' "$B")"
  for w in "$@"; do
    curl -s -o /dev/null -b "$J" -w "%{http_code} %{time_total}s /walls/$w\n" "$U/walls/$w"
  done
done
