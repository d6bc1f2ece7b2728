#!/usr/bin/env bash
# Installs missing Debian packages (scripts/install-deps.sh), configures and builds granflow
# in build/ (Release). Incremental: cheap when nothing changed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
jobs="$(nproc 2>/dev/null || echo 2)"
if [ ! -f "$root/build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$root/build" -j"$jobs" >/dev/null 2>"$root/build/last-build.err" || {
  cat "$root/build/last-build.err" >&2; echo "granflow: build failed" >&2; exit 1; }
