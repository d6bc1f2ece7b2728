"""The "Known disagreements" section: where granflow and the paper differ, what was measured
about it and what is not known."""
import math

import numpy as np

from .measures import (basal_slip_near_front, front_state, granular_rho, local_slope,
                       min_area_two_slopes, momentum_budget, redistance_period)
from .runs import A_GRIDS, B_RUNOUT_PAPER, THETA_RUNS, RF_RUNS
from .text import isnan, pct, rel


def momentum_bullet(doneB, R):
    """The 'Momentum budget of case B' item of Known disagreements (finest case B run)."""
    if not doneB:
        return "- **Momentum budget of case B.** Not run."
    r, n = doneB[-1]
    mb = momentum_budget(r, granular_rho(r))
    if mb is None:
        return ("- **Momentum budget of case B.** The finest run has no wall forces in "
                "diagnostics.csv.")
    by_n = []
    for rr, nn in doneB:
        m2 = momentum_budget(rr, granular_rho(rr))
        if m2 is not None:
            by_n.append((nn, m2["rms"]))
    return ("- **Momentum budget and deceleration of case B** (n = " + str(n) +
            ", from diagnostics.csv): the "
            "horizontal momentum of the grains follows M dU/dt = −F_bottom + N_back (the bottom's "
            "Coulomb friction and the back wall's push) with an RMS residual of "
            f"{mb['rms']:.1f} N/m (max {mb['max']:.1f} N/m, at the output interval of 0.01 s) "
            f"against a mean friction of {mb['fb_mean']:.0f} N/m"
            + (", and the residual falls with h (" + ", ".join(
                f"n = {nn}: {res:.1f} N/m" for nn, res in by_n) + ")" if len(by_n) > 1 else "")
            + ": the runout is what the wall "
            "forces give, not a conservation error. In the deceleration phase (0.6–0.8 s) the "
            f"bottom friction is {mb['fb']:.0f} N/m, the back wall pushes with {mb['nl']:.0f} N/m, "
            f"and the mean velocity falls at {mb['decel']:.2f} m/s² ((F − N)/M = "
            f"{(mb['fb'] - mb['nl']) / mb['M']:.2f} m/s²). The front passes the paper's final "
            f"1.145 m at t = {mb['t_pass']:.2f} s, still moving at about {mb['vfront_08']:.2f} m/s "
            f"at 0.8 s (the paper: front at rest near 0.9 s). The friction law and the wall load "
            "of a Drucker–Prager layer are verified where the answer is known "
            "(`tests/verification/test_dp_slide.sh`: plug acceleration within 0.21 %, friction = "
            "tan α_b × load to 10 digits)." + coulomb_bound_text(r) + eroding_fronts_text(R))


def eroding_fronts_text(R, t0=0.6):
    """The time-step study's runs with more frequent redistancing, read against the Coulomb
    bound: where their fronts stop short of what a front of material could reach."""
    runs = [R[k] for k in ("b_n64_dt1e-4", "b_n64_dt1e-4_r15", "b_n64_dt1e-4_r5") if R[k].ok]
    if len(runs) < 2:
        return ""
    parts = []
    for r in runs:
        x0, v0, xb = front_state(r, t0)
        d = r.diag
        vc0 = float(np.interp(t0, d["t"], d["volume_change_pct"]))
        parts.append(f"`{r.name}` (every {redistance_period(r) * 1e3:.1f} ms): front {x0:.3f} m "
                     f"at {v0:.2f} m/s at {t0} s, bound {xb:.3f} m, furthest front "
                     f"{r.v('max_front_x_m'):.3f} m, stopped at t3 = {r.v('t3_s'):.2f} s, "
                     f"volume change {vc0:+.2f} % at {t0} s and {r.v('volume_change_pct'):+.2f} % "
                     "at the end")
    base = front_state(runs[0], t0)
    short = []
    for r in runs[1:]:
        x0, _, xb = front_state(r, t0)
        short.append(f"every {redistance_period(r) * 1e3:.1f} ms the front at {t0} s is "
                     f"{100 * (base[0] - x0):.1f} cm behind the {redistance_period(runs[0]) * 1e3:.0f} "
                     f"ms run's and its furthest front stops {100 * (xb - r.v('max_front_x_m')):.1f} "
                     f"cm short of its own bound, at t3 = {r.v('t3_s'):.2f} s")
    return (" The redistancing frequency acts in that last stage (time-step study, n = 64, "
            "dt = 1e-4 s): " + "; ".join(parts) + ". Redistanced more often, " + "; ".join(short)
            + ": a front of material cannot do that, the level set loses the thin head (the "
            f"volume loss grows after {t0} s). The paper tells of a front that stops near 0.9 s; "
            "it does not give its redistancing frequency, so this is a possible cause of the "
            "difference, not a shown one.")


def coulomb_bound_text(r, t0=0.6, t_stop_paper=0.9, wall_deg=15.0, g=9.81):
    """What Coulomb friction allows the head of case B after t0. The bottom grains at the front
    slide at u_b; nothing ahead holds them back, the section behind only pushes (p >= 0 there,
    |T'| <= tan(alpha) p, viscous tension negligible away from a mesh-thin tip) and the wall load
    is about the weight, so u_b falls at most at a_max = g tan(alpha_b). Compares the least
    runout this allows from the run's state at t0 with the paper's account of its stages."""
    d = r.diag
    t, x = d["t"], d["front_x"]
    if ((t >= t0 - 0.05 - 1e-9) & (t <= t0 + 0.05 + 1e-9)).sum() < 3:
        return ""
    x0, v0, _ = front_state(r, t0, g, wall_deg)
    a_max = g * math.tan(math.radians(wall_deg))
    vel = np.gradient(x, t)
    decel = []
    for a in np.arange(t0, r.v("t3_s") - 0.1 + 1e-9, 0.1):
        w = (t >= a - 1e-9) & (t <= a + 0.1 + 1e-9)
        if w.sum() >= 3:
            decel.append(float(-np.polyfit(t[w], vel[w], 1)[0]))
    ub = basal_slip_near_front(r, t0)
    # (position, speed) pairs: the front itself, and the slowest / fastest bottom grains of its
    # last cm, placed at the back of that cm (the least runout they can give).
    pairs = [(x0, v0)] + ([(x0 - 0.01, ub[0]), (x0 - 0.01, ub[1])] if ub else [])
    lo = min(xp + v ** 2 / (2 * a_max) for xp, v in pairs)
    hi = max(xp + v ** 2 / (2 * a_max) for xp, v in pairs)
    return (" **Deceleration.** The material sliding on the bottom at the head of the flow "
            f"slows at most at a_max = g tan α_b = {a_max:.2f} m/s²: nothing ahead of it holds "
            "it back, the material behind can only push while its pressure is positive "
            "(|T'| ≤ tan α p; viscous tension is negligible except in a mesh-thin tip), and its "
            f"wall load is about its weight. granflow at t = {t0} s: front at {x0:.3f} m, "
            f"advancing at {v0:.2f} m/s"
            + (f", the grains on the bottom in its last cm sliding at {ub[0]:.2f}–{ub[1]:.2f} m/s"
               if ub else "")
            + f"; from there the bound allows no runout below {lo:.3f}"
            + (f"–{hi:.3f}" if hi - lo > 5e-4 else "") +
            f" m (granflow: {r.v('runout_m'):.3f} m, front stopped at t3 = "
            f"{r.v('t3_s'):.2f} s)."
            + (" Its front slows at " + ", ".join(f"{v:.1f}" for v in decel)
               + f" m/s² over successive 0.1 s from {t0} s"
               + ("; the last value is above the bound, where the front is a few cells thick "
                  "and the level set's tip erodes" if decel and decel[-1] > a_max else "")
               + "." if decel else "") +
            f" So granflow's distance to the paper's 1.145 m is set before {t0} s, not by how "
            "its head stops. Read literally, the paper's stage times (deceleration from about "
            f"{t0} s, front at rest near {t_stop_paper} s at 1.145 m) do not fit this bound: "
            f"they would need a front slower than {a_max * (t_stop_paper - t0):.2f} m/s and "
            f"beyond {B_RUNOUT_PAPER[15.0] - 0.5 * a_max * (t_stop_paper - t0) ** 2:.3f} m at "
            f"{t0} s, a mean speed above "
            f"{(B_RUNOUT_PAPER[15.0] - 0.5 * a_max * (t_stop_paper - t0) ** 2 - r.v('gate_x_m')) / t0:.2f}"
            " m/s since release, in a constant-speed phase said to last to 0.5 s. Those times "
            "are read off the paper's curves, so this report uses only its runout and deposit "
            "as quantitative targets for case B, not its stage times.")


def case_a_volume_pressure(ctx):
    """Per grid of case A: the volume change, the pressure peak (ratio to rho_s g H_c, its time,
    the interval above the bound) and the state at t_f; the trend of the pressure excess."""
    R, An = ctx.R, A_GRIDS
    vc = {n: R[k].v("volume_change_pct") for k, n in An if R[k].ok}
    pr = {}
    for k, n in An:
        r = R[k]
        if r.ok:
            d = r.diag
            ratio = d["max_p_granular"] / r.v("pressure_scale_pa")
            above = d["t"][ratio > 1.0]
            pr[n] = (r.v("max_p_granular_ratio"), float(d["t"][np.argmax(ratio)]),
                     (float(above.min()), float(above.max())) if len(above) else None)
    after = []
    for k, n in An:
        r = R[k]
        if r.ok and not isnan(r.v("tf_s")):
            d = r.diag
            i = int(np.argmin(np.abs(d["t"] - r.v("tf_s"))))
            after.append(f"n = {n}: {d['volume_change_pct'][i]:+.2f} % and front "
                         f"{d['front_x'][i]:.3f} m at t_f = {r.v('tf_s'):.2f} s, "
                         f"{d['volume_change_pct'][-1]:+.2f} % and {d['front_x'][-1]:.3f} m at "
                         f"{d['t'][-1]:.2f} s")
    ex = [v[0] - 1 for v in pr.values()]
    p_trend = ("" if len(ex) < 2 else
               "The excess does not fall with n (not a resolution effect)." if ex[-1] > 0.8 * ex[0]
               else "The excess falls with n.")
    return vc, pr, after, p_trend


def volume_bullet(vc, after):
    return (
          "- **Granular volume.** Case A loses "
          + ", ".join(f"{-v:.2f} % (n = {n})" for n, v in vc.items()) +
          " against the paper's < 0.84 % (at n = 256). The paper's cases use an interface "
          "half-width of 1 cell (`levelset.eps_cells = 1.0` in cases/*.toml; the default 1.5 "
          "lost 3.0 % at n = 64 and 1.6 % at n = 128): the smeared band 0 < φ < ε is heavy but "
          "has no yield stress, and after the grains stop it slides down the deposit and takes "
          "level-set volume with it (docs/LEVELSET_VOLUME.md). What is left is lost mostly "
          "after the motion has stopped, and the front recedes with it, so the final front "
          "(runout) lies behind the furthest front (both are reported) and depends on how long "
          "a run continues at rest: " + "; ".join(after) + "."
    )


def pressure_bullet(R, pr, p_trend):
    return (
          "- **Pressure.** The max granular pressure of case A against ρ_s g H_c: "
          + "; ".join((f"n = {n}: above it by {100 * (v - 1):.1f} % at t = {tm:.2f} s"
                       + (f", above the bound for {ab[0]:.2f} ≤ t ≤ {ab[1]:.2f} s" if ab else ""))
                      if v > 1 else f"n = {n}: below it (peak {v:.3f} at t = {tm:.2f} s)"
                      for n, (v, tm, ab) in pr.items()) +
          ", at the end of the acceleration phase, when the collapsing column's upper part "
          "is decelerated; the paper reports p ≤ ρ_s g H_c at all times. " + p_trend +
          " Where it is (n = 64, VTK every 0.01 s over t ≤ 0.16 s, `--set time.t_end=0.16 "
          "--set output.vtk_interval=0.01`): in the bottom row at x ≈ 0.19 m, under the "
          "former edge of the column, inside the static basal zone (u = v = 0 in the 7 rows "
          "above the bottom), 17 cells from the interface. There the overburden of the "
          "granular column above is only 0.67 ρ_s g H_c, and p rises smoothly from it 7 rows "
          "up to 1.06 ρ_s g H_c at the bottom: the flowing layer above shears and pushes the "
          "static wedge, and the wedge carries that load as a locked-in stress. Inside a rigid "
          "zone the rigid-plastic model leaves the stress undetermined; the scheme fixes it "
          "through the relaxation θ(Sⁿ − S) of eq. 31, which makes the rigid zone respond like "
          "a stiff elastic solid whose stiffness r κ²/(θ δt) depends on h, dt and the "
          "augmentation r. That the converged step depends on r/θ is shown (unit test, "
          "\"Augmentation r\" above); that this is what sets the peak is a hypothesis, not "
          "a proof" + (f"; the paper's dt = 1e-4 s leaves the n = 128 peak at "
          f"{R['a_n128_dt1e-4'].v('max_p_granular_ratio'):.3f} ρ_s g H_c" if R["a_n128_dt1e-4"].ok
          else "") + (
          "; but the relaxation itself moves it: at n = 64 the peak is "
          + ", ".join(f"{R[k].v('max_p_granular_ratio'):.3f}" for k, _ in THETA_RUNS if R[k].ok)
          + " ρ_s g H_c for θ = " + ", ".join(f"{th}" for k, th in THETA_RUNS if R[k].ok)
          + " δt (\"Relaxation θ of eq. 31\" above), the smaller θ (the stiffer rigid zone) "
          "giving the larger peak" if sum(R[k].ok for k, _ in THETA_RUNS) >= 3 else "") + (
          "; and so does r: " + "; ".join(
              f"n = {n}: " + ", ".join(f"{R[k].v('max_p_granular_ratio'):.3f}"
                                        for k, c, m, _ in RF_RUNS if c == "A" and m == n and R[k].ok)
              + " for r_factor = " + ", ".join(f"{rf}" for k, c, m, rf in RF_RUNS
                                                if c == "A" and m == n and R[k].ok)
              for n in (64, 128)
              if sum(R[k].ok for k, c, m, _ in RF_RUNS if c == "A" and m == n) >= 2)
          if sum(R[k].ok for k, c, _, _ in RF_RUNS if c == "A") >= 2 else "") +
          ". The pressure falls back below the bound afterwards (scalars figure). The "
          "HP run's excess is larger (see its table)."
    )


def b_runout_bullet(doneB):
    return (
          "- **Runout of case B.** " + ("; ".join(
              f"n = {n}: {r.v('runout_m'):.3f} m (furthest {r.v('max_front_x_m'):.3f} m)"
              for r, n in doneB) if doneB else "not run") +
          " against the paper's 1.145 m (768 × 256) and the experiment's 1.213 m. "
          + ("The runout grows with n and exceeds the paper's value from n = "
             f"{next((n for r, n in doneB if r.v('runout_m') > B_RUNOUT_PAPER[15.0]), '?')} on: "
             f"between the two finest grids it changes by "
             f"{pct(rel(doneB[-1][0].v('runout_m'), doneB[-2][0].v('runout_m')))}, and the finer "
             "runs overshoot the paper's" + (", also at the paper's own grid (n = 256)"
                          if any(n == 256 for _, n in doneB) else
                          "; whether n = 256 (the paper's grid, full tier) comes back to 1.145 m "
                          "is not known") + "; the cause of the difference is not identified."
             if len(doneB) >= 2 and all(b[0].v("runout_m") > a[0].v("runout_m")
                                        for a, b in zip(doneB, doneB[1:]))
             and doneB[-1][0].v("runout_m") > B_RUNOUT_PAPER[15.0] else "")
    )


def b_slopes_bullet(doneB):
    return (
          "- **Slopes of case B.** " + ("; ".join(
              f"n = {n}: {r.v('slope_back_deg'):.1f}° and {r.v('slope_front_deg'):.1f}°"
              for r, n in doneB) if doneB else "not run") +
          " against the paper's 29° (x ≤ 0.35 m) and 7° (x ≥ 0.5 m), fitted as straight lines "
          "over those ranges (to the front). Read that way the paper's figures cannot hold: a "
          "non-increasing surface at 29° over [0, 0.35] m and 7° from 0.5 m to a front at "
          f"1.145 m holds at least {min_area_two_slopes(1.145):.3f} m² "
          f"({min_area_two_slopes(1.213):.3f} m² to the experiment's 1.213 m), more than the "
          "column's 0.2 × 0.4 = 0.080 m². The paper describes the experimental deposit "
          "(\"clearly has two slopes\", section 4.2.2): its 7° can describe the surface near "
          "x = 0.5 m, not a line to the front. Local fits of the final surface: " + ("; ".join(
              f"n = {n}: {local_slope(r, 0.0, 0.2):.1f}° over [0, 0.2] m and "
              f"{local_slope(r, 0.5, 0.7):.1f}° over [0.5, 0.7] m" for r, n in doneB)
              if doneB else "not run")
          + (f": the far-field slope then comes within "
             f"{max(abs(local_slope(r, 0.5, 0.7) - 7) for r, _ in doneB):.1f}° of 7°, the back "
             f"slope stays {min(29 - local_slope(r, 0.0, 0.2) for r, _ in doneB):.1f}-"
             f"{max(29 - local_slope(r, 0.0, 0.2) for r, _ in doneB):.1f}° below 29° (the "
             "internal friction angle is 27°)" if doneB else "") +
          ". A fact of the model that bears on it (infinite slope, traction-free surface): at "
          "rest, a 2D Drucker–Prager material (|T'| ≤ tan α p) can hold a slope β up to "
          f"sin β = tan α, i.e. {math.degrees(math.asin(math.tan(math.radians(27)))):.1f}° "
          "for α = 27°; above α only with the along-slope normal stress more compressive than "
          "the slope-normal one (T'_along < 0; at the limit their ratio is (1 + tan²α)/(1 − "
          f"tan²α) = {(1 + math.tan(math.radians(27)) ** 2) / (1 - math.tan(math.radians(27)) ** 2):.2f}). "
          "Simple shear flow gives T'_along = 0, and a layer shearing at β > α keeps "
          "accelerating: slopes steeper than α stand only where the history compressed the "
          "material along the slope (against the back wall, say). The paper's 29° lies in that "
          "range" + (
              f"; granflow's local back slopes ({min(local_slope(r, 0.0, 0.2) for r, _ in doneB):.1f}"
              f"–{max(local_slope(r, 0.0, 0.2) for r, _ in doneB):.1f}°) stay near or below α, "
              "where material that stopped flowing in shear ends" if doneB else "") +
          ". The discrete model can hold steeper slopes at rest: the pile of "
          "`cases/verify/dp_pile.toml` (α = 25.5°, bottom friction 25.5°, equilibrium start) "
          "made 5 cm high with 29° sides, above α and above the infinite-slope limit of 28.5°, "
          "stays at rest (granular speed at most 2.9e-4 m/s over 0.5 s, 5.5e-7 m/s at the end; "
          "`granflow run cases/verify/dp_pile.toml --set initial.slope=29 --set "
          "initial.height=0.05`; a finite pile, not an infinite slope). So slopes above α are "
          "representable at rest here, and the back slope is what granflow's collapse leaves, "
          "not a limit of the discretisation. That part, and the runout, "
          "are not explained. The "
          "angle at the front is fitted over the last 2 cm, i.e. 1.4–3 cells at n ≤ 64 (not "
          "resolved; NaN where there are too few cells) and 5.6 / 11 cells at n = 128 / 256."
    )


def resolution_bullet(ctx):
    doneA, fineB, hp_fine, hpb = ctx.doneA, ctx.fineB, ctx.hp_fine, ctx.hpb
    return (
          "- **Resolution.** The finest runs here against the paper's grids: case A "
          f"{doneA[-1][0].grid if doneA else '–'} (paper 1024 × 256), case B "
          f"{fineB[0].grid if fineB else '–'} (paper 768 × 256), HP case A "
          f"{hp_fine.grid if hp_fine else '–'} and HP case B {hpb.grid if hpb else '–'} (paper "
          "n = 128); the paper itself shows the n = 64 runout short of the finer ones. The "
          "`full` tier runs the paper's grids; those not run are listed as such above."
    )


def known_disagreements(ctx):
    R, doneB = ctx.R, ctx.doneB
    vc, pr, after, p_trend = case_a_volume_pressure(ctx)
    return ["## Known disagreements", "",
            volume_bullet(vc, after),
            pressure_bullet(R, pr, p_trend),
            b_runout_bullet(doneB),
            momentum_bullet(doneB, R),
            b_slopes_bullet(doneB),
            resolution_bullet(ctx),
          "- **Stage times.** granflow's stages follow rules on the front (diagnostics/"
          "Collapse.hpp); the paper reads its t1, t2, t3 off its figures, so the stage "
          "differences are indicative.",
          "- **The gate** of the experiments is not modelled (as in the paper); the experimental "
          "times are compared after the paper's −0.03 s shift for case A in the figures of "
          "`plot_collapse.py` only.", ""]
