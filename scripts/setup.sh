#!/usr/bin/env bash
# Installs the Debian packages strangebeta needs to build, test and run.
# Installs nothing when everything is present. Safe to run repeatedly.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config ninja-build
  libcli11-dev nlohmann-json3-dev
  libsqlite3-dev sqlite3 libcpp-httplib-dev libcairo2-dev libsodium-dev
  libpango1.0-dev libqrencode-dev
  libpq-dev postgresql
  libopenmpi-dev openmpi-bin
  libgtest-dev libgmock-dev libbenchmark-dev
  wrk chromium chromium-driver nodejs npm
  poppler-utils fonts-dejavu-core fonts-noto-cjk zbar-tools
  fonts-noto-color-emoji
  libboost-dev libboost-locale-dev gettext python3-scipy
  python3 curl
  clang libclang-rt-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    # nodejs/npm may come from outside Debian (e.g. a preinstalled toolchain).
    if [[ "$p" == nodejs && -x "$(command -v node)" ]]; then continue; fi
    if [[ "$p" == npm && -x "$(command -v npm)" ]]; then continue; fi
    missing+=("$p")
  fi
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO=sudo; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all Debian packages present"
fi

# Playwright for the browser tests (playwright-core only: it drives the Debian
# chromium above and downloads no browser), from the npm registry, pinned by
# tests/browser/package-lock.json. tests/browser.sh retries when this fails.
browser_dir="$(cd "$(dirname "$0")/.." && pwd)/tests/browser"
if [[ -f "$browser_dir/package-lock.json" && ! -d "$browser_dir/node_modules/playwright-core" ]] &&
   command -v npm >/dev/null; then
  echo "setup: npm ci in tests/browser"
  (cd "$browser_dir" && npm ci --no-audit --no-fund --loglevel=error) ||
    echo "setup: warning: npm ci in tests/browser failed"
fi
