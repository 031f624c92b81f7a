#!/usr/bin/env bash
# Novelty levels on the bundled example pairs (docs/setting.md, "Novelty the setter chooses"):
# for each pair of one discipline (as scripts/setting_gallery_check.sh pairs them) and each
# level, the printed plan's change line, its warnings line and how many notes it printed.
# Usage: scripts/novelty_check.sh [ROOT]   (SB=path/to/strangebeta, default build/strangebeta)
set -euo pipefail
cd "${1:-.}"
b=(beginner-jugs campus-rail crimp-ladder dyno-problem pinch-prow sloper-arete)
r=(edge-crack pocket-traverse roof-jugs slab-dance undercling-flake volume-mantle)
for set in b r; do
  eval "names=(\"\${$set[@]}\")"
  for ((i=0; i<${#names[@]}; i++)); do
    j=$(( (i+1) % ${#names[@]} ))
    for lv in close mix new; do
      out=$("${SB:-build/strangebeta}" vary --preset setter --novelty "$lv" \
        "data/examples/${names[$i]}.crdl" "data/examples/${names[$j]}.crdl")
      echo "${names[$i]}+${names[$j]} $lv: $(echo "$out" | sed -n 3p) |" \
        "$(echo "$out" | grep -m1 '^Warnings' || true) | notes $(echo "$out" | grep -c '^Note' || true)"
    done
  done
done
