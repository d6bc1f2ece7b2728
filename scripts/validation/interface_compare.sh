#!/usr/bin/env bash
# The paper's cases and the deposits with each interface method (issue 18): case A (DP, HP,
# mu(I)), case B, the sand column on a 20 deg plane (cases/incline_column.toml) and the 20 deg
# pile with the default settings (cases/verify/pile_default.toml), with interface.method =
# "clsvof" (the default) and "level_set" (the paper's scheme), one run after the other on one
# rank (nice; a_n256 on 2 ranks, about 45 min each on this 2-core machine), into
# runs/interface/<name>_<method>/ (b_n64_Lx2: case B in a 2 m long channel, for
# a front that reaches case B's far wall at x = 1.38 m); then scripts/validation/interface_compare.py
# writes docs/interface_compare.md from whatever runs exist.
#
#   scripts/validation/interface_compare.sh                       # the runs below, in order
#   ONLY="a_n64 b_n64" METHODS=clsvof scripts/validation/interface_compare.sh
#   LIST=1 scripts/validation/interface_compare.sh                # the runs and their commands
#
# A run whose summary.json says "completed" is skipped unless FORCE=1. GRANFLOW=path chooses
# the binary (default build/granflow), OUT_ROOT the output root (default runs/interface).
# One-core wall times (clsvof, shared machine) are in docs/interface_compare.md.
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
gf="${GRANFLOW:-$root/build/granflow}"
out_root="${OUT_ROOT:-$root/runs/interface}"
methods="${METHODS:-clsvof level_set}"
novtk="--set output.vtk_interval=0"
RUNS=(
  "a_n32|cases/ar07_rough.toml|--set grid.n=32 $novtk"
  "a_n64|cases/ar07_rough.toml|--set grid.n=64 $novtk"
  "b_n64|cases/ar2_smooth.toml|--set grid.n=64 $novtk"
  "b_n64_Lx2|cases/ar2_smooth.toml|--set grid.n=64 --set domain.Lx=2.0 $novtk"
  "a_mui_n64|cases/ar07_rough_mui.toml|--set grid.n=64 $novtk"
  "incline_n64|cases/incline_column.toml|--set grid.n=64 $novtk"
  "pile_n32|cases/verify/pile_default.toml|--set grid.n=32 --set output.vtk_interval=1.0"
  "a_n128|cases/ar07_rough.toml|--set grid.n=128 $novtk"
  "a_hp_n64|cases/ar07_rough_hp.toml|--set grid.n=64 $novtk"
  "b_n128|cases/ar2_smooth.toml|--set grid.n=128 $novtk"
  "a_mui_n128|cases/ar07_rough_mui.toml|--set grid.n=128 $novtk"
  "a_hp_n128|cases/ar07_rough_hp.toml|--set grid.n=128 $novtk"
  "a_n256|cases/ar07_rough.toml|--set grid.n=256 $novtk|2"
)
[[ -n "${LIST:-}" || -x "$gf" ]] || "$root/scripts/build.sh" || exit 1
mkdir -p "$out_root"
# shellcheck source=run_lib.sh
source "$root/scripts/validation/run_lib.sh"
run_variants interface.method "$methods"
[[ -n "${LIST:-}" ]] || /usr/bin/python3 "$root/scripts/validation/interface_compare.py" \
  "$out_root" "$root/docs/interface_compare.md"
