#!/usr/bin/python3
"""The channel's physics of issue 21 from the runs of scripts/validation/channel.sh.

usage: channel.py RUN_ROOT OUT_MD [FIG_DIR]

Reads RUN_ROOT/<name>_<variant>/ (summary.json, diagnostics.csv) for the variants none (the
paper's 2D model), side (the channel's side walls), gate (the gate) and both, and writes OUT_MD:
per run the collapse figures of summary.json (runout, back-wall height, stage times with no time
shift, front speed, deposit slopes and front angle, peak granular pressure over rho_s g H_c, the
largest granular volume change, capped fixed-point steps, wall time); what each variant moves
against `none`; and the figures set against the experiments (paper_targets.md: case A runout
0.475 m, front speed 0.775 m/s, back wall 0.1405 m; case B runout 1.213 m, slopes 29 deg back
and 7 deg front, front angle 2.5 deg); the static/flowing structure of the paper's section 4.2.5
from deposit.csv (cut-off 7.5 % of the largest granular speed: the largest length of the sliding
head L_h, the paper's simulation 0.56 m and the experiment 0.49 m for case B, and the deposit's
share A_d/A at t = 0.3 s, in the constant-speed phase, 20-25 % in the paper). With FIG_DIR
(default: OUT_MD's folder/figures) the front position against time of each case and grid,
all variants: channel_front_<name>.png, or channel_front_<tag>_<name>.png when OUT_MD is
channel_compare_<tag>.md (SET=fine of channel.sh: docs/channel_compare_fine.md).
"""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import granflow_run as gr  # noqa: E402
import records  # noqa: E402
from interface_compare import f, start, variant_runs  # noqa: E402

VARIANTS = ("none", "side", "gate", "both")
# figures compared as relative changes (the others as differences)
REL = {"runout_m", "backwall_height_m", "front_speed_mps", "max_p_granular_ratio", "max_speed",
       "steps"}
# the figures of the tables of differences between two runs
MOVES = ("runout_m", "backwall_height_m", "t1_s", "t2_s", "t3_s", "front_speed_mps",
         "slope_back_deg", "slope_front_deg", "max_p_granular_ratio")


def deltas(s, b, keys):
    """The cells of run s against run b: relative (%) for REL, else differences (times in s with
    3 decimals, angles with 1)."""
    cells = []
    for k in keys:
        x, y = s.get(k), b.get(k)
        if k in REL:
            d = None if x is None or y is None or y == 0 else 100 * (x / y - 1)
            cells.append(f(d, "+.1f") + " %")
        else:
            d = None if x is None or y is None else x - y
            cells.append(f(d, "+.3f" if k.endswith("_s") else "+.1f"))
    return cells


DESCR = {"none": "the paper's 2D model", "side": "side walls", "gate": "gate",
         "both": "side walls and gate"}
# name: column of summary.json, label, format
COLS = [("runout_m", "runout (m)", ".4f"), ("backwall_height_m", "back wall (m)", ".4f"),
        ("t1_s", "t1", ".3g"), ("t2_s", "t2", ".3g"), ("t3_s", "t3", ".3g"), ("tf_s", "tf", ".3g"),
        ("front_speed_mps", "front speed (m/s)", ".3f"), ("slope_back_deg", "back slope (°)", ".1f"),
        ("slope_front_deg", "front slope (°)", ".1f"), ("front_angle_deg", "front angle (°)", ".1f"),
        ("max_p_granular_ratio", "p_max / ρ g H_c", ".3f"), ("L_h_max", "L_h max (m)", ".3f"),
        ("Ad_A_03", "A_d/A at 0.3 s", ".2f")]
# The experiments (../shared/reference/paper_targets.md).
EXPERIMENT = {"a": {"runout_m": 0.475, "front_speed_mps": 0.775, "backwall_height_m": 0.1384 / 0.985},
              "b": {"runout_m": 1.213, "slope_back_deg": 29.0, "slope_front_deg": 7.0,
                    "front_angle_deg": 2.5}}


def load(root):
    runs = {}
    for name, variant, path, s, d in variant_runs(root, VARIANTS):
        s["dv_max"] = abs(d["volume_change_pct"]).max() / 100
        s["front"] = (d["t"], d["front_x"])
        # the largest speed on the grid, air or grains (the CFL condition's)
        s["max_speed"] = float(d["max_speed"].max())
        # where an interrupted run stopped: its summary's checkpoint (steps and wall time are
        # those of summary.json), else its last diagnostics row
        s["t_reached"] = s.get("checkpoint_t") or float(d["t"][-1])
        dep = os.path.join(path, "deposit.csv")
        if os.path.isfile(dep):
            q = gr.read_csv(dep)
            c = abs(q["cutoff"] - 0.075) < 1e-9
            s["L_h_max"] = q["L_h"][c].max() if c.any() else None
            # the output nearest to 0.3 s (a gate's or a wall's steps move them by < dt)
            k = c & (abs(q["t"] - 0.3) < 0.006)
            s["Ad_A_03"] = q["Ad_over_A"][k][0] if k.any() else None
        runs[(name, variant)] = s
    return runs


# The figures of a run that its record in OUT_MD's .json keeps (with the front, thinned).
KEEP = [k for k, _, _ in COLS] + ["status", "warnings_fp_capped_steps", "wall_s", "dv_max",
                                  "steps", "max_speed", "t_reached"]
FRONT_POINTS = 400


def record(s):
    """The JSON record of a run read from disk: KEEP and the front (t, x), at most FRONT_POINTS."""
    t, x = s["front"]
    k = max(1, -(-len(t) // FRONT_POINTS))
    idx = list(range(0, len(t), k))
    if idx[-1] != len(t) - 1:
        idx.append(len(t) - 1)
    r = {key: s.get(key) for key in KEEP}
    r["front"] = [[float(f"{t[i]:.6g}") for i in idx], [float(f"{x[i]:.6g}") for i in idx]]
    return r


def load_with_records(root, path):
    """The runs on disk, and from path (records.merge) the runs no longer on disk; "source" says
    which."""
    disk = load(root) if os.path.isdir(root) else {}
    runs = {k: dict(s, source="run") for k, s in disk.items()}
    for key, r in records.merge(path, {f"{n}_{v}": s for (n, v), s in disk.items()},
                                record).items():
        runs[tuple(key.rsplit("_", 1))] = dict(r, front=tuple(r["front"]), source="record")
    return runs


def main(argv):
    json_path = records.json_path(argv[2]) if len(argv) > 2 else ""
    runs = start(argv, __doc__, lambda root: load_with_records(root, json_path), "channel.py",
                 nargs=(2, 3))
    if isinstance(runs, int):
        return runs
    shown = {k: s for k, s in runs.items() if s.get("status") == "completed"}
    from_record = sorted(f"{n}_{v}" for (n, v), s in runs.items() if s["source"] == "record")
    names = sorted({k[0] for k in runs}, key=lambda n: (n[0], int(re.sub(r"\D", "", n) or 0), n))
    tag = re.fullmatch(r"channel_compare_?(.*)\.md", os.path.basename(argv[2]))
    tag = tag.group(1) if tag else ""
    sh = (f"SET={tag} " if tag else "") + "scripts/validation/channel.sh"
    L = ["# The channel's side walls and the gate (issue 21)" + (f": {tag}" if tag else "") + "\n",
         "*Generated by `scripts/validation/channel.py` from the runs of "
         f"`{sh}` (one rank unless its command says `mpirun`, nice, on the shared 2-core machine; "
         f"`LIST=1 {sh}` prints every command); do not edit by hand.*\n",
         "Variants: " + "; ".join(f"`{v}` = {DESCR[v]}" for v in VARIANTS) + ". Case B runs in a "
         "2 m long channel (`domain.Lx=2.0`) where its command says so; at n = 256 (the paper's "
         "768 × 256) in the case file's 1.38 m, which its front with the side walls or the gate "
         "stays well short of. The stage times are the run's own, with no time shift.\n",
         f"Each run's figures are also kept in `{os.path.basename(json_path)}` beside this page "
         "(its front thinned to at most 400 points); a run no longer on disk is listed from there"
         + (": " + ", ".join(from_record) if from_record else " (none here: every run was read "
            "from disk)") + ".\n",
         "| run | variant | status | " + " | ".join(c[1] for c in COLS) +
         " | max abs dV/V | max speed (m/s) | steps | capped steps | wall (s) |",
         "|---|---|---|" + "---|" * len(COLS) + "---|---|---|---|---|"]
    for n in names:
        for v in VARIANTS:
            s = runs.get((n, v))
            if not s:
                continue
            # a run that did not complete has no collapse figures (they would be those of the
            # time it reached): its status says where it stopped
            done = s.get("status") == "completed"
            status = s.get("status", "?") if done else (
                f"{s.get('status', '?')} at t = {f(s.get('t_reached'), '.3g')} s")
            L.append(f"| {n} | {v} | {status} | " +
                     " | ".join(f(s.get(k) if done else None, fmt) for k, _, fmt in COLS) +
                     f" | {s['dv_max']:.1e} | {f(s.get('max_speed'), '.2f')} | "
                     f"{s.get('steps') or '–'} | {s.get('warnings_fp_capped_steps', '–')} | "
                     f"{f(s.get('wall_s'), '.0f')} |")
    if any((n, "none") in shown and (n, v) in shown for n in names for v in VARIANTS[1:]):
        L += ["\nWhat each piece of physics moves: the figure of the variant minus that of `none` "
              "on the same grid (lengths relative, in %; times in s; angles in degrees).\n",
              "| run | variant | runout | back wall | t1 | t2 | t3 | front speed | back slope | "
              "front slope | p_max |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]

    for n in names:
        b = shown.get((n, "none"))
        if not b:
            continue
        for v in VARIANTS[1:]:
            s = shown.get((n, v))
            if s:
                L.append(f"| {n} | {v} | " + " | ".join(deltas(s, b, MOVES)) + " |")
    tall = [(n, v) for n in names for v in VARIANTS
            if n.endswith("_tall") and (n, v) in shown and (n[:-5], v) in shown]
    if tall:
        L += ["\nThe taller domain (`<run>_tall`: the same cells and more rows above them, as "
              "its command says) minus the case file's (lengths and speeds relative, in %; times "
              "in s; angles in degrees).\n",
              "| run | variant | runout | back wall | t1 | t2 | t3 | front speed | back slope | "
              "front slope | p_max | max speed | steps |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for n, v in tall:
            L.append(f"| {n} | {v} | " + " | ".join(
                deltas(shown[(n, v)], shown[(n[:-5], v)], MOVES + ("max_speed", "steps"))) + " |")
    L += ["\nAgainst the experiments (Mangeney et al. 2010 for case A, Roche et al. 2010 for case B, "
          "as the paper reports them, `../shared/reference/paper_targets.md`): the run's figure "
          "and its difference from the experiment's (relative for lengths and speeds, in degrees "
          "for angles).\n",
          "| run | variant | " + " | ".join(
              f"{k} (exp. {EXPERIMENT[c][k]:g})" for c in ("a", "b") for k in EXPERIMENT[c]) + " |",
          "|---|---|" + "---|" * sum(len(e) for e in EXPERIMENT.values())]
    for n in names:
        c = n[0]
        for v in VARIANTS:
            s = shown.get((n, v))
            if not s or c not in EXPERIMENT:
                continue
            cells = []
            for cc in ("a", "b"):
                for k, e in EXPERIMENT[cc].items():
                    x = s.get(k) if cc == c else None
                    if x is None:
                        cells.append("")
                    elif k.endswith("_deg"):
                        cells.append(f"{x:.1f} ({x - e:+.1f})")
                    else:
                        cells.append(f"{x:.4g} ({100 * (x / e - 1):+.1f} %)")
            L.append(f"| {n} | {v} | " + " | ".join(cells) + " |")
    fig_names = [n for n in names if any((n, v) in shown for v in VARIANTS)
                 and not (n.endswith("_tall") and n[:-5] in names)]
    figs = argv[3] if len(argv) > 3 else os.path.join(os.path.dirname(os.path.abspath(argv[2])), "figures")
    prefix = "channel_front_" + (tag + "_" if tag else "")
    L += ["\nThe front against time, each variant (no time shift): " + ", ".join(
        f"[{n}](figures/{prefix}{n}.png)" for n in fig_names) + "."]
    front_figures(shown, fig_names, figs, prefix)
    with open(argv[2], "w") as fh:
        fh.write("\n".join(L) + "\n")
    print(f"channel.py: wrote {argv[2]} ({len(runs)} runs)")
    return 0


def front_figures(runs, names, folder, prefix):
    import figstyle
    out = figstyle.Output(folder)
    colors = {"none": "tab:blue", "side": "tab:red", "gate": "tab:green", "both": "black"}
    for n in names:
        fig, ax = figstyle.plt.subplots(figsize=(6.4, 4.0))
        for v in VARIANTS:
            s = runs.get((n, v))
            if s:
                ax.plot(*s["front"], color=colors[v], lw=1.3, label=f"{v}: {DESCR[v]}")
            t = runs.get((n + "_tall", v))  # SET=lid: the taller domain's run on the same axes
            if t:
                ax.plot(*t["front"], color=colors[v], lw=1.3, ls="--",
                        label=f"{v}, the taller domain")
        e = EXPERIMENT.get(n[0], {}).get("runout_m")
        if e:
            ax.axhline(e, color="gray", ls="--", lw=1, label=f"experiment's runout {e:g} m")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("front x (m)")
        ax.set_title(f"{n}: the front at the bottom, with no time shift")
        ax.legend(fontsize=8)
        out.save(fig, f"{prefix}{n}.png")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
