#!/usr/bin/python3
"""Physics of the small beam run that can fail: the fitted elastic slope,
turned into an effective modulus by fixed-end beam theory, lies below the
particle modulus as a bonded pack's must (and not far below); the loading is
quasi-static at the peak; the beam fails and unloads."""
import json
import sys

case = sys.argv[1]
s = json.load(open(f"{case}/postProcessing/summary.json"))

span, width, thickness = 2.5, 0.50, 0.55
second_moment = thickness * width**3 / 12.0
e_eff = s["elastic_slope_N_per_m"] * span**3 / (48.0 * second_moment)   # scenes.md section 1
e_particle = 5.4e8
ratio = e_eff / e_particle
print(f"effective modulus {e_eff:.3e} Pa = {ratio:.3f} of the particle modulus; "
      f"slope fit R2 {s['elastic_slope_fit_R2']:.4f}; "
      f"kinetic/elastic energy at peak {s['kinetic_to_elastic_energy_at_peak']:.3g}; "
      f"broken bonds {s['crack_pattern']['broken_bonds']}")
failures = []
if not 0.15 < ratio < 1.0:
    failures.append(f"effective modulus ratio {ratio:.3f} outside (0.15, 1.0)")
if s["elastic_slope_fit_R2"] < 0.98:
    failures.append("force does not rise linearly before the peak")
if s["kinetic_to_elastic_energy_at_peak"] > 0.1:
    failures.append("not quasi-static at the peak")
if not s["half_load_reached"]:
    failures.append("the load never fell to half the peak")
for f in failures:
    print("FAIL:", f)
print(f"{1 if not failures else 0} passed, {1 if failures else 0} failed")
sys.exit(1 if failures else 0)
