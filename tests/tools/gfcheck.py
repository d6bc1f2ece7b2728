#!/usr/bin/python3
"""Checkers for the verification and regression script tests (tests/*/test_*.sh).

Run with Debian's /usr/bin/python3 (needs numpy). Every subcommand prints what it measured
and exits 0 on pass, 1 on a failed check, 2 on unreadable or malformed input.

  gfcheck.py ghia RUN_DIR REF_DIR [--tol 0.02] [--steady-tol 1e-4]
      Lid-driven cavity at Re = 100 against Ghia, Ghia & Shin (1982).
  gfcheck.py rest RUN_DIR [--max-speed 1e-6] [--volume-pct 1e-6] [--rows N]
      A fluid at rest must stay at rest: every row of diagnostics.csv.
  gfcheck.py compare A.csv B.csv [--rtol R] [--atol COL=V ...] [--int-tol COL=N ...]
                     [--columns c1,c2,...] [--block-key t]
      Row-by-row comparison of two CSV files (see cmd_compare for the rule).
  gfcheck.py extract RUN_DIR/diagnostics.csv OUT.csv --columns t,max_speed,...
      Writes the chosen columns (17 significant digits): how regression references are made.
  gfcheck.py pvd RUN_DIR/fields.pvd [--count N] [--same-as OTHER.pvd]
      The ParaView collection is valid XML, lists files that exist (each a VTK XML
      RectilinearGrid file), with strictly increasing times, and every BASE_*.vtr file of the
      folder is listed; optionally exactly N entries, or the same (time, file) list as OTHER.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import granflow_run as gr  # noqa: E402  (the one reader of granflow's files)


class InputProblem(Exception):
    pass


def read_csv(path):
    """(header list, 2-D float array) of a CSV with one header line; '#' lines are comments."""
    try:
        t = gr.read_csv(path, units={})
    except OSError as e:
        raise InputProblem(f"cannot read {path}: {e}")
    except gr.RunFileError as e:
        raise InputProblem(str(e))
    if not t.columns:
        raise InputProblem(f"{path}: empty")
    if not len(t):
        raise InputProblem(f"{path}: no data rows")
    return t.columns, t.array()


def col(header, data, name, path):
    if name not in header:
        raise InputProblem(f"{path}: no column {name!r} (columns: {', '.join(header)})")
    return data[:, header.index(name)]


def probe_blocks(path, field):
    """Probe CSV (t,x,y,fields...) -> list of (t, x, y, values) per output time."""
    h, d = read_csv(path)
    t = col(h, d, "t", path)
    x, y, v = col(h, d, "x", path), col(h, d, "y", path), col(h, d, field, path)
    blocks = []
    for tv in np.unique(t):
        m = t == tv
        blocks.append((tv, x[m], y[m], v[m]))
    return blocks


# ------------------------------------------------------------------------------------------
def cmd_ghia(a):
    """Centre-line velocities of the last output time against Ghia's Re = 100 columns.

    The probe values are interpolated linearly (in the coordinate along the line) to Ghia's
    tabulated stations. The wall stations (y = 0, 1 for u; x = 0, 1 for v) are boundary
    conditions, not results, and the probes hold the value of the first interior sample row
    between a wall and half a cell from it (no extrapolation, see src/io/Probes.hpp), so at
    the moving lid the probe does not give u = 1. They are therefore left out of the error
    and printed separately. Also checks that the run is steady: the last two output blocks
    differ by less than --steady-tol.
    """
    failed = False
    specs = [("u_vertical_centerline", "u", "y", "ghia1982_u_vertical_centerline.csv",
              "y", "u_Re100"),
             ("v_horizontal_centerline", "v", "x", "ghia1982_v_horizontal_centerline.csv",
              "x", "v_Re100")]
    for probe, field, coord, ref_name, ref_coord, ref_col in specs:
        blocks = probe_blocks(f"{a.run_dir}/probes/{probe}.csv", field)
        if len(blocks) < 2:
            raise InputProblem(f"{probe}: need at least two output times, got {len(blocks)}")
        (t1, x1, y1, v1), (t0, _, _, v0) = blocks[-1], blocks[-2]
        if len(v0) != len(v1):
            raise InputProblem(f"{probe}: blocks of different length")
        drift = float(np.max(np.abs(v1 - v0)))
        ok_steady = drift < a.steady_tol
        print(f"{probe}: steadiness max |{field}(t={t1:g}) - {field}(t={t0:g})| = "
              f"{drift:.3e} (limit {a.steady_tol:g}) {'ok' if ok_steady else 'FAIL'}")
        failed |= not ok_steady

        s = x1 if coord == "x" else y1
        order = np.argsort(s)
        s, v1 = s[order], v1[order]
        rh, rd = read_csv(f"{a.ref_dir}/{ref_name}")
        rs, rv = col(rh, rd, ref_coord, ref_name), col(rh, rd, ref_col, ref_name)
        if rs.min() < s.min() - 1e-12 or rs.max() > s.max() + 1e-12:
            raise InputProblem(f"{probe}: reference stations outside the probe segment")
        sim = np.interp(rs, s, v1)
        wall = (rs <= 1e-12) | (rs >= 1.0 - 1e-12)
        err = np.abs(sim - rv)
        inner = np.where(~wall)[0]
        k = inner[np.argmax(err[inner])]
        ok = err[k] < a.tol
        print(f"{probe}: {len(inner)} interior stations, max |{field} - Ghia| = {err[k]:.4f} "
              f"at {ref_coord} = {rs[k]:.4f} (granflow {sim[k]:.5f}, Ghia {rv[k]:.5f}); "
              f"limit {a.tol:g} -> {'ok' if ok else 'FAIL'}")
        for i in np.where(wall)[0]:
            print(f"  wall station {ref_coord} = {rs[i]:.4f} (not checked): "
                  f"probe {sim[i]:.5f}, Ghia {rv[i]:.5f}")
        if a.verbose:
            for i in range(len(rs)):
                print(f"  {ref_coord} = {rs[i]:.4f}  granflow {sim[i]:+.5f}  "
                      f"Ghia {rv[i]:+.5f}  diff {sim[i] - rv[i]:+.5f}")
        failed |= not ok
    return 1 if failed else 0


# ------------------------------------------------------------------------------------------
def cmd_rest(a):
    path = f"{a.run_dir}/diagnostics.csv"
    h, d = read_csv(path)
    t, step = col(h, d, "t", path), col(h, d, "step", path)
    speed, vol = col(h, d, "max_speed", path), col(h, d, "volume_change_pct", path)
    failed = False
    if a.rows and len(t) != a.rows:
        print(f"FAIL: {len(t)} rows in diagnostics.csv, expected {a.rows}")
        failed = True
    if a.steps and int(step[-1]) != a.steps:
        print(f"FAIL: last step {int(step[-1])}, expected {a.steps}")
        failed = True
    ks, kv = int(np.argmax(np.where(np.isfinite(speed), speed, np.inf))), \
        int(np.argmax(np.where(np.isfinite(vol), np.abs(vol), np.inf)))
    ok_s = bool(np.all(np.isfinite(speed)) and np.all(speed < a.max_speed))
    ok_v = bool(np.all(np.isfinite(vol)) and np.all(np.abs(vol) < a.volume_pct))
    print(f"max_speed over {len(t)} rows: largest {speed[ks]:.3e} m/s at t = {t[ks]:g} s "
          f"(step {int(step[ks])}); limit {a.max_speed:g} -> {'ok' if ok_s else 'FAIL'}")
    print(f"|volume_change_pct|: largest {abs(vol[kv]):.3e} % at t = {t[kv]:g} s; "
          f"limit {a.volume_pct:g} -> {'ok' if ok_v else 'FAIL'}")
    failed |= not (ok_s and ok_v)
    return 1 if failed else 0


# ------------------------------------------------------------------------------------------
def parse_kv(items, conv):
    out = {}
    for it in items or []:
        k, _, v = it.partition("=")
        if not _:
            raise InputProblem(f"expected COLUMN=VALUE, got {it!r}")
        out[k] = conv(v)
    return out


def cmd_compare(a):
    """Row-by-row comparison of the columns of B (or --columns) in A and B.

    Rule, per value: |a - b| <= rtol * max(|a|, |b|) + atol(column), where atol(column) is
    the --atol given for that column, else rtol * (largest |value| of the column in both
    files): values near 0 are compared against the column's scale, not their own size.
    Integer columns named in --int-tol (KSP iteration counts) may differ by that many.
    Both files must have the same number of rows.
    """
    ha, da = read_csv(a.a)
    hb, db = read_csv(a.b)
    cols = a.columns.split(",") if a.columns else hb
    atol = parse_kv(a.atol, float)
    itol = parse_kv(a.int_tol, int)
    if da.shape[0] != db.shape[0]:
        print(f"FAIL: {a.a} has {da.shape[0]} rows, {a.b} has {db.shape[0]}")
        return 1
    tcol = a.label if a.label in ha else None
    failed = False
    for c in cols:
        x, y = col(ha, da, c, a.a), col(hb, db, c, a.b)
        if c in itol:
            diff = np.abs(x - y)
            bad = ~(diff <= itol[c])
            rule = f"|diff| <= {itol[c]} (iteration count)"
            worst = int(np.argmax(np.where(np.isfinite(diff), diff, np.inf)))
        else:
            scale = float(np.nanmax(np.abs(np.concatenate([x, y])))) if len(x) else 0.0
            floor = atol.get(c, a.rtol * scale)
            diff = np.abs(x - y)
            lim = a.rtol * np.maximum(np.abs(x), np.abs(y)) + floor
            bad = ~(diff <= lim)  # NaN counts as bad
            rule = f"rtol {a.rtol:g}, atol {floor:.3g}"
            excess = np.where(np.isfinite(diff), diff / np.where(lim > 0, lim, 1e-300), np.inf)
            worst = int(np.argmax(excess))
        where = f"row {worst + 1}" + (f" ({a.label} = {da[worst, ha.index(tcol)]:.17g})"
                                      if tcol else "")
        status = "FAIL" if bad.any() else "ok"
        print(f"{c:>18}: max |diff| {np.nanmax(diff) if len(diff) else 0:.3e} "
              f"[{rule}] worst at {where}: {x[worst]:.17g} vs {y[worst]:.17g}  {status}"
              + (f" ({int(bad.sum())} rows out of tolerance)" if bad.any() else ""))
        if bad.any():
            for i in np.where(bad)[0][:8]:
                print(f"{'':>20}out of tolerance at row {i + 1}"
                      + (f" ({a.label} = {da[i, ha.index(tcol)]:.17g})" if tcol else "")
                      + f": {x[i]:.17g} vs {y[i]:.17g} (diff {y[i] - x[i]:+.3e})")
        failed |= bool(bad.any())
    print(f"compared {len(cols)} columns x {da.shape[0]} rows: {'FAIL' if failed else 'ok'}")
    return 1 if failed else 0


def cmd_extract(a):
    h, d = read_csv(a.src)
    cols = a.columns.split(",")
    idx = [h.index(c) for c in cols if c in h]
    if len(idx) != len(cols):
        raise InputProblem(f"{a.src}: missing one of {cols}")
    with open(a.dst, "w") as f:
        for line in a.comment or []:
            f.write(f"# {line}\n")
        f.write(",".join(cols) + "\n")
        for row in d:
            f.write(",".join(f"{row[i]:.17g}" for i in idx) + "\n")
    print(f"wrote {a.dst}: {len(d)} rows, columns {', '.join(cols)}")
    return 0


def pvd_entries(path):
    try:
        return gr.read_pvd(path, join=False)
    except OSError as e:
        raise InputProblem(f"{path}: not valid XML: {e}")
    except gr.RunFileError as e:
        raise InputProblem(str(e))


def cmd_pvd(a):
    import glob
    entries = pvd_entries(a.pvd)
    folder = os.path.dirname(os.path.abspath(a.pvd))
    base = os.path.splitext(os.path.basename(a.pvd))[0]
    bad = []
    for t, f in entries:
        path = os.path.join(folder, f)
        if not os.path.isfile(path):
            bad.append(f"lists {f} (t = {t}), which does not exist")
            continue
        with open(path, "rb") as fh:
            head = fh.read(300)
        if not head.startswith(b"<?xml") or b'<VTKFile type="RectilinearGrid"' not in head:
            bad.append(f"{f} is not a VTK XML RectilinearGrid file")
    times = [t for t, _ in entries]
    if any(t1 <= t0 for t0, t1 in zip(times, times[1:])):
        bad.append(f"times are not strictly increasing: {times}")
    listed = {f for _, f in entries}
    for f in sorted(glob.glob(os.path.join(folder, base + "_*.vtr"))):
        if os.path.basename(f) not in listed:
            bad.append(f"{os.path.basename(f)} is in the folder but not listed")
    if a.count is not None and len(entries) != a.count:
        bad.append(f"{len(entries)} entries, expected {a.count}")
    if a.same_as:
        other = pvd_entries(a.same_as)
        if other != entries:
            bad.append(f"entries differ from {a.same_as}: {entries} vs {other}")
    for b in bad:
        print(f"FAIL  {a.pvd}: {b}")
    print(f"{a.pvd}: valid XML, {len(entries)} files listed, t = {times[0] if times else '-'}"
          f" .. {times[-1] if times else '-'}: {'FAIL' if bad else 'ok'}")
    return 1 if bad else 0


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    g = sub.add_parser("ghia")
    g.add_argument("run_dir"), g.add_argument("ref_dir")
    g.add_argument("--tol", type=float, default=0.02)
    g.add_argument("--steady-tol", type=float, default=1e-4)
    g.add_argument("--verbose", action="store_true")
    r = sub.add_parser("rest")
    r.add_argument("run_dir")
    r.add_argument("--max-speed", type=float, default=1e-6)
    r.add_argument("--volume-pct", type=float, default=1e-6)
    r.add_argument("--rows", type=int, default=0)
    r.add_argument("--steps", type=int, default=0)
    c = sub.add_parser("compare")
    c.add_argument("a"), c.add_argument("b")
    c.add_argument("--rtol", type=float, default=1e-8)
    c.add_argument("--atol", action="append", metavar="COL=V")
    c.add_argument("--int-tol", action="append", metavar="COL=N")
    c.add_argument("--columns", default="")
    c.add_argument("--label", default="t", help="column printed to locate a row")
    e = sub.add_parser("extract")
    e.add_argument("src"), e.add_argument("dst")
    e.add_argument("--columns", required=True)
    e.add_argument("--comment", action="append")
    v = sub.add_parser("pvd")
    v.add_argument("pvd")
    v.add_argument("--count", type=int)
    v.add_argument("--same-as")
    a = p.parse_args()
    try:
        return {"ghia": cmd_ghia, "rest": cmd_rest, "compare": cmd_compare,
                "extract": cmd_extract, "pvd": cmd_pvd}[a.cmd](a)
    except InputProblem as ex:
        print(f"gfcheck: {ex}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
