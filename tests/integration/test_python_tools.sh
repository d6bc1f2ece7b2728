#!/usr/bin/env bash
# The Python tools of scripts/ as a user meets them, on two tiny runs (case A at grid.n = 16 and
# 20, to t = 0.05 s, VTK every 0.025 s; about a second each):
#  1. granflow_run reads a run: the columns of diagnostics.csv with their units, its values
#     against the file's own text, an output time picked by distance (within a tolerance;
#     refused beyond it, although the times carry float noise), summary.json and case.toml with
#     units, a VTK field on the grid with its coordinates and the granular mask phi < 0;
#  2. plot_run.py writes the figures of a run; --help exits 0 and creates nothing; a bad option
#     and a folder that is not a run exit 2 with an error line and write nothing;
#  3. plot_collapse.py A --compare B writes into A/figures/compare_B/, leaving A's own figures
#     as they were, each curve with its own legend (read in the SVG's text: the folder names, or
#     the --label texts);
#  4. animate_run.py makes a GIF with one frame per VTK snapshot.
# Every external command is bounded in time (timeout). Figures at a low resolution (--dpi 40):
# what is checked is what is drawn and where it goes, not how fine.
# Usage: bash test_python_tools.sh <granflow binary> <source dir>
set -uo pipefail
bin="$1"; src="$2"
py=/usr/bin/python3
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fails=0
ok() { echo "ok    $*"; }
bad() { echo "FAIL  $*"; fails=$((fails + 1)); }
T() { timeout 120 "$@"; }

for r in runA:16 runB:20; do
  name="${r%%:*}"
  T "$bin" run "$src/cases/ar07_rough.toml" --set grid.n="${r#*:}" --set time.t_end=0.05 \
    --set output.vtk_interval=0.025 --out "$tmp/$name" > "$tmp/$name.log" 2>&1 ||
    { cat "$tmp/$name.log"; echo "FAIL: granflow run $name"; exit 1; }
done
A="$tmp/runA" B="$tmp/runB"

# ---- 1. the reader
if T env PYTHONPATH="$src/scripts" "$py" - "$A" <<'PY'
import sys
import numpy as np
import granflow_run as gr

run, bad = gr.Run(sys.argv[1]), []
def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        bad.append(what)

d = run.diagnostics
lines = [ln for ln in open(run.path("diagnostics.csv")) if ln.strip()]
header, last = lines[0].strip().split(","), lines[-1].strip().split(",")
check(d.columns == header, f"diagnostics.csv: the columns in the file's order ({len(header)})")
check(len(d) == len(lines) - 1, f"diagnostics.csv: {len(d)} rows, one per data line")
check(all(d[k][-1] == float(v) for k, v in zip(header, last)),
      "diagnostics.csv: the last row's values are the file's numbers")
units = {k: d.units[k] for k in ("t", "front_x", "max_p_granular", "kinetic_energy")}
check(units == {"t": "s", "front_x": "m", "max_p_granular": "Pa", "kinetic_energy": "J/m"},
      f"units {units}")
check(all(d.units[k] for k in d.columns), "every column of diagnostics.csv has a unit")
# Output times: 0, 0.01, ... 0.05 s, as the run summed them (not exact decimals).
row = d.at(0.03)
check(len(row) == 1 and abs(row["t"][0] - 0.03) < 1e-9, f"at(0.03): t = {row['t'][0]!r}")
check(d.at(0.0334, tol=0.005)["t"][0] == row["t"][0], "at(0.0334, tol=0.005) picks 0.03")
try:
    d.at(0.0334)
    check(False, "at(0.0334) with the default tolerance must be refused")
except LookupError as e:
    check("0.0334" in str(e), f"at(0.0334) refused: {e}")
p = run.profiles.at(0.05)
check(len(p) == 64 and p.units["h"] == "m", f"profiles.csv at 0.05 s: {len(p)} columns, h in m")
s = run.summary
check(s.get("status") == "completed" and run.summary_units["runout_m"] == "m"
      and run.summary_units["t1_s"] == "s", "summary.json with units (runout_m m, t1_s s)")
check(run.case["grid"]["n"] == 16 and run.case_units.get("domain.Lx") == "m",
      "case.toml: grid.n = 16, domain.Lx in m (from the file's comments)")
f = run.fields(0.025)
check(abs(f.t - 0.025) < 1e-9 and len(run.snapshots) == 3, f"snapshot at t = {f.t!r} of 3")
check(f["p"].shape == (16, 64) and f["u"].shape == (16, 64, 3), "p (16, 64), u (16, 64, 3)")
check(np.isclose(f.xc[0], 0.8 / 128) and np.isclose(f.yn[-1], 0.2), "cell centres and nodes")
g = f.granular_mask
check(0 < g.sum() < g.size and np.array_equal(f.granular("speed").mask, ~g),
      f"granular mask phi < 0: {g.sum()} of {g.size} cells, the speed masked elsewhere")
u, v = f["u"][..., 0], f["u"][..., 1]
check(np.array_equal(f["speed"][g], np.sqrt(u * u + v * v)[g]),
      "speed = |u| cell by cell (the field layout is (y, x))")
sys.exit(1 if bad else 0)
PY
then ok "granflow_run reads the run"; else bad "granflow_run"; fi

# ---- 2. plot_run.py
rc=0; T "$py" "$src/scripts/plot_run.py" "$A" --dpi 40 > "$tmp/plot.log" 2>&1 || rc=$?
missing=""
for f in diagnostics front collapse_front collapse_speed collapse_structure collapse_head; do
  [[ -s "$A/figures/$f.png" ]] || missing+=" $f.png"
done
if [[ $rc == 0 && -z "$missing" ]]; then ok "plot_run.py: exit 0, figures in $A/figures"
else cat "$tmp/plot.log"; bad "plot_run.py: exit $rc, missing:$missing"; fi
mkdir -p "$tmp/cwd" "$tmp/notarun"
rc=0; (cd "$tmp/cwd" && T "$py" "$src/scripts/plot_run.py" --help > "$tmp/help.log" 2>&1) || rc=$?
if [[ $rc == 0 ]] && grep -q "^usage: plot_run.py" "$tmp/help.log" && [[ -z "$(ls -A "$tmp/cwd")" ]]
then ok "plot_run.py --help: exit 0, usage printed, nothing created"
else bad "plot_run.py --help: exit $rc, created: $(ls -A "$tmp/cwd")"; cat "$tmp/help.log"; fi
for args in "--bogus $A" "$tmp/notarun" "$A --format png" "$A --dpi 0" "$tmp/missing"; do
  rc=0
  # shellcheck disable=SC2086  # $args is a list of words on purpose
  (cd "$tmp/cwd" && T "$py" "$src/scripts/plot_run.py" $args > "$tmp/err.log" 2>&1) || rc=$?
  if [[ $rc == 2 ]] && grep -q "plot_run.py: error: " "$tmp/err.log" &&
     [[ -z "$(ls -A "$tmp/cwd")$(ls -A "$tmp/notarun")" ]]; then
    ok "plot_run.py $args: exit 2: $(grep -o 'error: .*' "$tmp/err.log")"
  else bad "plot_run.py $args: exit $rc (expected 2 and nothing written)"; cat "$tmp/err.log"; fi
done

# ---- 3. plot_collapse.py --compare
sum_before=$(cd "$A/figures" && md5sum collapse_front.png collapse_profile.png)
legends() {  # the texts of an SVG figure
  "$py" -c 'import re, sys, html; print("\n".join(html.unescape(t) for t in
            re.findall(r"<text[^>]*>([^<]*)</text>", open(sys.argv[1]).read())))' "$1"
}
rc=0
T "$py" "$src/scripts/plot_collapse.py" "$A" --compare "$B" --format svg --dpi 40 \
  > "$tmp/cmp.log" 2>&1 || rc=$?
cmpdir="$A/figures/compare_runB"
if [[ $rc == 0 && -s "$cmpdir/collapse_front.png" && -s "$cmpdir/collapse_profile.svg" ]] &&
   [[ "$(cd "$A/figures" && md5sum collapse_front.png collapse_profile.png)" == "$sum_before" ]]
then ok "--compare: figures in $cmpdir, $A/figures/collapse_*.png untouched"
else cat "$tmp/cmp.log"; bad "--compare: exit $rc, or not in $cmpdir, or A's figures changed"; fi
texts="$(legends "$cmpdir/collapse_front.svg")"
if grep -qxF "runA (64 x 16)" <<< "$texts" && grep -qxF "runB (80 x 20)" <<< "$texts"; then
  ok "--compare legends: 'runA (64 x 16)', 'runB (80 x 20)'"
else bad "--compare legends are not the runs' names: $(tr '\n' '|' <<< "$texts")"; fi
rc=0
T "$py" "$src/scripts/plot_collapse.py" "$A" --compare "$B" --label "coarse" "fine" \
  --figures "$tmp/labelled" --format svg --dpi 40 > "$tmp/cmp2.log" 2>&1 || rc=$?
texts="$(legends "$tmp/labelled/collapse_profile.svg" 2> /dev/null)"
if [[ $rc == 0 ]] && grep -q "^coarse (64 x 16), t = " <<< "$texts" &&
   grep -q "^fine (80 x 20), t = " <<< "$texts"; then
  ok "--label coarse fine: the profile's legends say so"
else cat "$tmp/cmp2.log"; bad "--label: exit $rc, legends $(tr '\n' '|' <<< "$texts")"; fi

# ---- 4. animate_run.py
rc=0
T "$py" "$src/scripts/animate_run.py" "$A" --format gif --dpi 40 --out "$tmp/anim.gif" \
  > "$tmp/anim.log" 2>&1 || rc=$?
frames=$("$py" -c 'import sys; from PIL import Image; print(Image.open(sys.argv[1]).n_frames)' \
         "$tmp/anim.gif" 2> /dev/null)
if [[ $rc == 0 && "$frames" == 3 ]]; then ok "animate_run.py: a GIF of 3 frames (3 snapshots)"
else cat "$tmp/anim.log"; bad "animate_run.py: exit $rc, frames '$frames' (expected 3)"; fi

if ((fails)); then echo "$fails check(s) failed"; exit 1; fi
echo "all Python tool checks passed"
