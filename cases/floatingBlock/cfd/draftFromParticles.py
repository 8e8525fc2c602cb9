#!/usr/bin/python3
"""Floating block at the cfd level (iceFoam) or the vof level (iceInterFoam): draft, submerged volume fraction,
kinetic energy and drift from postProcessing/particles.csv, written as the
hydrostatic case writes them (postProcessing/draft.csv, summary.json), so that
../plotDraft.py draws both. With --check, fails (exit 1) unless the submerged
fraction is within --tolerance of rho_i/rho_w, the block is at rest, has not
drifted more than --max-drift, and has every bond it started with.

    /usr/bin/python3 draftFromParticles.py CASE [--ranks N] [--wall S] [--check]

Kinetic energy is the translational one (particles.csv has no spin); at rest:
below restKineticEnergy M g H (system/controlDict) for restDuration s up to
the end of the run. At the vof level the water level is that of the columns
no particle reaches (postProcessing/vof.csv, the latest row at or before each
logged time), and the summary adds its rise and the water volume's change."""
import argparse
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "postProcessing"))
from iceCases import get_entry, write_atomically  # noqa: E402


def number(path, dotted):
    return float(get_entry(path, dotted).split()[0])


def cap_volume(depth, r):
    """Volume of a sphere of radius r below a plane `depth` above its lowest point."""
    h = min(max(depth, 0.0), 2.0 * r)
    return math.pi * h * h * (3.0 * r - h) / 3.0


def level_lattice_draft(layers, r, ratio):
    """Draft of a level simple cubic block of `layers` layers whose spheres have
    `ratio` of their volume under water (bisection; each layer the same)."""
    def fraction(draft):
        return sum(cap_volume(draft - 2 * r * k, r) for k in range(layers)) / (layers * 4 / 3 * math.pi * r ** 3)
    lo, hi = 0.0, 2 * r * layers
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if fraction(mid) < ratio else (lo, mid)
    return 0.5 * (lo + hi)


def samples(case):
    """Per logged time: list of (x, y, z, vx, vy, vz, d), the last row of each (time, tag)."""
    by_time = {}
    with open(os.path.join(case, "postProcessing", "particles.csv")) as f:
        for r in csv.DictReader(f):
            by_time.setdefault(float(r["time"]), {})[r["tag"]] = [float(r[k]) for k in
                                                                 ("x", "y", "z", "vx", "vy", "vz", "diameter")]
    return [(t, list(by_time[t].values())) for t in sorted(by_time)]


def vof_levels(case):
    """(time, level, water volume change) rows of postProcessing/vof.csv."""
    with open(os.path.join(case, "postProcessing", "vof.csv")) as f:
        return [(float(r["time"]), float(r["level"]), float(r["waterVolumeChange"])) for r in csv.DictReader(f)]


def level_at(levels, t):
    """The level of the latest row at or before t (rows sorted by time)."""
    best = levels[0]
    for row in levels:
        if row[0] <= t + 1e-9:
            best = row
    return best[1]


def analyse(case, ranks, wall):
    props = os.path.join(case, "constant", "couplingProperties")
    control = os.path.join(case, "system", "controlDict")
    vof = get_entry(props, "hydrodynamics").strip() == "vof"
    levels = vof_levels(case) if vof else None
    fixed_level = None if vof else number(props, "waterLevel")
    layers = int(number(props, "demVariables.layers"))
    rho_w = number(os.path.join(case, "constant", "transportProperties"), "water.rho" if vof else "rho")
    rho_i = number(os.path.join(case, "constant", "iceProperties"), "material.density")
    g = abs(float(get_entry(os.path.join(case, "constant", "g"), "value").strip("() ").split()[2]))
    rest_ke, rest_duration = number(control, "restKineticEnergy"), number(control, "restDuration")

    rows, series = [], samples(case)
    for t, ps in series:
        level = level_at(levels, t) if vof else fixed_level
        r = [0.5 * p[6] for p in ps]
        volume = sum(4 / 3 * math.pi * ri ** 3 for ri in r)
        mass = rho_i * volume
        submerged = sum(cap_volume(level - (p[2] - ri), ri) for p, ri in zip(ps, r))
        low = min(p[2] - ri for p, ri in zip(ps, r))
        high = max(p[2] + ri for p, ri in zip(ps, r))
        centre = [sum(p[k] * ri ** 3 for p, ri in zip(ps, r)) / sum(ri ** 3 for ri in r) for k in range(3)]
        kinetic = sum(0.5 * rho_i * 4 / 3 * math.pi * ri ** 3 * (p[3] ** 2 + p[4] ** 2 + p[5] ** 2)
                      for p, ri in zip(ps, r))
        rows.append({"time": t, "draft": level - low, "draftOverHeight": (level - low) / (high - low),
                     "submergedVolumeFraction": submerged / volume, "centreX": centre[0],
                     "centreY": centre[1], "centreZ": centre[2], "kineticEnergy": kinetic,
                     "height": high - low, "level": level})
    first, last = rows[0], rows[-1]
    radius = 0.5 * series[0][1][0][6]
    energy_scale = mass * g * (2 * radius * layers)
    rest_since = None
    for row in rows:
        if row["kineticEnergy"] < rest_ke * energy_scale:
            rest_since = row["time"] if rest_since is None else rest_since
        else:
            rest_since = None
    at_rest = rest_since is not None and last["time"] - rest_since >= rest_duration - 1e-9
    late = [row["submergedVolumeFraction"] for row in rows if row["time"] >= last["time"] - rest_duration]
    ratio = rho_i / rho_w
    level_draft = level_lattice_draft(layers, radius, ratio)
    bonds = list(csv.DictReader(open(os.path.join(case, "postProcessing", "bonds.csv"))))
    s = {
        "case": "floatingBlock/vof" if vof else "floatingBlock/cfd",
        "submerged_volume_fraction": last["submergedVolumeFraction"],
        "density_ratio": ratio,
        "submerged_volume_fraction_error": last["submergedVolumeFraction"] / ratio - 1.0,
        "submerged_volume_fraction_mean_last_s": sum(late) / len(late),
        "submerged_volume_fraction_range_last_s": [min(late), max(late)],
        "draft_m": last["draft"],
        "height_m": last["height"],
        "draft_over_height": last["draft"] / last["height"],
        "level_lattice_draft_m": level_draft,
        "draft_error_vs_level_lattice": last["draft"] / level_draft - 1.0,
        "max_lateral_drift_m": max(math.hypot(r["centreX"] - first["centreX"], r["centreY"] - first["centreY"])
                                   for r in rows),
        "kinetic_energy_J": last["kineticEnergy"],
        "kinetic_energy_over_MgH": last["kineticEnergy"] / energy_scale,
        "kinetic_energy_note": "translational only (particles.csv has no spin)",
        "rest_threshold_over_MgH": rest_ke,
        "at_rest": at_rest,
        "at_rest_since_s": rest_since if at_rest else None,
        "end_time_s": last["time"],
        "bonds_at_start": int(float(bonds[0]["intactBonds"])),
        "bonds_at_end": int(float(bonds[-1]["intactBonds"])),
        "broken_bonds": int(float(bonds[-1]["brokenBonds"])),
        "particles": len(series[0][1]),
        **({"water_level_m": last["level"], "initial_water_level_m": first["level"],
            "max_water_volume_change": max(abs(v[2]) for v in levels)} if vof else {}),
        "ranks": ranks,
        "wall_s": wall,
    }
    header = ["time", "draft", "draftOverHeight", "submergedVolumeFraction", "centreX", "centreY", "centreZ",
              "kineticEnergy"]
    lines = [",".join(header)] + [",".join(f"{row[k]:.10g}" for k in header) for row in rows]
    write_atomically(os.path.join(case, "postProcessing", "draft.csv"), "\n".join(lines) + "\n")
    write_atomically(os.path.join(case, "postProcessing", "summary.json"), json.dumps(s, indent=2) + "\n")
    return s


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--wall", type=float, default=None, help="wall time of the run, s (for the summary)")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--tolerance", type=float, default=0.01)
    ap.add_argument("--max-drift", type=float, default=1e-3, help="m")
    args = ap.parse_args()
    s = analyse(args.case, args.ranks, args.wall)
    print(f"submerged volume fraction {s['submerged_volume_fraction']:.5f} "
          f"({100 * s['submerged_volume_fraction_error']:+.3f} % from {s['density_ratio']:.3f}; mean over the last "
          f"second {s['submerged_volume_fraction_mean_last_s']:.5f}), draft {s['draft_m']:.5f} m "
          f"(level lattice {s['level_lattice_draft_m']:.5f} m), drift {1e3 * s['max_lateral_drift_m']:.3g} mm, "
          f"kinetic {s['kinetic_energy_over_MgH']:.2e} M g H, at rest since {s['at_rest_since_s']} s, "
          f"bonds {s['bonds_at_start']} -> {s['bonds_at_end']}")
    if not args.check:
        return 0
    failures = []
    if abs(s["submerged_volume_fraction_error"]) > args.tolerance:
        failures.append("submerged volume fraction off by more than the tolerance")
    if not s["at_rest"]:
        failures.append("the block did not come to rest")
    if s["max_lateral_drift_m"] > args.max_drift:
        failures.append("the block drifted sideways")
    if s["bonds_at_end"] != s["bonds_at_start"] or s["broken_bonds"] != 0:
        failures.append("bonds broke")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
