#!/usr/bin/env bash
# Cessation of a Bingham flow (issue 3): cases/verify/bingham_cessation.toml, a vortex in a
# no-slip unit box (rho 1, eta 0.1, tau_y 0.1, Bi = 1), no forcing, n = 32, dt 5e-3, to t = 1 s.
# A Bingham flow stops in finite time: the kinetic energy must fall below 1e-14 of its start
# and stay there, and keep falling to the fixed-point tolerance's level (< 1e-20 of the start at
# t = 1 s), where an exponential (viscous) tail would stall orders of magnitude higher.
#
# The case uses rheology.plastic_grid = "cell_node". With the paper's cell-only S
# (plastic_grid = "cell") the same run stalls: KE 3.7e-10 J/m at 0.5 s, 3.5e-11 at 1 s
# (2e-10 of the start), a near-null mode of the cell-centred strain rate (docs/RHEOLOGY.md);
# this test also runs that variant and requires it to stay above 1e-12 of the start at 1 s,
# so that the test itself is shown to tell the two apart.
#
# The last phase of the arrest is a fast damped oscillation (period ~9 steps, the rigid zone made
# elastic-like by the pseudo-relaxation theta of eq. 31), so KE first dips below 1e-14 KE(0)
# at 0.595 s and stays below from 0.725 s. Required: below for good before 0.9 s, and
# KE(1 s) < 1e-20 KE(0).
# Measured (1 rank, Release, ~6 s + 5 s): cell_node: below 1e-14 KE(0) first at 0.595 s, for
# good from 0.725 s, KE(1 s) = 1.7e-23 J/m; cell: KE(1 s) = 3.5e-11 J/m.
# Usage: bash test_bingham_cessation.sh <granflow binary> <source dir>
set -euo pipefail
bin="$1"; src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
case_file="$src/cases/verify/bingham_cessation.toml"
for g in cell_node cell; do
  "$bin" run "$case_file" --set output.interval=0.005 output.vtk_interval=1 \
    "rheology.plastic_grid=\"$g\"" --out "$tmp/$g" > "$tmp/$g.log" 2>&1 ||
    { cat "$tmp/$g.log"; echo "FAIL: run $g"; exit 1; }
done

PYTHONPATH="$src/scripts" /usr/bin/python3 - "$tmp" <<'PY'
import sys
import granflow_run as gr
tmp = sys.argv[1]
ok = True
def load(g):
    d = gr.read_csv(f"{tmp}/{g}/diagnostics.csv")
    return d["t"].tolist(), d["kinetic_energy"].tolist()
t, ke = load("cell_node")
ke0 = ke[0]
thr = 1e-14 * ke0
first = next((k for k, e in enumerate(ke) if e < thr), None)
last_above = max((k for k, e in enumerate(ke) if e >= thr), default=-1)
stay = last_above + 1  # from this sample on, KE < 1e-14 KE(0) until the end
if first is None or stay >= len(ke):
    print(f"FAIL: cell_node: KE does not stay below 1e-14 KE(0) = {thr:.3e} (min {min(ke):.3e})")
    ok = False
else:
    print(f"cell_node: KE(0) = {ke0:.4f} J/m; below 1e-14 KE(0) first at t = {t[first]:.3f} s, "
          f"for good from t = {t[stay]:.3f} s; KE(t_end = {t[-1]:.2f} s) = {ke[-1]:.2e} J/m")
    if not (t[stay] < 0.9 and ke[-1] < 1e-20 * ke0):
        print("FAIL: cell_node: arrest later than 0.9 s or KE(t_end) >= 1e-20 KE(0)"); ok = False
tc, kc = load("cell")
print(f"cell (paper): KE(t_end) = {kc[-1]:.2e} J/m = {kc[-1] / kc[0]:.1e} KE(0)")
if not kc[-1] > 1e-12 * kc[0]:
    print("FAIL: the cell-only variant no longer stalls: this test no longer tells them apart "
          "(update the test and docs/RHEOLOGY.md)"); ok = False
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
PY
