#!/usr/bin/python3
"""The dam-break energy study of issue 18 from the runs of scripts/validation/dambreak_energy.sh.

usage: dambreak_energy.py RUN_ROOT DOCS_DIR

Reads RUN_ROOT/<method>_<cells per a>/ (diagnostics.csv, summary.json) of the water column of
cases/verify/dambreak_energy.toml and writes DOCS_DIR/figures/dambreak_energy_front.png (the front
Z(T) = x_front / a against T = t sqrt(2 g / a) for every run, with the ideal Ritter front
Z = 1 + 2T), DOCS_DIR/figures/dambreak_energy.png (the energy budget of each method on its finest
grid: kinetic energy, released potential energy, viscous dissipation and the residual) and
DOCS_DIR/dambreak_energy.md (the table: the largest kinetic energy over the released potential
energy at any output, the largest speed against 4 sqrt(2 g a), the largest volume change, Z at
T = 1, 2, 3, 4 and the change of Z(4) from the grid below).
"""
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import granflow_run as gr  # noqa: E402
import figstyle  # noqa: E402

A = 0.05715  # m, the column width of the case
G = 9.81
T_SCALE = math.sqrt(2 * G / A)  # 1/s: T = t sqrt(2 g / a)
SPEED_BOUND = 4 * math.sqrt(2 * G * A)  # m/s: twice the ideal dam-break front speed
LABELS = {"clsvof": "CLSVOF (interface.method = \"clsvof\")",
          "level_set": "level set (the paper's scheme)"}


def load(root):
    runs = {}
    for name in sorted(os.listdir(root)):
        m = re.fullmatch(r"(clsvof|level_set)_(\d+)", name)
        path = os.path.join(root, name)
        if not m or not os.path.isfile(os.path.join(path, "diagnostics.csv")) or \
                not os.path.isfile(os.path.join(path, "summary.json")):
            continue  # not a run, or one still going (summary.json is written at the end)
        d = gr.read_csv(os.path.join(path, "diagnostics.csv"))
        with open(os.path.join(path, "summary.json")) as f:
            summ = json.load(f)
        runs[(m.group(1), int(m.group(2)))] = (d, summ)
    return runs


def measures(d):
    t = d["t"] * T_SCALE
    pe = d["potential_energy"]
    released = pe[0] - pe
    ke = d["kinetic_energy"]
    later = released > 0
    ratio = (ke[later] / released[later]).max() if later.any() else math.nan
    z = d["front_x"] / A

    def z_at(T):
        k = abs(t - T).argmin()
        return z[k] if abs(t[k] - T) < 0.06 else math.nan

    return {"ratio": ratio, "vmax": d["max_speed"].max(),
            "dv": abs(d["volume_change_pct"]).max() / 100, "Z": [z_at(T) for T in (1, 2, 3, 4)],
            "residual": d["energy_residual"][-1] / released[-1] if released[-1] > 0 else math.nan}


def main(argv):
    if len(argv) != 3:
        print(__doc__.split("\n\n")[1].strip(), file=sys.stderr)
        return 2
    root, docs = argv[1], argv[2]
    runs = load(root)
    if not runs:
        print(f"dambreak_energy.py: no runs in {root}", file=sys.stderr)
        return 1
    import matplotlib.pyplot as plt
    out = figstyle.Output(os.path.join(docs, "figures"))

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    styles = {"clsvof": "-", "level_set": "--"}
    cmap = plt.get_cmap("viridis")
    grids = sorted({k for _, k in runs})
    for (m, k), (d, _) in sorted(runs.items()):
        col = cmap(grids.index(k) / max(1, len(grids) - 1) * 0.85)
        ax.plot(d["t"] * T_SCALE, d["front_x"] / A, styles[m], color=col, lw=1.2,
                label=f"{m}, {k} cells per a")
    T = [0, 4]
    ax.plot(T, [1 + 2 * x for x in T], ":", color="grey", lw=1, label="Ritter (ideal): 1 + 2T")
    ax.set_xlim(0, 4.05)
    ax.set_ylim(1, 9)
    ax.set_xlabel("T = t sqrt(2g/a)")
    ax.set_ylabel("Z = x_front / a")
    ax.legend(fontsize=7, ncol=2)
    figstyle.title(ax, "Water column of Martin & Moyce's geometry (a = 0.05715 m, height 2a): "
                   "the front against time")
    out.save(fig, "dambreak_energy_front.png")

    methods = sorted({m for m, _ in runs})
    fig, axes = plt.subplots(1, len(methods), figsize=(5.2 * len(methods), 3.8), squeeze=False)
    for ax, m in zip(axes[0], methods):
        k = max(kk for mm, kk in runs if mm == m)
        d, _ = runs[(m, k)]
        t = d["t"] * T_SCALE
        released = d["potential_energy"][0] - d["potential_energy"]
        ax.plot(t, released, color="k", lw=1.2, label="potential energy released")
        ax.plot(t, d["kinetic_energy"], color=cmap(0.3), lw=1.2, label="kinetic energy")
        ax.plot(t, d["dissipated_viscous"], color=cmap(0.6), lw=1.2, label="viscous dissipation")
        ax.plot(t, d["energy_residual"], color=cmap(0.85), lw=1.2,
                label="residual (numerical dissipation; < 0: created)")
        ax.axhline(0, color="grey", lw=0.5)
        ax.set_xlabel("T = t sqrt(2g/a)")
        ax.set_ylabel("energy (J/m)")
        ax.legend(fontsize=7)
        figstyle.title(ax, f"{LABELS[m]}, {k} cells per a")
    out.save(fig, "dambreak_energy.png")

    lines = ["# The water column: no energy from nothing, the front converging (issue 18)\n",
             "*Generated by `scripts/validation/dambreak_energy.py` from the runs of "
             "`scripts/validation/dambreak_energy.sh` (cases/verify/dambreak_energy.toml at "
             "grid.n = 3 x cells per a, one rank); do not edit by hand.*\n",
             f"Columns: the largest kinetic energy over the released potential energy at any "
             f"output (T > 0); the largest speed anywhere against 4 sqrt(2 g a) = "
             f"{SPEED_BOUND:.3f} m/s; the largest relative change of the water volume; the "
             f"front Z = x_front / a at T = 1, 2, 3, 4; the change of Z(4) from the next "
             f"coarser grid (% of Z(4)); the energy residual at T = 4 over the released energy "
             f"(numerical dissipation; < 0: energy created).\n",
             "| method | cells per a | max KE / released PE | max speed (m/s) | max volume "
             "change | Z(1) | Z(2) | Z(3) | Z(4) | Z(4) change | residual / released | "
             "steps | wall (s) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for m in methods:
        prev = None
        for k in sorted(kk for mm, kk in runs if mm == m):
            d, s = runs[(m, k)]
            q = measures(d)
            z4 = q["Z"][3]
            change = "" if prev is None or math.isnan(z4) else f"{100 * (z4 - prev) / z4:+.2f} %"
            prev = z4
            status = "" if s.get("status") == "completed" else f" ({s.get('status')})"
            lines.append(
                f"| {m}{status} | {k} | {q['ratio']:.4f} | {q['vmax']:.3f} | {q['dv']:.1e} | " +
                " | ".join("" if math.isnan(z) else f"{z:.3f}" for z in q["Z"]) +
                f" | {change} | {q['residual']:+.4f} | {s.get('steps', '')} | "
                f"{s.get('wall_s', 0):.0f} |")
    lines += ["", "![front](figures/dambreak_energy_front.png)", "",
              "![energy](figures/dambreak_energy.png)", ""]
    with open(os.path.join(docs, "dambreak_energy.md"), "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines[4:4 + 2 + len(runs)]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
