#!/usr/bin/env bash
# The gate of the dam break (boundary/Gate.hpp, issue 21), on case A at grid.n = 32 (h = 6.25 mm;
# the plate on the grid line x = 0.2 m, 0.16 m high, Coulomb tan(10.5 deg) for the grains):
#  1. A gate that is not lifted (speed 0) holds the column: over 0.3 s the largest granular
#     speed (cells with phi < -eps) stays below 1e-6 m/s and the front at the gate, within
#     0.1 cell, and the volume is kept to 1e-12. No equilibrium start: the column starts from the
#     pressure of its own projection with the gate in place. Measured: 5.0e-9 m/s, 0 cells, 1.2e-15.
#  2. A gate lifted infinitely fast (speed 1e9 m/s: gone after the first step) gives back the
#     release of the paper's model (no gate): runout and back-wall height within 1e-3 relative,
#     the stage times t1, t2, t3 within one output interval (0.01 s). The only difference is the
#     start: the pressure of a column held by its gate instead of that of a fluid released from
#     rest. Measured at n = 32: runout +1.9e-5, back wall -2.7e-5, same t1, t2, t3.
# Usage: bash test_gate.sh <granflow binary> <source dir>
set -euo pipefail
bin="$1"; src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
A=("$src/cases/ar07_rough.toml" --set grid.n=32 --set output.vtk_interval=0
   --set output.progress_interval=0)
G=(--set boundary.gate.x=0.2 --set boundary.gate.height=0.16 --set boundary.gate.friction_angle=10.5)
run() {  # run <name> <args...>
  local name="$1"; shift
  "$bin" run "$@" --out "$tmp/$name" > "$tmp/$name.log" 2>&1 ||
    { cat "$tmp/$name.log"; echo "FAIL: run $name"; exit 1; }
}
run held "${A[@]}" "${G[@]}" --set boundary.gate.speed=0 --set time.t_end=0.3 &
run none "${A[@]}" &
wait
run fast "${A[@]}" "${G[@]}" --set boundary.gate.speed=1e9
PYTHONPATH="$src/scripts" /usr/bin/python3 - "$tmp" <<'PY'
import json, sys
import numpy as np
import granflow_run as gr
tmp = sys.argv[1]
ok = True
d = gr.read_csv(f"{tmp}/held/diagnostics.csv")
h = 0.8 / 128
vmax = d["max_speed_granular"].max()
fr = np.abs(d["front_x"] - 0.2).max() / h
dv = np.abs(d["volume_change_pct"]).max() / 100
good = vmax < 1e-6 and fr < 0.1 and dv < 1e-12
ok &= good
print(f"held by the gate over 0.3 s: largest granular speed {vmax:.2e} m/s, front moved "
      f"{fr:.3f} cells, volume {dv:.1e}{'' if good else '  <-- FAIL'}")
a, b = (json.load(open(f"{tmp}/{n}/summary.json")) for n in ("fast", "none"))
for k in ("runout_m", "backwall_height_m"):
    e = a[k] / b[k] - 1
    good = abs(e) < 1e-3
    ok &= good
    print(f"gate lifted at 1e9 m/s against no gate: {k} {a[k]:.5f} vs {b[k]:.5f} ({e:+.1e})"
          f"{'' if good else '  <-- FAIL'}")
for k in ("t1_s", "t2_s", "t3_s"):
    good = a[k] is not None and b[k] is not None and abs(a[k] - b[k]) <= 0.01 + 1e-9
    ok &= good
    print(f"  {k}: {a[k]} vs {b[k]}{'' if good else '  <-- FAIL'}")
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
PY
