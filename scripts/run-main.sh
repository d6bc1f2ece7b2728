#!/usr/bin/env bash
# The main job of the README: installs what is missing, builds, runs the bundled main case and
# makes its figures. The main case is case A of the paper (cases/ar07_rough.toml: a column of
# glass beads of aspect ratio 0.7 collapsing on a rough bottom, Drucker-Prager, eta_0 = 0.5,
# n = 64 i.e. 256 x 64 cells, to t = 1.06 s; under a minute on one core). Output folder:
# out/<case name>/ (override with OUT=dir; another case with CASE=file; extra arguments go to
# `granflow run`, e.g. --set grid.n=128).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
case_file="${CASE:-$root/cases/ar07_rough.toml}"
name="$(basename "$case_file" .toml)"
out="${OUT:-$root/out/$name}"
# --overwrite: running the main job again replaces its previous run (granflow refuses an
# existing run folder otherwise).
"$root/build/granflow" run "$case_file" --out "$out" --overwrite "$@"
/usr/bin/python3 "$root/scripts/plot_run.py" "$out"
echo "granflow: results in $out (figures: $out/figures/)"
