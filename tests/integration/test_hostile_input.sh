#!/usr/bin/env bash
# Hostile inputs and faults (issue 20): every hole found there, and malformed inputs of our own,
# each one row with its expected exit code (core/Error.hpp) and a fragment of its message.
#
# A refused input (exit 2 usage, 3 input) must be refused before any computation: the command
# runs in an empty working folder with --out inside it, and afterwards that folder must still
# be empty (no ./out, no --out folder, nothing). Every command is bounded by `timeout` (a hang
# is exit 124, or 137 if the command ignores timeout's SIGTERM: a failure of the row; the bound
# is GF_ROW_LIMIT seconds, 120 by default), none may print a PETSc traceback ("PETSC ERROR") or
# a raw ESC / CR byte, none may exit 70 (internal error) or 143 (killed by SIGTERM).
# The faults (a SIGTERM at start-up, the output folder removed during the run, a blow-up, an
# edited or damaged checkpoint) have their own rows below, each with the same exit-code and
# message checks and its own check of what was (or was not) written.
#
# Usage: bash test_hostile_input.sh <granflow binary> <source dir>
set -uo pipefail
bin="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"; src="$(cd "$2" && pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mpirun="${MPIEXEC:-mpirun}"
export OMP_NUM_THREADS=1
[[ $(id -u) == 0 ]] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cwd="$tmp/cwd"; mkdir -p "$cwd"
runs="$tmp/runs"; mkdir -p "$runs"
A="$src/cases/ar07_rough.toml"
D="$src/cases/dambreak_water.toml"
fails=0 rows=0 start=$SECONDS
limit=${GF_ROW_LIMIT:-120}  # s, the most any one command may take
bad() { echo "FAIL  $*"; fails=$((fails + 1)); }

# The checks every command gets: exit code, message fragments, no traceback, no raw control
# bytes, no internal error, no kill. $1 label, $2 expected code, $3 log, $4 actual code, then
# the fragments. Returns 1 (after reporting) on a failure.
judge() {
  local label="$1" code="$2" log="$3" rc="$4"; shift 4
  local msg="" p
  [[ $rc == "$code" ]] || msg+=" exit $rc (expected $code);"
  [[ $rc == 124 || $rc == 137 ]] && msg+=" timed out after $limit s (a hang);"
  for p in "$@"; do grep -aqF -- "$p" "$log" || msg+=" message lacks '$p';"; done
  grep -aq "PETSC ERROR" "$log" && msg+=" a PETSc traceback;"
  grep -aq $'[\x1b\r]' "$log" && msg+=" a raw ESC or CR byte in the output;"
  if [[ -n "$msg" ]]; then bad "$label:$msg"; sed 's/^/      | /' "$log" | cut -c1-300 | head -20; return 1; fi
  return 0
}

# refused LABEL CODE FRAGMENT... -- GRANFLOW ARGS: run in the empty working folder; exit CODE,
# every FRAGMENT, and nothing left in the folder.
refused() {
  local label="$1" code="$2"; shift 2
  local -a frags=()
  while [[ $# -gt 0 && "$1" != "--" ]]; do frags+=("$1"); shift; done
  shift
  rows=$((rows + 1))
  local log="$tmp/row_$rows.log" rc=0
  (cd "$cwd" && timeout -k 10 "$limit" "$bin" "$@") > "$log" 2>&1 || rc=$?
  local left; left="$(ls -A "$cwd")"
  rm -rf "${cwd:?}"/* "$cwd"/.[!.]* 2> /dev/null  # the next row starts from an empty folder
  if judge "$label" "$code" "$log" "$rc" "${frags[@]}"; then
    if [[ -n "$left" ]]; then bad "$label: left files behind: $(echo $left)"
    else echo "ok    $label: exit $code: $(grep -aF -- "${frags[0]}" "$log" | head -1 | cut -c1-150)"; fi
  fi
}

# mpi_refused: the same with N ranks (mpirun's own lines are not judged for fragments).
mpi_refused() {
  local label="$1" code="$2" frag="$3" n="$4"; shift 4
  rows=$((rows + 1))
  local log="$tmp/row_$rows.log" rc=0
  (cd "$cwd" && timeout -k 10 "$limit" "$mpirun" --oversubscribe -n "$n" "$bin" "$@") > "$log" 2>&1 || rc=$?
  local left; left="$(ls -A "$cwd")"
  rm -rf "${cwd:?}"/* 2> /dev/null
  # mpirun reports the first non-zero exit code of the ranks as its own.
  if judge "$label" "$code" "$log" "$rc" "$frag"; then
    if [[ -n "$left" ]]; then bad "$label: left files behind: $(echo $left)"
    else echo "ok    $label: exit $code: $(grep -aF -- "$frag" "$log" | head -1 | cut -c1-150)"; fi
  fi
}

# check_and_run LABEL CODE FRAGMENT -- CASE ARGS: the same input given to check and to run.
check_and_run() {
  local label="$1" code="$2" frag="$3"; shift 4
  refused "check: $label" "$code" "$frag" -- check "$@"
  refused "run: $label" "$code" "$frag" -- run "$@" --out o
}

small=(--set grid.n=16 --set output.progress_interval=0)

echo "--- the holes of issue 20"
# Output schedule: these passed check and then hung at 100 % CPU after step 1.
check_and_run "output.interval = 1e-300" 3 "diagnostics outputs, more than 1e+07" -- \
  "$A" --set output.interval=1e-300
check_and_run "output.vtk_interval = 1e-300" 3 "VTK files, more than 1e+05" -- \
  "$A" --set output.vtk_interval=1e-300
check_and_run "time.t_end = 1e308" 3 "steps at least (the adaptive step is at most time.dt_max), more than 1e+09" -- \
  "$A" --set time.t_end=1e308
# A case path that is a folder, or whose read fails, was read as an empty case (all defaults).
mkdir -p "$tmp/folder.toml"
check_and_run "the case path is a folder" 3 "is a folder, not a case file" -- "$tmp/folder.toml"
check_and_run "the case file cannot be read" 3 "cannot read the case file (Input/output error)" -- \
  /proc/self/mem
# A fixed step of 0, or far beyond the stability limit.
check_and_run "time.dt_mode = fixed with dt = 0" 3 'time.dt_mode = "fixed" needs the step: must be > 0 (s)' -- \
  "$A" --set time.dt_mode=fixed --set time.dt=0
check_and_run "a fixed dt of 0.5 s (CFL 187)" 3 "the step is 187.5 times the stability limit, CFL number U dt / h = 187.5" -- \
  "$A" --set time.dt_mode=fixed --set time.dt=0.5
# PETSc user errors: exit 70 with a 60-line traceback before.
refused "a PETSc type that does not exist (after --)" 3 \
  "a PETSc option was refused" "-pres_pc_type nonsense" "Unable to find requested PC type nonsense" -- \
  run "$D" "${small[@]}" --out o -- -pres_pc_type nonsense
refused "a PETSc value that is not a number (after --)" 3 \
  "a PETSc option was refused" "Input string abc has no numeric value" -- \
  run "$D" "${small[@]}" --out o -- -visc_ksp_rtol abc
refused "a PETSc type that does not exist (solver.petsc_options)" 3 \
  "Unable to find requested KSP type nonsense" -- \
  run "$D" "${small[@]}" --set 'solver.petsc_options="-visc_ksp_type nonsense"' --out o
# Grids inside the allowed range of grid.n that cannot run.
check_and_run "grid.n = 25000 (2.5e9 cells: 32-bit indices)" 3 "beyond PETSc's 32-bit index limit" -- \
  "$A" --set grid.n=25000
check_and_run "grid.n = 8000 (memory)" 3 "GiB of memory (2.637 KiB per cell and 50 MiB per rank" -- \
  "$A" --set grid.n=8000
mpi_refused "check: a part of the grid thinner than the stencil on 3 ranks" 3 \
  "cuts ny into 3 parts of 2 cells, thinner than the stencil (3 cells)" 3 \
  check "$A" --set grid.n=8 -- -da_processors_y 3
mpi_refused "run: a part of the grid thinner than the stencil on 3 ranks" 3 \
  "cuts ny into 3 parts of 2 cells, thinner than the stencil (3 cells)" 3 \
  run "$A" --set grid.n=8 --out o -- -da_processors_y 3
# The case file's syntax and the command line.
printf '"grid.n" = 32\n[grid]\nn = 16\n' > "$tmp/quoted.toml"
check_and_run "a quoted root key \"grid.n\" beside [grid] n" 3 'a quoted key "grid.n" is the same parameter as n' -- \
  "$tmp/quoted.toml"
printf '[[probe]]\nname = "%s"\nx0 = 0\ny0 = 0.01\nx1 = 0.8\ny1 = 0.01\n' "$(printf 'p%.0s' {1..300})" > "$tmp/longprobe.toml"
check_and_run "a 300-character probe name" 3 "is 300 characters long: at most 64" -- "$tmp/longprobe.toml"
refused "run: --set without its value before --out" 2 "--set needs key=value right after it, got '--out'" -- \
  run "$D" --set --out o
refused "check: --set without a value at the end" 2 "--set: 1 required TEXT missing" -- check "$D" --set
check_and_run "--set domain.Lx=1e999" 3 "domain.Lx = 1e999: out of range" -- "$D" --set domain.Lx=1e999
printf 'title = "a\\u001b[2J\\u001b[31mred"\n' > "$tmp/esc.toml"
check_and_run "ESC in the title" 3 "control character 0x1B (ESC)" -- "$tmp/esc.toml"
printf 'title = "shown\\rhidden"\n' > "$tmp/cr.toml"
check_and_run "CR in the title" 3 "control character 0x0D (CR)" -- "$tmp/cr.toml"
# --out onto an existing file, an existing run, a non-empty folder.
touch "$tmp/a_file"
refused "run: --out onto an existing file" 3 "is a file, not a folder" -- run "$D" "${small[@]}" --out "$tmp/a_file"
refused "run: --out under an existing file" 3 "a_file is a file, not a folder" -- run "$D" "${small[@]}" --out "$tmp/a_file/sub"
rows=$((rows + 1)); rc=0
timeout -k 10 "$limit" "$bin" run "$D" "${small[@]}" --set time.t_end=0.1 --set output.vtk_interval=0.02 \
  --out "$runs/old" > "$tmp/old.log" 2>&1 || rc=$?
[[ $rc == 0 && -f "$runs/old/fields_000005.vtr" ]] || bad "the run to overwrite: exit $rc"
refused "run: --out onto an existing run" 3 "holds a granflow run already" "--overwrite" -- \
  run "$D" "${small[@]}" --out "$runs/old"
mkdir -p "$runs/mine"; touch "$runs/mine/thesis.tex"
refused "run: --out onto a non-empty folder that is no run, even with --overwrite" 3 \
  "is not empty and is not a granflow run folder" -- run "$D" "${small[@]}" --out "$runs/mine" --overwrite
[[ -f "$runs/mine/thesis.tex" ]] || bad "--overwrite removed a folder that was no run"
rows=$((rows + 1)); rc=0
timeout -k 10 "$limit" "$bin" run "$D" "${small[@]}" --set time.t_end=0.05 --set output.vtk_interval=0.02 \
  --out "$runs/old" --overwrite > "$tmp/ow.log" 2>&1 || rc=$?
if judge "run: --overwrite" 0 "$tmp/ow.log" "$rc" "removed the old run in $runs/old" &&
   [[ ! -e "$runs/old/fields_000005.vtr" && -f "$runs/old/fields_000002.vtr" ]] &&
   [[ $(grep -c "^command:" "$runs/old/command.txt") == 1 ]]; then
  echo "ok    run: --overwrite: exit 0, the old run removed first (no stale fields_000005.vtr, one command.txt block)"
else bad "run: --overwrite did not replace the old run cleanly"; fi
# --version.
rows=$((rows + 1)); rc=0
timeout -k 10 "$limit" "$bin" --version > "$tmp/version.log" 2>&1 || rc=$?
if judge "--version" 0 "$tmp/version.log" "$rc" "granflow " "PETSc 3."; then
  echo "ok    --version: exit 0: $(tr '\n' ' ' < "$tmp/version.log")"; fi
# Unknown PETSc options: reported by name (a warning; the run goes on).
rows=$((rows + 1)); rc=0
(cd "$runs" && timeout -k 10 "$limit" "$bin" run "$D" "${small[@]}" --set time.t_end=0.01 --out typo \
  -- -pres_ksp_rtoll 1e-8) > "$tmp/typo.log" 2>&1 || rc=$?
judge "an unknown PETSc option" 0 "$tmp/typo.log" "$rc" \
  "warning: PETSc option -pres_ksp_rtoll 1e-8 was not used by the first step" &&
  echo "ok    an unknown PETSc option: exit 0, warned: $(grep -o 'PETSc option -pres_ksp_rtoll[^:]*' "$tmp/typo.log")"

echo "--- faults"
# A SIGTERM at any moment of the start-up: never the default kill (exit 143, nothing said).
# Before the run folder is opened: exit 6, nothing written; after: exit 6 with a checkpoint.
# Started directly (not under timeout, which would take the signal itself), with a watchdog;
# the delay counts from the execve of granflow (before it, the signal would hit this shell's
# fork, not granflow).
for delay in 0 0.01 0.03 0.06 0.1 0.2 0.35 0.7; do
  rows=$((rows + 1)); rc=0
  out="$runs/term_$delay"
  "$bin" run "$A" "${small[@]}" --set time.t_end=0.3 --out "$out" > "$tmp/term.log" 2>&1 &
  pid=$!
  for _ in $(seq 1 1000); do
    case "$(readlink "/proc/$pid/exe" 2> /dev/null)" in */granflow | */granflow-core | "") break ;; esac
  done
  sleep "$delay"; kill -TERM "$pid" 2> /dev/null
  for _ in $(seq 1 $((limit * 20))); do kill -0 "$pid" 2> /dev/null || break; sleep 0.05; done
  kill -KILL "$pid" 2> /dev/null  # the watchdog: still running after $limit s is a hang
  wait "$pid" || rc=$?
  label="SIGTERM $delay s after the start"
  if judge "$label" 6 "$tmp/term.log" "$rc" "stopped by SIGTERM"; then
    if [[ -e "$out" ]]; then
      if [[ -f "$out/checkpoint/header.txt" ]] && grep -q '"status": "interrupted"' "$out/summary.json"; then
        echo "ok    $label: exit 6, checkpoint at step $(sed -n 's/^step //p' "$out/checkpoint/header.txt")"
      else bad "$label: an output folder without a checkpoint or an interrupted summary.json"; fi
    else
      grep -aqF "before anything was written" "$tmp/term.log" &&
        echo "ok    $label: exit 6, nothing written: $(grep -ao 'stopped by SIGTERM during[^,]*' "$tmp/term.log")" ||
        bad "$label: no folder, but the message does not say that nothing was written"
    fi
  fi
done
# The output folder removed during the run (no VTK, no periodic checkpoints): exit 0 and
# "completed" before, with diagnostics and probes gone.
for what in folder diagnostics.csv; do
  rows=$((rows + 1)); rc=0
  out="$runs/removed_$what"
  timeout -k 10 "$limit" "$bin" run "$A" "${small[@]}" --set time.t_end=3 --set output.vtk_interval=0 \
    --set output.checkpoint_wall_s=0 --out "$out" > "$tmp/rm.log" 2>&1 &
  pid=$!
  for _ in $(seq 1 400); do
    [[ $({ wc -l < "$out/diagnostics.csv"; } 2> /dev/null || echo 0) -ge 5 ]] && break; sleep 0.05
  done
  if [[ $what == folder ]]; then rm -rf "$out"; else rm -f "$out/diagnostics.csv"; fi
  wait "$pid" || rc=$?
  label="the $what removed during the run"
  name=$([[ $what == folder ]] && echo "was deleted while the run was writing it" || echo "diagnostics.csv' was deleted")
  if judge "$label" 5 "$tmp/rm.log" "$rc" "granflow: file error:" "$name"; then
    if grep -qs '"status": "completed"' "$out/summary.json"; then bad "$label: summary.json says completed"
    else echo "ok    $label: exit 5: $(grep -o 'file error: .*' "$tmp/rm.log" | cut -c1-120)"; fi
  fi
done
# A failed write of summary.json (its temporary file's name taken by a folder, made during
# the run): exit 5, and no summary.json saying "completed".
rows=$((rows + 1)); rc=0
out="$runs/nosummary"
timeout -k 10 "$limit" "$bin" run "$A" "${small[@]}" --set time.t_end=1 --set output.vtk_interval=0 \
  --out "$out" > "$tmp/sum.log" 2>&1 &
pid=$!
for _ in $(seq 1 400); do [[ -f "$out/diagnostics.csv" ]] && break; sleep 0.05; done
mkdir -p "$out/summary.json.tmp"
wait "$pid" || rc=$?
if judge "summary.json cannot be written" 5 "$tmp/sum.log" "$rc" "summary.json.tmp"; then
  if [[ -f "$out/summary.json" ]]; then bad "summary.json cannot be written: yet there is one"
  else echo "ok    summary.json cannot be written: exit 5: $(grep -o 'file error: .*' "$tmp/sum.log" | cut -c1-120)"; fi
fi
# A blow-up (case A at n = 32, a fixed dt = 0.01 s, a checkpoint every step): the checkpoint
# kept must be from before the blow-up (max|u| <= 10 U), and a restart from it with a smaller
# step must continue to the end.
rows=$((rows + 1)); rc=0
out="$runs/blowup"
timeout -k 10 "$limit" "$bin" run "$A" --set grid.n=32 --set time.dt_mode=fixed --set time.dt=0.01 \
  --set output.checkpoint_interval_steps=1 --set output.vtk_interval=0 --set output.progress_interval=0 \
  --out "$out" > "$tmp/blow.log" 2>&1 || rc=$?
if judge "blow-up at a fixed dt = 0.01 s" 4 "$tmp/blow.log" "$rc" "beyond the stability limit" \
     "no checkpoint at" "the state is not sane" "The last good checkpoint"; then
  step=$(sed -n 's/^step //p' "$out/checkpoint/header.txt")
  speed=$(awk -F, -v s="$step" 'NR > 1 && $3 == s {print $6}' "$out/diagnostics.csv")
  if /usr/bin/python3 -c "import sys; sys.exit(not float('$speed') <= 10 * (9.81 * 0.14) ** 0.5)"; then
    echo "ok    blow-up at a fixed dt = 0.01 s: exit 4, checkpoint kept at step $step with max|u| = $speed m/s (<= 10 U)"
  else bad "blow-up: the checkpoint kept (step $step) has max|u| = $speed m/s, above 10 U"; fi
  rows=$((rows + 1)); rc=0
  timeout -k 10 "$limit" "$bin" run --restart "$out" --set time.dt_mode=fixed --set time.dt=0.001 \
    --set time.t_end=0.12 > "$tmp/blow_re.log" 2>&1 || rc=$?
  judge "restart after the blow-up with dt = 0.001 s" 0 "$tmp/blow_re.log" "$rc" "restarted from" &&
    grep -q '"status": "completed"' "$out/summary.json" &&
    echo "ok    restart after the blow-up with dt = 0.001 s: exit 0, completed to t = 0.12 s"
fi
# Checkpoint header edits (step, t, dt, t nan): caught by the header's checksum. With the
# checkpoint before it kept (checkpoint.prev), a damaged latest one is replaced by it, said.
rows=$((rows + 1)); rc=0
timeout -k 10 "$limit" "$bin" run "$D" "${small[@]}" --set time.max_steps=20 --set output.checkpoint_interval_steps=10 \
  --set output.vtk_interval=0 --out "$runs/ck" > "$tmp/ck.log" 2>&1 || rc=$?
[[ $rc == 0 && -d "$runs/ck/checkpoint.prev" ]] || bad "checkpoint run: exit $rc, checkpoint.prev kept: $([[ -d $runs/ck/checkpoint.prev ]] && echo yes || echo no)"
edit() {  # edit LABEL SED-EXPRESSION [FILE]: on a copy of the run without checkpoint.prev
  local label="$1" expr="$2" file="${3:-header.txt}"
  rows=$((rows + 1)); rm -rf "$runs/ed"; cp -r "$runs/ck" "$runs/ed"; rm -rf "$runs/ed/checkpoint.prev"
  sed -i "$expr" "$runs/ed/checkpoint/$file"
  cmp -s "$runs/ck/checkpoint/$file" "$runs/ed/checkpoint/$file" && { bad "$label: the edit changed nothing"; return; }
  local rc=0
  timeout -k 10 "$limit" "$bin" run --restart "$runs/ed" > "$tmp/ed.log" 2>&1 || rc=$?
  judge "restart from an edited checkpoint: $label" 5 "$tmp/ed.log" "$rc" "fails its checksum" \
    "no $runs/ed/checkpoint.prev to fall back to" &&
    echo "ok    restart from an edited checkpoint: $label: exit 5: $(grep -o 'the header fails[^)]*)\|case.toml. fails[^)]*)' "$tmp/ed.log" | head -1)"
}
edit "step 20 -> 25" 's/^step 20$/step 25/'
edit "t -> 0.5" 's/^t .*/t 0x1p-1 # 0.5/'
edit "dt -> 0.01" 's/^dt .*/dt 0x1.47ae147ae147bp-7 # 0.01/'
edit "t nan" 's/^t .*/t nan/'
edit "the case stored in the checkpoint" 's/^n = 16$/n = 17/' case.toml
rows=$((rows + 1)); rm -rf "$runs/fb"; cp -r "$runs/ck" "$runs/fb"; rc=0
printf '\x7f' | dd of="$runs/fb/checkpoint/state.bin" bs=1 seek=3000 conv=notrunc status=none
timeout -k 10 "$limit" "$bin" run --restart "$runs/fb" > "$tmp/fb.log" 2>&1 || rc=$?
judge "a damaged latest checkpoint beside a good checkpoint.prev" 0 "$tmp/fb.log" "$rc" \
  "checkpoint is damaged" "continuing from the previous checkpoint, $runs/fb/checkpoint.prev (t = 0.01" \
  "restarted from $runs/fb/checkpoint.prev" &&
  echo "ok    a damaged latest checkpoint beside a good checkpoint.prev: exit 0, continued from checkpoint.prev (step 10)"

echo "--- more malformed inputs"
check_and_run "a TOML syntax error" 3 "TOML syntax error" -- "$(printf '[time\nt_end = 1\n' > "$tmp/syn.toml"; echo "$tmp/syn.toml")"
check_and_run "a binary file as the case" 3 "TOML syntax error: Encountered invalid utf-8" -- /bin/true
check_and_run "a control byte in a string" 3 "unescaped control characters" -- \
  "$(printf 'title = "a\x01b"\n' > "$tmp/nul.toml"; echo "$tmp/nul.toml")"
check_and_run "a key twice in one table" 3 "cannot redefine existing integer 'n'" -- \
  "$(printf '[grid]\nn = 16\nn = 32\n' > "$tmp/dup.toml"; echo "$tmp/dup.toml")"
check_and_run "--set with an empty value" 3 'grid.n = "": wrong type: expected an integer' -- "$D" --set grid.n=
check_and_run "a count written as a float" 3 "grid.n = 64.0: wrong type: expected an integer" -- "$D" --set grid.n=64.0
check_and_run "an integer beyond 64 bits" 3 "out of range: beyond the 64-bit integers" -- "$D" --set grid.n=99999999999999999999
check_and_run "nan" 3 "domain.Lx = nan: must be a finite number (m)" -- "$D" --set domain.Lx=nan
check_and_run "inf" 3 "time.t_end = inf: must be a finite number (s)" -- "$D" --set time.t_end=inf
check_and_run "a negative zero interval" 3 "output.interval = 0.0: must be > 0 (s)" -- "$D" --set output.interval=-0.0
check_and_run "an array for a number" 3 "time.cfl = [0.5]: wrong type: expected a number" -- "$D" "--set" "time.cfl=[0.5]"
check_and_run "gravity with one component" 3 "expected an array of 2 numbers (m/s^2), got an array of 1 element" -- \
  "$D" "--set" "physics.gravity=[0]"
check_and_run "a key made of dots" 3 ".. = 1: unknown key" -- "$D" --set ..=1
check_and_run "a misspelled section" 3 "did you mean phase.granular.rho?" -- \
  "$(printf '[phase.granuler]\nrho = 1500\n' > "$tmp/sec.toml"; echo "$tmp/sec.toml")"
refused "run: a PETSc integer option that is not a number" 3 "Input string abc has no integer value" -- \
  run "$D" "${small[@]}" --out o -- -da_processors_x abc
refused "check: a PETSc integer option that is not a number" 3 "Input string abc has no integer value" -- \
  check "$D" -- -da_processors_x abc
mkdir -p "$runs/empty"
refused "run: --restart of a folder that is no run" 3 "not a granflow output folder" -- run --restart "$runs/empty"
refused "run: --restart with --overwrite" 2 "--out and --overwrite are not allowed with it" -- \
  run --restart "$runs/ck" --overwrite

echo "$rows rows, $((SECONDS - start)) s"
if ((fails)); then echo "$fails check(s) failed"; exit 1; fi
echo "all hostile-input checks passed"
