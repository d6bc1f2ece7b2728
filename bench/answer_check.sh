#!/usr/bin/env bash
# The answer must not move (issue 6, item 3): runs case A at n = 64 to t = 1.06 s with the current
# build and case file (about 1.5-2.5 min on one core) and compares its summary figures with
# bench/answer_ref_a64.json (made before the speed changes) within the tolerances stated in
# bench/answer_check.py. The reference is the paper's level set: the run pins
# interface.method = "level_set" (the default is "clsvof" since issue 18).
# Usage: bench/answer_check.sh [OUT_DIR] [-- PETSc options]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/out/answer_check_a64}"
shift || true
"$root/scripts/build.sh" > /dev/null
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
"$root/build/granflow" run "$root/cases/ar07_rough.toml" --out "$out" --overwrite --set grid.n=64 \
  --set output.vtk_interval=0 --set interface.method=level_set "$@" > "$out.log" 2>&1 ||
  { tail -5 "$out.log"; exit 1; }
exec /usr/bin/python3 "$root/bench/answer_check.py" "$out"
