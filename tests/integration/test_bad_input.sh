#!/usr/bin/env bash
# Verification of input checking (src/core/Error.hpp: kExitInput = 3 for a bad case).
# For each bad input, both `granflow check` and `granflow run` must
#   - exit with code 3 (a missing case file is reported as an input error too: code 3,
#     "cannot open the case file", see Params::load),
#   - print a message naming the key (or the file) and the allowed range / the suggestion,
#   - for `run`: create neither the --out folder nor a default out/ folder (nothing computed).
# Then `granflow check` on every bundled case in cases/ and cases/verify/ must exit 0.
# Usage: bash test_bad_input.sh <granflow binary> <source dir>
set -uo pipefail
bin="$1"; src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/cwd"
# A run without --out would write to ./out/<case>: that must not appear either.
cd "$tmp/cwd" || exit 1
base="$src/cases/dambreak_water.toml"
fails=0
n=0

# expect_error LABEL CASEFILE "SET ARGS" PATTERN...  (patterns: fixed strings, all required)
expect_error() {
  local label="$1" case="$2" sets="$3"; shift 3
  local cmd
  for cmd in check run; do
    n=$((n + 1))
    local out="$tmp/out_${n}" log="$tmp/log_${n}" rc=0
    local -a extra=()
    [[ "$cmd" == run ]] && extra=(--out "$out")
    # shellcheck disable=SC2086  # $sets is a list of words on purpose
    "$bin" "$cmd" "$case" $sets "${extra[@]}" > "$log" 2>&1 || rc=$?
    local bad=""
    [[ $rc -eq 3 ]] || bad+=" exit code $rc (expected 3);"
    local p
    for p in "$@"; do grep -qF -- "$p" "$log" || bad+=" message lacks '$p';"; done
    if [[ "$cmd" == run ]]; then
      [[ ! -e "$out" ]] || bad+=" created the output folder $out;"
      [[ ! -e "$tmp/cwd/out" ]] || bad+=" created ./out;"
    fi
    if [[ -n "$bad" ]]; then
      echo "FAIL  $cmd: $label:$bad"; sed 's/^/      | /' "$log"; fails=$((fails + 1))
    else
      echo "ok    $cmd: $label: exit 3: $(grep -v '^granflow: error in the case:' "$log" |
        head -1)"
    fi
  done
}

# Variants of the water dam break, one defect each.
sed 's/^rho = 1000.0/rhoo = 1000.0/' "$base" > "$tmp/unknown_key.toml"
sed 's/^rho = 1000.0/rho = -1000.0/' "$base" > "$tmp/negative_rho.toml"
sed 's/^x1 = 0.146/x1 = 0.7/' "$base" > "$tmp/column_outside.toml"
sed 's/^x1 = 0.584/x1 = 0.7/' "$base" > "$tmp/probe_outside.toml"  # the probe's end point
for f in unknown_key negative_rho column_outside probe_outside; do
  if cmp -s "$base" "$tmp/$f.toml"; then
    echo "FAIL: could not make $f.toml from $base (the case file changed?)"; exit 1
  fi
done

expect_error "missing file" "$tmp/no_such_case.toml" "" \
  "no_such_case.toml" "cannot open the case file"
expect_error "unknown key in the file" "$tmp/unknown_key.toml" "" \
  "phase.granular.rhoo" "unknown key" "did you mean phase.granular.rho?"
expect_error "negative density in the file" "$tmp/negative_rho.toml" "" \
  "phase.granular.rho" "must be > 0 (kg/m^3)"
expect_error "negative density by --set" "$base" "--set phase.granular.rho=-5" \
  "phase.granular.rho = -5" "must be > 0 (kg/m^3)"
expect_error "column outside the domain" "$tmp/column_outside.toml" "" \
  "initial.x1" "must lie inside the domain" "must be <= domain.Lx = 0.584"
expect_error "column outside the domain by --set" "$base" "--set initial.y1=0.5" \
  "initial.y1" "must lie inside the domain" "domain.Ly = 0.35"
expect_error "--set of an unknown key" "$base" "--set grid.nn=64" \
  "grid.nn" "unknown key" "did you mean grid.n?"
expect_error "--set out of range" "$base" "--set grid.n=4" \
  "grid.n = 4" "must be in [8, 100000]"
expect_error "--set of the wrong type" "$base" "--set grid.n=abc" \
  "grid.n" "wrong type" "expected an integer"
expect_error "--set without '='" "$base" "--set grid.n" \
  "--set grid.n" "expected key=value"

expect_error "column touching the top" "$base" "--set initial.y1=0.34" \
  "initial.y1 = 0.34" "the column touches the top" "so the smeared interface does not touch"
expect_error "probe outside the domain" "$tmp/probe_outside.toml" "" \
  "probe[1].x1 = 0.7" "the probe must lie inside the domain" "domain.Lx = 0.584"
expect_error "mu(I) without d" "$base" "--set rheology.viscosity=mu_i --set rheology.yield=dp" \
  "rheology.d" "mu(I) without d" "must be > 0 (m)"
expect_error "mu(I) with the hp yield stress" "$base" \
  "--set rheology.viscosity=mu_i --set rheology.yield=hp --set rheology.d=0.001" \
  "rheology.viscosity" "needs rheology.yield = \"dp\", not \"hp\""
expect_error "bingham without a yield stress" "$base" "--set rheology.yield=bingham" \
  "rheology.tau_y" "needs a yield stress: must be > 0 (Pa)"
expect_error "friction angle of 90 degrees" "$base" "--set rheology.friction_angle=90" \
  "rheology.friction_angle = 90" "must be in (0, 90) (degrees)"
expect_error "CFL above 1" "$base" "--set time.cfl=1.5" "time.cfl = 1.5" "must be in (0, 1]"
expect_error "dt_min above dt_max" "$base" "--set time.dt_min=0.01" \
  "time.dt_min = 0.01" "must be < time.dt_max = 0.001 (s)"
# The keys of checkpoints and failure handling (README "Checkpoints, restarts, exit codes").
expect_error "max_speed of 0" "$base" "--set time.max_speed=0" \
  "time.max_speed = 0" "must be > 0 (m/s)"
expect_error "negative checkpoint interval" "$base" "--set output.checkpoint_interval_steps=-1" \
  "output.checkpoint_interval_steps = -1" "must be >= 0 (steps)"
expect_error "negative checkpoint wall time" "$base" "--set output.checkpoint_wall_s=-5" \
  "output.checkpoint_wall_s = -5" "must be >= 0 (s)"
expect_error "volume warning threshold of 0" "$base" "--set output.volume_warn_pct=0" \
  "output.volume_warn_pct = 0" "must be > 0 (%)"
expect_error "the exact plastic step with the gate" "$src/cases/ar07_rough_channel.toml" \
  "--set rheology.solver=newton" "rheology.solver" "not available with boundary.gate.x" \
  "fixed_point"

# A processor grid that does not fit the ranks (a PETSc option, checked when the grid is made).
n=$((n + 1)); rc=0
"$bin" run "$base" --out "$tmp/out_$n" -- -da_processors_x 2 > "$tmp/log_$n" 2>&1 || rc=$?
if [[ $rc -eq 3 ]] && grep -qF -- "-da_processors_x = 2" "$tmp/log_$n" &&
   grep -qF "do not fit the 1 MPI ranks" "$tmp/log_$n"; then
  echo "ok    processor grid 2 x ? on 1 rank: exit 3 with the option named"
else
  echo "FAIL  processor grid 2 x ? on 1 rank: exit $rc"; sed 's/^/      | /' "$tmp/log_$n"
  fails=$((fails + 1))
fi

# Every bundled case is valid.
for f in "$src"/cases/*.toml "$src"/cases/verify/*.toml; do
  n=$((n + 1))
  rc=0
  "$bin" check "$f" > "$tmp/log_$n" 2>&1 || rc=$?
  if [[ $rc -ne 0 ]]; then
    echo "FAIL  check ${f#"$src"/}: exit $rc"; sed 's/^/      | /' "$tmp/log_$n"
    fails=$((fails + 1))
  else
    echo "ok    check ${f#"$src"/}: exit 0"
  fi
done

if ((fails)); then echo "$fails check(s) failed"; exit 1; fi
echo "all input checks passed"
