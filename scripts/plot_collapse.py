#!/usr/bin/python3
"""Figures of a granular column collapse, from a granflow output folder alone.

usage: plot_collapse.py OUTDIR [--compare DIR ...] [--label TEXT ...] [--figures DIR]
                         [--time-shift S] [--format pdf|svg|pdf,svg] [--dpi N]

Reads diagnostics.csv, profiles.csv, structure.csv, deposit.csv, summary.json and the VTK
snapshots (fields.pvd, fields_*.vtr) written by `granflow run` (diagnostics/Collapse.hpp defines
every quantity), and writes OUTDIR/figures/ (PNG at 200 dpi; --format pdf or svg adds a vector
copy of each, its text kept as text):

  collapse_front.png      front position against t (paper Figs. 7, 10, 16, 21), the stages
                          t1, t2, t3, tf found by granflow, and the paper's and the experiment's
                          numbers (runout, front speed, stage times) as reference marks;
  collapse_profile.png    final surface profile h(x) (Figs. 6, 9, 15, 20) with the runout and
                          back-wall references and the two slope fits;
  collapse_speed.png      snapshots of |u| in the granular phase with the interface (Figs. 3, 17);
  collapse_strain.png     snapshots of |D(u)| (Figs. 4, 19);
  collapse_pressure.png   snapshots of p (Figs. 5, 18);
  collapse_structure.png  basal deposit and flowing layer at several times (Fig. 23);
  collapse_hl.png         flowing-layer height h_l(x) and its time derivative (Figs. 24, 25);
  collapse_head.png       L_h against t and L_h/L_f against L_d/L_f; A_d/A against t and
                          against L_d/L_f (Figs. 26, 27);
  collapse_scalars.png    back-wall height, max granular pressure / (rho_s g H_c), volume change
                          and max granular speed against t.

--compare DIR ...  overlays the fronts and final profiles of other runs (resolutions, Fig. 6;
                   viscosities, Fig. 9; wall frictions, Fig. 15): writes collapse_front.png and
                   collapse_profile.png only, into OUTDIR/figures/compare_<DIR names>/ (or
                   --figures), so that OUTDIR's own figures stay as they are. Each curve is
                   labelled by its run's folder name, or by --label.
--label TEXT ...   the legend labels of OUTDIR and of each --compare DIR, in that order.
--figures DIR      where the figures go instead.
--time-shift S     the gate of the experiments is not modelled: the paper compares case A with
                   the experiment after a time shift of -0.03 s (half the lifting time of the
                   gate, section 4.1.1). Experimental times t_exp are drawn at t_exp + S on the
                   simulation's time axis. Default: -0.03 for case A, 0 otherwise. The paper's
                   own (numerical) stage times are drawn unshifted.

The reference numbers are those of ../shared/reference/paper_targets.md (the paper's text; its
figures are not available as data, so no experimental curve is drawn, only its numbers).
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figstyle  # noqa: E402
import granflow_run as gr  # noqa: E402

# ---- Reference numbers (paper_targets.md). Times in s, lengths in m, speeds in m/s.
REFERENCES = {
    "A": {
        "name": "case A (aspect ratio 0.7, rough bottom; Mangeney et al. 2010)",
        "time_shift": -0.03,
        "runout_exp": 0.4750, "runout_paper": 0.442,  # paper: n = 256, eta_0 = 0.5
        "speed_exp": 0.775, "speed_paper": 0.952,
        "stages_paper": {"t1": 0.1, "t2": 0.35, "t3": 0.45, "tf": 1.06},
        "backwall_paper": 0.14,
        "stage_note": "paper: t1 ~ 0.1, t2 ~ 0.35, t3 ~ 0.45, tf = 1.06 s (section 4.1.3)",
    },
    "A_hp": {
        "name": "case A, HP model",
        "time_shift": -0.03,
        "runout_exp": 0.4750,
        "runout_paper": 0.4750 * (1 - 0.24),  # "underestimated by 24 %" (section 4.1.5)
        "stages_paper": {"tf": 1.06},
        "backwall_paper": 0.14,
        "stage_note": "paper: runout 24 % short of the experiment, at rest near 1.06 s",
    },
    "B": {
        "name": "case B (aspect ratio 2, smooth bottom; Roche et al. 2010)",
        "time_shift": 0.0,
        "runout_exp": 1.213, "runout_paper": 1.145,  # 15 deg, eta_0 = 0.1, 768 x 256
        "stages_paper": {"t1": 0.15, "t2": 0.5, "t3": 0.9, "tf": 1.36},
        "slopes_paper": {"back": 29.0, "front": 7.0, "front_angle": 4.85,
                         "front_angle_exp": 2.5},
        "Lh_max": {"paper": 0.56, "exp": 0.49},
        "stage_note": "paper: acceleration to 0.15 s, constant speed to 0.5 s, front stops "
                      "~0.9 s, at rest 1.36 s (section 4.2)",
        "snap_times": [0.2, 0.32, 0.44, 0.56, 0.72, 0.8],
        "exp_times": {"deceleration (experiment)": 0.75},
    },
    "B_hp": {
        "name": "case B, HP model",
        "time_shift": 0.0,
        "runout_exp": 1.213,
        "runout_paper": 1.213 * 0.5,  # "underestimated by nearly 50 %" (section 4.2.6)
        "stages_paper": {"tf": 1.98},
        "stage_note": "paper: runout ~50 % short, at rest at 1.98 s",
    },
}


class Run(gr.Run):
    """A two-phase run folder (granflow_run.Run) with the short names this script uses."""

    def __init__(self, out, label=None):
        super().__init__(out)
        for name in ("case.toml", "summary.json", "diagnostics.csv", "profiles.csv"):
            if not self.has(name):
                raise FileNotFoundError(f"{out}: no {name}")
        self.out = out
        self.diag, self.prof = self.diagnostics, self.profiles
        self.struct, self.dep = self.structure, self.deposit  # empty where the file is missing
        self.times = self.prof.times
        self.label = f"{self.summary.get('nx')} x {self.summary.get('ny')}"  # the grid
        self.legend = label or self.name  # the run's own name in a comparison

    def profile(self, t):
        """(x, h) at the output time nearest to t."""
        p = self.prof.at(t, tol=None)
        return p.times[0], p["x"], p["h"]

    def s(self, key):
        return self.value(key)


def which_case(case):
    """The paper's case a run reproduces, from its geometry and yield model (or None)."""
    ini = case.get("initial", {})
    hp = case.get("rheology", {}).get("yield") == "hp"
    if ini.get("shape", "rectangle") != "rectangle":
        return None
    if math.isclose(ini.get("x1", 0), 0.2) and math.isclose(ini.get("y1", 0), 0.14):
        return "A_hp" if hp else "A"
    if math.isclose(ini.get("x1", 0), 0.2) and math.isclose(ini.get("y1", 0), 0.4):
        return "B_hp" if hp else "B"
    return None


def fmt(v, unit="", nd=3):
    return "n/a" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.{nd}g}{unit}"


def curve_label(run, compared):
    """The legend of a run's curve: its grid alone, or its name and grid among others."""
    return f"{run.legend} ({run.label})" if compared else f"granflow {run.label}"


# ---- Front position against time, with the stages (Figs. 7, 8, 16).
def plot_front(run, others, ref, shift, out):
    fig, ax = plt.subplots(figsize=(8, 5.5))
    d = run.diag
    ax.plot(d["t"], d["front_x"], "-", color="k", lw=1.8, label=curve_label(run, others))
    for o in others:
        ax.plot(o.diag["t"], o.diag["front_x"], "-", lw=1.2, label=curve_label(o, True))
    colors = {"t1": "tab:green", "t2": "tab:orange", "t3": "tab:red", "tf": "tab:purple"}
    for k, c in colors.items():
        v = run.s(k + "_s")
        if not math.isnan(v):
            ax.axvline(v, color=c, lw=1.0, ls="-", alpha=0.8)
            ax.text(v, 0.02, f" {k} = {v:.2f}", color=c, transform=ax.get_xaxis_transform(),
                    rotation=90, va="bottom", fontsize=8)
    t1, t2 = run.s("t1_s"), run.s("t2_s")
    V = run.s("front_speed_mps")
    if ref:
        for k, v in ref.get("stages_paper", {}).items():
            ax.axvline(v, color=colors[k], lw=1.0, ls=":", alpha=0.9)
        if "runout_exp" in ref:
            ax.axhline(ref["runout_exp"], color="tab:pink", ls="--", lw=1.2,
                       label=f"experiment runout {ref['runout_exp']} m")
        if "runout_paper" in ref:
            ax.axhline(ref["runout_paper"], color="tab:blue", ls="--", lw=1.2,
                       label=f"paper runout {ref['runout_paper']:.4g} m")
        # Speed lines through granflow's front at the middle of its constant-speed phase:
        # compare slopes, not positions.
        if not (math.isnan(t1) or math.isnan(t2)):
            tm = 0.5 * (t1 + t2)
            xm = np.interp(tm, d["t"], d["front_x"])
            tt = np.array([t1 - 0.05, t2 + 0.05])
            for key, col, lab in (("speed_exp", "tab:pink", "experiment"),
                                  ("speed_paper", "tab:blue", "paper")):
                if key in ref:
                    ax.plot(tt, xm + ref[key] * (tt - tm), ls="-.", color=col, lw=1.0,
                            label=f"{lab} front speed {ref[key]} m/s")
        ax.plot([], [], "k:", lw=1.0, label="paper's stage times (dotted)")
        for lab, te in ref.get("exp_times", {}).items():
            ax.axvline(te + shift, color="tab:pink", ls=":", lw=1.2)
            ax.text(te + shift, 0.5, f" {lab}", color="tab:pink", rotation=90, fontsize=7,
                    transform=ax.get_xaxis_transform())
        ax.text(0.99, 0.02, ref.get("stage_note", "") +
                (f"\nexperimental times shifted by {shift:+.3g} s" if shift else ""),
                transform=ax.transAxes, ha="right", va="bottom", fontsize=7, color="0.3")
    if not (math.isnan(t1) or math.isnan(t2) or math.isnan(V)):
        tt = np.array([t1, t2])
        x1 = np.interp(t1, d["t"], d["front_x"])
        ax.plot(tt, x1 + V * (tt - t1), color="tab:green", lw=3, alpha=0.4,
                label=f"granflow constant phase: {V:.3f} m/s")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("front position x (m)")
    figstyle.title(ax, f"{run.title}\nrunout {fmt(run.s('runout_m'), ' m')} "
                   f"(furthest {fmt(run.s('max_front_x_m'), ' m')})")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right", bbox_to_anchor=(1.0, 0.1))
    out.save(fig, "collapse_front.png")


# ---- Final profile (Figs. 6, 9, 15).
def plot_profile(run, others, ref, out):
    t, x, h = run.profile(run.times[-1])
    t0, x0, h0 = run.profile(run.times[0])
    aspect = 1.15 * max(h0.max(), h.max()) / (x[-1] + 0.5 * (x[1] - x[0]))
    fig, ax = plt.subplots(figsize=(10, max(3.0, 10 * aspect + 1.2)))
    ax.plot(x0, h0, color="0.6", lw=1, label=f"t = {t0:g} s")
    ax.plot(x, h, color="k", lw=1.8, label=f"{curve_label(run, others)}, t = {t:.3g} s")
    for o in others:
        to, xo, ho = o.profile(o.times[-1])
        ax.plot(xo, ho, lw=1.2, label=f"{curve_label(o, True)}, t = {to:.3g} s")
    front = run.s("runout_m")
    # The slope fits of summary.json, drawn over their ranges.
    col = run.case.get("collapse", {})
    for key, rng_key, c in (("slope_back_deg", "slope_back_range", "tab:green"),
                            ("slope_front_deg", "slope_front_range", "tab:orange")):
        ang = run.s(key)
        rng = col.get(rng_key, [0.05, 0.15] if "back" in key else [0.2, 0.8])  # the defaults
        m = (x >= rng[0]) & (x <= rng[1]) & (x < front) & (h > 0)
        if m.sum() >= 2 and not math.isnan(ang):
            a, b = np.polyfit(x[m], h[m], 1)
            xx = x[m][[0, -1]]
            ax.plot(xx, a * xx + b, color=c, lw=3, alpha=0.5,
                    label=f"{key[:-4].replace('_', ' ')} fit: {ang:.1f} deg on x in {rng}")
    if ref:
        if "runout_exp" in ref:
            ax.axvline(ref["runout_exp"], color="tab:pink", ls="--",
                       label=f"experiment runout {ref['runout_exp']} m")
        if "runout_paper" in ref:
            ax.axvline(ref["runout_paper"], color="tab:blue", ls="--",
                       label=f"paper runout {ref['runout_paper']:.4g} m")
        if "backwall_paper" in ref:
            ax.plot([0, 0.03], [ref["backwall_paper"]] * 2, color="tab:red", lw=2,
                    label=f"paper back-wall height {ref['backwall_paper']} m")
        sp = ref.get("slopes_paper")
        if sp:
            ax.text(0.99, 0.95, f"paper: back {sp['back']} deg (x <= 0.35), front {sp['front']} deg "
                    f"(x >= 0.5), front angle {sp['front_angle']} deg (experiment "
                    f"{sp['front_angle_exp']} deg)", transform=ax.transAxes, ha="right",
                    fontsize=7, color="0.3")
    ax.set_aspect("equal")
    ax.set_xlim(0, x[-1] + 0.5 * (x[1] - x[0]))
    ax.set_ylim(0, 1.15 * max(h0.max(), h.max()))
    ax.set_xlabel("x (m)")
    ax.set_ylabel("h (m)")
    figstyle.title(ax, f"final deposit: runout {fmt(run.s('runout_m'), ' m')}, back wall "
                   f"{fmt(run.s('backwall_height_m'), ' m')}, front angle "
                   f"{fmt(run.s('front_angle_deg'), ' deg')}")
    ax.legend(fontsize=7, loc="upper right", bbox_to_anchor=(1.0, 0.9))
    ax.grid(alpha=0.3)
    out.save(fig, "collapse_profile.png")


def snapshot_times(run, ref, n=6):
    files = run.snapshots
    if not files:
        return []
    if ref and "snap_times" in ref:
        want = ref["snap_times"]
    else:
        want = [t for t, _ in files if t > 0][:n - 1] + [files[-1][0]]
    chosen = []
    for w in want:
        t, f = min(files, key=lambda tf: abs(tf[0] - w))
        if (t, f) not in chosen:
            chosen.append((t, f))
    return chosen[:n]


# ---- Snapshots of a cell field in the granular phase, with the interface (Figs. 3-5, 17-19).
def shown_region(run):
    """(xmax, ymax) in m of a collapse run (a granflow_run.Run): the region the mass occupies (the air above it is not part of these
    figures)."""
    Lx = run.case.get("domain", {}).get("Lx", 1.0)
    Ly = run.case.get("domain", {}).get("Ly", 1.0)
    ymax = min(Ly, 1.15 * max(run.profiles["h"].max(), 1e-3))
    xmax = min(Lx, 1.1 * np.nanmax(run.diagnostics["front_x"]) + 0.02)
    return xmax, ymax


def panel_grid(n, xmax, ymax, pw):
    """A figure of n panels of the region [0, xmax] x [0, ymax] at equal aspect, pw inches
    wide each, in 2 columns from 4 panels on: sized to the panels, so that the canvas is not
    left blank around them. Returns (fig, axes array (rows, columns))."""
    ncol = 2 if n > 3 else 1
    nrow = math.ceil(n / ncol)
    ph = (pw - 0.6) * ymax / xmax  # the height of a panel's data area (tick labels take 0.6 in)
    fig = plt.figure(figsize=(ncol * pw + 1.4, nrow * (ph + 0.5) + 0.8), layout="constrained")
    axs = fig.subplots(nrow, ncol, squeeze=False, sharex=True, sharey=True)
    for ax in list(axs.flat)[n:]:
        ax.axis("off")
    for k, ax in enumerate(axs.flat[:n]):
        row, col = divmod(k, ncol)
        below = (row + 1) * ncol + col  # the panel under this one, if there is one
        if below >= n:
            ax.set_xlabel("x (m)")
            ax.xaxis.set_tick_params(labelbottom=True)
        if col == 0:
            ax.set_ylabel("y (m)")
        ax.tick_params(labelsize=7)
    return fig, axs


def plot_snapshots(run, ref, out, name, fname, label, log=False, cmap="viridis"):
    snaps = snapshot_times(run, ref)
    if not snaps:
        return
    xmax, ymax = shown_region(run)
    vals = []
    data = []
    for t, f in snaps:
        fld = gr.read_vtr(f)
        phi = fld["phi"]
        a = fld.granular(name)
        data.append((t, fld.xn, fld.yn, phi, a))
        if a.count():
            vals.append(a.compressed())
    if not vals:
        return
    allv = np.concatenate(vals)
    if log:
        pos = allv[allv > 0]
        vmin, vmax = (np.percentile(pos, 5), pos.max()) if len(pos) else (1e-3, 1)
        norm = matplotlib.colors.LogNorm(vmin=vmin, vmax=vmax)
    else:
        norm = matplotlib.colors.Normalize(vmin=min(0.0, allv.min()), vmax=allv.max())
    fig, axs = panel_grid(len(data), xmax, ymax, 5.2)
    im = None
    for ax, (t, xn, yn, phi, a) in zip(axs.flat, data):
        a_plot = np.ma.masked_where(a <= 0, a) if log else a
        # Rasterized: in a PDF or SVG the cells are an image, the axes and text stay vector.
        im = ax.pcolormesh(xn, yn, a_plot, norm=norm, cmap=cmap, shading="flat", rasterized=True)
        xc, yc = 0.5 * (xn[1:] + xn[:-1]), 0.5 * (yn[1:] + yn[:-1])
        ax.contour(xc, yc, phi, levels=[0], colors="k", linewidths=0.8)
        ax.set_xlim(0, xmax)
        ax.set_ylim(0, ymax)
        ax.set_aspect("equal")
        ax.set_title(f"t = {t:.3g} s", fontsize=9)
    fig.colorbar(im, ax=axs.ravel().tolist(), shrink=0.8, label=label)
    figstyle.suptitle(fig, f"{run.title} ({run.label}): {label} where phi < 0, interface "
                           "phi = 0 (black)")
    out.save(fig, fname, tight=False)


def structure_times(run, ref, n=6):
    """Times for the deposit / flowing-layer figures: the paper's (case B) or n outputs spread
    over the flowing phase, from the first output after 0.05 s to t3 (or the end)."""
    if ref and "snap_times" in ref:
        want = ref["snap_times"]
    else:
        t_end = run.s("t3_s")
        if math.isnan(t_end):
            t_end = run.times[-1]
        want = list(np.linspace(min(0.1, t_end), t_end, n))
    ts = []
    for w in want:
        t = run.times[np.argmin(np.abs(run.times - w))]
        if t not in ts:
            ts.append(t)
    return ts


# ---- Basal deposit and flowing layer (Fig. 23).
def plot_structure(run, ref, out):
    s = run.struct
    if not s:
        return
    cut = np.unique(s["cutoff"]).max()  # the largest cut-off (7.5 % by default), as Fig. 23
    ts = structure_times(run, ref)
    xmax = min(run.case.get("domain", {}).get("Lx", 1.0), 1.1 * np.nanmax(run.diag["front_x"]))
    ymax = 1.1 * s["h"].max()
    pw = 7.0
    fig, axs = plt.subplots(len(ts), 1, sharex=True, layout="constrained",
                            figsize=(pw + 0.8, len(ts) * ((pw - 0.6) * ymax / xmax + 0.12) + 0.9))
    axs = np.atleast_1d(axs)
    for ax, t in zip(axs, ts):
        m = (s["t"] == t) & (s["cutoff"] == cut)
        x, h, hd = s["x"][m], s["h"][m], s["h_deposit"][m]
        ax.fill_between(x, 0, hd, color="0.35", step="mid", label="basal deposit")
        ax.fill_between(x, hd, h, color="0.8", step="mid", label="flowing layer")
        ax.plot(x, h, color="k", lw=0.6)
        ax.set_xlim(0, xmax)
        ax.set_ylim(0, ymax)
        ax.set_aspect("equal")
        ax.set_ylabel("y (m)", fontsize=8)
        ax.text(0.99, 0.8, f"t = {t:.3g} s", transform=ax.transAxes, ha="right", fontsize=8)
        ax.tick_params(labelsize=7)
    axs[0].legend(fontsize=7, loc="upper center", ncol=2)
    axs[-1].set_xlabel("x (m)")
    figstyle.suptitle(fig, f"{run.title} ({run.label}): deposit = |u| <= {cut:g} max granular "
                           "|u|")
    out.save(fig, "collapse_structure.png", tight=False)


# ---- Flowing-layer height and its time derivative (Figs. 24, 25).
def plot_hl(run, ref, out):
    s = run.struct
    if not s:
        return
    cuts = np.unique(s["cutoff"])
    cut = cuts.max()
    ts = structure_times(run, ref)
    fig, axs = plt.subplots(1, 2, figsize=(12, 4.5))
    xmax = min(run.case.get("domain", {}).get("Lx", 1.0), 1.1 * np.nanmax(run.diag["front_x"]))
    times = run.times
    for t in ts:
        m = (s["t"] == t) & (s["cutoff"] == cut)
        line, = axs[0].plot(s["x"][m], s["h_l"][m], lw=1.2, label=f"t = {t:.3g} s")
        # d h_l / dt by centred differences between the neighbouring outputs.
        k = int(np.argmin(np.abs(times - t)))
        if 0 < k < len(times) - 1:
            ma = (s["t"] == times[k - 1]) & (s["cutoff"] == cut)
            mb = (s["t"] == times[k + 1]) & (s["cutoff"] == cut)
            dh = (s["h_l"][mb] - s["h_l"][ma]) / (times[k + 1] - times[k - 1])
            axs[1].plot(s["x"][m], dh, lw=1.0, color=line.get_color(), label=f"t = {t:.3g} s")
    axs[0].set_ylabel("h_l (m)")
    axs[1].set_ylabel("d h_l / dt (m/s)")
    axs[1].axhline(0, color="k", lw=0.6)
    for ax in axs:
        ax.set_xlabel("x (m)")
        ax.set_xlim(0, xmax)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    figstyle.suptitle(fig, f"{run.title} ({run.label}): flowing layer h_l = h - h_deposit, "
                           f"cut-off {cut:g}")
    out.save(fig, "collapse_hl.png")


# ---- Sliding head and deposit area (Figs. 26, 27).
def plot_head(run, ref, out):
    d = run.dep
    if not d:
        return
    # L_f: the runout reached, from the gate. The furthest front rather than the last: a thin
    # tip lost with granular volume makes the front recede after it stopped.
    Lf = run.s("max_front_x_m") - run.s("gate_x_m")
    fig, axs = plt.subplots(2, 2, figsize=(11, 8))
    for c in np.unique(d["cutoff"]):
        m = d["cutoff"] == c
        lab = f"cut-off {100 * c:g} %"
        axs[0, 0].plot(d["t"][m], d["L_h"][m], lw=1.2, label=lab)
        axs[0, 1].plot(d["L_d"][m] / Lf, d["L_h"][m] / Lf, ".-", ms=3, lw=0.8, label=lab)
        axs[1, 0].plot(d["t"][m], d["Ad_over_A"][m], lw=1.2, label=lab)
        axs[1, 1].plot(d["L_d"][m] / Lf, d["Ad_over_A"][m], ".-", ms=3, lw=0.8, label=lab)
    if ref and "Lh_max" in ref:
        axs[0, 0].axhline(ref["Lh_max"]["paper"], color="tab:blue", ls="--",
                          label=f"paper max L_h {ref['Lh_max']['paper']} m")
        axs[0, 0].axhline(ref["Lh_max"]["exp"], color="tab:pink", ls="--",
                          label=f"experiment max L_h {ref['Lh_max']['exp']} m")
        axs[1, 0].axhspan(0.20, 0.25, color="tab:blue", alpha=0.15,
                          label="paper: A_d/A ~ 20-25 % in the constant phase")
    axs[0, 0].set(xlabel="t (s)", ylabel="L_h = L - L_d (m)")
    axs[0, 1].set(xlabel="L_d / L_f (-)", ylabel="L_h / L_f (-)")
    axs[1, 0].set(xlabel="t (s)", ylabel="A_d / A (-)")
    axs[1, 1].set(xlabel="L_d / L_f (-)", ylabel="A_d / A (-)")
    for ax in axs.flat:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    figstyle.suptitle(fig, f"{run.title} ({run.label}): sliding head and basal deposit beyond "
                           f"the gate (L_f = furthest front - L_c = {Lf:.3g} m; deposit: |u| <= "
                           "cut-off x the largest granular |u| so far)")
    out.save(fig, "collapse_head.png")


def plot_scalars(run, out):
    d = run.diag
    scale = run.s("pressure_scale_pa")
    fig, axs = plt.subplots(2, 2, figsize=(10, 7))
    axs[0, 0].plot(d["t"], d["backwall_h"])
    axs[0, 0].set_ylabel("back-wall height (m)")
    axs[0, 1].plot(d["t"], d["max_p_granular"] / scale)
    axs[0, 1].axhline(1.0, color="k", ls="--", lw=0.8)
    axs[0, 1].set_ylabel(f"max granular p / rho_s g H_c (-)\n(rho_s g H_c = {scale:.4g} Pa)")
    axs[1, 0].plot(d["t"], d["volume_change_pct"])
    axs[1, 0].axhline(-0.84, color="tab:blue", ls="--", lw=0.8, label="paper: loss < 0.84 %")
    axs[1, 0].legend(fontsize=7)
    axs[1, 0].set_ylabel("granular volume change (%)")
    axs[1, 1].semilogy(d["t"], np.maximum(d["max_speed_granular"], 1e-12))
    axs[1, 1].set_ylabel("max granular |u| (m/s)")
    for ax in axs.flat:
        ax.set_xlabel("t (s)")
        ax.grid(alpha=0.3)
    figstyle.suptitle(fig, f"{run.title} ({run.label})")
    out.save(fig, "collapse_scalars.png")


def reference(run, time_shift=None):
    """(the paper's numbers for the run's case or None, the time shift of the experiment)."""
    key = which_case(run.case)
    ref = REFERENCES.get(key) if key else None
    shift = time_shift if time_shift is not None else (ref["time_shift"] if ref else 0.0)
    return ref, shift


def draw_all(run, out, time_shift=None):
    """Every figure of one run into `out` (a figstyle.Output)."""
    ref, shift = reference(run, time_shift)
    plot_front(run, [], ref, shift, out)
    plot_profile(run, [], ref, out)
    plot_snapshots(run, ref, out, "speed", "collapse_speed.png", "|u| (m/s)")
    plot_snapshots(run, ref, out, "D_norm", "collapse_strain.png", "|D(u)| (1/s)", log=True,
                   cmap="magma")
    plot_snapshots(run, ref, out, "p", "collapse_pressure.png", "p (Pa)", cmap="cividis")
    plot_structure(run, ref, out)
    plot_hl(run, ref, out)
    plot_head(run, ref, out)
    plot_scalars(run, out)


def compare_folder(out, compare):
    """OUTDIR/figures/compare_<names of the compared folders>: a comparison's own folder."""
    names = "_".join(os.path.basename(os.path.normpath(c)) for c in compare)
    return os.path.join(out, "figures", "compare_" + names[:120])


def main(out, compare=(), time_shift=None, labels=(), figures=None, formats=(), dpi=None):
    """The figures of run `out`; with `compare`, its front and final profile against those runs
    (labels: of out, then of each compared run; default their folder names)."""
    folders = [out, *compare]
    if labels and len(labels) != len(folders):
        raise ValueError(f"--label: {len(labels)} labels for {len(folders)} runs")
    runs = [Run(f, lab) for f, lab in zip(folders, list(labels) or [None] * len(folders))]
    names = [r.legend for r in runs]
    if len(set(names)) < len(names):  # the same folder name in different places
        for r, f in zip(runs, folders):
            r.legend = f if not labels else r.legend
    run, others = runs[0], runs[1:]
    if figures is None:
        figures = compare_folder(out, compare) if compare else os.path.join(out, "figures")
    dest = figstyle.Output(figures, dpi or figstyle.DPI, formats)
    if others:
        ref, shift = reference(run, time_shift)
        plot_front(run, others, ref, shift, dest)
        plot_profile(run, others, ref, dest)
    else:
        draw_all(run, dest, time_shift)
    return figures


def parse_args(argv=None):
    ap = figstyle.parser(__doc__)
    ap.add_argument("out", metavar="OUTDIR", help="a two-phase granflow run folder")
    ap.add_argument("--compare", nargs="+", default=[], metavar="DIR",
                    help="other run folders to overlay (front and final profile)")
    ap.add_argument("--label", nargs="+", default=[], metavar="TEXT",
                    help="legend labels: OUTDIR's, then each --compare DIR's")
    ap.add_argument("--figures", metavar="DIR", help="folder of the figures")
    ap.add_argument("--time-shift", type=float, default=None, metavar="S")
    figstyle.add_arguments(ap)
    a = ap.parse_args(argv)
    for d in [a.out] + a.compare:
        if not os.path.exists(os.path.join(d, "profiles.csv")):
            ap.error(f"{d}: no profiles.csv (not a two-phase granflow run folder?)")
    if a.label and len(a.label) != 1 + len(a.compare):
        ap.error(f"--label takes one label per run: {1 + len(a.compare)} (OUTDIR and each "
                 f"--compare DIR), got {len(a.label)}")
    figstyle.check_arguments(ap, a)
    return a


if __name__ == "__main__":
    a = parse_args()
    where = main(a.out, a.compare, a.time_shift, a.label, a.figures, a.format, a.dpi)
    print(f"plot_collapse: figures in {where}")
