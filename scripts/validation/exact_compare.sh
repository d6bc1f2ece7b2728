#!/usr/bin/env bash
# The paper's cases with the exact plastic solver next to the paper's scheme (issue 19): case A
# (DP, HP, mu(I)) and case B with rheology.solver = "newton" (the semismooth Newton method,
# theta = 0, docs/RHEOLOGY.md) and "fixed_point" (the paper's projection fixed point, the
# default), everything else the case files' and the defaults (the CLSVOF interface), one run
# after the other on one rank (nice), into runs/exact/<name>_<solver>/; then
# scripts/validation/exact_compare.py writes docs/exact_compare.md from whatever runs exist.
# b_n64_Lx2: case B in a 2 m long channel (at n = 64 case B's front reaches the case file's far
# wall at x = 1.38 m with either solver).
#
#   scripts/validation/exact_compare.sh                        # every run below, in order
#   ONLY="a_n64 b_n64" SOLVERS=newton scripts/validation/exact_compare.sh
#   LIST=1 scripts/validation/exact_compare.sh                 # the runs and their commands
#
# A run whose summary.json says "completed" is skipped unless FORCE=1. GRANFLOW=path chooses
# the binary (default build/granflow), OUT_ROOT the output root (default runs/exact). The
# exact solver's one-core wall times on this 2-core machine, two runs at a time, from the runs
# of 2026-12-07 (docs/exact_compare.md): a_n64 7-16 min, b_n64 5 min, a_mui_n64 6 min, a_n128
# 40 min, a_mui_n128 43 min, b_n128 44 min; the HP files take dt = 1e-4 s (10,600 steps): a_hp_n32 9 min, a_hp_n64
# 40 min. The fixed point's are 5 to 15 times shorter. Not made yet: a_hp_n128,
# a_n256, b_n256 (hours each with the exact solver).
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
gf="${GRANFLOW:-$root/build/granflow}"
out_root="${OUT_ROOT:-$root/runs/exact}"
solvers="${SOLVERS:-newton fixed_point}"
novtk="--set output.vtk_interval=0"
RUNS=(
  "a_n64|cases/ar07_rough.toml|--set grid.n=64 $novtk"
  "b_n64|cases/ar2_smooth.toml|--set grid.n=64 $novtk"
  "b_n64_Lx2|cases/ar2_smooth.toml|--set grid.n=64 --set domain.Lx=2.0 $novtk"
  "a_mui_n64|cases/ar07_rough_mui.toml|--set grid.n=64 $novtk"
  "a_hp_n32|cases/ar07_rough_hp.toml|--set grid.n=32 $novtk"
  "a_n128|cases/ar07_rough.toml|--set grid.n=128 $novtk"
  "b_n128|cases/ar2_smooth.toml|--set grid.n=128 $novtk"
  "a_mui_n128|cases/ar07_rough_mui.toml|--set grid.n=128 $novtk"
  "a_hp_n64|cases/ar07_rough_hp.toml|--set grid.n=64 $novtk"
  "a_hp_n128|cases/ar07_rough_hp.toml|--set grid.n=128 $novtk"
  "a_n256|cases/ar07_rough.toml|--set grid.n=256 $novtk|2"
  "b_n256|cases/ar2_smooth.toml|--set grid.n=256 $novtk|2"
)
[[ -n "${LIST:-}" || -x "$gf" ]] || "$root/scripts/build.sh" || exit 1
mkdir -p "$out_root"
# shellcheck source=run_lib.sh
source "$root/scripts/validation/run_lib.sh"
run_variants rheology.solver "$solvers"
[[ -n "${LIST:-}" ]] || /usr/bin/python3 "$root/scripts/validation/exact_compare.py" \
  "$out_root" "$root/docs/exact_compare.md"
