#!/usr/bin/env bash
# Issue 19's knob criterion for the exact plastic solver (rheology.solver = newton): case A and
# case B at a coarse grid with r_factor and newton_tol each 4 times smaller and larger, and the
# fixed point with r_factor / 4 beside them. Writes docs/newton_knobs.md.
# Usage: scripts/validation/newton_knobs.sh [n_A] [n_B] [out.md]   (defaults 16 16
# docs/newton_knobs.md; 2 runs at a time; about 8 minutes at 16 on this 2-core machine, about
# 10 minutes per Newton run at 32). RUNS="a_newton a_newton_r_div4 ..." runs only those (the
# names below); the table then has only their rows. T_END=0.2 stops every run there (case A's
# and B's peak granular pressures are made before it). T_SPLIT=0.2 runs each case to 0.2 s and
# then continues it with --restart to its case file's end, so that a 0.2-s table and the whole
# runs' table come from the same runs (every run then shares the same time grid: a run stopped
# at 0.2 s shortens its last step to land there, which shifts the later steps; RHEOLOGY.md).
# The first part's summary.json is kept as summary_split.json (the 0.2-s figures); the
# continued run's wall_s counts both parts (a restart carries the wall clock on).
# The tolerances are 4 times newton_tol each way: TOL=X sets it for every Newton run (the
# default: rheology.newton_tol's default, read from src/setup/Schema.cpp).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
"$root/scripts/build.sh" > /dev/null
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
na="${1:-16}"; nb="${2:-16}"; md="${3:-$root/docs/newton_knobs.md}"
tol="${TOL:-$(sed -n 's/.*add_real("rheology.newton_tol", "", \([0-9.e+-]*\),.*/\1/p' \
  "$root/src/setup/Schema.cpp")}"
[[ -n "$tol" ]] || { echo "newton_knobs.sh: no newton_tol default found in Schema.cpp" >&2; exit 1; }
tol_div4="$(awk -v t="$tol" 'BEGIN { printf "%g", t / 4 }')"
tol_x4="$(awk -v t="$tol" 'BEGIN { printf "%g", t * 4 }')"
out="$root/runs/newton_knobs"
mkdir -p "$out"
bin="$root/build/granflow"
job() {  # job <name> <args...>: at most two at a time
  while (( $(jobs -rp | wc -l) >= 2 )); do wait -n; done
  local name="$1"; shift
  [[ -z "${RUNS:-}" || " $RUNS " == *" $name "* ]] || return 0
  rm -f "$out/$name.failed"
  { "$bin" run "$@" ${T_SPLIT:+--set time.t_end=$T_SPLIT} --out "$out/$name" --overwrite \
      > "$out/$name.log" 2>&1 &&
    { [[ -z "${T_SPLIT:-}" ]] ||
      { cp "$out/$name/summary.json" "$out/$name/summary_split.json" &&
        "$bin" run --restart "$out/$name" --set time.t_end=$t_case >> "$out/$name.log" 2>&1; }; } ||
      touch "$out/$name.failed"; } &
}
for c in a b; do
  if [[ $c == a ]]; then f=cases/ar07_rough.toml; n=$na; else f=cases/ar2_smooth.toml; n=$nb; fi
  t_case="$(sed -n 's/^t_end *= *\([0-9.e+-]*\).*/\1/p' "$root/$f" | head -1)"
  A=("$root/$f" --set grid.n=$n --set output.vtk_interval=0 ${T_END:+--set time.t_end=$T_END})
  N=("${A[@]}" --set rheology.solver=newton ${TOL:+--set rheology.newton_tol=$TOL})
  job ${c}_newton "${N[@]}"
  job ${c}_newton_r_div4 "${N[@]}" --set rheology.r_factor=0.125
  job ${c}_newton_r_x4 "${N[@]}" --set rheology.r_factor=2
  job ${c}_newton_tol_div4 "${N[@]}" --set rheology.newton_tol=$tol_div4
  job ${c}_newton_tol_x4 "${N[@]}" --set rheology.newton_tol=$tol_x4
  job ${c}_newton_iterate "${N[@]}" --set rheology.newton_wall_load=iterate
  job ${c}_fp "${A[@]}"
  job ${c}_fp_r_div4 "${A[@]}" --set rheology.r_factor=0.125
done
wait
/usr/bin/python3 "$root/scripts/validation/newton_knobs.py" "$out" "$md" \
  "${TOL:+TOL=$TOL }${T_END:+T_END=$T_END }${T_SPLIT:+T_SPLIT=$T_SPLIT }${RUNS:+RUNS=\"$RUNS\" }scripts/validation/newton_knobs.sh $na $nb${3:+ $3}" "$na" "$nb" \
  ${RUNS:+$RUNS}
