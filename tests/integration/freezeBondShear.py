#!/usr/bin/python3
"""Reduced freeze-bond shear tests (cases/freezeBondShear) that can fail:
the bond plane fails (mostly in shear), the effective strength is linear in
the particle-level strength (through two points and the origin's offset, a
third point within 3 % of the line), and 1 and 2 ranks give the same peak.

usage: freezeBondShear.py CASE WORKDIR APP"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402

case, work, app = sys.argv[1:]
iceCases.copy_case(case, work)
iceCases.set_entry(os.path.join(work, "constant", "shearTestProperties"), "loading.samples", 300)
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def run(label, ranks, strength):
    iceCases.run_app(app, work, ranks, ["-label", label, "-shearStrength", strength], f"log.{label}")
    return json.load(open(os.path.join(work, "postProcessing", "runs", label, "summary.json")))


runs = {s: run(f"S{s:g}", 1, s) for s in (100e3, 200e3, 400e3)}
two = run("S200000_np2", 2, 200e3)
for s, r in runs.items():
    check(r["failed"], f"S_p {s * 1e-3:g} kPa: the bond plane fails")
    check(r["breaks_in_shear"] > 0.5 * r["breaks"],
          f"S_p {s * 1e-3:g} kPa: most bonds break in shear ({r['breaks_in_shear']} of {r['breaks']})")
lo, mid, hi = (runs[s]["effective_shear_strength_Pa"] for s in (100e3, 200e3, 400e3))
slope = (hi - lo) / 300e3
predicted = lo + slope * 100e3
check(abs(mid / predicted - 1) < 0.03, f"effective strength linear in S_p: {mid:.0f} Pa against {predicted:.0f} Pa on the line")
check(slope > 0, f"effective strength rises with S_p (slope {slope:.3f})")
check(abs(two["peak_load_N"] / runs[200e3]["peak_load_N"] - 1) < 0.02,
      f"1 and 2 ranks: peak load {runs[200e3]['peak_load_N']:.1f} and {two['peak_load_N']:.1f} N (within 2 %)")
sys.exit(1 if failures else 0)
