#!/usr/bin/python3
"""Does a punched rubble bend as one beam before it cracks? The first freeze-bond failures of a
platen run, read from its breakage record (issue 18, scenes.md section 6).

    beamPhase.py RUN_DIR [--first N] [--json OUT]

In the laboratory the bonded rubble first bends as one solid beam with no freeze-bond failing,
then freeze-bonds at the bottom centre fail in tension and a crack grows to the top. This reads
RUN_DIR/postProcessing/{breakage.h5, platenForce.csv, geometry.json} and reports:

- the first freeze-bond failure: time, platen travel and force at it, where (distance from the
  load line along the span, height in the keel as a fraction of its depth) and in which mode;
- the force's rise before it: the force at the first failure over the force at a quarter of
  that travel (a bent beam's force grows with its deflection; a rubble that gives way next to
  the platen fails at the first contact, at no rise);
- of the first N freeze-bond failures (default 10), the share in tension in the bottom half of
  the keel within a quarter of the span of the load line ("bottom centre");
- the peak force and its travel, and the freeze-bonds broken before it;
- where the curve has them (a punch's platenForce.csv: buoyancyShare, brokenBonds), the force,
  buoyancy share and broken bonds every 5 mm to 30 mm, and the largest force minus buoyancy
  share before 40 mm of travel (the rubble's own resistance: a beam's peak).

Prints a one-line verdict and, with --json, writes these figures (atomically).
Exit status 1 with a message naming the file and entry on bad input."""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from breakageRecord import MODES, InputError, read_breakage, read_curve, read_geometry  # noqa: E402
from iceCases import write_atomically  # noqa: E402

FREEZE = 1
TENSION = 1


def force_at(travel, force, at):
    """The force curve's value at a travel (linear between samples)."""
    return float(np.interp(at, travel, force))


def beam_curve(curve_path, travel, force):
    """Samples every 5 mm to 30 mm and the rubble's largest share before 40 mm, or {} when the
    curve has no buoyancyShare and brokenBonds columns."""
    try:
        _, share, broken = read_curve(curve_path, ("time", "buoyancyShare", "brokenBonds"))
    except InputError:
        return {}
    if len(share) != len(travel):
        return {}
    samples = []
    for mm in range(5, 35, 5):
        k = int(np.argmin(np.abs(travel - 1e-3 * mm)))
        samples.append({"travel_mm": mm, "force_N": float(force[k]), "buoyancy_share_N": float(share[k]),
                        "broken_bonds": int(broken[k])})
    early = travel < 0.04
    rubble = np.where(early, force - share, -np.inf)
    k = int(np.argmax(rubble))
    return {"samples": samples, "rubble_share_peak_N": float(rubble[k]), "rubble_share_peak_travel_m": float(travel[k])}


def first_failures(run, first=10):
    """The figures of the module docstring for a finished platen run."""
    post = os.path.join(run, "postProcessing")
    record = read_breakage(os.path.join(post, "breakage.h5"))
    time, travel, force = read_curve(os.path.join(post, "platenForce.csv"))
    geometry = read_geometry(os.path.join(post, "geometry.json"))
    keel = next((layer for layer in geometry["layers"] if layer["name"] == "keel"), None)
    if keel is None:
        raise InputError(os.path.join(post, "geometry.json"), "layers", "no layer named 'keel'")
    depth = keel["zTop"] - keel["zBottom"]
    freeze = np.flatnonzero(record["family"] == FREEZE)
    peak = int(np.argmax(force))
    out = {"run": os.path.basename(os.path.abspath(run)), "peak_force_N": float(force[peak]),
           "peak_travel_m": float(travel[peak]),
           "freeze_bonds_broken": int(len(freeze)),
           "freeze_bonds_broken_before_peak": int(np.sum(record["time"][freeze] <= time[peak]))}
    out.update(beam_curve(os.path.join(post, "platenForce.csv"), travel, force))
    if len(freeze) == 0:
        out["first_failure"] = None
        return out
    k = freeze[0]
    at = float(np.interp(record["time"][k], time, travel))
    height = (record["z"][freeze] - keel["zBottom"]) / depth
    from_load = np.abs(record["x"][freeze] - geometry["loadX"])
    bottom_centre = (record["mode"][freeze] == TENSION) & (height <= 0.5) & (from_load <= 0.25 * geometry["length"])
    n = min(first, len(freeze))
    before = force_at(travel, force, 0.25 * at)
    out["first_failure"] = {
        "time_s": float(record["time"][k]), "travel_m": at, "force_N": force_at(travel, force, at),
        "force_at_quarter_travel_N": before,
        "force_rise": force_at(travel, force, at) / before if before > 0 else None,
        "from_load_line_m": float(from_load[0]), "height_in_keel": float(height[0]),
        "mode": MODES.get(int(record["mode"][k]), str(record["mode"][k]))}
    out["first_n"] = n
    out["bottom_centre_tension_share_of_first_n"] = float(np.mean(bottom_centre[:n]))
    out["first_broken_bond_family"] = "freeze" if record["family"][0] == FREEZE else "ice"
    return out


def verdict(figures):
    f = figures["first_failure"]
    if f is None:
        return "no freeze-bond broke"
    return (f"first freeze-bond failure at {1e3 * f['travel_m']:.2f} mm of travel and {f['force_N']:.0f} N "
            + (f"(x{f['force_rise']:.1f} the force at a quarter of that travel)" if f["force_rise"] is not None
               else "(no force yet at a quarter of that travel)")
            + f", {100 * f['from_load_line_m']:.0f} cm "
            f"from the load line, {100 * f['height_in_keel']:.0f} % up the keel, in {f['mode']}; "
            f"{100 * figures['bottom_centre_tension_share_of_first_n']:.0f} % of the first {figures['first_n']} "
            f"in tension at the bottom centre; peak {figures['peak_force_N']:.0f} N at "
            f"{1e3 * figures['peak_travel_m']:.1f} mm after {figures['freeze_bonds_broken_before_peak']} "
            f"freeze-bonds broke")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("--first", type=int, default=10)
    ap.add_argument("--json")
    a = ap.parse_args()
    try:
        figures = first_failures(a.run, a.first)
    except InputError as error:
        sys.exit(f"beamPhase.py: {error}")
    print(verdict(figures))
    if a.json:
        write_atomically(a.json, json.dumps(figures, indent=2) + "\n")


if __name__ == "__main__":
    main()
