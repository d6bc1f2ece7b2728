#!/usr/bin/env bash
# The Bagnold mu(I) profile (analytic (b1), Gerris parameters, cases/verify/bagnold.toml) at
# n = 8, 16, 32 cells across the layer, to its steady state (t = 400 s): error norms of u at
# the cell-centre heights against the exact profile and against the peer code's norms in
# tests/data/bagnold_gerris_test.csv. Writes docs/bagnold.md (or OUT); exits 1 if a
# norm is larger than the peer's at some N (tests/verification/test_bagnold.sh runs N = 8 16).
# usage: scripts/bagnold_study.sh [build dir] [N list, default "8 16 32"] [OUT]   (~45 s)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
ns="${2:-8 16 32}"
out_md="${3:-$root/docs/bagnold.md}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for n in $ns; do
  start=$SECONDS
  "$build/granflow" run "$root/cases/verify/bagnold.toml" --set grid.n=$n --out "$tmp/n$n" > "$tmp/log$n" 2>&1
  echo "$n $((SECONDS - start))" >> "$tmp/times"
done
PYTHONPATH="$root/scripts" /usr/bin/python3 - "$tmp" "$root" "$out_md" $ns <<'PY'
import math, sys
import numpy as np
import granflow_run as gr
tmp, root, out_md = sys.argv[1], sys.argv[2], sys.argv[3]
ns = [int(v) for v in sys.argv[4:]]
mus, dmu, I0, d, a = 0.38, 0.26, 0.3, 0.04, 0.43
Ia = I0 * (math.tan(a) - mus) / (mus + dmu - math.tan(a))
U0 = Ia * math.sqrt(math.cos(a)) / d
ref = gr.read_csv(f"{root}/tests/data/bagnold_gerris_test.csv")  # '#' lines skipped
peer = {int(n): (l1, l2, li) for n, l1, l2, li in
        zip(*(ref[k].tolist() for k in ("N_cells", "L1_error", "L2_error", "Linf_error")))}
times = dict(line.split() for line in open(f"{tmp}/times"))
rows = []
for n in ns:
    dat = gr.read_csv(f"{tmp}/n{n}/probes/profile.csv")
    blocks = [dat.where(dat["t"] == t) for t in dat.times[-2:]]
    b = blocks[-1]
    sel = np.abs(b["y"] * n - 0.5 - np.round(b["y"] * n - 0.5)) < 1e-9
    y, u = b["y"][sel], b["u"][sel]
    e = np.abs(u - 2 / 3 * U0 * (1 - (1 - y) ** 1.5))
    drift = np.max(np.abs(blocks[-1]["u"] - blocks[-2]["u"]))
    rows.append((n, e.mean(), math.sqrt((e ** 2).mean()), e.max(), peer[n], u[-1], drift, times[str(n)]))
out = [
    "# Bagnold mu(I) profile: error norms against the exact profile and the peer code",
    "",
    "Command: `scripts/bagnold_study.sh` (runs `granflow run cases/verify/bagnold.toml --set grid.n=N`",
    "for N = %s to t = 400 s, 1 rank). Errors of u at the N cell-centre heights against" % ", ".join(map(str, ns)),
    "(b1) of `../shared/reference/analytical_solutions.md` (u_surface = %.6f); mean, RMS and max" % (2 / 3 * U0),
    "(Gerris's `OutputErrorNorm` first, second and infinity norms); the peer's norms from",
    "`tests/data/bagnold_gerris_test.csv`.",
    "",
    "| N | L1 | L2 | Linf | Gerris L1 | Gerris L2 | Gerris Linf | u at top cell | drift over last 50 s | wall s |",
    "|---|---|---|---|---|---|---|---|---|---|",
]
for n, l1, l2, li, p, us, dr, w in rows:
    out.append(f"| {n} | {l1:.3e} | {l2:.3e} | {li:.3e} | {p[0]:.3e} | {p[1]:.3e} | {p[2]:.3e} | {us:.5f} | {dr:.1e} | {w} |")
ok = all(r[1] <= r[4][0] and r[2] <= r[4][1] and r[3] <= r[4][2] for r in rows)
out += ["", "No larger than the peer's at every N: " + ("yes" if ok else "**no**"), ""]
open(out_md, "w").write("\n".join(out))
print("\n".join(out))
sys.exit(0 if ok else 1)
PY
