#!/usr/bin/env bash
# The main job on its embedded default: a variation of the bundled example routes,
# then the web app (strangebeta serve) on var/strangebeta.db.
set -euo pipefail
build=${1:-build}
cd "$(dirname "$0")/.."
# A variation of two bundled examples first (skipped when they are absent):
# the setter's preset, a variation a setter could set, at the `mix` novelty
# level (a third to two thirds of its moves new; docs/setting.md).
if [[ -f data/examples/crimp-ladder.crdl && -f data/examples/slab-dance.crdl ]]; then
  "$build/strangebeta" vary --preset setter --novelty mix data/examples/crimp-ladder.crdl data/examples/slab-dance.crdl || true
fi

# Then the web app on the embedded default database (seeded with the bundled
# examples and the demo account when fresh: --demo, its password is published).
# SB_PORT overrides the port.
mkdir -p var
seed=()
[[ -d data/examples ]] && seed=(--seed-examples data/examples)
exec "$build/strangebeta" serve --demo --port "${SB_PORT:-8080}" --db var/strangebeta.db "${seed[@]}"
