#!/bin/bash
# The time of a new tick with its gym's ascent-grade fit warm, and of the next
# wall pages (docs/BENCHMARKS.md, "A new tick, incrementally"). Run against a
# server on a COPY of a database (it writes ticks):
#   bench/tick_latency.sh PORT ROUTE N WALL... (e.g. 18761 200001 5 1 121)
# Logs in as head-1 (the synthetic chain's password) for the wall pages, then
# N times: a tick on ROUTE from a new device (no cookie), then each WALL page.
# Prints "HTTP-code seconds what" per request. Warm the walls first (a first
# request fits the gym's grades).
set -eu
P=$1; ROUTE=$2; N=$3; shift 3
U=http://127.0.0.1:$P
J=$(mktemp)
trap 'rm -f "$J"' EXIT
curl -s -o /dev/null -c "$J" -H 'Content-Type: application/json' \
  -d '{"username":"head-1","password":"synth-chain-password"}' "$U/api/sessions"
for i in $(seq "$N"); do
  curl -s -o /dev/null -H 'Content-Type: application/json' \
    -w "%{http_code} %{time_total}s POST /api/routes/$ROUTE/ticks\n" \
    -d '{"outcome":"send","attempts":3}' "$U/api/routes/$ROUTE/ticks"
  for w in "$@"; do
    curl -s -o /dev/null -b "$J" -w "%{http_code} %{time_total}s /walls/$w\n" "$U/walls/$w"
  done
done
