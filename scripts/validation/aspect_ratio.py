#!/usr/bin/python3
"""Case A's material across aspect ratios (issue 21): the tables, fits and figures of docs/aspect_ratio.md.

usage: scripts/validation/aspect_ratio.py RUN_ROOT OUT_MD FIG_DIR

Reads every run folder RUN_ROOT/<a>_c<cells across L>_<variant>/ written by
scripts/validation/aspect_ratio.sh (whatever exists: a missing or unfinished run is listed as
such), and writes OUT_MD (docs/aspect_ratio.md) and FIG_DIR/aspect_runout.png,
FIG_DIR/aspect_height.png.

Per run: a = H_i/L_i from summary.json (column_height_m, gate_x_m: the column of the run's
grid); the normalised runout (L_f - L_i)/L_i with L_f = runout_m (the front at the end,
measured from the back wall); H_f/L_i with H_f the largest height of the deposit at the last
output time of profiles.csv (the top of the granular phase per column, sub-cell from phi; for
these half-columns against the back wall it is the back-wall height backwall_height_m within
a fraction of a cell, which is listed beside it); whether the deposit had stopped (the largest
granular speed at the end, diagnostics.csv's max_speed_granular; how far the front moved in the
last STOP_WINDOW s; summary's tf_s) and how far the furthest front stayed from the right wall.
Between successive grids of each (a, variant): the relative difference (coarser - finer)/finer.
Fits: c a^p by least squares of log y on log a, on the finer grid, for each variant, over
FIT_RANGES. Published laws: PUBLISHED below, each with its source and how it was checked.

Needs numpy and matplotlib (/usr/bin/python3 on Debian) and scripts/granflow_run.py.
"""
import math
import os
import re
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))
import granflow_run as gr  # noqa: E402
import records  # noqa: E402
import figstyle  # noqa: E402  (sets the Agg backend)
import matplotlib.pyplot as plt  # noqa: E402

NAME_RE = re.compile(r"^a(\d+)_c(\d+)_([A-Za-z0-9]+)$")
STOP_WINDOW = 0.2      # s: the front may move at most STOP_FRONT_M over the run's last 0.2 s ...
STOP_FRONT_M = 1e-3    # m
STOP_SPEED = 1e-3      # m/s: ... and the largest granular speed at the end stay below 1 mm/s
WALL_CELLS = 5         # the furthest front must stay this many (fine) cells from the right wall
# Fit ranges of a (inclusive). With five aspect ratios a split range has three points: a <= 1 is
# the range where the published runout laws are linear in a (Lube: a <~ 1.8, Lajeunesse: a <~ 3),
# a >= 1 the range that reaches into their a^(2/3) branch (a >~ 2-3); the whole range is one power
# law for comparison with Balmforth & Kerswell's single exponents.
FIT_RANGES = [("all a (0.5-4)", 0.0, 1e9), ("a <= 1", 0.0, 1.0 + 1e-9), ("a >= 1", 1.0 - 1e-9, 1e9)]
VARIANT_LABELS = {"nowalls": "side walls off (2D)",
                  "walls": "side walls on (W = 0.1 m, 10.5 deg)",
                  "both": "side walls and gate (2.333 m/s, 10.5 deg)"}
VARIANT_COLORS = {"nowalls": "tab:blue", "walls": "tab:red", "both": "tab:green"}

# Published laws for quasi-2D (channel) collapses and 2D simulations. "kind": runout =
# (L_f - L_i)/L_i, height = H_f/L_i. c None: only the exponent is published (the constant depends
# on the material); it is drawn as a slope guide through the finer grid's value at a = 1.
# "checked": how the law was checked here (search tool of this session):
#   "abstract": read in the paper's abstract (a copy found by the search tool);
#   "secondary": read in a secondary source only (named in "checked_note"), not in the paper;
#   "recalled": from memory, not found in any source this session.
SECONDARY_LSP = ("a public repository's README (validation of an SPH code) quoting Lagree, Staron "
                 "& Popinet 2011, J. Fluid Mech. 686, 378, eq. (3.1), and the laws they cite")
PUBLISHED = [
    dict(key="lube_lin", kind="runout", c=1.2, p=1.0, amin=0.0, amax=1.8,
         source="Lube, Huppert, Sparks & Freundt 2005, Phys. Rev. E 72, 041301",
         setting="quasi-2D channel; sand, rice, sugar (and other granular media)",
         checked="secondary", checked_note=SECONDARY_LSP + " (a0 = 1.8-2.8); also the brief of issue 21"),
    dict(key="lube_pow", kind="runout", c=1.9, p=2.0 / 3.0, amin=2.8, amax=1e9,
         source="Lube, Huppert, Sparks & Freundt 2005, Phys. Rev. E 72, 041301",
         setting="quasi-2D channel; sand, rice, sugar (and other granular media)",
         checked="secondary", checked_note=SECONDARY_LSP + "; also the brief of issue 21"),
    dict(key="laj_lin", kind="runout", c=1.8, p=1.0, amin=0.0, amax=3.0,
         source="Lajeunesse, Monnier & Homsy 2005, Phys. Fluids 17, 103302",
         setting="quasi-2D channel; glass beads",
         checked="secondary", checked_note=SECONDARY_LSP + " (a0 = 3)"),
    dict(key="laj_pow", kind="runout", c=2.3, p=2.0 / 3.0, amin=3.0, amax=1e9,
         source="Lajeunesse, Monnier & Homsy 2005, Phys. Fluids 17, 103302",
         setting="quasi-2D channel; glass beads",
         checked="secondary", checked_note=SECONDARY_LSP),
    dict(key="bk_wide", kind="runout", c=None, p=0.9, pm=0.1, amin=0.0, amax=1e9,
         source="Balmforth & Kerswell 2005, J. Fluid Mech. 538, 399",
         setting="wide channel; four granular media; constant material-dependent",
         checked="abstract", checked_note="abstract: (l_inf - L)/L ~ a^(0.9 +- 0.1) in wide channels"),
    dict(key="bk_narrow", kind="runout", c=None, p=0.65, pm=0.05, amin=0.0, amax=1e9,
         source="Balmforth & Kerswell 2005, J. Fluid Mech. 538, 399",
         setting="narrow slot; four granular media; constant material-dependent",
         checked="abstract", checked_note="abstract: (l_inf - L)/L ~ a^(0.65 +- 0.05) in narrow slots"),
    dict(key="rods_lo", kind="runout", c=3.25, p=0.96, amin=0.65, amax=1.5,
         source="'Failure mechanism of true 2D granular flows', arXiv:1512.05180 (2015)",
         setting="true 2D: aluminium rods, no side walls; hard bed",
         checked="abstract", checked_note="abstract: (d - d0)/d0 = 3.25 a^0.96 for 0.65 < a < 1.5"),
    dict(key="rods_hi", kind="runout", c=3.80, p=0.73, amin=1.5, amax=1e9,
         source="'Failure mechanism of true 2D granular flows', arXiv:1512.05180 (2015)",
         setting="true 2D: aluminium rods, no side walls; hard bed",
         checked="abstract", checked_note="abstract: (d - d0)/d0 = 3.80 a^0.73 for a > 1.5"),
    dict(key="lube_h_lin", kind="height", c=1.0, p=1.0, amin=0.0, amax=1.15,
         source="Lube, Huppert, Sparks & Freundt 2005, Phys. Rev. E 72, 041301",
         setting="quasi-2D channel; the column's top is not reached by the collapse (H_f = H_i)",
         checked="recalled", checked_note="H_f/L_i = a for a <~ 1.15: from memory"),
    dict(key="lube_h_pow", kind="height", c=1.0, p=0.4, amin=1.15, amax=1e9,
         source="Lube, Huppert, Sparks & Freundt 2005, Phys. Rev. E 72, 041301",
         setting="quasi-2D channel",
         checked="secondary", checked_note=SECONDARY_LSP + " (lambda_4 ~ 1, alpha ~ 0.4); exponent 2/5 also from memory"),
    dict(key="bk_h_wide", kind="height", c=None, p=0.4, amin=0.0, amax=1e9,
         source="Balmforth & Kerswell 2005, J. Fluid Mech. 538, 399",
         setting="wide channel; constant material-dependent",
         checked="abstract", checked_note="abstract: H/h_inf ~ a^0.6 in wide channels, i.e. h_inf/L ~ a^0.4"),
    dict(key="bk_h_narrow", kind="height", c=None, p=0.5, amin=0.0, amax=1e9,
         source="Balmforth & Kerswell 2005, J. Fluid Mech. 538, 399",
         setting="narrow slot; constant material-dependent",
         checked="abstract", checked_note="abstract: H/h_inf ~ a^0.5 in narrow slots, i.e. h_inf/L ~ a^0.5"),
    dict(key="rods_h", kind="height", c=1.0 / 1.42, p=1.0 / 3.0, amin=0.65, amax=1e9,
         source="'Failure mechanism of true 2D granular flows', arXiv:1512.05180 (2015)",
         setting="true 2D: aluminium rods, no side walls (H_f = H_i for a < 0.65)",
         checked="abstract", checked_note="abstract: h0/h = 1.42 a^(2/3) for a > 0.65, i.e. h/d0 = a^(1/3)/1.42"),
]
SHORT_NAMES = {"lube": "Lube et al. 2005", "laj": "Lajeunesse et al. 2005",
               "bk": "Balmforth & Kerswell 2005", "rods": "2D rods, arXiv:1512.05180"}
PUB_STYLE = {"lube": ("k", "-"), "laj": ("0.45", "--"), "bk": ("tab:purple", ":"), "rods": ("tab:olive", "-.")}


def law_value(law, a):
    return law["c"] * a ** law["p"]


# ------------------------------------------------------------------------------- reading
def final_height(run):
    """H_f: the largest height of profiles.csv at its last output time (m), and that time."""
    prof = run.profiles
    if not prof:
        return float("nan"), float("nan"), float("nan")
    t_last = prof.times[-1]
    block = prof.at(t_last)
    h = block["h"]
    hmax = float(np.nanmax(h))
    # where it lies: the first column within 1e-3 H_f of the maximum (a flat top: its wall end)
    i = int(np.argmax(h >= hmax - 1e-3 * hmax))
    return hmax, float(t_last), float(block["x"][i])


def read_run(folder):
    name = os.path.basename(folder)
    m = NAME_RE.match(name)
    if not m:
        return None
    r = dict(name=name, tag="a" + m.group(1), cells=int(m.group(2)), variant=m.group(3))
    run = gr.Run(folder, must_exist=False)
    s = run.summary if run.has("summary.json") else {}
    r["status"] = s.get("status", "missing")
    if r["status"] != "completed":
        r["ok"] = False
        return r
    case = run.case
    Li = s.get("gate_x_m") or case["initial"]["x1"]
    Hi = s.get("column_height_m") or case["initial"]["y1"]
    Lx, Ly = case["domain"]["Lx"], case["domain"]["Ly"]
    h = Ly / case["grid"]["n"]
    d = run.diagnostics
    t = d["t"]
    t_end = float(t[-1])
    late = t >= t_end - STOP_WINDOW - 1e-9
    front_move = float(np.max(d["front_x"][late]) - np.min(d["front_x"][late]))
    speed_end = float(d["max_speed_granular"][-1])
    Hf, t_prof, x_Hf = final_height(run)
    r.update(ok=True, a=case["initial"]["y1"] / case["initial"]["x1"], Li=Li, Hi=Hi, Lx=Lx, Ly=Ly,
             h=h, nx=s.get("nx"), ny=s.get("ny"), t_end=t_end, Lf=s["runout_m"],
             Lmax=s["max_front_x_m"], Hw=s["backwall_height_m"], Hf=Hf, t_prof=t_prof, x_Hf=x_Hf,
             tf=s.get("tf_s"), t3=s.get("t3_s"), speed_end=speed_end, front_move=front_move,
             wall=s.get("wall_s", float("nan")), steps=s.get("steps"),
             dV=s.get("volume_change_pct", float("nan")),
             side_W=case.get("boundary", {}).get("side_walls", {}).get("width", 0.0))
    r["runout"] = (r["Lf"] - Li) / Li
    r["height"] = Hf / Li
    r["height_wall"] = r["Hw"] / Li
    r["clear_cells"] = (Lx - r["Lmax"]) / h
    r["Hf_at_wall"] = x_Hf < h  # the maximum in the first column of cells, on the back wall
    r["stopped"] = speed_end < STOP_SPEED and front_move < STOP_FRONT_M
    return r


# ------------------------------------------------------------------------------- analysis
def fit_power(a, y):
    """c, p and the standard error of p of log y = log c + p log a (least squares)."""
    x, z = np.log(np.asarray(a)), np.log(np.asarray(y))
    n = len(x)
    A = np.vstack([np.ones(n), x]).T
    coef, res, *_ = np.linalg.lstsq(A, z, rcond=None)
    lc, p = coef
    if n > 2:
        resid = z - A @ coef
        s2 = float(resid @ resid) / (n - 2)
        sp = math.sqrt(s2 / float(((x - x.mean()) ** 2).sum()))
        rms = math.sqrt(float(resid @ resid) / n)
    else:
        sp, rms = float("nan"), 0.0
    return math.exp(lc), p, sp, rms


def fit_fixed_p(a, y, p):
    """c of y = c a^p for a given p (least squares in log space: the geometric mean)."""
    return math.exp(float(np.mean(np.log(y) - p * np.log(a))))


def fmt(x, nd=3):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    return f"{x:.{nd}f}"


def main(argv):
    if len(argv) != 4:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    root, out_md, fig_dir = argv[1:]
    runs = []
    for n in sorted(os.listdir(root)) if os.path.isdir(root) else []:
        if os.path.isdir(os.path.join(root, n)):
            r = read_run(os.path.join(root, n))
            if r:
                r["source"] = "run"
                runs.append(r)
    # A run no longer on disk is read from the page's JSON (records.py).
    json_path = records.json_path(out_md)
    kept_only = records.merge(json_path, {r["name"]: r for r in runs},
                              lambda r: {k: v for k, v in r.items() if k != "source"})
    from_record = sorted(kept_only)
    runs = sorted(runs + [dict(r, source="record") for r in kept_only.values()],
                  key=lambda r: r["name"])
    done = [r for r in runs if r["ok"]]
    variants = sorted({r["variant"] for r in runs}, key=lambda v: (list(VARIANT_LABELS).index(v)
                                                                   if v in VARIANT_LABELS else 99, v))
    grids = sorted({r["cells"] for r in done})
    by = {(r["tag"], r["cells"], r["variant"]): r for r in done}
    tags = sorted({r["tag"] for r in done}, key=lambda t: min(x["a"] for x in done if x["tag"] == t))
    # fine: the finest grid that every aspect ratio has (the fits' grid); extra: finer grids that
    # only some aspect ratios have (a check of the grid convergence)
    common = [g for g in grids if all(any((t, g, v) in by for v in variants) for t in tags)]
    fine = max(common) if common else (max(grids) if grids else None)
    coarse = min(grids) if grids else None
    extra = [g for g in grids if fine is not None and g > fine]

    # (a, grid) of the two grids every aspect ratio has where the gate variant has no run
    both_missing = [f"a = {min(x['a'] for x in done if x['tag'] == t):g} at {g}" for g in
                    sorted({coarse, fine} - {None}) for t in tags
                    if "both" in variants and (t, g, "both") not in by]
    L = []
    w = L.append
    w("# Case A's material across aspect ratios (issue 21)")
    w("")
    rel = " ".join(os.path.relpath(os.path.abspath(x), ROOT) for x in argv[1:])
    w(f"*Generated by `/usr/bin/python3 scripts/validation/aspect_ratio.py {rel}`, which "
      "`scripts/validation/aspect_ratio.sh` calls after its runs (the command that made this page: "
      "`scripts/validation/aspect_ratio.sh`); do not edit by hand. Machine: a shared 2-core machine "
      "(another job on the other core), one MPI rank per run, `nice`.*")
    w("")
    w(f"Each run's figures are also kept in `{os.path.basename(json_path)}` beside this page; a run "
      "no longer on disk is listed from there" + (": " + ", ".join(from_record) if from_record else
                                                  " (none here: every run was read from disk)") + ".")
    w("")
    w("Columns of width L_i and height H_i = a L_i against the back wall (L_i = 0.2 m for a <= 2, "
      "0.1 m for a = 4) with the material and walls of case A (`cases/ar07_rough.toml`: Drucker-Prager "
      "tan 25.5 deg, eta_0 = 0.5 Pa s, rho_s = 1550 kg/m^3, Coulomb tan 25.5 deg on the bottom and "
      "tan 10.5 deg on the back wall, the default clsvof interface), each with the channel's side walls "
      "off (the 2D model) and on (`--set boundary.side_walls.width=0.1 --set "
      "boundary.side_walls.friction_angle=10.5`, the friction of `cases/ar07_rough_channel.toml`), "
      f"at {coarse} and {fine} cells across L_i (the cell is L_i/{coarse} and L_i/{fine})"
      + (f", and for some aspect ratios also at {', '.join(map(str, extra))} cells across L_i, a check of the "
         "grid convergence" if extra else "") +
      "; domains and end times are in `scripts/validation/aspect_ratio.sh` and below. In `nowalls` and `walls` the column is "
      "released at t = 0; `both` adds to `walls` the gate of `cases/ar07_rough_channel.toml` at x = L_i (lifted at "
      "2.333 m/s, tan 10.5 deg, its plate one coarse cell below the domain's top)" + (
          f"; no completed run with it: {', '.join(both_missing)} cells across L_i" if both_missing else "") + ".")
    w("")
    w("Quantities: the normalised runout (L_f - L_i)/L_i with L_f = `runout_m` of summary.json (the front "
      "at the end, from the back wall); the final height H_f/L_i with H_f the **largest height of the "
      "deposit** at the last output time of `profiles.csv` (the top of the granular phase in each column of "
      "cells, sub-cell from phi; `x(H_f)` is the centre of the first column within 0.1 % of it). The column "
      "`back wall` gives `backwall_height_m`/L_i (summary.json), the usual height for a half-column against "
      "a wall; the two differ where the deposit's top is not on the wall or by the half cell between the "
      "wall and the profile's first column.")
    w("")

    # ---- domains
    w("## Domains")
    w("")
    w("| a | L_i (m) | H_i (m) | Lx (m) | Ly (m) | t_end (s) | grids (nx x ny) |")
    w("|---|---|---|---|---|---|---|")
    for tag in tags:
        rr = sorted([r for r in done if r["tag"] == tag], key=lambda r: r["cells"])
        r0 = rr[0]
        gl = ", ".join(sorted({f"{r['nx']} x {r['ny']}" for r in rr}, key=lambda t: int(t.split()[0])))
        w(f"| {r0['a']:g} | {r0['Li']:.3g} | {r0['Hi']:.3g} | {r0['Lx']:g} | {r0['Ly']:g} | {r0['t_end']:g} | {gl} |")
    w("")

    # ---- per-run table
    w("## Runs")
    w("")
    w(f"`stopped`: the largest granular speed at the end (diagnostics.csv, `max_speed_granular`) below "
      f"{STOP_SPEED * 1e3:g} mm/s and the front moving less than {STOP_FRONT_M * 1e3:g} mm over the last "
      f"{STOP_WINDOW:g} s; tf = summary's `tf_s` (from then on the granular speed stays below 1 mm/s). "
      "`clear` is the distance from the furthest front to the right wall, in cells of that grid. "
      "Wall time: `wall_s` of summary.json.")
    w("")
    w("| run | a | grid (nx x ny) | t_end (s) | status | (L_f - L_i)/L_i | H_f/L_i | x(H_f) (m) | back wall / L_i | "
      "furthest front (m) | clear (cells) | tf (s) | speed at end (m/s) | front moved in last 0.2 s (mm) | "
      "stopped | dV/V (%) | wall (s) |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in sorted(runs, key=lambda r: (r["tag"], r["cells"], variants.index(r["variant"]))):
        if not r["ok"]:
            w(f"| {r['name']} | | | | {r['status']} | | | | | | | | | | | | |")
            continue
        w(f"| {r['name']} | {r['a']:g} | {r['nx']} x {r['ny']} | {r['t_end']:g} | {r['status']} | "
          f"{r['runout']:.3f} | {r['height']:.3f} | {r['x_Hf']:.4f} | {r['height_wall']:.3f} | {r['Lmax']:.4f} | "
          f"{r['clear_cells']:.0f} | {fmt(r['tf'], 2)} | {r['speed_end']:.1e} | {r['front_move'] * 1e3:.3f} | "
          f"{'yes' if r['stopped'] else '**no**'} | {r['dV']:+.1e} | {r['wall']:.0f} |")
    total = sum(r["wall"] for r in done)
    w("")
    w(f"Total wall time of the runs listed: {total:.0f} s ({total / 60:.1f} min).")
    bad = [r["name"] for r in runs if not r["ok"]]
    notstop = [r["name"] for r in done if not r["stopped"]]
    near = [r["name"] for r in done if r["clear_cells"] < WALL_CELLS]
    off_wall = [r["name"] for r in done if not r["Hf_at_wall"]]
    w("")
    w(f"Runs not completed: {', '.join(bad) if bad else 'none'}. Runs that had not stopped by t_end: "
      f"{', '.join(notstop) if notstop else 'none'}. Runs whose front came within {WALL_CELLS} cells of "
      f"the right wall: {', '.join(near) if near else 'none'}. Runs whose deposit is highest away from "
      f"the back wall's column of cells: {', '.join(off_wall) if off_wall else 'none'}.")
    w("")

    # ---- grid convergence
    w("## Grid convergence")
    w("")
    w(f"Relative difference between successive grids, (coarser - finer)/finer; grids in cells across L_i. "
      "With three grids, the observed order p = log2((y_1 - y_2)/(y_2 - y_3)) (none when the "
      "differences change sign or are below 1e-3 relative).")
    w("")
    for q, qname in (("runout", "(L_f - L_i)/L_i"), ("height", "H_f/L_i")):
        pairs = list(zip(grids[:-1], grids[1:]))
        w(f"{qname}:")
        w("")
        w("| a | variant | " + " | ".join(str(g) for g in grids) + " | " +
          " | ".join(f"{g0} vs {g1}" for g0, g1 in pairs) + (" | p |" if len(grids) >= 3 else " |"))
        w("|---|---|" + "---|" * (len(grids) + len(pairs) + (1 if len(grids) >= 3 else 0)))
        for tag in tags:
            for v in variants:
                rr = [by.get((tag, g, v)) for g in grids]
                if sum(1 for r in rr if r) < 2:
                    continue
                a = next(r["a"] for r in rr if r)
                vals = [fmt(r[q]) if r else "–" for r in rr]
                dif = []
                for g0, g1 in pairs:
                    r0, r1 = by.get((tag, g0, v)), by.get((tag, g1, v))
                    dif.append(f"{(r0[q] - r1[q]) / r1[q]:+.1%}" if r0 and r1 else "–")
                line = f"| {a:g} | {v} | " + " | ".join(vals) + " | " + " | ".join(dif) + " |"
                if len(grids) >= 3:
                    pv = "–"
                    if all(rr[:3]):
                        d1, d2 = rr[0][q] - rr[1][q], rr[1][q] - rr[2][q]
                        tiny = 1e-3 * abs(rr[2][q])  # differences this small: no order
                        if d1 * d2 > 0 and abs(d1) > tiny and abs(d2) > tiny:
                            pv = f"{math.log2(d1 / d2):.2f}"
                    line += f" {pv} |"
                w(line)
        w("")

    # ---- side-wall effect
    if "nowalls" in variants and "walls" in variants:
        w("## Effect of the side walls")
        w("")
        w("Relative change of each quantity with the side walls on, (on - off)/off, on each grid.")
        w("")
        w("| a | grid | runout off | runout on | change | H_f/L_i off | H_f/L_i on | change |")
        w("|---|---|---|---|---|---|---|---|")
        for tag in tags:
            for g in grids:
                r0, r1 = by.get((tag, g, "nowalls")), by.get((tag, g, "walls"))
                if r0 and r1:
                    w(f"| {r0['a']:g} | {g} | {r0['runout']:.3f} | {r1['runout']:.3f} | "
                      f"{(r1['runout'] - r0['runout']) / r0['runout']:+.1%} | {r0['height']:.3f} | "
                      f"{r1['height']:.3f} | {(r1['height'] - r0['height']) / r0['height']:+.1%} |")
        w("")

    # ---- fits
    w("## Power-law fits c a^p (finer grid)")
    w("")
    w(f"Least squares of log y on log a over the points of the finest grid that every aspect ratio has "
      f"({fine} cells across L_i); s_p is "
      "the standard error of p (from the residuals; none for two points), rms the rms residual in log y. "
      "Ranges: the whole range, and the two halves that meet at a = 1: the published runout laws are "
      "linear in a below a0 ~ 1.8-3 and go as a^(2/3) above it; with five aspect ratios, a split at a = 2 "
      "would leave two points above it, so the halves are a <= 1 (0.5, 0.7, 1) and a >= 1 (1, 2, 4). "
      "The local exponent between successive aspect ratios, d log y / d log a, shows where the curve "
      "bends. Last columns: the constant of the published exponents fitted with p held (1 over a <= 1, "
      "2/3 over a >= 2), to set beside Lube's 1.2 and 1.9 and Lajeunesse's 1.8 and 2.3.")
    w("")
    fits = {}
    w("| quantity | variant | range | points | c | p | s_p | rms | c with p = 1 (a <= 1) | c with p = 2/3 (a >= 2) |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    for q, qname in (("runout", "(L_f - L_i)/L_i"), ("height", "H_f/L_i")):
        for v in variants:
            pts = sorted([r for r in done if r["cells"] == fine and r["variant"] == v], key=lambda r: r["a"])
            if len(pts) < 2:
                continue
            a = np.array([r["a"] for r in pts])
            y = np.array([r[q] for r in pts])
            lo, hi = a <= 1 + 1e-9, a >= 2 - 1e-9
            c1 = fit_fixed_p(a[lo], y[lo], 1.0) if lo.any() else float("nan")
            c23 = fit_fixed_p(a[hi], y[hi], 2.0 / 3.0) if hi.any() else float("nan")
            for rname, amin, amax in FIT_RANGES:
                sel = (a >= amin) & (a <= amax)
                if sel.sum() < 2:
                    continue
                c, p, sp, rms = fit_power(a[sel], y[sel])
                fits[(q, v, rname)] = (c, p, sp, a[sel].min(), a[sel].max())
                extra = f"{c1:.2f} | {c23:.2f}" if rname.startswith("all") else " | "
                w(f"| {qname} | {v} | {rname} | {int(sel.sum())} | {c:.3f} | {p:.3f} | {fmt(sp)} | "
                  f"{rms:.3f} | {extra} |")
    w("")
    w("Local exponents d log y / d log a between successive aspect ratios (finer grid):")
    w("")
    w("| quantity | variant | " + " | ".join(f"{tags[i]}-{tags[i + 1]}" for i in range(len(tags) - 1)) + " |")
    w("|---|---|" + "---|" * max(len(tags) - 1, 0))
    for q, qname in (("runout", "(L_f - L_i)/L_i"), ("height", "H_f/L_i")):
        for v in variants:
            cells = []
            for i in range(len(tags) - 1):
                r0, r1 = by.get((tags[i], fine, v)), by.get((tags[i + 1], fine, v))
                cells.append(fmt(math.log(r1[q] / r0[q]) / math.log(r1["a"] / r0["a"]), 2)
                             if r0 and r1 else "–")
            w(f"| {qname} | {v} | " + " | ".join(cells) + " |")
    w("")

    # ---- published laws
    w("## Published laws")
    w("")
    w("Each law as carried by `PUBLISHED` in `scripts/validation/aspect_ratio.py`. *checked*: **abstract** = "
      "read in the paper's abstract (a copy found with the search tool); **secondary** = read only in a "
      "secondary source (named), not in the paper itself; **recalled** = from memory, found in no source "
      "during this work. The laws' channel widths could not be checked in any source found: for the "
      "experiments they are not given here. Balmforth & Kerswell give exponents only (their constants "
      "depend on the material); the figures draw them as slope guides through the finer grid's value at "
      "a = 1 (side walls off).")
    w("")
    w("| quantity | law | range of a | setting | source | checked |")
    w("|---|---|---|---|---|---|")
    for law in PUBLISHED:
        q = "(L_f - L_i)/L_i" if law["kind"] == "runout" else "H_f/L_i"
        pm = f" +- {law['pm']:g}" if "pm" in law else ""
        expr = (f"{law['c']:.3g} a^{law['p']:.3g}" if law["c"] is not None else f"~ a^({law['p']:g}{pm})")
        rng = ("all" if law["amin"] <= 0 and law["amax"] > 1e8 else
               f"a < {law['amax']:g}" if law["amin"] <= 0 else
               f"a > {law['amin']:g}" if law["amax"] > 1e8 else f"{law['amin']:g} < a < {law['amax']:g}")
        w(f"| {q} | {expr} | {rng} | {law['setting']} | {law['source']} | **{law['checked']}**: "
          f"{law['checked_note']} |")
    w("")
    w("Not in the table: Staron & Hinch 2005 (J. Fluid Mech. 545, 1; 2D contact-dynamics discs): their "
      "abstract (checked) says only that the normalised runout has a power-law dependence on a, "
      "'incompatible with a simple friction model', and that the deposit's shape depends on a alone; "
      "their coefficients and exponents were not found in any source here (an a^(2/3) branch for large a is "
      "recalled, not checked).")
    w("")

    # ---- comparison
    w("## Comparison at the aspect ratios run")
    w("")
    w("The published laws with constants, evaluated where a lies in their range, beside the values of the "
      f"{fine}-cell grid. Case A's own runout against the grid (a = 0.7, side walls off, 32 to 256 cells "
      "across L_i) is in `docs/interface_compare.md`.")
    w("")
    laws_c = [law for law in PUBLISHED if law["c"] is not None]
    for kind, qname in (("runout", "(L_f - L_i)/L_i"), ("height", "H_f/L_i")):
        ks = [law for law in laws_c if law["kind"] == kind]
        w(f"{qname}:")
        w("")
        w("| a | " + " | ".join(f"granflow {v}" for v in variants) + " | " +
          " | ".join(law["key"] for law in ks) + " |")
        w("|---|" + "---|" * (len(variants) + len(ks)))
        for tag in tags:
            rr = [by.get((tag, fine, v)) for v in variants]
            a = next(r["a"] for r in rr if r)
            vals = [fmt(r[kind]) if r else "–" for r in rr]
            pub = [fmt(law_value(law, a)) if law["amin"] <= a <= law["amax"] else "" for law in ks]
            w(f"| {a:g} | " + " | ".join(vals) + " | " + " | ".join(pub) + " |")
        w("")
        w("Keys: " + "; ".join(f"{law['key']} = {SHORT_NAMES[law['key'].split('_')[0]]} "
                               f"({law['checked']})" for law in ks) + ".")
        w("")
        w(f"Ratio granflow / law ({qname}, finer grid), where a lies in the law's range:")
        w("")
        w("| a | variant | " + " | ".join(law["key"] for law in ks) + " |")
        w("|---|---|" + "---|" * len(ks))
        for tag in tags:
            for v in variants:
                r = by.get((tag, fine, v))
                if not r:
                    continue
                rat = [f"{r[kind] / law_value(law, r['a']):.2f}" if law["amin"] <= r["a"] <= law["amax"] else ""
                       for law in ks]
                w(f"| {r['a']:g} | {v} | " + " | ".join(rat) + " |")
        w("")

    # ---- summary (numbers of the tables above), inserted after the introduction
    S = ["## Summary", ""]
    S.append(f"From the tables below ({len(done)} completed runs of {len(runs)}; finer grid = {fine} cells "
             "across L_i):")
    S.append("")
    for v in variants:
        f_all = fits.get(("runout", v, FIT_RANGES[0][0]))
        f_lo = fits.get(("runout", v, FIT_RANGES[1][0]))
        f_hi = fits.get(("runout", v, FIT_RANGES[2][0]))
        h_lo = fits.get(("height", v, FIT_RANGES[1][0]))
        h_hi = fits.get(("height", v, FIT_RANGES[2][0]))
        parts = []
        if f_all:
            parts.append(f"runout {f_all[0]:.2f} a^{f_all[1]:.2f} over all a")
        if f_lo and f_hi:
            parts.append(f"{f_lo[0]:.2f} a^{f_lo[1]:.2f} for a <= 1 and {f_hi[0]:.2f} a^{f_hi[1]:.2f} for a >= 1")
        if h_lo and h_hi:
            parts.append(f"final height {h_lo[0]:.2f} a^{h_lo[1]:.2f} for a <= 1 and "
                         f"{h_hi[0]:.2f} a^{h_hi[1]:.2f} for a >= 1")
        if parts:
            S.append(f"- {VARIANT_LABELS.get(v, v)}: " + "; ".join(parts) + ".")
    for g0, g1 in zip(grids[:-1], grids[1:]):
        for q in ("runout", "height"):
            dq = [(abs((by[(t, g0, v)][q] - by[(t, g1, v)][q]) / by[(t, g1, v)][q]), t, v)
                  for t in tags for v in variants if (t, g0, v) in by and (t, g1, v) in by]
            if dq:
                worst, best = max(dq), min(dq)
                S.append(f"- Grids {g0} and {g1} cells across L_i ({', '.join(sorted({t for _, t, _ in dq}))}): "
                         f"the {q} differs by {best[0]:.1%} to {worst[0]:.1%} (largest: {worst[1]}, {worst[2]}).")
    if "nowalls" in variants and "walls" in variants:
        ch = [((by[(t, fine, 'walls')]['runout'] - by[(t, fine, 'nowalls')]['runout'])
               / by[(t, fine, 'nowalls')]['runout'], by[(t, fine, 'nowalls')]['a'])
              for t in tags if (t, fine, "walls") in by and (t, fine, "nowalls") in by]
        if ch:
            S.append("- The side walls shorten the runout (finer grid) by " +
                     ", ".join(f"{-c:.1%} at a = {a:g}" for c, a in ch) + ".")
    for kind in ("runout", "height"):
        for v in variants:
            bits = []
            for law in PUBLISHED:
                if law["kind"] != kind or law["c"] is None:
                    continue
                rs = [(by[(t, fine, v)][kind] / law_value(law, by[(t, fine, v)]["a"]), by[(t, fine, v)]["a"])
                      for t in tags if (t, fine, v) in by and law["amin"] <= by[(t, fine, v)]["a"] <= law["amax"]]
                if rs:
                    bits.append(f"{law['key']} {min(x for x, _ in rs):.2f}-{max(x for x, _ in rs):.2f} "
                                f"(a = {', '.join(f'{a:g}' for _, a in rs)})")
            if bits:
                S.append(f"- {kind}, {v}: granflow / published law = " + "; ".join(bits) + ".")
    S.append(f"- Not completed: {', '.join(bad) if bad else 'none'}; not stopped by t_end: "
             f"{', '.join(notstop) if notstop else 'none'}; front within {WALL_CELLS} cells of the far wall: "
             f"{', '.join(near) if near else 'none'}.")
    S.append("")
    cut = L.index("## Domains")
    L[cut:cut] = S

    os.makedirs(os.path.dirname(os.path.abspath(out_md)), exist_ok=True)
    with open(out_md, "w") as f:
        f.write("\n".join(L))
    make_figures(done, variants, grids, fine, fig_dir, by, tags)
    print(f"wrote {out_md}, {fig_dir}/aspect_runout.png, {fig_dir}/aspect_height.png "
          f"({len(done)} completed runs of {len(runs)})")
    return 0


def make_figures(done, variants, grids, fine, fig_dir, by, tags):
    out = figstyle.Output(fig_dir)
    agrid = np.logspace(np.log10(0.4), np.log10(5.0), 200)
    for kind, fname, ylabel in (("runout", "aspect_runout.png", r"$(L_f - L_i)/L_i$"),
                                ("height", "aspect_height.png", r"$H_f/L_i$")):
        fig, ax = plt.subplots(figsize=(6.4, 4.8))
        for v in variants:
            col = VARIANT_COLORS.get(v, "tab:gray")
            for g in grids:
                pts = sorted([r for r in done if r["variant"] == v and r["cells"] == g], key=lambda r: r["a"])
                if not pts:
                    continue
                filled = g == fine
                if g > fine:
                    ax.plot([r["a"] for r in pts], [r[kind] for r in pts], "^", color=col, ms=7, mfc="none",
                            label=f"granflow, {VARIANT_LABELS.get(v, v)}, {g} cells/L")
                    continue
                ax.plot([r["a"] for r in pts], [r[kind] for r in pts], "-" if filled else ":",
                        color=col, marker="o" if filled else "s", mfc=col if filled else "none",
                        label=f"granflow, {VARIANT_LABELS.get(v, v)}, {g} cells/L")
                for r in pts:
                    if not r["stopped"]:
                        ax.plot(r["a"], r[kind], "x", color="k", ms=10)
        anchor = by.get(("a10", fine, "nowalls"))
        for law in PUBLISHED:
            if law["kind"] != kind:
                continue
            colr, ls = PUB_STYLE[law["key"].split("_")[0]]
            lo, hi = max(law["amin"], 0.4), min(law["amax"], 5.0)
            aa = agrid[(agrid >= lo) & (agrid <= hi)]
            if len(aa) < 2:
                continue
            short = SHORT_NAMES[law["key"].split("_")[0]]
            if law["c"] is None:
                if not anchor:
                    continue
                yy = anchor[kind] * (aa / anchor["a"]) ** law["p"]
                lab = f"{short}: slope {law['p']:g}, {law['setting'].split(';')[0]} [{law['checked']}]"
                ax.plot(aa, yy, ls, color=colr, lw=1.0, label=lab)
            else:
                yy = law_value(law, aa)
                lab = f"{short}: {law['c']:.3g} a^{law['p']:.3g} [{law['checked']}]"
                ax.plot(aa, yy, ls, color=colr, lw=1.3, label=lab)
        if kind == "height":
            aa = agrid[agrid <= 1.5]
            ax.plot(aa, aa, color="0.7", lw=0.8, label=r"$H_f = H_i$ (top not reached)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(r"aspect ratio $a = H_i/L_i$")
        ax.set_ylabel(ylabel)
        ax.set_xticks([0.5, 0.7, 1, 2, 4])
        ax.get_xaxis().set_major_formatter(plt.matplotlib.ticker.ScalarFormatter())
        ax.set_yticks([0.5, 1, 2, 5, 10] if kind == "runout" else [0.5, 0.7, 1, 1.5, 2])
        ax.get_yaxis().set_major_formatter(plt.matplotlib.ticker.ScalarFormatter())
        ax.get_yaxis().set_minor_formatter(plt.matplotlib.ticker.NullFormatter())
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
        ax.set_title(figstyle.wrap(
            f"Case A's material: {'normalised runout' if kind == 'runout' else 'final height'} against a "
            "(x: had not stopped)", 6.0, 10), fontsize=10)
        ax.legend(fontsize=6, loc="upper left" if kind == "runout" else "lower right")
        out.save(fig, fname)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
