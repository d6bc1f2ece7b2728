#!/usr/bin/env bash
# Friction on the side walls of a channel (boundary/SideWalls.hpp, issue 21), against the exact
# answer of a rigid layer sliding down a tilted channel (cases/verify/side_wall_layer.toml: a
# Bingham layer H = 0.05 m deep, periodic in x, theta = 30 deg, bottom friction alpha_b = 20 deg,
# side walls alpha_w = 10 deg; its pressure is hydrostatic, so both normal-stress closures give
# the same exact answer):
#  1. While it slides, the side walls take exactly tan(alpha_w) K g cos(theta) H / W off the
#     acceleration: the layer's acceleration (least-squares slope of the mean granular velocity
#     over t in [0.02, 0.2] s) with the side walls minus the same run without them, at
#     W = 0.1 and 0.05 m (-0.7490 and -1.4980 m/s^2). Measured: normal_stress = "hydrostatic"
#     +8.4e-6 and -4.6e-5 relative; "pressure" +1.5e-3 and +1.5e-3 (p is zero at the lid, so it
#     also carries the weight of the 0.05 m of air above the layer: +0.15 %). Required: within
#     5e-4 (hydrostatic) and 3e-3 (pressure), and the side walls' friction force (diagnostics.csv
#     side_friction_x_N, the last row) within the same of tan(alpha_w) (2/W) rho g cos(theta)
#     H^2/2 Lx, the whole layer sliding (side_slide_m2 = its area).
#  2. Where the side walls' share exceeds the drive (W = 0.03 and 0.02 m, below W = 0.0413 m) the
#     layer holds: over 0.1 s the mean granular speed stays below 1e-8 m/s and the largest below
#     1e-7 m/s. With the equilibrium start and tolerances of the Coulomb block's holding test
#     (test_coulomb_block.sh: initial.stress = "equilibrium", initial.stress_tol =
#     rheology.fp_tol = 1e-9): from S = 0 the relaxed fixed point of eq. 31 lets it creep at
#     5e-4 m/s, the issue of the plastic solver (issue 19), not of the side walls. Measured
#     1.0e-9 / 4.6e-9 m/s (W = 0.03), 1.4e-9 / 5.8e-9 m/s (W = 0.02).
#  3. The same with the exact plastic step (rheology.solver = "newton", the side walls' friction in
#     its Newton iteration: momentum/ExactPlasticStep.hpp NewtonSide), with no step capped:
#     sliding at W = 0.1 m (hydrostatic), the side walls' share within 5e-4 as in 1, and the same
#     on 2 ranks split across the periodic seam (-da_processors_x 2) to 1e-8 of the mean granular
#     velocity; holding at W = 0.03 m from S = 0 with the default settings (no equilibrium start,
#     no tolerance set), below 1e-8 m/s mean and 1e-7 m/s largest as in 2. Measured
#     (2026-12-07): +3.8e-5 (against the fixed point's run without side walls), 2 ranks 9.6e-12,
#     hold 1.8e-12 / 5.3e-12 m/s; 204 and 107 Newton iterations for 200 and 100 steps. The held
#     layer's load splits otherwise than the fixed point's (side walls 7.96 N/m and bottom
#     11.05 N/m, against 9.69 and 9.32): a held layer's friction is statically indeterminate,
#     and any split within both limits is a solution.
# Usage: bash test_side_walls.sh <granflow binary> <source dir>
set -euo pipefail
bin="$1"; src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
case_file="$src/cases/verify/side_wall_layer.toml"
run() {  # run <name> <--set ...>
  local name="$1"; shift
  "$bin" run "$case_file" "$@" --out "$tmp/$name" > "$tmp/$name.log" 2>&1 ||
    { cat "$tmp/$name.log"; echo "FAIL: run $name"; exit 1; }
}
run none --set boundary.side_walls.width=0 --set boundary.side_walls.friction_angle=0 &
run hyd10 --set boundary.side_walls.width=0.1 --set boundary.side_walls.normal_stress=hydrostatic &
wait
run hyd05 --set boundary.side_walls.width=0.05 --set boundary.side_walls.normal_stress=hydrostatic &
run p10 --set boundary.side_walls.width=0.1 &
wait
run p05 --set boundary.side_walls.width=0.05 &
hold="--set time.t_end=0.1 --set initial.stress=equilibrium --set initial.stress_tol=1e-9
      --set rheology.fp_tol=1e-9 --set rheology.fp_max_iter=1000"
# shellcheck disable=SC2086
run hold03 --set boundary.side_walls.width=0.03 $hold &
wait
# shellcheck disable=SC2086
run hold02 --set boundary.side_walls.width=0.02 $hold &
run n_hyd10 --set boundary.side_walls.width=0.1 --set boundary.side_walls.normal_stress=hydrostatic \
  --set rheology.solver=newton
wait
run n_hold03 --set boundary.side_walls.width=0.03 --set time.t_end=0.1 --set rheology.solver=newton
"${MPIEXEC:-mpirun}" --oversubscribe -n 2 "$bin" run "$case_file" --set boundary.side_walls.width=0.1 \
  --set boundary.side_walls.normal_stress=hydrostatic --set rheology.solver=newton \
  --out "$tmp/n_hyd10_np2" -- -da_processors_x 2 -da_processors_y 1 > "$tmp/n_hyd10_np2.log" 2>&1 ||
  { cat "$tmp/n_hyd10_np2.log"; echo "FAIL: run n_hyd10_np2"; exit 1; }
PYTHONPATH="$src/scripts" /usr/bin/python3 - "$tmp" <<'PY'
import math, sys
import numpy as np
import granflow_run as gr
tmp = sys.argv[1]
g, th, aw, H, Lx, rho = 9.81, math.radians(30), math.radians(10), 0.05, 0.05, 1550.0
def accel(name):
    d = gr.read_csv(f"{tmp}/{name}/diagnostics.csv")
    m = d["t"] >= 0.02 - 1e-12
    return np.polyfit(d["t"][m], d["granular_u"][m], 1)[0], d
a0, _ = accel("none")
ok = True
for name, W, tol in (("hyd10", 0.1, 5e-4), ("hyd05", 0.05, 5e-4), ("p10", 0.1, 3e-3), ("p05", 0.05, 3e-3),
                     ("n_hyd10", 0.1, 5e-4)):
    a, d = accel(name)
    da_exact = -math.tan(aw) * g * math.cos(th) * H / W
    f_exact = math.tan(aw) * 2 / W * rho * g * math.cos(th) * H * H / 2 * Lx
    ea = (a - a0) / da_exact - 1
    ef = -d["side_friction_x_N"][-1] / f_exact - 1
    slide = d["side_slide_m2"][-1] / (H * Lx)
    good = abs(ea) < tol and abs(ef) < tol and abs(slide - 1) < 1e-6
    ok &= good
    print(f"{name}: W = {W} m, a - a(no side walls) = {a - a0:.5f} m/s^2 (exact {da_exact:.5f}, "
          f"{ea:+.1e}), friction {-d['side_friction_x_N'][-1]:.4f} N/m (exact {f_exact:.4f}, {ef:+.1e}), "
          f"sliding area {slide:.3f} of the layer{'' if good else '  <-- FAIL (tolerance %g)' % tol}")
for name in ("hold03", "hold02", "n_hold03"):
    run = gr.Run(f"{tmp}/{name}")
    d = run.diagnostics
    mean = max(math.hypot(u, v) for u, v in zip(d["granular_u"].tolist(), d["granular_v"].tolist()))
    peak = max(d["max_speed_granular"].tolist())
    good = mean < 1e-8 and peak < 1e-7
    ok &= good
    print(f"{name}: holds, mean granular speed <= {mean:.2e} m/s, largest {peak:.2e} m/s, side walls "
          f"{-d['side_friction_x_N'][-1]:.3f} N/m + bottom {abs(d['bottom_friction_N'][-1]):.3f} N/m "
          f"against the drive {rho * g * math.sin(th) * H * Lx:.3f} N/m{'' if good else '  <-- FAIL'}")
for name in ("n_hyd10", "n_hold03"):
    s = gr.Run(f"{tmp}/{name}").summary
    capped = s.get("warnings_fp_capped_steps", 0)
    print(f"{name} (exact plastic step): {capped} of {s['steps']} steps capped, "
          f"{s['fp_iters_total']} Newton iterations{'' if capped == 0 else '  <-- FAIL'}")
    ok &= capped == 0
u1 = gr.read_csv(f"{tmp}/n_hyd10/diagnostics.csv")["granular_u"]
u2 = gr.read_csv(f"{tmp}/n_hyd10_np2/diagnostics.csv")["granular_u"]
e2 = float(np.max(np.abs(u2 - u1)) / np.max(np.abs(u1)))
good = len(u1) == len(u2) and e2 < 1e-8
ok &= good
print(f"n_hyd10 on 2 ranks: mean granular velocity within {e2:.1e} of 1 rank's"
      f"{'' if good else '  <-- FAIL'}")
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
PY
