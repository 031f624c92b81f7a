#!/usr/bin/env bash
# Load benchmark of the web app (docs/BENCHMARKS.md, "Web app"): wrk against a
# loopback server on a temporary database, bounded duration.
#   bench/web_load.sh [BUILD_DIR] [SECONDS] [CONNECTIONS]
# Measures POST /api/variations (generate + store a variation of two example
# routes, logged in with session cookie and CSRF header; without and with
# smoothing) and GETs of a plan page and of a route.
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
secs=${2:-10}
conns=${3:-16}
root=$(cd "$(dirname "$0")/.." && pwd)
command -v wrk >/dev/null || { echo "web_load.sh: wrk missing (scripts/setup.sh)"; exit 1; }
command -v curl >/dev/null || { echo "web_load.sh: curl missing"; exit 1; }

tmp=$(mktemp -d)
pid=""
cleanup() {
  if [[ -n "$pid" ]]; then kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT

"$build/strangebeta" serve --port 0 --db "$tmp/bench.db" --seed-examples "$root/data/examples" \
  >"$tmp/serve.log" 2>&1 &
pid=$!
url=""
for _ in $(seq 1 100); do
  url=$(grep -o 'http://127\.0\.0\.1:[0-9]*' "$tmp/serve.log" | head -1 || true)
  [[ -n "$url" ]] && break
  sleep 0.1
done
[[ -n "$url" ]] || { cat "$tmp/serve.log"; exit 1; }

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

echo "== POST /api/variations (routes $ids, preset more): wrk -t2 -c$conns -d${secs}s --latency"
wrk -t2 -c"$conns" -d"${secs}s" --latency -s "$tmp/post.lua" "$url/api/variations"
sed 's/"smooth":false/"smooth":true/' "$tmp/post.lua" >"$tmp/post_smooth.lua"
echo "== POST /api/variations with smoothing (smooth: true): wrk -t2 -c$conns -d${secs}s --latency"
wrk -t2 -c"$conns" -d"${secs}s" --latency -s "$tmp/post_smooth.lua" "$url/api/variations"
echo "== GET /variations/$vid (plan page with trajectory SVG): wrk -t2 -c$conns -d${secs}s --latency"
wrk -t2 -c"$conns" -d"${secs}s" --latency "$url/variations/$vid"
echo "== GET /api/routes/$vid: wrk -t2 -c$conns -d${secs}s --latency"
wrk -t2 -c"$conns" -d"${secs}s" --latency "$url/api/routes/$vid"
