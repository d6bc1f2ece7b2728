"""The runs of the validation report and the paper's numbers they are compared with: data.

The runs themselves are listed once, in scripts/validation/run_validation.sh (name, tier,
estimated time, command); `run_list()` reads that list. Here: the reference numbers of the
paper (../shared/reference/paper_targets.md, the paper's text), the groups of runs each study
of the report reads, and `Run`, one run folder of runs/validation/ as the report sees it.
"""
import os
import subprocess
import sys
import tomllib

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import granflow_run as gr  # noqa: E402

RUN_SCRIPT = os.environ.get("RUN_SCRIPT", os.path.join(ROOT, "scripts/validation/run_validation.sh"))
GEN_CMD = "/usr/bin/python3 scripts/validation/make_validation_md.py"
RUN_CMD = "scripts/validation/run_validation.sh"
FIG_REL = "figures/validation"  # relative to docs/

# ---- Reference numbers (paper_targets.md).
A_RUNOUT_EXP, A_RUNOUT_PAPER = 0.475, 0.442
A_BACKWALL = 0.14
A_SPEED_EXP, A_SPEED_PAPER = 0.775, 0.952
A_STAGES = {"t1_s": 0.1, "t2_s": 0.35, "t3_s": 0.45, "tf_s": 1.06}
A_VOL_BOUND = 0.84
A_HP_DEFICIT = 0.24
B_RUNOUT_EXP = 1.213
B_RUNOUT_PAPER = {12.5: 1.282, 15.0: 1.145, 17.5: B_RUNOUT_EXP * (1 - 0.15)}
B_RUNOUT_PAPER_ETA001 = 1.08  # m, 15 deg walls, eta_0 = 0.01 (section 4.2.4)
# Case A at n = 64 with theta = theta_per_dt x dt of eq. 31 changed (10: the paper, a_n64).
THETA_RUNS = [("a_n64_theta1", 1), ("a_n64_theta3", 3), ("a_n64_rf0.5", 10), ("a_n64_theta30", 30),
              ("a_n64_theta100", 100)]
# The augmentation study: (run, case, n, r_factor); 0.5 is the case files' value.
# The 0.5 rows are the case files as they are now (the older a_n64, a_n128, b_n64_w15 were made
# with other fixed-point and solver tolerances).
RF_RUNS = [("a_n64_rf0.125", "A", 64, 0.125), ("a_n64_rf0.25", "A", 64, 0.25),
           ("a_n64_rf0.5", "A", 64, 0.5), ("a_n128_rf0.125", "A", 128, 0.125),
           ("a_n128_rf0.25", "A", 128, 0.25), ("a_n128_rf0.5", "A", 128, 0.5),
           ("b_n64_rf0.125", "B", 64, 0.125), ("b_n64_rf0.25", "B", 64, 0.25),
           ("b_n64_rf0.5", "B", 64, 0.5)]
B_FRONT_ANGLE_PAPER = {12.5: 3.0, 15.0: 4.85, 17.5: 10.0}
B_FRONT_ANGLE_EXP = 2.5
B_SLOPES = {"slope_back_deg": 29.0, "slope_front_deg": 7.0}
B_STAGES = {"t1_s": 0.15, "t2_s": 0.5, "t3_s": 0.9, "tf_s": 1.36}
B_MAXSPEED_PAPER = 1.6
B_LH_MAX = {"paper": 0.56, "exp": 0.49}
B_HP_DEFICIT = 0.50
B_HP_TF = 1.98

# ---- The groups of runs of each table and study (run name, and what varies).
A_GRIDS = [("a_n32", 32), ("a_n64", 64), ("a_n128", 128), ("a_n256", 256)]
B_GRIDS = [("b_n32_w15", 32), ("b_n64_w15", 64), ("b_n128_w15", 128), ("b_n256_w15", 256)]
A_VISCOSITY = [("a_n64", 0.5), ("a_n64_eta0.1", 0.1), ("a_n64_eta0.01", 0.01)]
B_VISCOSITY = [("b_n64_w15", 0.1), ("b_n64_eta0.01", 0.01), ("b_n64_eta0.01_r10", 0.01),
               ("b_n128_w15", 0.1), ("b_n128_eta0.01", 0.01)]
HP_A = ("a_hp_n64", "a_hp_n128")
HP_A_DT1E3 = ("a_hp_n64_dt1e-3", "a_hp_n128_dt1e-3")
HP_B = ("b_hp_n32", "b_hp_n64", "b_hp_n128")
HP_B_DT1E3 = ("b_hp_n32_dt1e-3", "b_hp_n64_dt1e-3", "b_hp_n64_gmres_dt1e-3", "b_hp_n128_dt1e-3")
# The time-step study: (run, case).
DT_RUNS = [("b_n64_w15", "B"), ("b_n64_dt2.5e-4", "B"), ("b_n64_dt1e-4", "B"),
           ("b_n64_dt1e-4_r15", "B"), ("b_n64_dt1e-4_r5", "B"), ("a_n128", "A"),
           ("a_n128_dt1e-4", "A"), ("a_hp_n64_dt1e-3", "A HP"), ("a_hp_n64", "A HP"),
           ("a_hp_n128_dt1e-3", "A HP"), ("a_hp_n128", "A HP"), ("b_hp_n32_dt1e-3", "B HP"),
           ("b_hp_n32", "B HP"), ("b_hp_n64_dt1e-3", "B HP"), ("b_hp_n64", "B HP"),
           ("b_hp_n128_dt1e-3", "B HP"), ("b_hp_n128", "B HP")]
HP_DT_RUNS = {32: [("a_hp_n32_dt1e-3", 1e-3), ("a_hp_n32_dt5e-4", 5e-4),
                   ("a_hp_n32_dt2.5e-4", 2.5e-4), ("a_hp_n32", 1e-4), ("a_hp_n32_dt5e-5", 5e-5)],
              64: [("a_hp_n64_dt1e-3", 1e-3), ("a_hp_n64_dt5e-4", 5e-4),
                   ("a_hp_n64_dt2.5e-4", 2.5e-4), ("a_hp_n64", 1e-4)]}
# Case B: what the paper leaves open, each run against its base run (the case file as it is now,
# b_n64_rf0.5 / b_n128_rf0.5, or the run named for the redistancing interval). b_n64_mass
# departs from the paper and is there for comparison. (run, change, base, n)
B_OPEN = [("b_n64_theta1", "relaxation θ = 1 δt (10 δt)", "b_n64_rf0.5", 64),
          ("b_n64_theta30", "relaxation θ = 30 δt (10 δt)", "b_n64_rf0.5", 64),
          ("b_n64_rf0.25", "augmentation r_factor = 0.25 (0.5)", "b_n64_rf0.5", 64),
          ("b_n64_rf0.125", "augmentation r_factor = 0.125 (0.5)", "b_n64_rf0.5", 64),
          ("b_n64_eps1.5", "interface half-width ε = 1.5 h (1.0 h)", "b_n64_rf0.5", 64),
          ("b_n64_dt1e-4", "dt = 1e-4 s (CFL 0.4, ≤ 1e-3 s), redistancing every 5 ms",
           "b_n64_rf0.5", 64),
          ("b_n64_dt1e-4_r15", "redistancing every 1.5 ms (5 ms), dt = 1e-4 s", "b_n64_dt1e-4", 64),
          ("b_n64_dt1e-4_r5", "redistancing every 0.5 ms (5 ms), dt = 1e-4 s", "b_n64_dt1e-4", 64),
          ("b_n64_mass", "not the paper's: yield stress and wall friction also in the band "
                         "0 < φ < ε", "b_n64_rf0.5", 64),
          ("b_n128_eps1.5", "interface half-width ε = 1.5 h (1.0 h)", "b_n128_rf0.5", 128),
          ("b_n128_ri5ms", "redistancing every 5 ms (every 5 steps, about 3.5 ms)", "b_n128_rf0.5",
           128),
          ("b_n128_ri1.5ms", "redistancing every 1.5 ms (5 ms)", "b_n128_ri5ms", 128),
          ("b_n128_r1", "redistancing every step (every 5 steps)", "b_n128_rf0.5", 128),
          ("b_n256_r1", "redistancing every step (every 5 steps)", "b_n256_w15", 256)]
B_OPEN_LEFT = ("b_n64_eps1.5", "b_n64_dt1e-4_r15", "b_n64_dt1e-4_r5")  # the paper's unknowns


def run_list():
    """{name: {"tier", "est", "cmd"}} of run_validation.sh, in its order."""
    out = subprocess.run(["bash", RUN_SCRIPT], env=dict(os.environ, LIST="psv"),
                         capture_output=True, text=True, check=True).stdout
    runs = {}
    for line in out.splitlines():
        name, tier, est, cmd = line.split("|", 3)
        runs[name] = {"tier": tier, "est": est, "cmd": cmd}
    return runs


class Run:
    """A run folder of runs/validation/ (granflow_run.Run) as the report reads it: `exists`
    (summary.json is there), `ok` (and completed), `s` the summary, `v(key)` a number of it."""

    def __init__(self, name, meta, runs_dir):
        self.name, self.meta = name, meta
        self.dir = os.path.join(runs_dir, name)
        self.run = gr.Run(self.dir, must_exist=False)
        self.exists = self.run.has("summary.json")
        self.s = self.run.summary
        self.status = self.s.get("status", "completed") if self.exists else "not run"
        self.ok = self.status == "completed"

    def v(self, key):
        return self.run.value(key)

    # Tables of the run (empty where the file is missing).
    diag = property(lambda self: self.run.diagnostics)
    prof = property(lambda self: self.run.profiles)
    dep = property(lambda self: self.run.deposit)

    @property
    def case(self):
        """The run's resolved case.toml ({} if it is missing or unreadable)."""
        try:
            return self.run.case
        except tomllib.TOMLDecodeError:
            return {}

    def final_profile(self):
        p = self.prof.at(self.prof["t"].max())
        return p["x"], p["h"]

    @property
    def grid(self):
        return f"{self.s.get('nx')} × {self.s.get('ny')}"

    def make_cmd(self):
        c = f"`ONLY={self.name} {RUN_CMD}` ({self.meta['tier']} tier, about {self.meta['est']})"
        if self.exists and not self.ok:
            d = self.diag
            fr = (f" (front then at x = {d['front_x'][-1]:.3f} m, furthest "
                  f"{np.max(d['front_x']):.3f} m)" if d else "")
            return (f"**{self.status}** at t = {self.v('t_end'):.3f} s{fr}: "
                    f"{self.s.get('message', '?').split(' (in the step')[0]}; made by {c}")
        return c



def load(runs_dir):
    """{name: Run} for every run of run_validation.sh, made or not."""
    return {n: Run(n, m, runs_dir) for n, m in run_list().items()}
