#!/usr/bin/python3
"""Figures of a granflow run, from its output folder alone.

usage: plot_run.py OUTDIR        (writes OUTDIR/figures/*.png)

- diagnostics.png: granular volume change, max |u|, kinetic energy, max divergence against t;
- front.png: for a two-phase run, the front position front_x of diagnostics.csv (the furthest
  x where the granular phase touches the bottom, diagnostics/Collapse.hpp) against time, with
  the shallow-water (Ritter) front x = x1 + 2 sqrt(g H) t as a reference bound;
- for a run with profiles.csv (every two-phase run), the column-collapse figures of
  scripts/plot_collapse.py (collapse_*.png), with the paper's numbers when the run is one of
  its cases.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import granflow_run as gr  # noqa: E402
import plot_collapse  # noqa: E402


def main(out):
    figs = os.path.join(out, "figures")
    os.makedirs(figs, exist_ok=True)
    run = gr.Run(out)
    case = run.case
    d = gr.read_csv(run.path("diagnostics.csv"))
    fig, ax = plt.subplots(2, 2, figsize=(10, 7))
    for a, (key, label) in zip(ax.flat, [("volume_change_pct", "granular volume change (%)"),
                                         ("max_speed", "max |u| (m/s)"),
                                         ("kinetic_energy", "kinetic energy (J/m)"),
                                         ("max_divergence", "max |div u| (1/s)")]):
        a.plot(d["t"], d[key])
        a.set_xlabel("t (s)")
        a.set_ylabel(label)
        a.grid(alpha=0.3)
    fig.suptitle(case.get("title", out))
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "diagnostics.png"), dpi=120)
    plt.close(fig)

    if "front_x" in d and os.path.exists(os.path.join(out, "profiles.csv")):
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
        ax.set_title(case.get("title", "") + ": front position")
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(figs, "front.png"), dpi=120)
        plt.close(fig)
        plot_collapse.main(out)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
