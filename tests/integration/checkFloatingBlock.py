#!/usr/bin/python3
"""The reduced floating block on 1 and on 2 ranks: each floats with its
submerged volume fraction within 1 % of rho_i/rho_w, comes to rest, does not
drift sideways, breaks no bond; and the two runs agree (same draft curve).

usage: checkFloatingBlock.py RUN_NP1 RUN_NP2"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402


def draft_curve(case):
    with open(os.path.join(case, "postProcessing", "draft.csv")) as f:
        return list(csv.DictReader(f))


def check_physics(case):
    s = iceCases.summary(case)
    print(f"{case}: {s['ranks']} rank(s), submerged fraction {s['submerged_volume_fraction']:.6f} "
          f"(rho_i/rho_w {s['density_ratio']}), error {s['submerged_volume_fraction_error'] * 100:.3f} %, "
          f"draft/height {s['draft_over_height']:.4f} (level lattice {s['level_lattice_draft_m'] / s['height_m']:.4f}), "
          f"drift {s['max_lateral_drift_m'] * 1e3:.3g} mm, kinetic {s['kinetic_energy_over_MgH']:.2e} M g H, "
          f"at rest since {s['at_rest_since_s']} s")
    assert abs(s["submerged_volume_fraction_error"]) < 0.01, s["submerged_volume_fraction_error"]
    assert abs(s["draft_error_vs_level_lattice"]) < 0.01, s["draft_error_vs_level_lattice"]
    assert s["at_rest"], "the block did not come to rest"
    assert s["max_lateral_drift_m"] < 1e-3, f"drifted {s['max_lateral_drift_m']} m sideways"
    assert s["broken_bonds"] == 0, s["broken_bonds"]
    return s


def main(one, two):
    sa, sb = check_physics(one), check_physics(two)
    assert sa["ranks"] == 1 and sb["ranks"] == 2, (sa["ranks"], sb["ranks"])
    assert min(sb["atoms_per_rank_at_start"]) > 0, f"one rank holds no atom: {sb['atoms_per_rank_at_start']}"
    a, b = draft_curve(one), draft_curve(two)
    assert len(a) == len(b), (len(a), len(b))
    worst = 0.0
    for ra, rb in zip(a, b):
        for key in ("draft", "submergedVolumeFraction", "centreZ"):
            worst = max(worst, abs(float(ra[key]) - float(rb[key])) / max(abs(float(ra[key])), 1e-3))
    print(f"1 against 2 ranks: {len(a)} samples, largest relative difference {worst:.3e}")
    assert worst < 1e-9, f"1 and 2 ranks differ by {worst:.3e}"


if __name__ == "__main__":
    main(*sys.argv[1:])
