#!/usr/bin/env bash
# Bingham plane Poiseuille flow (../shared/reference/analytical_solutions.md (a);
# cases/verify/bingham_poiseuille.toml): channel 0 < y < 1 (H = 0.5 m), periodic in x, no slip
# on both walls, body force G = 1 Pa/m, mu_p = 1 Pa s, tau_y = 0.1 Pa: plug half-width
# y0 = tau_y / G = 0.1 m, plug velocity u_p = G (H - y0)^2 / (2 mu_p) = 0.08 m/s.
# Fixed point of eq. 31 (set in the case): r_factor 0.5, theta_per_dt 10/s, fp_tol 1e-12,
# fp_max_iter 1000, Anderson on; solver.viscous_rtol 1e-13. Runs to t = 3 s (12 diffusion times
# H^2 rho / mu_p) at n = 16, 32, 64 cells across the channel.
#
# Checked at each n, from the last probe block (the u sample heights (j + 1/2) h, no
# interpolation) and the one before it:
#  - steady: max |u(t_end) - u(t_end - 0.5 s)| < 1e-9 m/s;
#  - plug velocity u_p: error falls with h (strictly) and is below 1 % at n = 16;
#  - plug half-width: (i) from the velocity: a parabola a + b|s| + c s^2 fitted to the yielded
#    cells (S_norm = 1, at least one cell from the plug) has its vertex at |s| = y0 (the
#    discrete yielded profile is the exact one plus a constant, so this is exact to round-off:
#    required < 1e-6 m); (ii) the discrete plug: the rigid cells (D_norm < 1e-10 G H / mu_p)
#    end within one cell of the exact edge: y0 lies in [y0_r, y0_r + h] with y0_r the
#    half-extent of the rigid cells (the bracket, h, falls with h);
#  - the plug is rigid: D_norm / (G H / mu_p) < 1e-12 in the cells at least one cell inside
#    the exact plug (|s| <= y0 - h), and S_norm < 1 there; S_norm = 1 to 1e-9 in the yielded
#    cells (|s| >= y0 + h).
#  - the whole profile: max |u - exact| / u_p falls with h (strictly), < 0.1 % at n = 64 (second
#    order: a constant offset in the yielded layers from the half cell next to the wall).
#
# Measured (2 cores shared, 1 rank, Release; wall time 0.6 / 1.2 / 10.4 s, ~13 s in all):
#    n   u_p           err u_p  |y0 vertex - y0|  y0 bracket (rigid)  D_norm/(GH/mu_p)  profile err
#   16   0.0804687500  5.9e-3   < 1e-12           [0.0625, 0.125]     4.7e-14           6.1e-3
#   32   0.0800781250  9.8e-4   < 1e-12           [0.0938, 0.125]     3.4e-14           1.5e-3
#   64   0.0800292969  3.7e-4   < 1e-12           [0.0938, 0.109]     7.1e-14           3.8e-4
#  steady: max |du| over the last 0.5 s ~1e-12 m/s at every n.
#  (err u_p relative; the rigid-cell edge is quantised by the grid (y0/h = 1.6, 3.2, 6.4),
#  so its midpoint error is not monotone: 6.3e-3, 9.4e-3, 1.6e-3 m, always < h/2.)
# Usage: bash test_bingham_poiseuille.sh <granflow binary> <source dir>
set -euo pipefail
bin="$1"; src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
case_file="$src/cases/verify/bingham_poiseuille.toml"

for n in 16 32 64; do
  "$bin" run "$case_file" --set grid.n=$n --out "$tmp/n$n" > "$tmp/log$n" 2>&1 ||
    { cat "$tmp/log$n"; echo "FAIL: run n=$n"; exit 1; }
done

PYTHONPATH="$src/scripts" /usr/bin/python3 - "$tmp" <<'PY'
import sys
import numpy as np
import granflow_run as gr

tmp = sys.argv[1]
G, mu, tau_y, H = 1.0, 1.0, 0.1, 0.5
y0 = tau_y / G
up = G * (H - y0) ** 2 / (2 * mu)
Dscale = G * H / mu
ok = True


def fail(msg):
    global ok
    ok = False
    print("FAIL:", msg)


def exact(s):
    s = np.abs(s)
    return np.where(s <= y0, up, G / (2 * mu) * (H**2 - s**2) - tau_y / mu * (H - s))


res = {}
for n in (16, 32, 64):
    d = gr.read_csv(f"{tmp}/n{n}/probes/profile.csv")
    times = d.times
    h = 1.0 / n
    blocks = []
    for tv in times[-2:]:
        b = d.where(d["t"] == tv)
        k = np.abs(b["y"] * n - 0.5 - np.round(b["y"] * n - 0.5)) < 1e-9  # u sample heights
        b = b.where(k)
        if len(b) != n:
            print(f"FAIL: n={n}: {len(b)} probe rows at the u sample heights, expected {n}")
            sys.exit(1)
        blocks.append(b)
    prev, last = blocks
    y, u, Dn, Sn = last["y"], last["u"], last["D_norm"], last["S_norm"]
    s = y - 0.5
    steady = np.max(np.abs(u - prev["u"]))
    if not steady < 1e-9:
        fail(f"n={n}: not steady: max |du| over the last output interval {steady:.2e} m/s")
    # plug velocity: the largest u (the plug is flat)
    u_p = u.max()
    e_up = abs(u_p / up - 1)
    # (i) parabola over the yielded cells at least one cell from the plug
    yl = (Sn >= 1 - 1e-9) & (np.abs(s) >= y0 + h)
    A = np.column_stack([np.ones(yl.sum()), np.abs(s[yl]), s[yl] ** 2])
    a, b_, c = np.linalg.lstsq(A, u[yl], rcond=None)[0]
    y0_vertex = -b_ / (2 * c)
    # (ii) the rigid cells and the bracket of the edge
    rigid = Dn < 1e-10 * Dscale
    y0_r = np.max(np.abs(s[rigid])) + h / 2 if rigid.any() else 0.0
    inside = np.abs(s) <= y0 - h + 1e-12
    outside = np.abs(s) >= y0 + h - 1e-12
    dplug = np.max(Dn[inside]) / Dscale
    prof = np.max(np.abs(u - exact(s))) / up
    res[n] = (u_p, e_up, y0_vertex, y0_r, dplug, prof)
    print(f"n={n:3d}: u_p = {u_p:.10f} (err {e_up:.2e}); y0 vertex err {abs(y0_vertex - y0):.0e}; "
          f"rigid cells to |s| = {y0_r:.4f} (bracket [{y0_r:.4f}, {y0_r + h:.4f}]); "
          f"max D_norm/(GH/mu_p) in plug {dplug:.1e}; max S_norm there {Sn[inside].max():.3f}; "
          f"profile max err/u_p {prof:.2e}; steady {steady:.1e}")
    if not abs(y0_vertex - y0) < 1e-6:
        fail(f"n={n}: parabola vertex of the yielded profile {y0_vertex} != y0 = {y0}")
    if not (y0_r <= y0 + 1e-12 and y0 <= y0_r + h + 1e-12):
        fail(f"n={n}: the rigid cells end at {y0_r}, not within one cell below y0 = {y0}")
    if not dplug < 1e-12:
        fail(f"n={n}: plug not rigid: D_norm/(GH/mu_p) = {dplug:.2e} >= 1e-12")
    if not np.all(Sn[inside] < 1 - 1e-6):
        fail(f"n={n}: S_norm reaches 1 inside the plug")
    if not np.all(np.abs(Sn[outside] - 1) < 1e-9):
        fail(f"n={n}: S_norm != 1 in the yielded layers")
e = [res[n][1] for n in (16, 32, 64)]
if not (e[0] > e[1] > e[2] and e[0] < 1e-2):
    fail(f"plug velocity errors {e} do not fall with h or are too large")
e = [res[n][5] for n in (16, 32, 64)]
if not (e[0] > e[1] > e[2] and e[2] < 1e-3):
    fail(f"profile errors {e} do not fall with h or are too large")
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
PY
