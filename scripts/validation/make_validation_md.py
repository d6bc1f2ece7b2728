#!/usr/bin/python3
"""Writes docs/VALIDATION.md: granflow against section 4 of Chupin, Dubois, Phan, Roche 2021.

usage: /usr/bin/python3 scripts/validation/make_validation_md.py [--runs DIR] [--out FILE]
                                                                [--no-figures]

Reads the runs made by scripts/validation/run_validation.sh (runs/validation/<name>/: summary.json,
diagnostics.csv, profiles.csv, deposit.csv, the VTK snapshots), whichever exist: a missing run is
reported as "not run" with the command that makes it. Writes the tables (quantity | experiment |
paper | granflow at each grid, with the relative differences to the paper and to the experiment),
the convergence, viscosity and wall-friction studies, the HP results, the slopes and the
L_h/L_f-against-L_d/L_f fit of case B, the pass/fail of each "must show" criterion of issue 4,
and the figures (docs/figures/validation/: comparison plots made here, and figures of
scripts/plot_collapse.py, each PNG kept under 200 kB).

The reference numbers are those of ../shared/reference/paper_targets.md (the paper's text).
"""
import argparse
import os

from report import document, runs


def included_section(path, title, intro):
    """A section made of an intro and the body of a generated page (its own title dropped), or
    nothing if the page does not exist."""
    if not os.path.isfile(path):
        return []
    with open(path) as f:
        body = f.read().splitlines()
    body = [ln for ln in body if not ln.startswith("# ")]  # its own title
    return ["", f"## {title}", "", intro, ""] + body


def interface_section(path):
    """The paper's scheme next to the mass-conserving interface (issue 18), the table of
    scripts/validation/interface_compare.py (docs/interface_compare.md) if it exists."""
    return included_section(
        path, "The interface methods: the paper's level set and CLSVOF (issue 18)",
        "Every run above is the paper's level set (`interface.method = \"level_set\"`, pinned "
        "by `scripts/validation/run_validation.sh`). The default since issue 18 is the "
        "mass-conserving CLSVOF (`docs/INTERFACE.md`). The paper's cases with both, made by "
        "`scripts/validation/interface_compare.sh` (the table of "
        "`docs/interface_compare.md`; what it says: `docs/INTERFACE.md`, \"The paper's cases, both "
        "methods\": case A's runout is the furthest front with CLSVOF, 4 % past the paper at "
        "n = 128 and 2.3 % at n = 256, converging slowly (observed order 0.27 from n = 64, "
        "not monotone from n = 32); case B's runs 24.5 % past the "
        "paper at n = 64, beyond its domain's far wall, and 18.7 % at n = 128):")


def exact_section(path):
    """The paper's cases with the exact plastic solver next to the paper's scheme (issue 19), the
    tables of scripts/validation/exact_compare.py (docs/exact_compare.md) if it exists."""
    return included_section(
        path, "The exact plastic solver next to the paper's scheme (issue 19)", EXACT_INTRO)


EXACT_INTRO = (
    "The paper's cases with `rheology.solver = \"newton\"` (the plastic step solved exactly by "
    "a semismooth Newton method, theta = 0: truly rigid zones, no relaxation, "
    "`docs/RHEOLOGY.md`) and with the paper's fixed point (the default), both with the default "
    "CLSVOF interface, made by `scripts/validation/exact_compare.sh` (the tables of "
    "`docs/exact_compare.md`). Which grids are still missing, and why, is said in "
    "`docs/STATUS.md` (issue 19).")


def channel_section(path):
    """The channel's side walls and the gate (issue 21), the tables of
    scripts/validation/channel.py (docs/channel_compare.md) if it exists."""
    return included_section(
        path, "The channel's side walls and the gate (issue 21)", CHANNEL_INTRO)


# What the tables of docs/channel_compare.md say (docs/CHANNEL.md has the whole account).
CHANNEL_INTRO = (
    "The physics the paper names as missing, with the default CLSVOF interface: the friction of "
    "the 10 cm channel's side walls and the gate (`docs/CHANNEL.md`), made by "
    "`scripts/validation/channel.sh` (the tables of `docs/channel_compare.md`). The stage "
    "times are the runs' own, with no time shift.")


def channel_fine_section(path):
    """The same on the finer grids (case A at n = 256, case B's `both` at n = 128 and 256),
    `SET=fine scripts/validation/channel.sh` (docs/channel_compare_fine.md) if it exists."""
    return included_section(
        path, "The channel's side walls and the gate on the finer grids (issue 21)",
        CHANNEL_FINE_INTRO)


CHANNEL_FINE_INTRO = (
    "The same on the finer grids: case A at n = 256 (the paper's finest grid) with the side "
    "walls, the gate and both; case B at n = 128 (`none`, `both`) and at the paper's "
    "768 × 256 with the side walls and with both, and case B's 2D model at 768 × 256 in the "
    "2 m channel (`b_n256_2m`, the reference for the side walls' and both's effects at that "
    "grid: docs/CHANNEL.md gives them), made by `SET=fine scripts/validation/channel.sh` (the "
    "tables of `docs/channel_compare_fine.md`). Case A's 2D model (`none`) at n = 256 is in the "
    "paper-case tables above. Case B's gate alone is at the same cell size (768 columns) in a "
    "domain a quarter taller (`b_n256_tall`, 768 × 320 cells: in the case file's domain the air "
    "over the plate held the step near 5e-5 s; the taller domain moves case B's figures by at "
    "most 1.5 % at n = 64 and 128, `docs/channel_compare_lid.md`).")


def channel_lid_section(path):
    """The domain's lid above the gate, `SET=lid scripts/validation/channel.sh`
    (docs/channel_compare_lid.md) if it exists."""
    return included_section(
        path, "The channel's gate under the domain's lid (issue 21)", CHANNEL_LID_INTRO)


CHANNEL_LID_INTRO = (
    "`gate` and `both` in the case files' domains and in domains a quarter taller (the same "
    "cells, more rows above), made by `SET=lid scripts/validation/channel.sh` (the tables of "
    "`docs/channel_compare_lid.md`): the case files' plate ends 2 cm below the lid, and the air "
    "that the collapse drives behind the column returns through that gap while the plate is in "
    "(`docs/CHANNEL.md`, \"The gate's effect on the air, and the lid above it\").")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", default=os.path.join(runs.ROOT, "runs/validation"))
    ap.add_argument("--out", default=os.path.join(runs.ROOT, "docs/VALIDATION.md"))
    ap.add_argument("--no-figures", action="store_true")
    a = ap.parse_args()
    R = runs.load(a.runs)
    figs_dir = os.path.join(os.path.dirname(a.out), runs.FIG_REL)
    if not a.no_figures:
        os.makedirs(figs_dir, exist_ok=True)
    L = document.build(document.Report(R, figs_dir, a.no_figures))
    L += interface_section(os.path.join(os.path.dirname(a.out), "interface_compare.md"))
    L += exact_section(os.path.join(os.path.dirname(a.out), "exact_compare.md"))
    L += channel_section(os.path.join(os.path.dirname(a.out), "channel_compare.md"))
    L += channel_fine_section(os.path.join(os.path.dirname(a.out), "channel_compare_fine.md"))
    L += channel_lid_section(os.path.join(os.path.dirname(a.out), "channel_compare_lid.md"))
    with open(a.out, "w") as f:
        f.write("\n".join(L))
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
