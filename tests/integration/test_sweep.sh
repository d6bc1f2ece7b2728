#!/usr/bin/env bash
# scripts/sweep.py on the water dam break at grid.n = 16 to t = 0.02 s: a 2 x 2 grid of values
# (phase.granular.rho x grid.nx) two at a time must give four completed runs in their own
# folders and a table of four rows with the varied values as columns and the summary figures
# of each run's summary.json; the same command again must skip all four (completed, same case);
# a changed --set must run them again; a run killed half-way (its summary.json removed) must be
# run again, alone; a bad combination is refused before anything runs (exit 2); --help exits 0.
# Usage: bash test_sweep.sh <granflow binary> <source dir>
set -uo pipefail
bin="$1"; src="$2"
py=/usr/bin/python3
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fails=0
bad() { echo "FAIL  $*"; fails=$((fails + 1)); }
ok() { echo "ok    $*"; }
S=("$py" "$src/scripts/sweep.py" "$src/cases/dambreak_water.toml" --granflow "$bin"
   --vary phase.granular.rho=1000,1500 --vary grid.nx=27,32 --set grid.n=16
   --set time.t_end=0.02 --set output.vtk_interval=0 --out "$tmp/sw" --jobs 2
   --columns steps,volume_change_pct,t_end)

rc=0; timeout 300 "${S[@]}" > "$tmp/a.log" 2>&1 || rc=$?
rows=$(($(wc -l < "$tmp/sw/sweep.csv") - 1))
header=$(head -1 "$tmp/sw/sweep.csv")
if [[ $rc == 0 && $rows == 4 && $header == "run,status,phase.granular.rho,grid.nx,steps,volume_change_pct,t_end" ]] &&
   [[ $(grep -c ",completed,1[05]00,\(27\|32\),20," "$tmp/sw/sweep.csv") == 4 ]] &&
   [[ -f "$tmp/sw/rho=1500,nx=32/summary.json" ]]; then
  ok "4 runs, 2 at a time: exit 0, table of 4 rows: $(sed -n 2p "$tmp/sw/sweep.csv")"
else cat "$tmp/a.log" "$tmp/sw/sweep.csv"; bad "the first sweep: exit $rc, $rows rows"; fi
# Each row is its run's summary.json.
"$py" - "$tmp/sw" <<'PY' || bad "the table's figures are not those of the runs' summary.json"
import csv, json, os, sys
for r in csv.DictReader(open(os.path.join(sys.argv[1], "sweep.csv"))):
    s = json.load(open(os.path.join(sys.argv[1], r["run"], "summary.json")))
    assert float(r["volume_change_pct"]) == s["volume_change_pct"], r
    assert int(r["steps"]) == s["steps"] and float(r["t_end"]) == s["t_end"], r
    case = open(os.path.join(sys.argv[1], r["run"], "case.toml")).read()
    assert f"rho = {float(r['phase.granular.rho'])}" in case and f"nx = {r['grid.nx']}" in case, r
PY

rc=0; timeout 300 "${S[@]}" > "$tmp/b.log" 2>&1 || rc=$?
if [[ $rc == 0 && $(grep -c "skipped (completed before)" "$tmp/b.log") == 4 ]]; then
  ok "the same command again: the 4 completed runs skipped"
else cat "$tmp/b.log"; bad "the second sweep: exit $rc, not 4 skipped"; fi

rm "$tmp/sw/rho=1000,nx=27/summary.json"
rc=0; timeout 300 "${S[@]}" > "$tmp/c.log" 2>&1 || rc=$?
if [[ $rc == 0 && $(grep -c "skipped" "$tmp/c.log") == 3 && $(grep -c "rho=1000,nx=27: exit 0" "$tmp/c.log") == 1 ]]; then
  ok "a run without its summary.json is run again, alone"
else cat "$tmp/c.log"; bad "resume after a lost run: exit $rc"; fi

rc=0; timeout 300 "${S[@]}" --set time.cfl=0.4 > "$tmp/d.log" 2>&1 || rc=$?
if [[ $rc == 0 && $(grep -c ": exit 0" "$tmp/d.log") == 4 ]]; then ok "another --set: all 4 run again"
else cat "$tmp/d.log"; bad "a changed --set: exit $rc"; fi

rc=0; timeout 300 "$py" "$src/scripts/sweep.py" "$src/cases/dambreak_water.toml" --granflow "$bin" \
  --vary grid.n=16,4 --out "$tmp/bad" > "$tmp/e.log" 2>&1 || rc=$?
if [[ $rc == 2 ]] && grep -q "n=4: granflow check refuses it" "$tmp/e.log" && [[ ! -e "$tmp/bad/n=16" ]]; then
  ok "a combination granflow check refuses: exit 2 before any run"
else cat "$tmp/e.log"; bad "a bad combination: exit $rc"; fi

rc=0; "$py" "$src/scripts/sweep.py" --help > "$tmp/h.log" 2>&1 || rc=$?
[[ $rc == 0 ]] && grep -q "Resumable" "$tmp/h.log" && ok "--help: exit 0" || bad "--help: exit $rc"

if ((fails)); then echo "$fails check(s) failed"; exit 1; fi
echo "all sweep checks passed"
