"""What the report measures on a run beyond summary.json: fits, budgets, bounds, and the
quantities read from the VTK snapshots (through granflow_run)."""
import math

import numpy as np

from .runs import gr
from .text import isnan


def lh_fit(run):
    """Linear fit of L_h/L_f against L_d/L_f for each cut-off over the decreasing branch: from the
    output where L_h peaks to the last where L_h > 1 % of L_f (the head then is gone). The rising
    branch before the peak (the head grows while the deposit starts beyond the gate) is left out:
    the paper's statement (section 4.2.5, Fig. 26) is that L_h/L_f *decreases* linearly with
    L_d/L_f. L_f = furthest front − gate (as plot_collapse.py). Returns per cut-off: slope,
    intercept, R², number of points, time range, the peak."""
    d = run.dep
    if not d:
        return {}
    Lf = run.v("max_front_x_m") - run.v("gate_x_m")
    res = {}
    for c in np.unique(d["cutoff"]):
        mc = (d["cutoff"] == c) & np.isfinite(d["L_h"]) & np.isfinite(d["L_d"])
        t, Lh, Ld = d["t"][mc], d["L_h"][mc], d["L_d"][mc]
        if len(t) < 3:
            continue
        ip = int(np.argmax(Lh))
        m = (np.arange(len(t)) >= ip) & (Lh > 0.01 * Lf)
        if m.sum() < 3:
            continue
        X, Y = Ld[m] / Lf, Lh[m] / Lf
        a, b = np.polyfit(X, Y, 1)
        r2 = 1 - np.sum((Y - (a * X + b)) ** 2) / max(np.sum((Y - Y.mean()) ** 2), 1e-300)
        res[float(c)] = {"slope": a, "intercept": b, "r2": r2, "n": int(m.sum()),
                         "X": X, "Y": Y, "Xall": Ld / Lf, "Yall": Lh / Lf, "Lf": Lf,
                         "t0": t[m].min(), "t1": t[m].max(), "Lh_max": Lh[ip], "t_peak": t[ip],
                         "n_moving": int(np.sum(t[m] < run.v("t3_s"))),
                         "Ad_A_const": mean_in(d["t"][mc], d["Ad_over_A"][mc], run.v("t1_s"),
                                               run.v("t2_s"))}
    return res


def mean_in(t, y, a, b):
    if isnan(a) or isnan(b):
        return float("nan")
    m = (t >= a) & (t <= b) & np.isfinite(y)
    return float(np.mean(y[m])) if m.any() else float("nan")


def nose(run, tmin=0.1, tmax=0.5):
    """The bump of the HP model at the upper right corner of the column (section 4.1.5): a nose
    that overhangs the foot of the mass. From the VTK snapshots with tmin <= t <= tmax: in each
    row of cells the interface's x (the zero of phi after the last granular cell from the back
    wall, linear), and the overhang = max over rows of that x − its value in the bottom row.
    Returns (overhang in m, t, height of the nose tip in m, cell size) for the snapshot where it
    is largest, or None without snapshots."""
    best = None
    for t, f in run.run.snapshots:
        if t < tmin - 1e-9 or t > tmax + 1e-9:
            continue
        fld = gr.read_vtr(f)
        phi, xn, xc, yc = fld["phi"], fld.xn, fld.xc, fld.yc
        xs = np.full(len(yc), np.nan)
        for jrow in range(len(yc)):
            neg = np.nonzero(phi[jrow] < 0)[0]
            if len(neg) == 0:
                continue
            k = neg[-1]
            if k + 1 < len(xc):
                a, b = phi[jrow, k], phi[jrow, k + 1]
                xs[jrow] = xc[k] + (xc[k + 1] - xc[k]) * a / (a - b)
            else:
                xs[jrow] = xn[-1]
        if np.isnan(xs[0]):
            continue
        jmax = int(np.nanargmax(xs))
        over = float(xs[jmax] - xs[0])
        if best is None or over > best[0]:
            best = (over, t, float(yc[jmax]), float(xn[1] - xn[0]))
    return best


def trapped_air(run):
    """Air enclosed in the granular mass in the last VTK snapshot: the area (m^2/m) of the
    cells with phi > 0 below the highest granular cell of their column, and the mean x of those
    cells (the nose of the HP model folds over air when it lands). None without snapshots."""
    files = run.run.snapshots
    if not files:
        return None
    t, f = files[-1]
    fld = gr.read_vtr(f)
    phi, xn, yn = fld["phi"], fld.xn, fld.yn
    dx, dy = xn[1] - xn[0], yn[1] - yn[0]
    area, xs = 0.0, []
    for i in range(phi.shape[1]):
        g = np.nonzero(phi[:, i] < 0)[0]
        if len(g) == 0:
            continue
        air = np.nonzero(phi[: g[-1], i] > 0)[0]
        area += len(air) * dx * dy
        xs += [0.5 * (xn[i] + xn[i + 1])] * len(air)
    return area, (float(np.mean(xs)) if xs else float("nan")), t


def heights_near_wall(run, xmax=0.3):
    x, h = run.final_profile()
    m = x <= xmax
    return float(np.mean(h[m])) if m.any() else float("nan")


def local_slope(r, a, b):
    """Slope (deg, positive downhill) of the least-squares line through the final surface height
    h(x) > 0 over a <= x <= b."""
    try:
        x, h = r.final_profile()
    except (KeyError, ValueError):
        return float("nan")
    m = (x >= a) & (x <= b) & (h > 0)
    if m.sum() < 3:
        return float("nan")
    return math.degrees(math.atan(-np.polyfit(x[m], h[m], 1)[0]))


def min_area_two_slopes(front, back_deg=29.0, x_back=0.35, front_deg=7.0, x_front=0.5):
    """Least area (m^2) under a non-increasing surface that falls at back_deg over [0, x_back] and
    at front_deg over [x_front, front] to h(front) = 0: the paper's two slopes read as lines."""
    tb, tf = math.tan(math.radians(back_deg)), math.tan(math.radians(front_deg))
    h_front = (front - x_front) * tf          # height at x_front, the least it can be at x_back
    return (x_back * h_front + 0.5 * x_back ** 2 * tb + (x_front - x_back) * h_front
            + 0.5 * (front - x_front) ** 2 * tf)


def momentum_budget(r, rho=1450.0):
    """Horizontal momentum of the granular mass against the wall forces, from diagnostics.csv:
    M dU/dt = -F_bottom + N_left (U = granular_u, M = rho V; bottom_friction_N is signed along
    +x and acts on the grains with the opposite sign; the back wall pushes with its normal load;
    the air's forces are left out). Returns None, or a dict: the residual's RMS and max over
    t >= 0.05 s against the mean |F_bottom|, and the forces, deceleration and front over the
    deceleration phase [0.6, 0.8] s."""
    d = r.diag
    need = ("t", "granular_u", "granular_volume", "bottom_friction_N", "left_normal_N", "front_x")
    if not all(k in d for k in need) or len(d["t"]) < 5:
        return None
    t, U = d["t"], d["granular_u"]
    M = rho * d["granular_volume"]
    lhs = np.gradient(M * U, t)
    rhs = -d["bottom_friction_N"] + d["left_normal_N"]
    m = t >= 0.05
    res = lhs[m] - rhs[m]
    fb = np.abs(d["bottom_friction_N"][m]).mean()
    w = (t >= 0.6 - 1e-9) & (t <= 0.8 + 1e-9)
    i8 = int(np.argmin(np.abs(t - 0.8)))
    return {"rms": float(np.sqrt((res ** 2).mean())), "max": float(np.abs(res).max()),
            "fb_mean": float(fb), "fb": float(d["bottom_friction_N"][w].mean()),
            "nl": float(d["left_normal_N"][w].mean()), "M": float(M[w].mean()),
            "decel": float(-np.polyfit(t[w], U[w], 1)[0]) if w.sum() >= 3 else float("nan"),
            "vfront_08": float(np.gradient(d["front_x"], t)[i8]),
            "t_pass": float(t[np.argmax(d["front_x"] >= 1.145)])
            if (d["front_x"] >= 1.145).any() else float("nan")}


def granular_rho(r, default=1450.0):
    """phase.granular.rho of a run's resolved case.toml (kg/m^3)."""
    gran = case_value(r, "phase", "granular", {})
    return gran.get("rho", default) if isinstance(gran, dict) else default


def front_state(r, t0=0.6, g=9.81, wall_deg=15.0):
    """Front position and advance speed at t0 (linear fit over t0 +- 0.05 s) and the least
    runout the Coulomb bound allows from them."""
    d = r.diag
    t, x = d["t"], d["front_x"]
    m = (t >= t0 - 0.05 - 1e-9) & (t <= t0 + 0.05 + 1e-9)
    v0 = float(np.polyfit(t[m], x[m], 1)[0])
    x0 = float(np.interp(t0, t, x))
    return x0, v0, x0 + v0 ** 2 / (2 * g * math.tan(math.radians(wall_deg)))


def basal_slip_near_front(r, t0, length=0.01):
    """Min and max of the bottom row's u over the last `length` m behind the front, from the VTK
    snapshot at t0 (None if there is none within 5 ms)."""
    files = [(t, f) for t, f in r.run.snapshots if abs(t - t0) < 5e-3]
    if not files:
        return None
    fld = gr.read_vtr(files[0][1])
    phi, u, xc = fld["phi"], fld["u"], fld.xc
    gran = np.where(phi[0] < 0)[0]
    if not len(gran):
        return None
    m = (xc >= xc[gran.max()] - length) & (xc <= xc[gran.max()]) & (phi[0] < 0)
    ub = u[0, m, 0]
    return float(ub.min()), float(ub.max())


def redistance_period(r):
    """Mean simulated time between redistancings (s): redistance_interval if set, else the mean
    step times redistance_every."""
    interval = case_value(r, "levelset", "redistance_interval", 0)
    if interval > 0:
        return float(interval)
    every = case_value(r, "levelset", "redistance_every", float("nan"))
    return r.v("t_end") / r.v("steps") * every


def case_value(r, section, key, default=float("nan")):
    """A value of a run's resolved case.toml (every key with the value used); default if the
    file or the key is missing (runs made before the key existed)."""
    try:
        return r.case[section][key]
    except KeyError:
        return default


def dt_label(r):
    """The time-step cap of a run and how often it redistanced, from its resolved case.toml."""
    dtm = case_value(r, "time", "dt_max", None)
    if dtm is None:
        return "?"
    interval = case_value(r, "levelset", "redistance_interval", 0)
    every = (f"every {interval:g} s" if interval > 0 else
             f"every {case_value(r, 'levelset', 'redistance_every', '?')} steps")
    return f"≤ {dtm:g} s, redistanced {every}"


def rest_speed(r):
    """collapse.rest_speed of a run (m/s), from its resolved case.toml (1e-3 if absent)."""
    return float(case_value(r, "collapse", "rest_speed", 1e-3))


def peak_p_time(r):
    """The output time (s) of a run's largest granular pressure."""
    d = r.diag
    return float(d["t"][int(np.argmax(d["max_p_granular"]))])
