#!/usr/bin/env bash
# levelset.redistance_interval (s): redistancing by simulated time instead of by steps, so that a
# change of dt does not change how often phi is redistanced (docs/VALIDATION.md, time step: each
# redistancing erodes a little granular volume where the interface meets a wall at a shallow
# angle; case B at n = 64 and dt = 1e-4 s runs out to 1.236 m redistanced every 5e-3 s and to
# 0.970 m every 5 steps). Case A (cases/ar07_rough.toml) at grid.n = 16 to t = 0.1 s with a
# fixed time step:
#  1. dt = 1e-3 s: redistance_interval = 5e-3 s is redistance_every = 5, step for step: the same
#     redistancing steps, so diagnostics.csv is identical to the last digit, and 20 redistancings
#     (summary.json `redistancings`).
#  2. dt = 5e-4 s: redistance_interval = 5e-3 s still redistances 20 times (every 10th step),
#     where redistance_every = 5 does it 40 times.
# The level set's redistancing: interface.method = "level_set" (pinned; with the default
# "clsvof" phi is rebuilt from the volume fraction every step and these keys do not apply).
# Usage: bash test_redistance_interval.sh <granflow binary> <source dir>
set -euo pipefail
bin="$1"; src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
common=(--set grid.n=16 --set time.t_end=0.1 --set time.dt_mode=fixed --set output.interval=0.01
        --set output.vtk_interval=0 --set interface.method=level_set)
run() {  # name, extra options...
  local name="$1"; shift
  "$bin" run "$src/cases/ar07_rough.toml" "${common[@]}" "$@" --out "$tmp/$name" \
    > "$tmp/$name.log" 2>&1 || { cat "$tmp/$name.log"; echo "FAIL: run $name"; exit 1; }
}
run steps --set time.dt=1e-3 --set levelset.redistance_every=5 &
run interval --set time.dt=1e-3 --set levelset.redistance_interval=5e-3 &
wait
run half_steps --set time.dt=5e-4 --set levelset.redistance_every=5 &
run half_interval --set time.dt=5e-4 --set levelset.redistance_interval=5e-3 &
wait
PYTHONPATH="$src/scripts" /usr/bin/python3 - "$tmp" <<'PY'
import json, sys
import granflow_run as gr
tmp = sys.argv[1]
ok = True
def summ(name):
    return json.load(open(f"{tmp}/{name}/summary.json"))
def fail(msg):
    global ok
    ok = False
    print("FAIL:", msg)
a = gr.read_csv(f"{tmp}/steps/diagnostics.csv")
b = gr.read_csv(f"{tmp}/interval/diagnostics.csv")
# Everything but the wall-clock columns must agree to the last digit: compared as the file
# writes them (%.17g, which gives back the number read).
skip = {k for k in a.columns if "wall" in k or k.startswith("time_")}
text = "{:.17g}".format
diff = [(text(a["t"][i]), k) for i in range(min(len(a), len(b))) for k in a.columns
        if k not in skip and text(a[k][i]) != text(b[k][i])]
print(f"dt = 1e-3: every 5 steps {summ('steps')['redistancings']} redistancings, every 5e-3 s "
      f"{summ('interval')['redistancings']}; {len(a)} diagnostics rows, {len(diff)} values differ")
if len(a) != len(b) or diff:
    fail(f"redistance_interval = 5e-3 s differs from redistance_every = 5 at dt = 1e-3: {diff[:3]}")
for name, want in (("steps", 20), ("interval", 20), ("half_steps", 40), ("half_interval", 20)):
    got = summ(name)["redistancings"]
    print(f"{name}: {got} redistancings (expected {want})")
    if got != want:
        fail(f"{name}: {got} redistancings, expected {want}")
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
PY
