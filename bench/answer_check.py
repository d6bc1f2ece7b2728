#!/usr/bin/python3
"""The answer must not move (issue 6, item 3): compare the summary figures of case A at n = 64
(a finished run's summary.json) with a reference, within stated tolerances.

usage: answer_check.py RUN_DIR [--ref bench/answer_ref_a64.json] [--write-ref]

The reference holds the figures of a run made before a speed change (its command and granflow
version are stored beside them). Tolerances, chosen from what the figures mean, not from what
passes:
  runout_m, backwall_height_m, max_front_x_m      1 % relative (the paper's n = 64 -> 128
                                                  change of the runout is ~3 %)
  front_speed_mps                                 2 % relative (a slope fitted over 0.1 s)
  t1_s, t2_s, t3_s                                0.02 s (two output intervals: they are read
                                                  off the 0.01 s diagnostics)
  tf_s                                            0.05 s (the end of motion is a threshold on a
                                                  slowly decaying max |u|)
  volume_change_pct                               0.1 percentage point
  max_p_granular_ratio                            2 % relative (a peak over space and time
                                                  that depends on how far the fixed point of
                                                  eq. 31 is converged: at n = 64 it is 0.6 %
                                                  below its fully converged value with
                                                  rheology.fp_tol = 1e-4, docs/PERFORMANCE.md)
  slope_back_deg, slope_front_deg, front_angle_deg 1 degree
Exit 0 when every figure is within its tolerance, 1 otherwise (the table says which).
"""
import argparse
import json
import os
import sys

TOL = {  # key: (kind, tolerance)
    "runout_m": ("rel", 0.01),
    "max_front_x_m": ("rel", 0.01),
    "backwall_height_m": ("rel", 0.01),
    "front_speed_mps": ("rel", 0.02),
    "t1_s": ("abs", 0.02),
    "t2_s": ("abs", 0.02),
    "t3_s": ("abs", 0.02),
    "tf_s": ("abs", 0.05),
    "volume_change_pct": ("abs", 0.1),
    "max_p_granular_ratio": ("rel", 0.02),
    "slope_back_deg": ("abs", 1.0),
    "slope_front_deg": ("abs", 1.0),
    "front_angle_deg": ("abs", 1.0),
}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("run", help="output folder of a finished case A n = 64 run to t = 1.06 s")
    ap.add_argument("--ref", default=os.path.join(here, "answer_ref_a64.json"))
    ap.add_argument("--write-ref", action="store_true",
                    help="store this run's figures as the new reference")
    a = ap.parse_args()
    s = json.load(open(os.path.join(a.run, "summary.json")))
    if s.get("status") != "completed" or s.get("nx") != 256 or s.get("ny") != 64:
        sys.exit(f"answer_check: {a.run} is not a completed case A run at n = 64 "
                 f"(status {s.get('status')}, {s.get('nx')} x {s.get('ny')} cells)")
    if a.write_ref:
        cmd = open(os.path.join(a.run, "command.txt")).read().strip() \
            if os.path.exists(os.path.join(a.run, "command.txt")) else "?"
        ref = {"version": s.get("version"), "command": cmd, "wall_s": s.get("wall_s"),
               "figures": {k: s.get(k) for k in TOL}}
        json.dump(ref, open(a.ref, "w"), indent=2)
        print(f"answer_check: reference written to {a.ref}")
        return 0
    ref = json.load(open(a.ref))
    print(f"reference: granflow {ref['version']}, wall {ref['wall_s']:.1f} s; "
          f"this run: granflow {s.get('version')}, wall {s.get('wall_s', 0):.1f} s")
    print(f"{'figure':24s} {'reference':>12s} {'this run':>12s} {'difference':>12s} "
          f"{'tolerance':>10s}  ok")
    bad = 0
    for k, (kind, tol) in TOL.items():
        r, v = ref["figures"].get(k), s.get(k)
        if r is None or v is None:
            ok = r is None and v is None
            print(f"{k:24s} {str(r):>12s} {str(v):>12s} {'':>12s} {'':>10s}  "
                  f"{'yes' if ok else 'NO (missing)'}")
            bad += not ok
            continue
        d = (v - r) / abs(r) if kind == "rel" else v - r
        ok = abs(d) <= tol
        bad += not ok
        ds = f"{100 * d:+.3f} %" if kind == "rel" else f"{d:+.4g}"
        ts = f"{100 * tol:g} %" if kind == "rel" else f"{tol:g}"
        print(f"{k:24s} {r:12.6g} {v:12.6g} {ds:>12s} {ts:>10s}  {'yes' if ok else 'NO'}")
    print("answer_check: " + ("the answer has not moved" if not bad else f"{bad} figure(s) moved"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
