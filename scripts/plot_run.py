#!/usr/bin/python3
"""Figures of a granflow run, from its output folder alone.

usage: plot_run.py OUTDIR [--format pdf|svg|pdf,svg] [--dpi N] [--figures DIR] [--animate]

Writes OUTDIR/figures/ (or --figures DIR), PNG at 200 dpi; --format pdf or svg adds a vector copy
of each figure, its text kept as text:

- diagnostics.png: granular volume change, max speed of the granular phase (max_speed_granular:
  the cells with phi < -eps; the largest speed of all phases, air included, dashed beside it),
  kinetic energy and max divergence against t (for a one-phase run, the max speed of the fluid);
- front.png: for a two-phase run, the front position front_x of diagnostics.csv (the furthest
  x where the granular phase touches the bottom, diagnostics/Collapse.hpp) against time, with
  the shallow-water (Ritter) front x = x1 + 2 sqrt(g H) t as a reference bound;
- for a run with profiles.csv (every two-phase run), the column-collapse figures of
  scripts/plot_collapse.py (collapse_*.png), with the paper's numbers when the run is one of
  its cases;
- with --animate, the animation of scripts/animate_run.py (|u| in the granular phase with the
  interface, from the VTK series): speed.mp4 if ffmpeg is installed, else speed.gif.
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
import plot_collapse  # noqa: E402


def plot_diagnostics(run, out):
    d = run.diagnostics
    two_phase = run.has("profiles.csv")
    fig, ax = plt.subplots(2, 2, figsize=(10, 7))
    speed = ("max_speed_granular", "max granular |u| (m/s)") if two_phase \
        else ("max_speed", "max |u| (m/s)")
    for a, (key, label) in zip(ax.flat, [("volume_change_pct", "granular volume change (%)"),
                                         speed,
                                         ("kinetic_energy", "kinetic energy (J/m)"),
                                         ("max_divergence", "max |div u| (1/s)")]):
        a.plot(d["t"], d[key])
        a.set_xlabel("t (s)")
        a.set_ylabel(label)
        a.grid(alpha=0.3)
    if two_phase:  # the air keeps moving after the grains stop: drawn, but not as the result
        ax[0, 1].lines[0].set_label("granular phase (phi < -eps)")
        ax[0, 1].plot(d["t"], d["max_speed"], "--", color="0.6", lw=0.9,
                      label="all phases, air included")
        ax[0, 1].legend(fontsize=7)
    figstyle.suptitle(fig, run.case.get("title", run.folder), fontsize=11)
    out.save(fig, "diagnostics.png")


def plot_front(run, out):
    d, case = run.diagnostics, run.case
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(d["t"], d["front_x"], "o-", ms=3, label="granflow")
    ini = case.get("initial", {})
    g = abs(case.get("physics", {}).get("gravity", [0, -9.81])[1])
    if "x1" in ini and "y1" in ini:
        x1, H = ini["x1"], ini["y1"] - ini.get("y0", 0.0)
        t = np.linspace(0, d["t"][-1], 50)
        ax.plot(t, x1 + 2 * math.sqrt(g * H) * t, "k--",
                label=r"shallow water (Ritter): $x_1 + 2\sqrt{gH}\,t$")
    Lx = case.get("domain", {}).get("Lx")
    if Lx:
        ax.axhline(Lx, color="gray", lw=0.8)
        ax.set_ylim(0, 1.05 * Lx)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("front position x (m)")
    figstyle.title(ax, case.get("title", "") + ": front position", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend()
    out.save(fig, "front.png")


def main(folder, figures=None, formats=(), dpi=figstyle.DPI, animate=False):
    run = gr.Run(folder)
    out = figstyle.Output(figures or run.path("figures"), dpi, formats)
    plot_diagnostics(run, out)
    if "front_x" in run.diagnostics and run.has("profiles.csv"):
        plot_front(run, out)
        plot_collapse.main(folder, figures=out.folder, formats=formats, dpi=dpi)
    if animate:
        import animate_run
        animate_run.main(folder, os.path.join(out.folder, "speed"))
    return out.folder


def parse_args(argv=None):
    ap = figstyle.parser(__doc__)
    ap.add_argument("out", metavar="OUTDIR", help="a granflow run folder (--out of granflow run)")
    figstyle.add_arguments(ap)
    ap.add_argument("--figures", metavar="DIR", help="folder of the figures (OUTDIR/figures)")
    ap.add_argument("--animate", action="store_true",
                    help="also the animation of |u| in the granular phase (animate_run.py)")
    a = ap.parse_args(argv)
    if not os.path.isdir(a.out):
        ap.error(f"{a.out}: no such folder")
    if not os.path.isfile(os.path.join(a.out, "diagnostics.csv")):
        ap.error(f"{a.out}: not a granflow run folder (no diagnostics.csv)")
    figstyle.check_arguments(ap, a)
    return a


if __name__ == "__main__":
    a = parse_args()
    try:
        where = main(a.out, a.figures, a.format, a.dpi, a.animate)
    except (gr.RunFileError, LookupError, OSError) as e:
        sys.exit(f"plot_run.py: {e}")
    print(f"plot_run: figures in {where}")
