#!/usr/bin/python3
"""Reduced freeze-bond tension tests (cases/freezeBondTension) that can fail:

- 1 and 2 MPI ranks create the same freeze-bonds and give the same strength;
- the confinement measured from the contact forces matches the applied pressure;
- after 3 h, strength is linear in the confinement (R2 > 0.99) and rises with it;
- the strengths at 24.8, 49.1 and 75 kPa lie within one standard deviation of
  the measured means (freezeBondTensile.csv tests 13-21).

usage: freezeBondTension.py CASE WORKDIR APP"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402

case, work, app = sys.argv[1:]
iceCases.copy_case(case, work)


def run(label, ranks, kPa, minutes):
    iceCases.run_app(app, work, ranks, ["-label", label, "-pressure", kPa * 1e3, "-time", minutes], f"log.{label}")
    return json.load(open(os.path.join(work, "postProcessing", "runs", label, "summary.json")))


low = run("low_np1", 1, 24.8, 180)
mid = run("mid_np1", 1, 49.1, 180)
high = run("high_np1", 1, 75.0, 180)
high2 = run("high_np2", 2, 75.0, 180)

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


check(high["freeze_bonds"] == high2["freeze_bonds"],
      f"same freeze-bond count on 1 and 2 ranks ({high['freeze_bonds']}, {high2['freeze_bonds']})")
check(abs(high2["strength_Pa"] / high["strength_Pa"] - 1) < 1e-3,
      f"same strength on 1 and 2 ranks ({high['strength_Pa']:.1f}, {high2['strength_Pa']:.1f} Pa)")
for s in (low, mid, high):
    ratio = s["mean_measured_confinement_Pa"] / s["confinement_pressure_Pa"]
    check(abs(ratio - 1) < 0.1, f"measured confinement / applied = {ratio:.3f} (within 10 %)")
p = [24.8, 49.1, 75.0]
y = [s["strength_Pa"] for s in (low, mid, high)]
pm, ym = sum(p) / 3, sum(y) / 3
slope = sum((a - pm) * (b - ym) for a, b in zip(p, y)) / sum((a - pm) ** 2 for a in p)
residual = sum((b - ym - slope * (a - pm)) ** 2 for a, b in zip(p, y))
r2 = 1 - residual / sum((b - ym) ** 2 for b in y)
check(slope > 0 and r2 > 0.99, f"strength linear in confinement: slope {slope / 1e3:.2f} kPa/kPa, R2 {r2:.4f}")
for s, mean, sd in ((low, 68e3, 6e3), (mid, 156e3, 31e3), (high, 270e3, 72e3)):
    check(abs(s["strength_Pa"] - mean) <= sd,
          f"strength {s['strength_Pa'] * 1e-3:.1f} kPa against measured {mean * 1e-3:.0f} +- {sd * 1e-3:.0f} kPa")
sys.exit(1 if failures else 0)
