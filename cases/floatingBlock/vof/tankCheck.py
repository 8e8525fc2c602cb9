#!/usr/bin/python3
"""Closed tank at the vof level: the block of this case pushed down into the
water (demVariables pushDepth, pushSpeed) and held. From a finished run:

  - the rise of the water level (the columns no particle reaches,
    postProcessing/vof.csv) against the rise that keeps the water's volume:
    A (h - h0) = V_sub(h) - V_sub(h0), A the tank's plan area, V_sub the
    spheres' volume below the level (caps; bisection for h);
  - the pressure force on the ice (vof.csv pressureForceZ) against the
    buoyancy rho_w g V_sub(h) of its submerged volume at rest.

    /usr/bin/python3 tankCheck.py CASE [--check] [--rise-tolerance 0.02] [--force-tolerance 0.01]
    /usr/bin/python3 tankCheck.py --run under|through [--np N] [--publish]

Writes CASE/postProcessing/tank.json; with --check exits 1 when either is off by
more than its tolerance. --run makes the case first (../runs/tank_MODE): the
water 5 cm below the block, which is pushed down at 0.1 m/s by 0.40 m (under:
its top ends 14 cm below the level) or 0.15 m (through: it ends through the
surface, half submerged), 7 s in all; --publish copies its tank.json to
results/tank_MODE.json."""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "postProcessing"))
from iceCases import get_entry, write_atomically  # noqa: E402


def cap_volume(depth, r):
    h = min(max(depth, 0.0), 2.0 * r)
    return math.pi * h * h * (3.0 * r - h) / 3.0


def submerged(particles, level):
    return sum(cap_volume(level - (z - 0.5 * d), 0.5 * d) for z, d in particles)


def particles_at(case, which):
    """(z, d) of every particle at the first (which=0) or last (-1) logged time."""
    by_time = {}
    with open(os.path.join(case, "postProcessing", "particles.csv")) as f:
        for r in csv.DictReader(f):
            by_time.setdefault(float(r["time"]), {})[r["tag"]] = (float(r["z"]), float(r["diameter"]))
    return list(by_time[sorted(by_time)[which]].values())


def plan_area(case):
    """Plan area of the blockMesh box (its vertices' x and y range)."""
    text = open(os.path.join(case, "system", "blockMeshDict")).read()
    body = text[text.index("vertices"):]
    body = body[body.index("(") + 1:body.index(");")]
    points = [tuple(float(v) for v in p.split()) for p in body.replace("(", " ").split(")") if p.strip()]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    return (max(xs) - min(xs)) * (max(ys) - min(ys))


def analyse(case):
    with open(os.path.join(case, "postProcessing", "vof.csv")) as f:
        rows = list(csv.DictReader(f))
    h0, h = float(rows[0]["level"]), float(rows[-1]["level"])
    area = plan_area(case)
    first, last = particles_at(case, 0), particles_at(case, -1)
    v0 = submerged(first, h0)
    lo, hi = h0 - 1.0, h0 + 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if area * (mid - h0) < submerged(last, mid) - v0 else (lo, mid)
    expected_level = 0.5 * (lo + hi)
    props = os.path.join(case, "constant", "transportProperties")
    rho_w = float(get_entry(props, "water.rho").split()[0])
    g = abs(float(get_entry(os.path.join(case, "constant", "g"), "value").strip("() ").split()[2]))
    v_sub = submerged(last, h)
    buoyancy = rho_w * g * v_sub
    force = float(rows[-1]["pressureForceZ"])
    total = sum(math.pi / 6 * d ** 3 for _, d in last)
    s = {
        "case": "floatingBlock/vof tank",
        "time_s": float(rows[-1]["time"]),
        "initial_level_m": h0,
        "level_rise_m": h - h0,
        "expected_level_rise_m": expected_level - h0,
        "level_rise_error": (h - h0) / (expected_level - h0) - 1.0,
        "submerged_share_of_ice": v_sub / total,
        "top_of_ice_below_level_m": h - max(z + 0.5 * d for z, d in last),
        "pressure_force_N": force,
        "buoyancy_N": buoyancy,
        "pressure_force_error": force / buoyancy - 1.0,
        "water_volume_change": max(abs(float(r["waterVolumeChange"])) for r in rows),
    }
    write_atomically(os.path.join(case, "postProcessing", "tank.json"), json.dumps(s, indent=2) + "\n")
    return s


def make_and_run(mode, np):
    here = os.path.dirname(os.path.abspath(__file__))
    case = os.path.join(here, "..", "runs", f"tank_{mode}")
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    for d in ("0", "constant", "system", "DEM"):
        shutil.copytree(os.path.join(here, d), os.path.join(case, d))
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    for f, entry, value in (("constant/couplingProperties", "vof/initialLevel", "-0.05"),
                            ("constant/couplingProperties", "demVariables/pushDepth", "0.4" if mode == "under" else "0.15"),
                            ("constant/couplingProperties", "demVariables/pushSpeed", "0.1"),
                            ("system/controlDict", "endTime", "7"), ("system/controlDict", "writeInterval", "7")):
        subprocess.run(["foamDictionary", "-entry", entry, "-set", value, os.path.join(case, f)],
                       check=True, stdout=subprocess.DEVNULL, env=env)
    subprocess.run([os.path.join(here, "Allrun"), "-np", str(np), "-case", case], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    return case


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", nargs="?")
    ap.add_argument("--run", choices=("under", "through"))
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--publish", action="store_true")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--rise-tolerance", type=float, default=0.02)
    ap.add_argument("--force-tolerance", type=float, default=0.01)
    args = ap.parse_args()
    if (args.case is None) == (args.run is None):
        ap.error("give a CASE or --run MODE")
    case = make_and_run(args.run, args.np) if args.run else args.case
    s = analyse(case)
    if args.publish and args.run:
        results = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
        write_atomically(os.path.join(results, f"tank_{args.run}.json"), json.dumps(dict(s, ranks=args.np), indent=2) + "\n")
    print(f"level rise {1e3 * s['level_rise_m']:.3f} mm against {1e3 * s['expected_level_rise_m']:.3f} mm "
          f"({100 * s['level_rise_error']:+.2f} %); pressure force {s['pressure_force_N']:.3f} N against buoyancy "
          f"{s['buoyancy_N']:.3f} N ({100 * s['pressure_force_error']:+.3f} %); ice {100 * s['submerged_share_of_ice']:.1f} % "
          f"submerged, its top {1e3 * s['top_of_ice_below_level_m']:.1f} mm below the level; water volume kept to "
          f"{s['water_volume_change']:.1e}")
    if not args.check:
        return 0
    failures = []
    if abs(s["level_rise_error"]) > args.rise_tolerance:
        failures.append("level rise off by more than the tolerance")
    if abs(s["pressure_force_error"]) > args.force_tolerance:
        failures.append("pressure force off the buoyancy by more than the tolerance")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
