#!/usr/bin/env bash
# Verification: a heavy layer (1550 kg/m^3) under air at rest must stay at rest.
# Runs cases/verify/rest_layer.toml (32^2, fixed dt = 1e-4 s, 1000 steps, output every
# 0.01 s) and requires, in every row of diagnostics.csv, max_speed < 1e-6 m/s and
# |volume_change_pct| < 1e-6; also that the run made exactly 1000 steps (11 rows, t = 0..0.1).
# A discrete imbalance between the gravity term and the pressure gradient across the density
# jump makes spurious currents that grow far above 1e-6 m/s within these 1000 steps.
# Usage: bash test_rest_layer.sh <granflow binary> <source dir>
set -euo pipefail
bin="$1"; src="$2"
py=/usr/bin/python3
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

start=$SECONDS
rc=0
"$bin" run "$src/cases/verify/rest_layer.toml" --out "$tmp/run" \
  2> "$tmp/log" || rc=$?
if ((rc)); then cat "$tmp/log"; echo "FAIL: granflow run exited with $rc"; exit 1; fi
echo "run: $((SECONDS - start)) s"
"$py" "$src/tests/tools/gfcheck.py" rest "$tmp/run" --max-speed 1e-6 --volume-pct 1e-6 \
  --rows 11 --steps 1000
