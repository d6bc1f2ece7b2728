#!/usr/bin/env bash
# The water column of Martin & Moyce (cases/verify/dambreak_energy.toml: a = 0.05715 m, 2a
# high, in a 10a x 3a channel, to T = t sqrt(2 g / a) = 4) at 16, 32, 64 and 128 cells per a,
# with each interface method (issue 18: no energy from nothing, the front Z(T) converging), one
# run after the other on one rank, into runs/dambreak_energy/<method>_<cells per a>/; then
# scripts/validation/dambreak_energy.py writes docs/figures/dambreak_energy_front.png,
# docs/figures/dambreak_energy.png and the table of docs/INTERFACE.md from whatever runs exist.
#
#   scripts/validation/dambreak_energy.sh                 # both methods, 16 to 128 cells per a
#   METHODS=clsvof GRIDS="16 32" scripts/validation/dambreak_energy.sh
#
# A run whose summary.json says "completed" is skipped unless FORCE=1. GRANFLOW=path chooses
# the binary (default build/granflow), OUT_ROOT the output root (default runs/dambreak_energy).
# Wall times on one core of the development machine (shared): about 3 s, 25 s, 3 min and 30 min
# per method for 16, 32, 64 and 128 cells per a (clsvof).
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
gf="${GRANFLOW:-$root/build/granflow}"
out_root="${OUT_ROOT:-$root/runs/dambreak_energy}"
methods="${METHODS:-clsvof level_set}"
grids="${GRIDS:-16 32 64 128}"
case="$root/cases/verify/dambreak_energy.toml"
[[ -x "$gf" ]] || "$root/scripts/build.sh"
mkdir -p "$out_root"
for m in $methods; do
  for k in $grids; do
    out="$out_root/${m}_$k"
    if [[ "${FORCE:-0}" != 1 && -f "$out/summary.json" ]] &&
       grep -q '"status": "completed"' "$out/summary.json"; then
      echo "skip $out (completed)"; continue
    fi
    # grid.n counts the cells over Ly = 3a.
    echo "run  $out: interface.method = $m, $k cells per a"
    start=$SECONDS
    nice "$gf" run "$case" --out "$out" --overwrite --set "grid.n=$((3 * k))" \
      --set "interface.method=$m" \
      --set output.progress_interval=60 > "$out.log" 2>&1
    echo "     exit $?, $((SECONDS - start)) s"
  done
done
/usr/bin/python3 "$root/scripts/validation/dambreak_energy.py" "$out_root" "$root/docs"
