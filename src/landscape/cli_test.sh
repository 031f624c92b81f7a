#!/usr/bin/env bash
# CTest: the landscape and pick command lines — summary format, map files,
# render, pick claims re-checked with a one-IC scan, and exit 2 on bad input.
# Usage: cli_test.sh STRANGEBETA
set -euo pipefail
sb=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
ok() { echo "ok   $1"; }
bad() { echo "FAIL $1"; fail=1; }

# --summary: exactly the two lines, n + 1 counts summing to the IC count.
"$sb" landscape --grid 12 --spacing 0.05 --skip 100 --mask 110 --summary --no-progress \
  --out "$tmp/m.map" >"$tmp/s.txt"
if [[ $(wc -l <"$tmp/s.txt") -eq 2 ]] &&
  head -1 "$tmp/s.txt" | awk '{ s = 0; for (i = 2; i <= NF; i++) s += $i;
                                 exit !($1 == "effect_histogram" && NF == 32 && s == 1728) }' &&
  sed -n 2p "$tmp/s.txt" | grep -Eq '^mean_change [0-9]+\.[0-9]{9}$'; then
  ok "summary format"
else
  bad "summary format: $(cat "$tmp/s.txt")"
fi
# The map's info reproduces the summary.
"$sb" landscape info "$tmp/m.map" | tail -2 >"$tmp/i.txt"
cmp -s "$tmp/s.txt" "$tmp/i.txt" && ok "info summary" || bad "info summary differs"

# Render PNG + CSV.
"$sb" landscape render "$tmp/m.map" --png "$tmp/e.png" --plane xz --at -12 --csv "$tmp/e.csv"
[[ $(head -c 8 "$tmp/e.png" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] && ok "png" || bad "png"
[[ $(wc -l <"$tmp/e.csv") -eq 145 ]] && ok "csv rows" || bad "csv rows"

# Pick: every candidate's claim holds when that IC alone is scanned (a 1-point grid there).
"$sb" pick "$tmp/m.map" --effect 20 --change 3 --count 3 --min-separation 3 | tail -n +2 >"$tmp/p.txt"
[[ $(wc -l <"$tmp/p.txt") -eq 3 ]] && ok "pick count" || bad "pick count"
while read -r x y z e c; do
  "$sb" landscape --grid 1 --center "$x,$y,$z" --skip 100 --mask 110 --no-progress --out "$tmp/one.map"
  "$sb" landscape render "$tmp/one.map" --csv "$tmp/one.csv"
  got=$(tail -1 "$tmp/one.csv")
  [[ "$got" == "$x,$y,$z,$e,$c" ]] && ok "pick claim $x,$y,$z" || bad "pick claim: $x $y $z $e $c vs $got"
done <"$tmp/p.txt"

# Bad input: exit status 2 and a message naming the problem.
expect2() {  # pattern args...
  local pat=$1
  shift
  set +e
  "$sb" "$@" >/dev/null 2>"$tmp/err"
  local rc=$?
  set -e
  if [[ $rc -eq 2 ]] && grep -q -- "$pat" "$tmp/err"; then ok "exit 2: $*"; else bad "exit $rc for $*: $(cat "$tmp/err")"; fi
}
expect2 "--grid" landscape --grid 0
expect2 "--mask" landscape --mask 2
expect2 "--ref-ic" landscape --ref-ic 1,2
expect2 "--plane" landscape --plane ab
expect2 "non-finite" landscape --step 0.5 --length 60 --grid 2
head -c 100 "$tmp/m.map" >"$tmp/short.map"
expect2 "truncated" landscape render "$tmp/short.map" --png "$tmp/x.png"
cp "$tmp/m.map" "$tmp/flip.map"
printf '\x55' | dd of="$tmp/flip.map" bs=1 seek=300 conv=notrunc status=none
expect2 "corrupt" landscape render "$tmp/flip.map" --png "$tmp/x.png"
expect2 "--at" landscape render "$tmp/m.map" --png "$tmp/x.png" --at 99
expect2 "--effect" pick "$tmp/m.map" --effect 99 --change 1
expect2 "scan option" pick "$tmp/m.map" --effect 3 --change 1 --grid 5
expect2 "--mpi" landscape --mpi --grid 2
[[ ! -e "$tmp/x.png" ]] && ok "no output on error" || bad "output written on error"
exit $fail
