#!/usr/bin/env bash
# Browser test of the web app (run by scripts/test.sh with the build dir as $1):
# starts `strangebeta serve` on a free loopback port with a temporary database,
# drives Debian's chromium headless through Playwright (tests/browser/run.js),
# and saves screenshots and PDFs under BUILD/browser/.
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
root=$(cd "$(dirname "$0")/.." && pwd)
out="$build/browser"
chromium=${SB_CHROMIUM:-/usr/bin/chromium}

for tool in node npm; do
  command -v "$tool" >/dev/null || { echo "browser.sh: $tool missing (run scripts/setup.sh)"; exit 1; }
done
[[ -x "$chromium" ]] || { echo "browser.sh: $chromium missing (run scripts/setup.sh)"; exit 1; }

# Playwright (playwright-core only: it uses the system chromium, downloads no browser).
if [[ ! -d "$root/tests/browser/node_modules/playwright-core" ]]; then
  (cd "$root/tests/browser" && npm ci --no-audit --no-fund --loglevel=error)
fi

tmp=$(mktemp -d)
server_pid=""
cleanup() {
  if [[ -n "$server_pid" ]]; then kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT

rm -rf "$out"
mkdir -p "$out"
# Every spec signs up its own accounts from 127.0.0.1: more than the default 10 sign-ups per
# address per hour (docs/web.md, "Log-in throttling"), so the suite raises that one limit.
"$build/strangebeta" serve --port 0 --db "$tmp/web.db" --signups-per-hour 200 >"$tmp/serve.log" 2>&1 &
server_pid=$!
url=""
for _ in $(seq 1 100); do
  url=$(grep -o 'http://127\.0\.0\.1:[0-9]*' "$tmp/serve.log" | head -1 || true)
  [[ -n "$url" ]] && break
  kill -0 "$server_pid" 2>/dev/null || { cat "$tmp/serve.log"; echo "browser.sh: server died"; exit 1; }
  sleep 0.1
done
[[ -n "$url" ]] || { cat "$tmp/serve.log"; echo "browser.sh: server did not start"; exit 1; }
echo "browser.sh: server at $url"

SB_CHROMIUM="$chromium" node "$root/tests/browser/run.js" "$url" "$out"
# The climbers' pages and the worked example of docs/studies.md (its own browser; needs the CLI;
# not a *.spec.js, which run.js would load).
SB_CHROMIUM="$chromium" node "$root/tests/browser/climbers_flow.js" "$url" "$out" "$build"
echo "browser.sh: screenshots in $out"
