#!/usr/bin/python3
"""A floating ice sphere (tests/coupling/floatingSphere): released half
submerged, it heaves about the draft where its submerged share of volume is
rho_p/rho_w = 0.917 and the heave decays. Checks the mean submerged share over
the second half of the run within 1 % of 0.917, and the heave amplitude of the
second half below 0.6 of the first half's (after the first 0.2 s).
Usage: checkFloating.py CASE"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
from iceCases import get_entry  # noqa: E402


def main():
    case = sys.argv[1]
    props = os.path.join(case, "constant", "couplingProperties")
    level = float(get_entry(props, "waterLevel"))
    r = 0.5 * float(get_entry(props, "demVariables.diameter").split()[0])
    rho_p = float(get_entry(props, "demVariables.density").split()[0])
    rho_w = float(get_entry(os.path.join(case, "constant", "transportProperties"), "rho").split()[0])
    with open(os.path.join(case, "postProcessing", "particles.csv")) as f:
        rows = [(float(row["time"]), float(row["z"])) for row in csv.DictReader(f)]
    end = rows[-1][0]

    def share(z):
        h = min(max(level - (z - r), 0.0), 2 * r)
        return h * h * (3 * r - h) / (4 * r ** 3)

    late = [z for t, z in rows if t >= 0.5 * end]
    early = [z for t, z in rows if 0.2 <= t < 0.5 * end]
    mean_share = sum(share(z) for z in late) / len(late)
    amplitude_early = 0.5 * (max(early) - min(early))
    amplitude_late = 0.5 * (max(late) - min(late))
    target = rho_p / rho_w
    print(f"mean submerged share {mean_share:.5f} (rho_p/rho_w = {target:.5f}, "
          f"{100 * (mean_share / target - 1):+.2f} %); heave amplitude {1e3 * amplitude_early:.3f} mm "
          f"then {1e3 * amplitude_late:.3f} mm")
    failures = []
    if abs(mean_share / target - 1) > 0.01:
        failures.append("draft off by more than 1 %")
    if amplitude_late > 0.6 * amplitude_early:
        failures.append("heave not decaying")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
