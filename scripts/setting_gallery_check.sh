#!/usr/bin/env bash
# The setting-day gallery against the default preset (docs/setting.md, "Setting days").
# For each pair of bundled examples of one discipline: the default preset's warnings,
# the setter preset's gallery (kept / rejected) and its printed (top-ranked) plan's warnings.
set -euo pipefail
cd "${1:-.}"
b=(beginner-jugs campus-rail crimp-ladder dyno-problem pinch-prow sloper-arete)
r=(edge-crack pocket-traverse roof-jugs slab-dance undercling-flake volume-mantle)
tot_c=0; tot_r=0; tot_dw=0; tot_sw=0; n=0; fewer=0
warn() { sed -n '/^Warnings:/,/^Summary:/p' | grep -c '^  ' || true; }
for set in b r; do
  eval "names=(\"\${$set[@]}\")"
  for ((i=0; i<${#names[@]}; i++)); do
    j=$(( (i+1) % ${#names[@]} ))
    f1=data/examples/${names[$i]}.crdl; f2=data/examples/${names[$j]}.crdl
    dw=$(${SB:-build/strangebeta} vary "$f1" "$f2" | warn)
    out=$(${SB:-build/strangebeta} vary --preset setter "$f1" "$f2")
    sw=$(echo "$out" | warn)
    c=$(echo "$out" | grep -cE '^[0-9]+\. IC' || true)
    rj=$(echo "$out" | grep -cE '^[0-9]+\. IC.*REJECTED' || true)
    echo "${names[$i]} + ${names[$j]}: default $dw warnings; setter gallery $c candidates, $rj rejected; top-ranked $sw warnings"
    tot_c=$((tot_c+c)); tot_r=$((tot_r+rj)); tot_dw=$((tot_dw+dw)); tot_sw=$((tot_sw+sw)); n=$((n+1))
    [[ $sw -lt $dw ]] && fewer=$((fewer+1))
  done
done
echo "pairs $n: candidates $tot_c, rejected $tot_r; warnings default $tot_dw vs top-ranked $tot_sw; fewer in $fewer of $n"
