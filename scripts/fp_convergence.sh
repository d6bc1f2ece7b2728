#!/usr/bin/env bash
# The convergence of the fixed point of eq. 31 on collapse steps of case A (n = 64): runs
# 3 steps with a cap of 400 iterations and rheology.fp_monitor, once as the plain Picard
# iteration of the paper (rheology.anderson_depth = 0) and once with the default Anderson
# acceleration (depth 5); writes
# the change per iteration to docs/fp_convergence.csv and docs/figures/fp_convergence.png.
# usage: scripts/fp_convergence.sh [build dir]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
echo "anderson,step,iteration,change,du_max_mps,u_max_mps" > "$root/docs/fp_convergence.csv"
for m in 0 5; do
  "$build/granflow" run "$root/cases/ar07_rough.toml" --out "$tmp/run$m" --set time.max_steps=3 \
    --set rheology.fp_max_iter=400 --set rheology.fp_tol=1e-8 --set output.vtk_interval=0 \
    --set rheology.fp_monitor=true --set rheology.anderson_depth=$m > "$tmp/log$m" 2>&1
  awk -v m=$m '/fixed point step/ {gsub(/[()]/,""); print m","$4","$6","$8","$10","$14}' "$tmp/log$m" \
    >> "$root/docs/fp_convergence.csv"
done
PYTHONPATH="$root/scripts" /usr/bin/python3 - "$root/docs/fp_convergence.csv" "$root/docs/figures/fp_convergence.png" <<'PY'
import sys
import granflow_run as gr
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
rows = gr.read_csv(sys.argv[1])
fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
for m, style in ((0, "-"), (5, "--")):
    for step in sorted(set(rows["step"].astype(int).tolist())):
        sel = rows.where((rows["step"] == step) & (rows["anderson"] == m))
        it = sel["iteration"].astype(int).tolist()
        lab = ("Picard" if m == 0 else "Anderson(5)") + f", step {step}"
        ax[0].semilogy(it, sel["change"].tolist(), style, label=lab)
        ax[1].semilogy(it, (sel["du_max_mps"] / sel["u_max_mps"]).tolist(), style, label=lab)
ax[0].set_ylabel(r"max change of $S$ and $s_t$ per iteration")
ax[1].set_ylabel(r"max $|\tilde u_k - \tilde u_{k-1}|$ / max $|\tilde u|$")
for a in ax:
    a.set_xlabel("fixed-point iteration")
    a.grid(alpha=0.3, which="both")
    a.legend(fontsize=7)
fig.suptitle("Fixed point of eq. 31, case A (n = 64, DP, eta_0 = 0.5), first steps (dt = 1e-3 s, theta = 0.01)")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
PY
echo "wrote docs/fp_convergence.csv and docs/figures/fp_convergence.png"
