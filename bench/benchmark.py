#!/usr/bin/python3
"""Speed benchmark of granflow on the paper's case A (issue 6), written to docs/PERFORMANCE.md.

usage: benchmark.py --bin build/granflow --src . [--sizes 64 128] [--ranks 1 2] [--repeats 3]
                    [--window 0.1] [--full DIR ...] [--out docs/PERFORMANCE.md]

Runs cases/ar07_rough.toml (DP, eta_0 = 0.5, Coulomb walls) from t = 0 to --window seconds (the
start of the collapse, where the flow accelerates and the fixed point of eq. 31 works hardest)
for each grid.n in --sizes and each rank count in --ranks, --repeats times, and reports medians:
wall time, steps, s/step, cell-steps per second, fixed-point iterations per step, KSP iterations
per viscous and pressure solve, the time split by phase (summary.json time_<phase>_s, from
core/Profile.hpp) and the peak memory. --full adds finished runs (output folders) of the full
physical time with their wall time against the issue's targets. Every run's summary is also
kept in docs/performance.csv.
"""
import argparse
import csv
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
import granflow_run as gr  # noqa: E402

PHASES = ["LevelSetAdvect", "Redistance", "Properties", "Assemble", "ViscousSolve", "Plastic",
          "Anderson", "Pressure", "Output", "Checkpoint"]
# Issue 6's targets on 2 cores (s) and the references quoted there.
TARGETS = {("A", 64): 30, ("A", 128): 240, ("A", 256): 1800, ("B", 256): 2700}
PAPER_CORE_HOURS = {("A", 256): 32 * 72, ("B", 256): 32 * 144}
MARKER = "<!-- Everything below this line is written by hand and kept by bench/benchmark.py. -->"
BASILISK_S = {("A", 64): 34, ("A", 128): 272}


def machine():
    model = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores, {platform.system()} {platform.release()}"


def load():
    try:
        return open("/proc/loadavg").read().split()[0]
    except OSError:
        return "?"


def run_one(args, n, ranks, outdir):
    cmd = []
    if ranks > 1:
        cmd = [os.environ.get("MPIEXEC", "mpirun"), "-n", str(ranks), "--bind-to", "core",
               "--oversubscribe"]
    cmd += [args.bin, "run", os.path.join(args.src, "cases/ar07_rough.toml"),
            "--set", f"grid.n={n}", "--set", f"time.t_end={args.window}",
            "--set", "output.vtk_interval=0", "--set", "output.checkpoint_wall_s=0",
            "--set", "output.progress_interval=0", "--out", outdir]
    t0 = time.time()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall_outer = time.time() - t0
    if r.returncode != 0:
        sys.exit(f"benchmark: run failed ({' '.join(cmd)}):\n{r.stdout[-2000:]}")
    run = gr.Run(outdir)
    s = dict(run.summary)
    d = run.diagnostics  # the first row is t = 0, before any step
    fp, visc, pres = (d[k].tolist()[1:] for k in ("fp_iters", "visc_its", "pres_its"))
    s["wall_outer_s"] = wall_outer
    s["fp_per_step"] = statistics.mean(fp) if fp else 0.0
    s["visc_per_solve"] = sum(visc) / max(sum(fp), 1.0)
    s["pres_per_solve"] = statistics.mean(pres) if pres else 0.0
    return s


def fmt(x, nd=3):
    if x is None:
        return "—"
    if isinstance(x, str):
        return x
    if abs(x) >= 100:
        return f"{x:.0f}"
    return f"{x:.{nd}g}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--src", required=True)
    ap.add_argument("--sizes", type=int, nargs="+", default=[64, 128])
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--repeats", type=int, nargs="+", default=[3],
                    help="runs per grid: one number for all, or one per --sizes entry")
    ap.add_argument("--window", type=float, default=0.1)
    ap.add_argument("--full", nargs="*", default=[])
    ap.add_argument("--out", default="docs/PERFORMANCE.md")
    args = ap.parse_args()
    env_note = f"OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}"
    load0 = load()
    if len(args.repeats) not in (1, len(args.sizes)):
        sys.exit("benchmark: --repeats takes one number or one per --sizes entry")
    reps = dict(zip(args.sizes, args.repeats * len(args.sizes) if len(args.repeats) == 1
                    else args.repeats))
    results = {}
    raw = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in args.sizes:
            for r in args.ranks:
                runs = []
                for k in range(reps[n]):
                    s = run_one(args, n, r, os.path.join(tmp, f"n{n}_r{r}_{k}"))
                    runs.append(s)
                    raw.append({"n": n, "ranks": r, "repeat": k, **{
                        key: s.get(key) for key in ["wall_s", "steps", "s_per_step", "fp_per_step",
                                                    "visc_per_solve", "pres_per_solve",
                                                    "peak_rss_mib_all_ranks"]}})
                    print(f"n = {n}, {r} rank(s), run {k + 1}/{reps[n]}: "
                          f"{s['wall_s']:.2f} s, {s['steps']} steps", flush=True)
                results[(n, r)] = runs
    load1 = load()

    def med(runs, key):
        return statistics.median(float(s.get(key, 0.0)) for s in runs)

    lines = []
    cmd = ("bench/run_benchmark.sh  (= /usr/bin/python3 bench/benchmark.py --bin build/granflow "
           f"--src . --sizes {' '.join(map(str, args.sizes))} --ranks "
           f"{' '.join(map(str, args.ranks))} --repeats {' '.join(map(str, args.repeats))} "
           f"--window {args.window}"
           + (f" --full {' '.join(args.full)}" if args.full else "") + ")")
    lines += ["# Performance of granflow (issue 6)", "",
              f"Generated by `{cmd}` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}.", "",
              f"Machine: {machine()}; {env_note}, ranks bound to cores; load average "
              f"{load0} at the start and {load1} at the end (other work on the machine slows "
              "the figures: compare runs made under the same load).", "",
              f"## Case A, t in [0, {args.window}] s (medians of "
              + ", ".join(f"{reps[n]} run(s) at n = {n}" for n in args.sizes) + ")", "",
              "Case A (`cases/ar07_rough.toml`: Drucker-Prager yield, eta_0 = 0.5, Coulomb "
              "walls, the paper's parameters), adaptive dt (CFL 0.4, dt_max 1e-3 s), "
              "fixed point of eq. 31 with Anderson(5), to the case's `rheology.fp_tol`.", "",
              "| grid (n) | cells | ranks | wall s (min–max) | steps | s/step | cell-steps/s | "
              "fixed-point its/step | viscous KSP its/solve | pressure KSP its/solve | "
              "peak memory MiB (all ranks) |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for (n, r), runs in results.items():
        walls = [s["wall_s"] for s in runs]
        cells = runs[0]["cells"]
        steps = med(runs, "steps")
        w = statistics.median(walls)
        lines.append(f"| {n} | {cells} | {r} | {w:.2f} ({min(walls):.2f}–{max(walls):.2f}) | "
                     f"{steps:.0f} | {w / steps:.4f} | {cells * steps / w:.3g} | "
                     f"{med(runs, 'fp_per_step'):.1f} | {med(runs, 'visc_per_solve'):.1f} | "
                     f"{med(runs, 'pres_per_solve'):.1f} | {med(runs, 'peak_rss_mib_all_ranks'):.0f} |")
    lines += ["", "Time by phase (median seconds, largest rank; `FixedPoint` contains "
              "`ViscousSolve`, `Plastic` and `Anderson`):", "",
              "| grid (n) | ranks | " + " | ".join(PHASES) + " | FixedPoint |",
              "|---|---|" + "---|" * (len(PHASES) + 1)]
    for (n, r), runs in results.items():
        vals = [med(runs, f"time_{p}_s") for p in PHASES]
        lines.append(f"| {n} | {r} | " + " | ".join(f"{v:.2f}" for v in vals) +
                     f" | {med(runs, 'time_FixedPoint_s'):.2f} |")
    if 1 in args.ranks and 2 in args.ranks:
        lines += ["", "2-rank speed-up (median wall time of 1 rank / 2 ranks): " + ", ".join(
            f"n = {n}: {statistics.median(s['wall_s'] for s in results[(n, 1)]) / statistics.median(s['wall_s'] for s in results[(n, 2)]):.2f}"
            for n in args.sizes) + "."]
    if args.full:
        lines += ["", "## Full runs against the targets of issue 6", "",
                  "| run | grid | ranks | t_end s | steps | wall s | target s (2 cores) | "
                  "ratio to target | Basilisk (1 core, no wall friction) | paper |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for d in args.full:
            s = json.load(open(os.path.join(d, "summary.json")))
            case = "B" if "ar2" in s.get("title", "") or "aspect ratio 2" in s.get("title", "") else "A"
            n = s["ny"]
            key = (case, n if case == "A" else 256)
            tgt = TARGETS.get(key)
            lines.append(
                f"| `{d}` ({case}) | {s['nx']} × {s['ny']} | {s['ranks']} | {s['t_end']:.3g} | "
                f"{s['steps']} | {s['wall_s']:.0f} | {tgt if tgt else '—'} | "
                f"{(s['wall_s'] / tgt):.1f} × | {str(BASILISK_S.get(key, '—')) + ' s' if key in BASILISK_S else '—'} | "
                f"{str(PAPER_CORE_HOURS[key]) + ' core-h' if key in PAPER_CORE_HOURS else '—'} |")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    # The hand-written part of the report (what was tried, with its before/after) follows
    # MARKER and is kept when the tables above it are regenerated.
    kept = ""
    if os.path.exists(args.out):
        old = open(args.out).read()
        if MARKER in old:
            kept = old[old.index(MARKER):]
    with open(args.out, "w") as f:
        f.write("\n".join(lines) + "\n\n" + (kept or MARKER + "\n"))
    raw_path = os.path.join(os.path.dirname(os.path.abspath(args.out)), "performance.csv")
    with open(raw_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(raw[0].keys()))
        w.writeheader()
        w.writerows(raw)
    print(f"wrote {args.out} and {raw_path}")


if __name__ == "__main__":
    main()
