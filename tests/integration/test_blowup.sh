#!/usr/bin/env bash
# Verification of failure handling (README "Checkpoints, restarts, exit codes").
# The water dam break at grid.n = 16 to t = 0.5 s; its adaptive step is dt_max = 1e-3 s.
#  1. Run to time.max_steps = 30 (a checkpoint at t = 0.03 s), then continue it with a fixed
#     dt = 0.05 s, fifty times the stable step: the run must stop with exit code 4 and a
#     message saying what (a speed above time.max_speed, or a non-finite field), where (the
#     cell and its coordinates), when (t, step) and what to try, write the diagnostics row of
#     the failure and summary.json ("status": "failed"), and leave the checkpoint untouched
#     (same bytes as before).
#  2. Continue the same folder again with the adaptive step: it must run to the end, and its
#     diagnostics.csv must be byte-identical to an uninterrupted adaptive run (the failed
#     attempt's rows are dropped by the restart); .pvd valid.
#  3. A viscous solve capped at 1 iteration (-visc_ksp_max_it 1): exit 4, the KSP reason and
#     the step in the message, a diagnostics row for the failure written.
# Usage: bash test_blowup.sh <granflow binary> <source dir>
set -uo pipefail
bin="$1"; src="$2"
py=/usr/bin/python3
check="$src/tests/tools/gfcheck.py"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fails=0
bad() { echo "FAIL  $*"; fails=$((fails + 1)); }
ok() { echo "ok    $*"; }
D=("$src/cases/dambreak_water.toml" --set grid.n=16 --set time.t_end=0.5
   --set output.vtk_interval=0.1 --set output.progress_interval=0)
start=$SECONDS

rc=0; "$bin" run "${D[@]}" --out "$tmp/full" > "$tmp/full.log" 2>&1 || rc=$?
[[ $rc == 0 ]] || { cat "$tmp/full.log"; bad "uninterrupted run exited $rc"; exit 1; }
rc=0; "$bin" run "${D[@]}" --set time.max_steps=30 --out "$tmp/run" > "$tmp/a.log" 2>&1 || rc=$?
[[ $rc == 0 ]] || { cat "$tmp/a.log"; bad "run to step 30 exited $rc"; exit 1; }
sums_before=$(cd "$tmp/run/checkpoint" && md5sum header.txt state.bin case.toml)

# --- 1. fifty times the stable step
rc=0
"$bin" run --restart "$tmp/run" --set time.dt_mode=fixed --set time.dt=0.05 \
  --set time.max_steps=0 > "$tmp/blow.log" 2>&1 || rc=$?
msg=""
[[ $rc == 4 ]] || msg+=" exit $rc (expected 4);"
for p in "granflow: the run failed:" "cell (i, j) = (" "at (x, y) = (" "try a smaller time step" \
         "The last good checkpoint (t = 0.03 s, step 30) is kept in $tmp/run/checkpoint" \
         "granflow run --restart $tmp/run"; do
  grep -qF -- "$p" "$tmp/blow.log" || msg+=" message lacks '$p';"
done
grep -qE "above time.max_speed|non-finite" "$tmp/blow.log" || msg+=" message does not say what blew up;"
grep -qE ", step [0-9]+ \(dt = 0.05 s" "$tmp/blow.log" || msg+=" message lacks the step and dt;"
grep -q '"status": "failed"' "$tmp/run/summary.json" || msg+=" summary.json status is not failed;"
grep -q "the run failed" "$tmp/run/granflow.log" || msg+=" granflow.log lacks the failure;"
sums_after=$(cd "$tmp/run/checkpoint" && md5sum header.txt state.bin case.toml)
[[ "$sums_before" == "$sums_after" ]] || msg+=" the checkpoint changed;"
# The failure's diagnostics row: the last row is past the checkpoint, with the fixed step.
last=$(tail -1 "$tmp/run/diagnostics.csv")
"$py" -c "import sys; t, dt = map(float, sys.argv[1].split(',')[:2]); sys.exit(not (t > 0.03 and dt == 0.05))" \
  "$last" || msg+=" the last diagnostics row is not the failure's ($last);"
if [[ -n "$msg" ]]; then bad "blow-up:$msg"; sed 's/^/      | /' "$tmp/blow.log"
else ok "blow-up: exit 4: $(grep -o 'the run failed: [^:]*' "$tmp/blow.log" | head -1)"; fi

# --- 2. the kept checkpoint continues with the adaptive step, exactly as the uninterrupted run
rc=0
"$bin" run --restart "$tmp/run" --set time.dt_mode=adaptive --set time.dt=0 \
  > "$tmp/c.log" 2>&1 || rc=$?
if [[ $rc == 0 ]] && cmp -s "$tmp/full/diagnostics.csv" "$tmp/run/diagnostics.csv"; then
  ok "restart after the blow-up: exit 0, diagnostics.csv identical to the uninterrupted run"
else
  cat "$tmp/c.log"; bad "restart after the blow-up: exit $rc, diagnostics.csv differs:"
  diff "$tmp/full/diagnostics.csv" "$tmp/run/diagnostics.csv" | head -5
fi
grep -q '"status": "completed"' "$tmp/run/summary.json" || bad "summary.json status is not completed"
"$py" "$check" pvd "$tmp/run/fields.pvd" --count 6 --same-as "$tmp/full/fields.pvd" || bad "fields.pvd"

# --- 3. a viscous solve at its iteration cap
rc=0
"$bin" run "${D[@]}" --set time.t_end=0.05 --out "$tmp/ksp" -- -visc_ksp_max_it 1 \
  > "$tmp/ksp.log" 2>&1 || rc=$?
msg=""
[[ $rc == 4 ]] || msg+=" exit $rc (expected 4);"
for p in "viscous solve (prefix -visc_) did not converge: DIVERGED_ITS" "in the step from t = 0 s, step 1"; do
  grep -qF -- "$p" "$tmp/ksp.log" || msg+=" message lacks '$p';"
done
[[ $(wc -l < "$tmp/ksp/diagnostics.csv") -ge 3 ]] || msg+=" no diagnostics row for the failure;"
if [[ -n "$msg" ]]; then bad "KSP cap:$msg"; sed 's/^/      | /' "$tmp/ksp.log"
else ok "KSP at its cap: exit 4: $(grep -o 'the run failed: .*' "$tmp/ksp.log" | cut -c1-120)"; fi

# --- 4. a fixed point of eq. 31 that does not converge (over-augmented: r_factor = 4 makes S
#        flip sign from one iteration to the next) stops the run; a converging one at its cap
#        is only a counted warning (the default case A run above is one).
rc=0
"$bin" run "$src/cases/ar07_rough.toml" --set grid.n=16 --set time.t_end=0.05 \
  --set rheology.r_factor=4 --set output.vtk_interval=0 --out "$tmp/fp" > "$tmp/fp.log" 2>&1 || rc=$?
msg=""
[[ $rc == 4 ]] || msg+=" exit $rc (expected 4);"
for p in "the fixed point of eq. 31 did not converge" "rheology.fp_fail_change" "step 1"; do
  grep -qF -- "$p" "$tmp/fp.log" || msg+=" message lacks '$p';"
done
if [[ -n "$msg" ]]; then bad "fixed point not converging:$msg"; sed 's/^/      | /' "$tmp/fp.log"
else ok "fixed point not converging: exit 4: $(grep -o 'the run failed: .*' "$tmp/fp.log" | cut -c1-120)"; fi

# --- 5. a pressure solve whose CG breaks down (a preconditioner made indefinite on purpose:
#        BoomerAMG with Jacobi smoothing over-relaxed by 3; -pres_pc_type hypre because PFMG is
#        the default) is solved again with GMRES; when that fails too, the run stops and says
#        both were tried.
rc=0
"$bin" run "${D[@]}" --set time.t_end=0.05 --out "$tmp/pres" -- -pres_pc_type hypre \
  -pres_pc_hypre_boomeramg_relax_type_all Jacobi -pres_pc_hypre_boomeramg_relax_weight_all 3 \
  > "$tmp/pres.log" 2>&1 || rc=$?
msg=""
[[ $rc == 4 ]] || msg+=" exit $rc (expected 4);"
for p in "pressure solve (prefix -pres_) did not converge" "(CG, then GMRES)"; do
  grep -qF -- "$p" "$tmp/pres.log" || msg+=" message lacks '$p';"
done
if [[ -n "$msg" ]]; then bad "pressure CG breakdown:$msg"; sed 's/^/      | /' "$tmp/pres.log"
else ok "pressure CG breakdown -> GMRES -> failure: exit 4: $(grep -o 'the run failed: .*' "$tmp/pres.log" | cut -c1-120)"; fi

echo "time: $((SECONDS - start)) s"
if ((fails)); then echo "$fails check(s) failed"; exit 1; fi
echo "all failure-handling checks passed"
