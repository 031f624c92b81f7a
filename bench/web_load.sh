#!/usr/bin/env bash
# Load benchmark of the web app (docs/BENCHMARKS.md, "Web app"): wrk against
# loopback servers on a temporary database, bounded duration.
#   bench/web_load.sh [BUILD_DIR] [SECONDS] [CONNECTIONS] [BACKEND] [PROCESSES]
# BACKEND: sqlite (default; a temporary file) or postgresql (a throw-away
# server started with scripts/pg_server.sh, stopped at the end). PROCESSES: 1
# (default) or more `strangebeta serve` processes over the one database; the
# connections are split between them (one wrk per process, run at once) and
# the requests/s summed.
# Measures POST /api/variations (generate + store a variation of two example
# routes, logged in with session cookie and CSRF header; without and with
# smoothing) and GETs of a plan page and of a route.
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
secs=${2:-10}
conns=${3:-16}
backend=${4:-sqlite}
procs=${5:-1}
root=$(cd "$(dirname "$0")/.." && pwd)
command -v wrk >/dev/null || { echo "web_load.sh: wrk missing (scripts/setup.sh)"; exit 1; }
command -v curl >/dev/null || { echo "web_load.sh: curl missing"; exit 1; }
[[ "$backend" == sqlite || "$backend" == postgresql ]] ||
  { echo "web_load.sh: BACKEND must be sqlite or postgresql"; exit 2; }
[[ "$procs" =~ ^[1-8]$ ]] || { echo "web_load.sh: PROCESSES must be 1..8"; exit 2; }

tmp=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; wait "$p" 2>/dev/null || true; done
  if [[ "$backend" == postgresql ]]; then bash "$root/scripts/pg_server.sh" stop "$tmp/pg" || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT

if [[ "$backend" == postgresql ]]; then
  bash "$root/scripts/pg_server.sh" start "$tmp/pg" >&2
  [[ -f "$tmp/pg/url" ]] || { echo "web_load.sh: no PostgreSQL (see above)"; exit 1; }
  admin=$(cat "$tmp/pg/url")
  psql=$(ls -d /usr/lib/postgresql/*/bin/psql | sort -V | tail -1)
  "$psql" "$admin" -qc "CREATE DATABASE bench"
  db="${admin%/*}/bench"
else
  db="$tmp/bench.db"
fi

# Starts one server and appends its URL to urls.
urls=()
start() {
  local log=$1
  shift
  "$build/strangebeta" serve --demo --port 0 --db "$db" --seed-examples "$root/data/examples" "$@" \
    >"$log" 2>&1 &
  pids+=($!)
  local url=""
  for _ in $(seq 1 200); do
    url=$(grep -o 'http://127\.0\.0\.1:[0-9]*' "$log" | head -1 || true)
    [[ -n "$url" ]] && break
    sleep 0.1
  done
  [[ -n "$url" ]] || { cat "$log" >&2; exit 1; }
  urls+=("$url")
}
# The first process seeds the fresh database; the others start after it.
start "$tmp/serve1.log"
for i in $(seq 2 "$procs"); do start "$tmp/serve$i.log" --no-seed; done
url=${urls[0]}

login=$(curl -s -c "$tmp/jar" -H 'Content-Type: application/json' \
  -d '{"username":"demo","password":"strangebeta-demo"}' "$url/api/sessions")
csrf=$(printf '%s' "$login" | sed -n 's/.*"csrf":"\([0-9a-f]*\)".*/\1/p')
cookie=$(awk '$6 == "sb_session" {print "sb_session=" $7}' "$tmp/jar")
[[ -n "$csrf" && -n "$cookie" ]] || { echo "web_load.sh: log-in failed: $login"; exit 1; }
# Two example routes (the first two ids), or a route of our own when none are seeded.
ids=$(curl -s "$url/api/routes?limit=2" | grep -o '"id":[0-9]*' | cut -d: -f2 | paste -sd, -)
if [[ -z "$ids" ]]; then
  ids=$(curl -s -b "$tmp/jar" -H "X-CSRF-Token: $csrf" -H 'Content-Type: application/json' \
    -d '{"crdl":"name: bench\n---\nR jug\nL crimp\nR sloper\nL pinch\nR match\nL jug\n"}' \
    "$url/api/routes" | grep -o '[0-9]*')
fi
body="{\"routes\":[$ids],\"preset\":\"more\",\"smooth\":false}"
cat >"$tmp/post.lua" <<LUA
wrk.method = "POST"
wrk.body = '$body'
wrk.headers["Content-Type"] = "application/json"
wrk.headers["Cookie"] = "$cookie"
wrk.headers["X-CSRF-Token"] = "$csrf"
LUA
first=$(curl -s -b "$tmp/jar" -H "X-CSRF-Token: $csrf" -H 'Content-Type: application/json' \
  -d "$body" "$url/api/variations")
vid=$(printf '%s' "$first" | sed -n 's/^{"id":\([0-9]*\).*/\1/p')
[[ -n "$vid" ]] || { echo "web_load.sh: variation failed: $first"; exit 1; }

# Runs wrk against every process at once (the connections split between
# them) and prints each one's output and the summed requests/s.
load() {
  local title=$1 path=$2 script=${3:-}
  local per=$(((conns + procs - 1) / procs))
  echo "== $title ($backend, $procs process(es)): wrk -t2 -c$per -d${secs}s --latency per process"
  local i=0 outs=() wrks=()
  for u in "${urls[@]}"; do
    if [[ -n "$script" ]]; then
      wrk -t2 -c"$per" -d"${secs}s" --latency -s "$script" "$u$path" >"$tmp/wrk$i.out" &
    else
      wrk -t2 -c"$per" -d"${secs}s" --latency "$u$path" >"$tmp/wrk$i.out" &
    fi
    wrks+=($!)
    outs+=("$tmp/wrk$i.out")
    i=$((i + 1))
  done
  wait "${wrks[@]}"
  cat "${outs[@]}"
  awk '/^Requests\/sec:/ {s += $2} END {printf "total requests/sec: %.0f\n", s}' "${outs[@]}"
  grep -h "Non-2xx" "${outs[@]}" || true
}
load "POST /api/variations (routes $ids, preset more)" /api/variations "$tmp/post.lua"
sed 's/"smooth":false/"smooth":true/' "$tmp/post.lua" >"$tmp/post_smooth.lua"
load "POST /api/variations with smoothing (smooth: true)" /api/variations "$tmp/post_smooth.lua"
load "GET /variations/$vid (plan page with trajectory SVG)" "/variations/$vid"
load "GET /api/routes/$vid" "/api/routes/$vid"
