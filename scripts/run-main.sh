#!/usr/bin/env bash
# The main job of the README: installs what is missing, builds, runs the bundled main case and
# makes its figures. Output folder: out/<case name>/ (override with OUT=dir).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
case_file="${CASE:-$root/cases/dambreak_water.toml}"
name="$(basename "$case_file" .toml)"
out="${OUT:-$root/out/$name}"
"$root/build/granflow" run "$case_file" --out "$out" "$@"
/usr/bin/python3 "$root/scripts/plot_run.py" "$out"
echo "granflow: results in $out (figures: $out/figures/)"
