#!/usr/bin/env bash
# The main job on its embedded default: a variation of the bundled example routes.
set -euo pipefail
build=${1:-build}
cd "$(dirname "$0")/.."
exec "$build/strangebeta" vary --preset more data/examples/crimp-ladder.crdl data/examples/slab-dance.crdl
