#!/usr/bin/env bash
# Verification of checkpoint and restart (README "Checkpoints, restarts, exit codes").
#  1. Case A in its channel (cases/ar07_rough_channel.toml: Drucker-Prager yield, Coulomb walls,
#     the side walls' friction, the Anderson-accelerated fixed point: the state includes S, s_t
#     and the side walls' s) at grid.n = 16 to t = 0.3 s, once uninterrupted and once
#     killed with SIGTERM after its first checkpoint (every 20 steps), then continued with
#     `granflow run --restart`. The killed run must exit 6 saying how to restart; the
#     continued run must reproduce the uninterrupted one byte for byte (1 rank):
#     diagnostics.csv, probes/bottom.csv, a VTK file written after the restart, the collapse
#     files (profiles.csv, structure.csv, deposit.csv) and the collapse keys of summary.json
#     (stage times from the whole history, restored from the checkpoint); fields.pvd
#     must be valid XML listing every .vtr, the same list as the uninterrupted run's.
#  2. 1 -> 2 ranks: the water dam break (Newtonian: 1 and 2 ranks agree to ~1e-12, see
#     test_mpi_consistency.sh) stopped at time.max_steps = 40 on 1 rank and continued on
#     2 ranks agrees with the uninterrupted 1-rank run to 1e-8 relative (same rule as
#     test_mpi_consistency.sh); its .pvd stays valid.
#  2b. The exact plastic step (rheology.solver = newton), whose Newton iteration starts from the
#     last prediction u~ (checkpointed as velocity_prediction): case A at n = 16 stopped at
#     step 53 and continued reproduces diagnostics.csv byte for byte.
#  3. Bad restarts, each with its exit code and message, none changing the folder: a
#     truncated state.bin (5), a corrupted byte (5), a truncated header (5), a case edited to
#     another grid.n (3), --set of a key a restart may not change (3), no checkpoint (3),
#     --restart with --out (2).
# Usage: bash test_restart.sh <granflow binary> <source dir>
set -uo pipefail
bin="$1"; src="$2"
py=/usr/bin/python3
check="$src/tests/tools/gfcheck.py"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mpirun="${MPIEXEC:-mpirun}"
fails=0
bad() { echo "FAIL  $*"; fails=$((fails + 1)); }
ok() { echo "ok    $*"; }

# run NAME LOG [launcher...] -- granflow arguments: runs, echoes the exit code.
run_rc() {
  local log="$1"; shift
  local rc=0
  "$@" > "$log" 2>&1 || rc=$?
  echo "$rc"
}

# ---------------------------------------------------------------- 1. SIGTERM and restart
A=("$src/cases/ar07_rough_channel.toml" --set grid.n=16 --set time.t_end=0.3
   --set output.vtk_interval=0.05 --set output.progress_interval=0)
start=$SECONDS
rc=$(run_rc "$tmp/full.log" "$bin" run "${A[@]}" --out "$tmp/full")
[[ $rc == 0 ]] || { cat "$tmp/full.log"; bad "uninterrupted case A exited $rc"; exit 1; }
echo "case A uninterrupted: $((SECONDS - start)) s"

start=$SECONDS
"$bin" run "${A[@]}" --set output.checkpoint_interval_steps=20 --out "$tmp/sig" \
  > "$tmp/sig.log" 2>&1 &
pid=$!
# SIGTERM as soon as the first checkpoint is complete (its header is written last).
for _ in $(seq 1 600); do
  [[ -f "$tmp/sig/checkpoint/header.txt" ]] && break
  kill -0 "$pid" 2> /dev/null || break
  sleep 0.05
done
kill -TERM "$pid" 2> /dev/null
rc=0; wait "$pid" || rc=$?
stopped_at=$(sed -n 's/^step //p' "$tmp/sig/checkpoint/header.txt" 2> /dev/null)
if [[ $rc == 6 ]] && grep -q "stopped by SIGTERM" "$tmp/sig.log" &&
   grep -q -- "granflow run --restart $tmp/sig" "$tmp/sig.log" &&
   grep -q '^reason SIGTERM' "$tmp/sig/checkpoint/header.txt" &&
   grep -q '"status": "interrupted"' "$tmp/sig/summary.json"; then
  ok "SIGTERM: exit 6, checkpoint at step $stopped_at, message: $(grep -o 'stopped by.*' "$tmp/sig.log" | head -1)"
else
  cat "$tmp/sig.log"; bad "SIGTERM: exit $rc (expected 6 with the restart message and a SIGTERM checkpoint)"
fi
grep -q "stopped by SIGTERM" "$tmp/sig/granflow.log" || bad "granflow.log lacks the stop message"

rc=$(run_rc "$tmp/re.log" "$bin" run --restart "$tmp/sig")
[[ $rc == 0 ]] || { cat "$tmp/re.log"; bad "restart exited $rc"; }
echo "case A killed + restarted: $((SECONDS - start)) s"
for f in diagnostics.csv probes/bottom.csv fields_000005.vtr fields.pvd profiles.csv structure.csv deposit.csv; do
  if cmp -s "$tmp/full/$f" "$tmp/sig/$f"; then ok "1 rank, SIGTERM + restart: $f identical to the uninterrupted run"
  else bad "1 rank, SIGTERM + restart: $f differs from the uninterrupted run"; cmp "$tmp/full/$f" "$tmp/sig/$f"; fi
done
if "$py" - "$tmp/full/summary.json" "$tmp/sig/summary.json" <<'PY'
import json, math, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
keys = ["runout_m", "max_front_x_m", "backwall_height_m", "front_speed_mps", "t1_s", "t2_s",
        "t3_s", "tf_s", "max_p_granular_pa", "slope_back_deg", "slope_front_deg", "front_angle_deg"]
diff = [k for k in keys if k not in a or not (a[k] == b.get(k) or (a[k] is None and b.get(k) is None))]
print("collapse keys differing after the restart:", diff or "none")
sys.exit(1 if diff else 0)
PY
then ok "1 rank, SIGTERM + restart: the collapse keys of summary.json are the uninterrupted run's"
else bad "1 rank, SIGTERM + restart: collapse keys of summary.json differ"; fi
"$py" "$check" pvd "$tmp/sig/fields.pvd" --count 7 --same-as "$tmp/full/fields.pvd" || bad "fields.pvd after the restart"
grep -q '"restarts": 1' "$tmp/sig/summary.json" || bad "summary.json does not count the restart"
grep -q '^restart$' "$tmp/sig/command.txt" || bad "command.txt does not record the restart"
# The uninterrupted run's history must be the restarted one's: same step count.
grep -q '"steps": 300' "$tmp/sig/summary.json" || bad "summary.json steps != 300"

# ---------------------------------------------------------------- 2. 1 -> 2 ranks
# With the conserved volume fraction (interface.method = "clsvof", the default) the volume
# changes are round-off (1e-14 %, 1e-16 per step) whose last digits depend on the order of the
# sums over the ranks: volume_change_pct and volume_step_change get absolute tolerances of
# 1e-10 % and 1e-12 (the granular volume itself keeps the relative 1e-8).
D=("$src/cases/dambreak_water.toml" --set grid.n=24 --set time.t_end=0.1
   --set output.vtk_interval=0.02 --set output.progress_interval=0)
start=$SECONDS
rc=$(run_rc "$tmp/d1.log" "$bin" run "${D[@]}" --out "$tmp/d1")
[[ $rc == 0 ]] || { cat "$tmp/d1.log"; bad "dam break 1 rank exited $rc"; }
rc=$(run_rc "$tmp/d12a.log" "$bin" run "${D[@]}" --set time.max_steps=40 --out "$tmp/d12")
[[ $rc == 0 ]] || { cat "$tmp/d12a.log"; bad "dam break to step 40 exited $rc"; }
cp -r "$tmp/d12" "$tmp/pristine"  # for the bad restarts below
rc=$(run_rc "$tmp/d12b.log" "$mpirun" --oversubscribe -n 2 "$bin" run --restart "$tmp/d12" \
     --set time.max_steps=0)
[[ $rc == 0 ]] || { cat "$tmp/d12b.log"; bad "2-rank restart exited $rc"; }
grep -q '"ranks": 2' "$tmp/d12/summary.json" || bad "the restart did not run on 2 ranks"
echo "dam break 1 rank, and 1 -> 2 ranks: $((SECONDS - start)) s"
echo "--- diagnostics.csv: 1 rank uninterrupted vs 1 rank to step 40 + 2 ranks from there"
"$py" "$check" compare "$tmp/d1/diagnostics.csv" "$tmp/d12/diagnostics.csv" --rtol 1e-8 \
  --atol max_divergence=1e-9 --atol volume_change_pct=1e-10 --atol volume_step_change=1e-12 \
  --int-tol visc_its=2 --int-tol pres_its=2 || bad "1 -> 2 ranks diagnostics"
"$py" "$check" compare "$tmp/d1/probes/bottom.csv" "$tmp/d12/probes/bottom.csv" --rtol 1e-8 \
  > "$tmp/probe_cmp.log" || { cat "$tmp/probe_cmp.log"; bad "1 -> 2 ranks probes"; }
"$py" "$check" pvd "$tmp/d12/fields.pvd" --count 6 --same-as "$tmp/d1/fields.pvd" || bad "fields.pvd after the 2-rank restart"

# ---------------------------------------------------------------- 2b. the exact plastic step
# rheology.solver = newton starts each step's Newton iteration from the last prediction u~,
# which the checkpoint holds (velocity_prediction): case A at n = 16 stopped at step 53 and
# continued reproduces the uninterrupted run's diagnostics.csv byte for byte.
N=("$src/cases/ar07_rough.toml" --set grid.n=16 --set time.t_end=0.1 --set output.vtk_interval=0
   --set output.progress_interval=0 --set rheology.solver=newton)
start=$SECONDS
rc=$(run_rc "$tmp/n1.log" "$bin" run "${N[@]}" --out "$tmp/n1")
[[ $rc == 0 ]] || { cat "$tmp/n1.log"; bad "Newton case A exited $rc"; }
rc=$(run_rc "$tmp/n2a.log" "$bin" run "${N[@]}" --set time.max_steps=53 --out "$tmp/n2")
[[ $rc == 0 ]] || { cat "$tmp/n2a.log"; bad "Newton case A to step 53 exited $rc"; }
rc=$(run_rc "$tmp/n2b.log" "$bin" run --restart "$tmp/n2" --set time.max_steps=0)
[[ $rc == 0 ]] || { cat "$tmp/n2b.log"; bad "Newton case A restart exited $rc"; }
if cmp -s "$tmp/n1/diagnostics.csv" "$tmp/n2/diagnostics.csv"; then
  ok "Newton, stopped at step 53 + restart: diagnostics.csv identical to the uninterrupted run"
else bad "Newton, stopped at step 53 + restart: diagnostics.csv differs"; fi
echo "Newton case A, restart: $((SECONDS - start)) s"

# ---------------------------------------------------------------- 3. bad restarts
# expect_restart LABEL CODE DIR "ARGS" PATTERN...: exit CODE, every PATTERN in the output, and
# the folder's diagnostics.csv untouched.
expect_restart() {
  local label="$1" code="$2" dir="$3" args="$4"; shift 4
  local before; before=$(md5sum < "$dir/diagnostics.csv")
  local rc=0 p msg=""
  # shellcheck disable=SC2086  # $args is a list of words on purpose
  "$bin" run --restart "$dir" $args > "$tmp/bad.log" 2>&1 || rc=$?
  [[ $rc == "$code" ]] || msg+=" exit $rc (expected $code);"
  for p in "$@"; do grep -qF -- "$p" "$tmp/bad.log" || msg+=" message lacks '$p';"; done
  [[ "$(md5sum < "$dir/diagnostics.csv")" == "$before" ]] || msg+=" diagnostics.csv changed;"
  if [[ -n "$msg" ]]; then bad "$label:$msg"; sed 's/^/      | /' "$tmp/bad.log"
  else ok "$label: exit $code: $(grep -v '^granflow: error in the case:$' "$tmp/bad.log" | head -1 | cut -c1-150)"; fi
}
mk() { rm -rf "$tmp/$1"; cp -r "$tmp/pristine" "$tmp/$1"; }
mk trunc; truncate -s -1000 "$tmp/trunc/checkpoint/state.bin"
expect_restart "truncated state.bin" 5 "$tmp/trunc" "" "state.bin" "truncated or corrupt"
mk flip; printf '\x7f' | dd of="$tmp/flip/checkpoint/state.bin" bs=1 seek=5000 conv=notrunc status=none
expect_restart "a corrupted byte in state.bin" 5 "$tmp/flip" "" "fails its checksum"
mk head; head -c 200 "$tmp/pristine/checkpoint/header.txt" > "$tmp/head/checkpoint/header.txt"
expect_restart "truncated header.txt" 5 "$tmp/head" "" "header.txt" "incomplete"
mk grid; sed -i 's/^n = 24$/n = 32/' "$tmp/grid/case.toml"
expect_restart "case.toml edited to another grid" 3 "$tmp/grid" "" \
  "grid.n: 24 at the checkpoint, 32 now" "differs from the one the checkpoint"
mk setn
expect_restart "--set grid.n on a restart" 3 "$tmp/setn" "--set grid.n=32" \
  "--set grid.n" "may only change time.t_end"
mk none; rm -rf "$tmp/none/checkpoint"
expect_restart "no checkpoint" 3 "$tmp/none" "" "no checkpoint in this folder"
rc=0; "$bin" run --restart "$tmp/pristine" --out "$tmp/x" > "$tmp/bad.log" 2>&1 || rc=$?
if [[ $rc == 2 && ! -e "$tmp/x" ]]; then ok "--restart with --out: exit 2"; else bad "--restart with --out: exit $rc"; fi
# A checkpoint left by a crash between the two renames (only checkpoint.prev) is still used.
mk prev; mv "$tmp/prev/checkpoint" "$tmp/prev/checkpoint.prev"
rc=$(run_rc "$tmp/prev.log" "$bin" run --restart "$tmp/prev" --set time.max_steps=1)
if [[ $rc == 0 ]] && grep -q "restarted from $tmp/prev/checkpoint.prev" "$tmp/prev.log"; then
  ok "checkpoint.prev used when checkpoint is missing"
else cat "$tmp/prev.log"; bad "restart from checkpoint.prev: exit $rc"; fi

if ((fails)); then echo "$fails check(s) failed"; exit 1; fi
echo "all restart checks passed"
