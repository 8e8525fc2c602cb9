#!/usr/bin/python3
"""The smoke punch bends as a beam before it cracks (issue 18): its first broken bond is a
freeze-bond, it breaks in tension in the bottom half of the keel, after the platen has travelled
at least MIN_TRAVEL and the force has risen at least MIN_RISE times over the last three quarters
of that travel (postProcessing/beamPhase.py). With freeze-bonds as stiff as the ice the first one
broke within 0.1-0.6 mm, next to the platen (cases/rubblePunch/README.md, "Beam phase").

usage: checkBeamPhase.py RUN_DIR"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
from beamPhase import first_failures, verdict  # noqa: E402

MIN_TRAVEL = 2e-3   # m
MIN_RISE = 2.0

figures = first_failures(sys.argv[1])
print(verdict(figures))
first = figures["first_failure"]
checks = [(first is not None, "a freeze-bond broke within the smoke punch's 10 mm")]
if first:
    checks += [(figures["first_broken_bond_family"] == "freeze", "the first broken bond is a freeze-bond"),
               (first["mode"] == "tension", f"it broke in tension (got {first['mode']})"),
               (first["height_in_keel"] <= 0.5, f"in the keel's bottom half ({first['height_in_keel']:.2f} of its depth)"),
               (first["travel_m"] >= MIN_TRAVEL, f"after {1e3 * first['travel_m']:.2f} mm >= {1e3 * MIN_TRAVEL:g} mm of travel"),
               (first["force_rise"] is not None and first["force_rise"] >= MIN_RISE,
                f"the force rose {first['force_rise'] or 0:.2f} >= {MIN_RISE:g} times before it")]
for ok, what in checks:
    print(("ok   " if ok else "FAIL ") + what)
sys.exit(0 if all(ok for ok, _ in checks) else 1)
