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
for f in unknown_key negative_rho column_outside; do
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
