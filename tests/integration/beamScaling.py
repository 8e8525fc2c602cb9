#!/usr/bin/python3
"""Scaling laws of the bonded-ice model on the small beam, each of which fails
if a spring, a strength or the damping is wrong:

- quasi-static, rate-independent loading with strain-based strengths: doubling
  the modulus (bonds and contacts) doubles the elastic slope and the peak force
  (stress = E * strain);
- at fixed modulus the load of the centre crack (the first peak) is
  proportional to breakN (levelIceParametric.csv, figure 7). The highest load,
  carried after the crack by the beam halves arching between the pads, is
  not: contacts carry it, and they have no strength to scale;
- the loading is quasi-static (kinetic / elastic energy small at the peak).

usage: beamScaling.py CASE WORKDIR APP
"""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402

case, work, app = sys.argv[1:4]
# 0.05 m/s: at 0.2 the crack's load is 1.29 x, not 1.5 x, for breakN x 1.5.
common = ["-particles", "400", "-platenSpeed", "0.05"]


def run(name, factors):
    """Runs a copy of the case with dictionary entries multiplied by factors."""
    target = iceCases.copy_case(case, os.path.join(work, name))
    ice = os.path.join(target, "constant", "iceProperties")
    for entry, factor in factors.items():
        value = float(re.search(r"[-+0-9.eE]+", iceCases.get_entry(ice, entry)).group(0))
        iceCases.set_entry(ice, entry, repr(value * factor))
    iceCases.run_app(app, target, 1, common, "log.iceBeamDEM")
    return iceCases.summary(target)


base = run("base", {})
stiff = run("doubleModulus", {"material.youngsModulus": 2.0, "bondFamilies.ice.youngsModulus": 2.0})
strong = run("breakN1.5", {"bondFamilies.ice.breakN": 1.5})

checks = [
    ("slope x2 with modulus x2", stiff["elastic_slope_N_per_m"] / base["elastic_slope_N_per_m"], 2.0, 0.05),
    ("peak x2 with modulus x2", stiff["peak_force_N"] / base["peak_force_N"], 2.0, 0.05),
    ("first peak x1.5 with breakN x1.5", strong["first_peak_force_N"] / base["first_peak_force_N"], 1.5, 0.05),
    ("slope unchanged with breakN x1.5", strong["elastic_slope_N_per_m"] / base["elastic_slope_N_per_m"], 1.0, 0.05),
]
failed = 0
for name, ratio, expected, tolerance in checks:
    ok = abs(ratio / expected - 1.0) <= tolerance
    failed += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {name}: ratio {ratio:.4f}, expected {expected} +- {tolerance:.0%}")
ke = base["kinetic_to_elastic_energy_at_peak"]
ok = ke < 0.01 and base["half_load_reached"]
failed += not ok
print(f"{'ok  ' if ok else 'FAIL'} quasi-static at peak (kinetic/elastic {ke:.2e} < 0.01) and the beam unloads")
print(f"{5 - failed} passed, {failed} failed")
sys.exit(1 if failed else 0)
