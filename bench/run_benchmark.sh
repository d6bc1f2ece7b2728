#!/usr/bin/env bash
# The speed benchmark of issue 6: builds if needed, runs case A at n = 64 and 128 on 1 and 2
# ranks (3 repeats each, t in [0, 0.1] s) and writes docs/PERFORMANCE.md and
# docs/performance.csv. Arguments are passed to bench/benchmark.py (e.g. --sizes 64 128 256
# --repeats 5 --window 0.2 --full runs/a128). Takes ~15 min with the defaults.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" > /dev/null
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
cd "$root"
exec /usr/bin/python3 bench/benchmark.py --bin build/granflow --src . "$@"
