#!/usr/bin/python3
"""Same particle trajectories from two runs (1 and 2 ranks): every logged
position and velocity agree within --tolerance, relative to the largest
displacement and speed of the run. Particles are matched by their initial
positions (LIGGGHTS numbers atoms it creates in an order that depends on the
decomposition). Usage: compareTrajectories.py CASE_A CASE_B [--tolerance T]"""
import argparse
import csv
import os
import sys


def load(case):
    """Rows sorted by time, then by the particle's initial position."""
    with open(os.path.join(case, "postProcessing", "particles.csv")) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    t0 = rows[0]["time"]
    start = {r["tag"]: (round(r["x"], 9), round(r["y"], 9), round(r["z"], 9)) for r in rows if r["time"] == t0}
    # The first coupling step may be logged twice at t0; keep the last of each (time, tag).
    unique = {(r["time"], r["tag"]): r for r in rows}
    return sorted(unique.values(), key=lambda r: (r["time"], start[r["tag"]]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--tolerance", type=float, default=1e-6)
    args = ap.parse_args()
    a, b = load(args.a), load(args.b)
    if len(a) != len(b) or len(a) < 10:
        print(f"FAIL: {len(a)} and {len(b)} trajectory rows")
        return 1
    start = {r["tag"]: r for r in a if r["time"] == a[0]["time"]}
    if any(abs(ra["time"] - rb["time"]) > 1e-12 for ra, rb in zip(a, b)):
        print("FAIL: the runs logged different times")
        return 1
    travel = max(abs(r[k] - start[r["tag"]][k]) for r in a for k in "xyz")
    speed = max(abs(r[k]) for r in a for k in ("vx", "vy", "vz"))
    dx = max(abs(ra[k] - rb[k]) for ra, rb in zip(a, b) for k in "xyz")
    dv = max(abs(ra[k] - rb[k]) for ra, rb in zip(a, b) for k in ("vx", "vy", "vz"))
    print(f"largest difference: position {dx:.3e} m of {travel:.4f} m travelled, "
          f"velocity {dv:.3e} m/s of {speed:.4f} m/s")
    if dx > args.tolerance * travel or dv > args.tolerance * speed:
        print(f"FAIL: more than {args.tolerance} of the motion")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
