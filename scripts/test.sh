#!/usr/bin/env bash
# The test command of the README: installs what is missing, builds, runs the whole test suite
# (unit, verification and regression tiers) with CTest. Extra arguments go to ctest,
# e.g. scripts/test.sh -L unit   or   scripts/test.sh -R levelset
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
# As root, OpenMPI refuses to start without these; one thread per rank (SOLVER_NOTES.md).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
cd "$root/build"
ctest --output-on-failure --timeout 900 "$@"
