"""The document: its head (how it is made, the runs), the criteria table, the sections in
order. `Report` is what the sections share: the runs, the criteria found so far, where the
figures go."""
import datetime
import os

from .case_a import case_a
from .case_b import case_b
from .disagreements import known_disagreements
from .runs import A_GRIDS, B_GRIDS, GEN_CMD, HP_A, HP_B, RUN_CMD
from .text import mins, table


class Report:
    """The runs ({name: Run}), the criteria ((criterion, value, pass/fail/not run, note), in the
    order of the table), the figures' folder and whether figures are made."""

    def __init__(self, R, figs_dir, no_figures=False):
        self.R, self.figs_dir, self.no_figures = R, figs_dir, no_figures
        self.crit = []

    def ok(self, names):
        return [self.R[n] for n in names if self.R[n].ok]

    # The completed runs of the grid studies, coarsest first, and the finest of each model.
    @property
    def doneA(self):
        return [(self.R[k], n) for k, n in A_GRIDS if self.R[k].ok]

    @property
    def fineA(self):
        """The finest case A run with field snapshots (a long run may be made without VTK
        output), else the finest; (run, n) or None."""
        doneA = self.doneA
        withvtk = [x for x in doneA if os.path.exists(os.path.join(x[0].dir, "fields.pvd"))]
        return withvtk[-1] if withvtk else (doneA[-1] if doneA else None)

    @property
    def doneB(self):
        return [(self.R[k], n) for k, n in B_GRIDS if self.R[k].ok]

    @property
    def fineB(self):
        doneB = self.doneB
        return doneB[-1] if doneB else None

    @property
    def hpA(self):
        return [self.R[k] for k in HP_A]

    @property
    def hp_fine(self):
        return next((r for r in reversed(self.hpA) if r.ok), None)

    @property
    def hpB(self):
        return [self.R[k] for k in HP_B]

    @property
    def hpb(self):
        return next((r for r in reversed(self.hpB) if r.ok), None)


def intro(ctx):
    R = ctx.R
    L = []
    versions = sorted({r.s.get("version", "?") for r in R.values() if r.ok})
    L += ["# Validation: granflow against Chupin, Dubois, Phan & Roche 2021 (section 4)", "",
          "Generated, do not edit by hand. The runs are made by", "",
          f"    {RUN_CMD}              # default tier (~35 min on one core)",
          f"    TIER=full {RUN_CMD}    # + the long runs (n = 128, 256; hours to days)", "",
          "(`A128_DIR=/path/to/run` lets an existing case A n = 128 output folder stand for "
          "`a_n128`), and this document and its figures by", "", f"    {GEN_CMD}", "",
          f"from whatever runs exist in `runs/validation/` ({datetime.date.today().isoformat()}; "
          f"granflow version(s) of the runs: {', '.join(versions) or 'none'}). The reference "
          "numbers are those of the paper's text (Chupin, Dubois, Phan, Roche 2021; its "
          "figures are not available as data). Cells read *value (±x % p, ±y % e)*: the relative "
          "difference to the paper's simulation (p) and to the experiment (e). *Runout* is the "
          "front (furthest x where the granular phase touches the bottom) at the end of the run; "
          "*furthest front* its maximum over the run (the two differ because the front recedes "
          "after stopping, see [Known disagreements](#known-disagreements)). Nothing is tuned: "
          "the parameters are the paper's (cases/*.toml), except the time step, which the case "
          "files take from CFL 0.4 capped at 1e-3 s where the paper fixed 1e-4 s (see [Time step]"
          "(#time-step-the-papers-dt--1e-4-s)).", ""]
    return L


def runs_table(ctx):
    """Every run of run_validation.sh: made, failed or not run, with its command."""
    R = ctx.R
    L = []
    L += ["## Runs", ""]
    rows = []
    for r in R.values():
        if r.ok:
            src = (f" (an existing run linked from `{os.path.realpath(r.dir)}`, granflow "
                   f"{r.s.get('version', '?')})" if os.path.islink(r.dir) else "")
            nr = int(r.s.get("ranks", 1) or 1)
            extra = f" on {nr} ranks" if nr > 1 else ""
            if int(r.s.get("restarts", 0) or 0) > 0:
                extra += f", {r.s.get('restarts')} restart(s)"
            rows.append([f"`{r.name}`", r.meta["tier"], r.grid, r.s.get("steps"),
                         mins(r.v("wall_s")) + extra, f"`{r.meta['cmd']}`{src}"])
        elif r.exists:
            rows.append([f"`{r.name}`", r.meta["tier"], f"{r.grid}, **{r.status}** at "
                         f"t = {r.v('t_end'):.3f} s", r.s.get("steps"), mins(r.v("wall_s")),
                         f"`{r.meta['cmd']}`: {r.s.get('message', '?')}"])
        else:
            rows.append([f"`{r.name}`", r.meta["tier"], "**not run**", "", f"(est. {r.meta['est']})",
                         f"`ONLY={r.name} {RUN_CMD}`"])
    L += [table(["run", "tier", "grid", "steps", "wall time", "command"], rows), "",
          "Wall times are `wall_s` of summary.json, one rank unless said, on a 2-core machine that was shared "
          "with other jobs while these runs were made (they may overstate an unloaded core's "
          "time by up to ~30 %).", ""]
    return L


def criteria_table(crit):
    """The criteria of issue 4, placed after the runs table."""
    C = ["## The criteria of issue 4 (\"what it must show\")", "",
         "Each criterion at the finest grid run here (the note says when that is coarser than "
         "the grid the issue names).", "",
         table(["criterion", "granflow", "result", "note"], [list(c) for c in crit]), ""]
    return C


def build(ctx):
    """The lines of the document."""
    head = intro(ctx) + runs_table(ctx)
    body = case_a(ctx) + case_b(ctx)  # these fill ctx.crit
    return head + criteria_table(ctx.crit) + body + known_disagreements(ctx)
