#!/usr/bin/env bash
# Coulomb friction on a wall (eqs. 22-23, 30; ../shared/reference/analytical_solutions.md (c)):
# a rigid granular block (Bingham, tau_y = 2000 Pa) on the bottom wall under gravity tilted by
# theta, wall friction alpha_b = 20 deg.
#  1. theta = 30 deg: the block slides with a = g (sin theta - tan alpha_b cos theta)
#     = 1.8128 m/s^2. The acceleration is the least-squares slope of the mean granular velocity
#     over t in [0.02, 0.2] s. The first steps are excluded: starting from S = 0 and s_t = 0, the
#     plastic stresses of the paper's relaxed fixed point (theta (S^n - S) in eq. 31) take a few
#     steps to carry the load (the initial pressure is the inviscid one, lower at the block's
#     edges), so the block gains a velocity offset of ~3e-3 m/s in the first 5 ms; after that it
#     accelerates at the Coulomb rate. Measured with the paper's level set: n = 30 +2.3 %,
#     n = 60 +0.5 % (docs/RHEOLOGY.md); with the default clsvof: -0.15 %, -0.14 % (a = 1.8100,
#     1.8102 m/s^2), friction force -0.13 %, -0.10 %.
#     Required: the error is below 1 % at n = 30 and at n = 60 (the issue's target was 2 % at
#     n = 60 and 4 % at n = 30); the mean friction force is within 2 % of
#     tan(alpha_b) m g cos(theta). Until 2026-12-07 the error was also required to fall from
#     n = 30 to n = 60; it sits at a floor of 0.1 to 0.7 % that does not fall with h (AMD EPYC,
#     fixed point converged every step: n = 30 -0.187 %, n = 60 -0.188 %, n = 120 -0.433 %;
#     dt / 4 -0.34 % and -0.30 %; fp_tol 1e-8 -0.29 %; the exact solver -0.37 % and -0.42 %;
#     the air 100 times lighter -0.41 % and -0.10 %; docs/VERIFICATION.md 5.4), so the order of
#     n = 30 and n = 60 was round-off: the test failed on that AMD EPYC at -0.187 % / -0.188 %
#     and passed on an Intel Xeon at -0.25 % / -0.17 %. On another AMD EPYC (2026-12-07) the
#     same runs give -0.22 % and -0.64 %; at n = 60 the fit over [0.02, 0.1] s gives -0.11 % and
#     the one over [0.1, 0.2] s -1.33 %. Late in the run the rigid block's base loses load,
#     likely because its stress, not unique, puts the rear in tension, and the friction takes
#     the wall load's positive part (docs/VERIFICATION.md 5.4).
#     The runs allow rheology.fp_max_iter = 300 and require that no step reaches it: with the
#     default 50, n = 60 capped 39 of 261 steps (last changes up to 8.4e-3), and what the
#     unconverged steps left depended on the processor: -0.14 % on an AMD EPYC, -1.11 % on an
#     Intel Xeon (2026-12-07; n = 30 -0.18 % there), where the error then rose with h. With 300,
#     no step capped on the Xeon: n = 30 -0.25 %, n = 60 -0.17 %.
#  2. theta = 15 deg < alpha_b: the block holds (sliding without friction would reach
#     g sin(theta) t = 0.25 m/s at 0.1 s). With the case file as it is, it creeps at up to 7e-4
#     m/s (mean granular speed). Four settings, each needed (docs/RHEOLOGY.md, "Holding block"),
#     bring that to the 1e-8 m/s level: rheology.yield_support = "mass" (the smeared band carries
#     its own weight, tau_y weighted by its granular fraction), levelset.redistance_every = 0 (the
#     redistancing rounds the block's corners: -0.75 % of its volume in 0.1 s),
#     initial.stress = "equilibrium" (it starts with its stresses, not from S = 0), and
#     rheology.fp_tol = initial.stress_tol = 1e-9 (a yield stress of 2000 Pa converged to 1e-4 of
#     itself leaves 0.2 Pa of unbalanced stress). Required with them: the pseudo-steps reach
#     initial.stress_tol, and over 0.1 s the mean granular speed stays below 1e-8 m/s (measured
#     3.9e-10), the largest granular speed (cells with phi < -eps) below 1e-7 m/s (1.1e-8) and
#     the volume change below 1e-5 % (7e-8 %). Those four are settings of the paper's level set:
#     this part runs with interface.method = "level_set" (pinned; the default is "clsvof" since
#     issue 18); part 1 runs with the default.
# Usage: bash test_coulomb_block.sh <granflow binary> <source dir>
set -euo pipefail
bin="$1"; src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
case_file="$src/cases/verify/coulomb_block.toml"

for n in 30 60; do
  "$bin" run "$case_file" --set grid.n=$n --set rheology.fp_max_iter=300 --out "$tmp/slide$n" \
    > "$tmp/log$n" 2>&1 &
done
wait || true
for n in 30 60; do
  [ -f "$tmp/slide$n/summary.json" ] || { cat "$tmp/log$n"; echo "FAIL: run n=$n"; exit 1; }
done
PYTHONPATH="$src/scripts" /usr/bin/python3 - "$tmp" <<'PY'
import math, sys
import numpy as np
import granflow_run as gr
g, th, ab = 9.81, math.radians(30), math.radians(20)
exact = g * (math.sin(th) - math.tan(ab) * math.cos(th))
# block 0.1 m x 0.05 m of rho 1550: the friction force at the Coulomb limit, N/m
f_exact = math.tan(ab) * 1550 * 0.1 * 0.05 * g * math.cos(th)
err, ferr, capped = {}, {}, {}
for n in (30, 60):
    capped[n] = gr.Run(f"{sys.argv[1]}/slide{n}").summary["warnings_fp_capped_steps"]
    d = gr.read_csv(f"{sys.argv[1]}/slide{n}/diagnostics.csv")
    t, u, f = d["t"], d["granular_u"], d["bottom_friction_N"]
    m = t >= 0.02 - 1e-12
    a = np.polyfit(t[m], u[m], 1)[0]
    err[n] = a / exact - 1
    ferr[n] = abs(f[m].mean()) / f_exact - 1
    print(f"n={n}: a = {a:.4f} m/s^2 (exact {exact:.4f}, {100*err[n]:+.2f} %), offset u(t) - exact t at "
          f"t = 0.2 s: {u[-1] - exact * t[-1]:.2e} m/s, mean friction {abs(f[m].mean()):.3f} N/m "
          f"(exact {f_exact:.3f}, {100*ferr[n]:+.2f} %), capped steps {capped[n]}")
ok = all(abs(e) < 0.01 for e in err.values()) \
     and all(abs(e) < 0.02 for e in ferr.values()) and not any(capped.values())
print("PASS" if ok else "FAIL: acceleration error above 1 %, or the friction force off by more than 2 %, or a step reached fp_max_iter")
sys.exit(0 if ok else 1)
PY
"$bin" run "$case_file" --set "physics.gravity=[2.539024, -9.475746]" --set time.t_end=0.1 \
  --set output.interval=0.01 --set rheology.yield_support=mass --set levelset.redistance_every=0 \
  --set initial.stress=equilibrium --set initial.stress_tol=1e-9 --set rheology.fp_tol=1e-9 \
  --set rheology.fp_max_iter=1000 --set interface.method=level_set \
  --out "$tmp/hold" > "$tmp/loghold" 2>&1 || { cat "$tmp/loghold"; echo "FAIL: run hold"; exit 1; }
PYTHONPATH="$src/scripts" /usr/bin/python3 - "$tmp/hold" <<'PY'
import math, sys
import granflow_run as gr
run = gr.Run(sys.argv[1])
d, summ = run.diagnostics, run.summary
mean = max(math.hypot(u, v) for u, v in zip(d["granular_u"].tolist(), d["granular_v"].tolist()))
peak = max(d["max_speed_granular"].tolist())
v0 = summ.get("initial_stress_speed_mps", 1.0)
dv = max(abs(x) for x in d["volume_change_pct"].tolist())
print(f"holding block (theta = 15 deg < alpha_b = 20 deg): {summ.get('initial_stress_steps')} "
      f"pseudo-steps (last {v0:.2e} m/s); max mean granular speed {mean:.3e} m/s, "
      f"max granular speed {peak:.3e} m/s, volume change {dv:.1e} %")
sys.exit(0 if (v0 < 1e-9 and mean < 1e-8 and peak < 1e-7 and dv < 1e-5) else 1)
PY
