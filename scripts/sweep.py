#!/usr/bin/python3
"""Runs one granflow case over a list or a grid of parameter values, and tabulates the results.

usage: scripts/sweep.py CASE --vary KEY=V1,V2,... [--vary KEY=...] [--set KEY=VALUE ...]
                        [--out SWEEP_DIR] [--jobs N] [--columns K1,K2,...] [--table FILE]
                        [--granflow BIN] [--dry-run] [-- PETSc options]

Every combination of the --vary values (their grid: the first --vary varies slowest) is one
`granflow run CASE --set KEY=VALUE ...` in its own folder under SWEEP_DIR, named after its
values (e.g. SWEEP_DIR/friction_angle=25.5,n=32). --set values apply to every run. N runs go at
a time (--jobs; default: the number of cores), each on one core (OMP_NUM_THREADS=1), with its
log in SWEEP_DIR/<run>.log. Every combination is checked (`granflow check`) before any runs.

When the runs are done, SWEEP_DIR/sweep.csv (or --table FILE) holds one row per run: its
folder, its status (summary.json), the varied values, one column each, then the --columns of
summary.json (default: runout_m, tf_s, volume_change_pct, steps, wall_s; `granflow_run.py RUN`
lists every key of a run with its unit). A value missing from a summary is left empty.

Resumable: run the same command again after an interruption (Ctrl-C, SIGTERM, a lost node).
A run whose summary.json says "completed" for the same case (the same case file contents, the
same --set values and PETSc options: recorded in SWEEP_DIR/<run>.json) is skipped; an
interrupted one with a checkpoint is continued (`granflow run --restart`); any other is run
again from the start (--overwrite). A Ctrl-C or SIGTERM stops the running runs politely (they
write their checkpoints) and writes the table of what is done so far.

Exit code: 0 when every run completed, 1 when one did not (its status in the table, its log
in SWEEP_DIR), 2 for a bad command line or a combination that `granflow check` refuses, 130
when interrupted.

Example: three friction angles of case A at grid.n = 32, two at a time:

    scripts/sweep.py cases/ar07_rough.toml --vary rheology.friction_angle=20,25.5,30 \\
        --set grid.n=32 --out out/sweep_alpha --jobs 2
    scripts/sweep.py cases/ar07_rough.toml --vary rheology.friction_angle=20,25.5,30 \\
        --vary grid.n=32,64 --out out/sweep_alpha_n     # a 3 x 2 grid: six runs

Needs only the Python standard library and numpy (through scripts/granflow_run.py, the reader of
run folders).
"""
import argparse
import concurrent.futures
import csv
import hashlib
import itertools
import json
import os
import re
import signal
import subprocess
import sys
import threading

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import granflow_run as gr  # noqa: E402  (the reader of run folders, beside this script)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_COLUMNS = ["runout_m", "tf_s", "volume_change_pct", "steps", "wall_s"]


def split_values(text):
    """'20,25.5,30' -> ['20', '25.5', '30']; commas inside [...] or quotes stay
    ('[0, -9.81],[1, -9.76]' -> two arrays)."""
    out, cur, depth, quote = [], "", 0, None
    for ch in text:
        if quote:
            quote = None if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch == "[":
            depth += 1
        elif ch == "]":
            depth -= 1
        elif ch == "," and depth == 0:
            out.append(cur.strip())
            cur = ""
            continue
        cur += ch
    out.append(cur.strip())
    return out


def parse_vary(items, ap):
    """[('rheology.friction_angle', ['20', '25.5', '30']), ...], refusing what is malformed."""
    vary = []
    for item in items:
        key, eq, values = item.partition("=")
        key = key.strip()
        if not eq or not key or key.startswith("-"):
            ap.error(f"--vary {item}: expected KEY=V1,V2,..., e.g. --vary grid.n=32,64")
        vals = split_values(values)
        if any(v == "" for v in vals):
            ap.error(f"--vary {item}: an empty value in the list")
        if len(set(vals)) != len(vals):
            ap.error(f"--vary {item}: a value is listed twice")
        if key in (k for k, _ in vary):
            ap.error(f"--vary {key} is given twice: list all its values in one --vary")
        vary.append((key, vals))
    return vary


def run_name(combo):
    """The folder of a run: its values, the last part of each key ('friction_angle=25.5,n=32'),
    characters a file name should not hold replaced by '_'."""
    parts = [f"{key.split('.')[-1]}={value}" for key, value in combo]
    return re.sub(r"[^A-Za-z0-9=,.+-]", "_", ",".join(parts))


def spec_of(case_text, sets, petsc):
    return {"case_sha256": hashlib.sha256(case_text).hexdigest(), "sets": sets, "petsc": petsc}


class Sweep:
    def __init__(self, args, vary, sets_common, petsc):
        self.a = args
        self.vary = vary
        self.sets_common = sets_common
        self.petsc = petsc
        with open(args.case, "rb") as f:
            self.case_text = f.read()
        self.runs = []  # (name, combo, sets)
        for values in itertools.product(*[v for _, v in vary]):
            combo = list(zip([k for k, _ in vary], values))
            sets = sets_common + [f"{k}={v}" for k, v in combo]
            self.runs.append((run_name(combo), combo, sets))
        names = [r[0] for r in self.runs]
        if len(set(names)) != len(names):
            sys.exit("sweep: two runs would share a folder name (keys with the same last part?)")
        self.procs = {}  # name -> Popen, the runs going on
        self.lock = threading.Lock()
        self.stopping = False

    def env(self):
        e = dict(os.environ, OMP_NUM_THREADS="1")
        if os.geteuid() == 0:
            e.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
            e.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        return e

    def set_args(self, sets):
        return [w for s in sets for w in ("--set", s)]

    def check_all(self):
        """granflow check of every combination: nothing runs if one is refused."""
        bad = 0
        for name, _, sets in self.runs:
            r = subprocess.run([self.a.granflow, "check", self.a.case] + self.set_args(sets) +
                               (["--"] + self.petsc if self.petsc else []),
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                               env=self.env())
            if r.returncode != 0:
                bad += 1
                print(f"sweep: {name}: granflow check refuses it (exit {r.returncode}):\n" +
                      "\n".join("  " + line for line in r.stdout.strip().splitlines()),
                      file=sys.stderr)
        return bad == 0

    def paths(self, name):
        d = os.path.join(self.a.out, name)
        return d, d + ".json", d + ".log"

    def plan(self, name, sets):
        """'skip', 'restart' or 'run' for this run, from its folder and recorded spec."""
        folder, spec_path, _ = self.paths(name)
        want = spec_of(self.case_text, sets, self.petsc)
        try:
            with open(spec_path) as f:
                same = json.load(f) == want
        except (OSError, ValueError):
            same = False
        status = gr.Run(folder, must_exist=False).summary.get("status") \
            if os.path.isdir(folder) else None
        if same and status == "completed":
            return "skip"
        if same and status == "interrupted" and os.path.isdir(os.path.join(folder, "checkpoint")):
            return "restart"
        return "run"

    def launch(self, name, sets):
        folder, spec_path, log_path = self.paths(name)
        what = self.plan(name, sets)
        if what == "skip":
            return name, "skipped (completed before)"
        if what == "restart":
            cmd = [self.a.granflow, "run", "--restart", folder]
        else:
            cmd = [self.a.granflow, "run", self.a.case] + self.set_args(sets) + \
                  ["--out", folder, "--overwrite"]
        if self.petsc:
            cmd += ["--"] + self.petsc
        with self.lock:
            if self.stopping:
                return name, "not started (interrupted)"
            if what == "run":  # what this run is: a later sweep skips it once completed
                with open(spec_path, "w") as f:
                    json.dump(spec_of(self.case_text, sets, self.petsc), f, indent=1)
            log = open(log_path, "a")
            log.write("$ " + " ".join(cmd) + "\n")
            log.flush()
            p = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, env=self.env(),
                                 start_new_session=True)  # Ctrl-C is passed on by us, once
            self.procs[name] = p
        rc = p.wait()
        log.close()
        with self.lock:
            self.procs.pop(name, None)
        return name, f"{'restarted, ' if what == 'restart' else ''}exit {rc}"

    def stop(self, *_):
        """SIGINT/SIGTERM: the running runs get a SIGTERM (they checkpoint and stop)."""
        with self.lock:
            if self.stopping:
                return
            self.stopping = True
            for p in self.procs.values():
                p.send_signal(signal.SIGTERM)
        print("sweep: stopping: the running runs write their checkpoints; run the same command "
              "again to continue", file=sys.stderr)

    def table(self, path):
        rows = []
        keys = [k for k, _ in self.vary]
        header = ["run", "status"] + keys + self.a.columns
        for name, combo, _ in self.runs:
            run = gr.Run(self.paths(name)[0], must_exist=False)
            s = run.summary if os.path.isdir(run.folder) else {}
            row = [name, s.get("status", "not run")] + [v for _, v in combo]
            for c in self.a.columns:
                v = s.get(c)
                row.append("" if v is None else repr(v) if isinstance(v, float) else str(v))
            rows.append(row)
        tmp = path + ".tmp"
        with open(tmp, "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(header)
            w.writerows(rows)
        os.replace(tmp, path)
        return rows

    def go(self):
        os.makedirs(self.a.out, exist_ok=True)
        signal.signal(signal.SIGINT, self.stop)
        signal.signal(signal.SIGTERM, self.stop)
        todo = [(n, s) for n, _, s in self.runs]
        print(f"sweep: {len(todo)} run(s) of {self.a.case} in {self.a.out}, {self.a.jobs} at a time")
        with concurrent.futures.ThreadPoolExecutor(max_workers=self.a.jobs) as pool:
            futures = [pool.submit(self.launch, n, s) for n, s in todo]
            for fut in concurrent.futures.as_completed(futures):
                name, what = fut.result()
                print(f"sweep: {name}: {what}")
        path = self.a.table or os.path.join(self.a.out, "sweep.csv")
        rows = self.table(path)
        done = sum(1 for r in rows if r[1] == "completed")
        print(f"sweep: {done} of {len(rows)} run(s) completed; table: {path}")
        if self.stopping:
            return 130
        return 0 if done == len(rows) else 1


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    petsc = []
    if "--" in argv:
        k = argv.index("--")
        argv, petsc = argv[:k], argv[k + 1:]
    ap = argparse.ArgumentParser(prog="sweep.py", description=__doc__.split("\n\n")[0],
                                 epilog=__doc__.split("\n", 1)[1],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", help="the case file (TOML)")
    ap.add_argument("--vary", action="append", default=[], metavar="KEY=V1,V2,...",
                    help="a case parameter and its values (repeatable: the runs are the grid)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a case parameter for every run (repeatable)")
    ap.add_argument("--out", help="the sweep folder (default out/sweep_<case name>)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                    help="runs at a time (default: the number of cores, %(default)s here)")
    ap.add_argument("--columns", default=",".join(DEFAULT_COLUMNS),
                    help="summary.json keys of the table (default %(default)s)")
    ap.add_argument("--table", help="the CSV table (default SWEEP_DIR/sweep.csv)")
    ap.add_argument("--granflow", default=os.path.join(ROOT, "build", "granflow"),
                    help="the granflow binary (default %(default)s)")
    ap.add_argument("--dry-run", action="store_true",
                    help="list the runs and what a sweep would do with each, run nothing")
    a = ap.parse_args(argv)
    if not a.vary:
        ap.error("at least one --vary KEY=V1,V2,... is needed")
    if a.jobs < 1:
        ap.error(f"--jobs {a.jobs}: must be >= 1")
    if not os.path.isfile(a.case):
        ap.error(f"{a.case}: no such case file")
    if not os.access(a.granflow, os.X_OK):
        ap.error(f"{a.granflow}: no granflow binary there (build it: scripts/build.sh)")
    for s in a.set:
        if "=" not in s or s.startswith("-"):
            ap.error(f"--set {s}: expected KEY=VALUE")
    a.columns = [c.strip() for c in a.columns.split(",") if c.strip()]
    a.out = a.out or os.path.join("out", "sweep_" + os.path.splitext(os.path.basename(a.case))[0])
    vary = parse_vary(a.vary, ap)
    clash = {k for k, _ in vary} & {s.split("=", 1)[0].strip() for s in a.set}
    if clash:
        ap.error(f"{', '.join(sorted(clash))}: both varied and --set")
    sw = Sweep(a, vary, a.set, petsc)
    if a.dry_run:
        for name, _, sets in sw.runs:
            print(f"{sw.plan(name, sets):8s} {os.path.join(a.out, name)}: --set {' --set '.join(sets)}")
        return 0
    if not sw.check_all():
        return 2
    return sw.go()


if __name__ == "__main__":
    sys.exit(main())
