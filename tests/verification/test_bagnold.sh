#!/usr/bin/env bash
# The Bagnold mu(I) profile (analytical_solutions.md (b1), the Gerris test's parameters,
# cases/verify/bagnold.toml): at N = 8 and 16 cells across the layer, the L1, L2 and Linf errors
# of the steady profile must be no larger than the peer code's
# (tests/data/bagnold_gerris_test.csv). N = 32 is in docs/bagnold.md
# (scripts/bagnold_study.sh). Measured: N = 8: 1.43e-2 / 1.45e-2 / 1.82e-2 (Gerris 3.64e-2 /
# 3.88e-2 / 5.19e-2); N = 16: 3.66e-3 / 3.74e-3 / 5.53e-3 (Gerris 1.16e-2 / 1.22e-2 / 1.44e-2).
# Usage: bash test_bagnold.sh <granflow binary> <source dir>
set -euo pipefail
bin="$1"; src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
bash "$src/scripts/bagnold_study.sh" "$(dirname "$bin")" "8 16" "$tmp/bagnold.md"
