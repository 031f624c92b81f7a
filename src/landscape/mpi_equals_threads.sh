#!/usr/bin/env bash
# CTest: `mpirun -np 2 strangebeta-mpi` writes and prints byte-for-byte what
# the threaded `strangebeta` does (map files, --summary, pick on the fly).
# Usage: mpi_equals_threads.sh MPIRUN STRANGEBETA STRANGEBETA_MPI
set -euo pipefail
mpirun=$1 sb=$2 sbmpi=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run_mpi() { "$mpirun" --allow-run-as-root --oversubscribe -np 2 "$sbmpi" "$@"; }
fail=0
check() {  # name file_a file_b
  if cmp -s "$2" "$3"; then echo "ok   $1"; else echo "FAIL $1: $2 and $3 differ"; fail=1; fi
}

# A 23^3 cube (12167 ICs: odd, so the ranks' blocks differ in size).
common=(landscape --grid 23 --spacing 0.05 --skip 100 --length 30 --mask 110 --summary --no-progress)
"$sb" "${common[@]}" --threads 2 --out "$tmp/t.map" >"$tmp/t.txt"
run_mpi "${common[@]}" --threads 1 --mpi --out "$tmp/m.map" >"$tmp/m.txt"
check "cube map" "$tmp/t.map" "$tmp/m.map"
check "cube summary" "$tmp/t.txt" "$tmp/m.txt"
grep -q '^effect_histogram ' "$tmp/m.txt" || { echo "FAIL no summary from MPI run"; fail=1; }

# An xz slice with RKF45 and a 3-D mask.
common=(landscape --grid 61 --spacing 0.1 --plane xz --integrator rkf45 --mask 111 --summary --no-progress)
"$sb" "${common[@]}" --out "$tmp/t2.map" >"$tmp/t2.txt"
run_mpi "${common[@]}" --out "$tmp/m2.map" >"$tmp/m2.txt"
check "slice map" "$tmp/t2.map" "$tmp/m2.map"
check "slice summary" "$tmp/t2.txt" "$tmp/m2.txt"

# The picker scanning on the fly.
pick=(pick --effect 20 --change 4 --count 4 --grid 15 --spacing 0.05 --skip 100 --no-progress)
"$sb" "${pick[@]}" >"$tmp/t3.txt"
run_mpi "${pick[@]}" >"$tmp/m3.txt"
check "pick" "$tmp/t3.txt" "$tmp/m3.txt"

# Bad input: exit 2 from every rank, one message.
set +e
run_mpi landscape --grid 0 2>"$tmp/err.txt" >/dev/null
rc=$?
set -e
if [[ $rc -eq 0 ]] || ! grep -q -- '--grid' "$tmp/err.txt"; then
  echo "FAIL bad input under MPI: rc=$rc $(cat "$tmp/err.txt")"
  fail=1
else
  echo "ok   bad input under MPI (rc=$rc)"
fi
exit $fail
