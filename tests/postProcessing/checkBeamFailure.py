#!/usr/bin/python3
"""failureAnalysis.py on the reduced level-ice beam's real output, against the figures the
beam program computed itself (postProcessing/summary.json: counts by mode, share near the
centre, peak, half load after it).

    checkBeamFailure.py BEAM_CASE OUT_DIR"""
import json
import os
import subprocess
import sys

TOP = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
from iceCases import get_entry  # noqa: E402


def main(case, out):
    properties = os.path.join(case, "constant", "beamProperties")
    length, width, thickness, pad, diameter = (
        float(get_entry(properties, key)) for key in
        ("beam.length", "beam.width", "beam.thickness", "beam.padLength", "platen.diameter"))
    os.makedirs(out, exist_ok=True)
    geometry = {"length": length, "width": width, "loadX": length / 2,
                "loadHalfLength": diameter / 2, "supports": [pad, length - pad],
                "layers": [{"name": "levelIce", "zBottom": 0.0, "zTop": thickness}]}
    geometry_path = os.path.join(out, "geometry.json")
    with open(geometry_path, "w") as f:
        json.dump(geometry, f)
    # The beam's summary counts breaks within 10 % of the length from the centre.
    subprocess.run([sys.executable, os.path.join(TOP, "postProcessing", "failureAnalysis.py"),
                    case, "--geometry", geometry_path, "--out", out,
                    "--centre-half-width", repr(0.1 * length)], check=True)
    with open(os.path.join(out, "summary.json")) as f:
        ours = json.load(f)
    with open(os.path.join(case, "postProcessing", "summary.json")) as f:
        beam = json.load(f)

    failures = []

    def check(what, value, expected, tolerance=0.0):
        ok = abs(value - expected) <= tolerance
        print("%-46s %-14.10g beam program %-14.10g %s" % (what, value, expected,
                                                           "ok" if ok else "DIFFERS"))
        if not ok:
            failures.append(what)

    pattern = beam["crack_pattern"]
    counts = ours["counts"]
    if pattern["broken_bonds"] < 20:
        failures.append("too few broken bonds (%d) for a check" % pattern["broken_bonds"])
    check("broken bonds", counts["total"], pattern["broken_bonds"])
    for mode, number in pattern["by_mode"].items():
        check("broken in " + mode, counts["mode"][mode], number)
    check("freeze-bonds broken (level ice has none)", counts["family"]["freeze"], 0)
    check("share within 10 % of the length of the centre",
          counts["region"]["centre"] / counts["total"],
          pattern["share_within_10pct_of_span_from_centre"], 1e-9)  # 10 digits
    moments = {m["name"]: m for m in ours["moments"]}
    onset = beam["contact_onset_travel_m"]
    check("peak force [N]", moments["peak"]["force"], beam["peak_force_N"],
          1e-9 * beam["peak_force_N"])
    check("travel at peak from contact [m]", moments["peak"]["travel"] - onset,
          beam["travel_at_peak_m"], 1e-8)
    if beam["half_load_reached"]:
        check("half-load travel after the peak [m]",
              moments["halfLoadAfterPeak"]["travel"] - moments["peak"]["travel"],
              beam["half_load_travel_after_peak_m"], 1e-8)
    else:
        failures.append("the reduced beam did not reach half load after the peak")
    for m in ours["moments"]:
        for key in ("vtp", "png"):
            if os.path.getsize(os.path.join(out, m[key])) < 1000:
                failures.append("%s of %s is nearly empty" % (key, m["name"]))
    if failures:
        sys.exit("checkBeamFailure.py: " + "; ".join(failures))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
