#!/usr/bin/env bash
# A busy gym's evening on the synthetic gym of 250,000 ticks (issue 34,
# docs/BENCHMARKS.md "A busy gym"), on SQLite and on a throw-away PostgreSQL
# server (scripts/pg_server.sh), one after the other:
#
#   bench/busy_gym.sh [BUILD_DIR] [SECONDS] [OUT_DIR]
#
# For each backend: `strangebeta synth --scale 0.05` (1 gym, 20 walls, 10,500
# routes, 250,000 ticks), the report of one setting day timed alone (3 times),
# then the server under bench/busy_gym.py for SECONDS (default 60). Figures go
# to OUT_DIR (default build/busy-gym): busy-sqlite.json, busy-postgresql.json
# and the printed tables.
set -euo pipefail
build=${1:-build}
seconds=${2:-60}
out=${3:-$build/busy-gym}
here=$(cd "$(dirname "$0")/.." && pwd)
exe=$(cd "$build" && pwd)/strangebeta
mkdir -p "$out"
out=$(cd "$out" && pwd)
today=2026-11-26
server_pid=""
pg_state="$out/pg"

cleanup() {
  [[ -n "$server_pid" ]] && kill "$server_pid" 2>/dev/null || true
  bash "$here/scripts/pg_server.sh" stop "$pg_state" >/dev/null 2>&1 || true
}
trap cleanup EXIT

serve() {  # DB LOG -> sets server_pid and port
  "$exe" serve --port 0 --db "$1" --no-seed >"$2" 2>&1 &
  server_pid=$!
  port=""
  for _ in $(seq 1 600); do
    port=$(grep -oE 'http://127\.0\.0\.1:[0-9]+/' "$2" | head -1 | grep -oE '[0-9]+/$' | tr -d / || true)
    [[ -n "$port" ]] && break
    sleep 0.1
  done
  [[ -n "$port" ]] || { echo "the server did not start" >&2; cat "$2" >&2; exit 1; }
}

report_alone() {  # PORT DATE: the report timed alone, 3 times, as head-1
  local jar="$out/cookies"
  curl -s -c "$jar" -H 'Content-Type: application/json' \
    -d '{"username":"head-1","password":"synth-chain-password"}' \
    "http://127.0.0.1:$1/api/sessions" >/dev/null
  for i in 1 2 3; do
    curl -s -b "$jar" -o /dev/null -w "report alone: %{http_code} %{time_total} s\n" \
      "http://127.0.0.1:$1/api/gyms/1/report?date=$2"
  done
}

run() {  # NAME DB
  local name=$1 db=$2
  local t0=$SECONDS
  "$exe" synth --db "$db" --scale 0.05 --today "$today" --fast-hash --quiet
  echo "$name: synth $((SECONDS - t0)) s"
  serve "$db" "$out/server-$name.log"
  # The busiest setting day of the gym (the report's date).
  report_alone "$port" 2026-10-08
  python3 "$here/bench/busy_gym.py" --url "http://127.0.0.1:$port" --pid "$server_pid" \
    --seconds "$seconds" --json "$out/busy-$name.json"
  report_alone "$port" 2026-10-08
  kill "$server_pid"
  wait "$server_pid" 2>/dev/null || true
  server_pid=""
}

rm -f "$out/busy.db" "$out/busy.db-wal" "$out/busy.db-shm"
run sqlite "$out/busy.db" 2>&1 | tee "$out/sqlite.txt"

bash "$here/scripts/pg_server.sh" start "$pg_state"
if [[ -f "$pg_state/url" ]]; then
  admin=$(cat "$pg_state/url")
  psql=$(ls -d /usr/lib/postgresql/*/bin | sort -V | tail -1)/psql
  "$psql" "$admin" -qc "CREATE DATABASE busy"
  run postgresql "${admin%/*}/busy" 2>&1 | tee "$out/postgresql.txt"
else
  echo "PostgreSQL is not installed: only SQLite measured"
fi
