#!/usr/bin/python3
"""Writes the README's results table from the published summaries (results/summary_<shape>.json),
between the README's `<!-- results table -->` and `<!-- end results table -->` lines, so that the
figures a reader sees are the committed run's, never typed. `./Allrun -publish` calls it.

usage: resultsTable.py [CASE_DIR]"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402

SHAPES = ("cuboid", "empirical")


def minutes(seconds):
    m, s = divmod(int(round(seconds)), 60)
    return f"{m} min {s} s" if m else f"{s} s"


ROWS = [
    ("blocks / particles", lambda s: f"{s['blocks']} / {s['particles']:,}"),
    ("block ice volume", lambda s: f"{s['block_ice_volume_m3']:.3f} m3"),
    ("settled after (simulated)", lambda s: f"{s['settled_time_s']:.1f} s" + ("" if s["at_rest"] else " (NOT at rest)")),
    ("layer (1st-99th percentile of sphere extents)",
     lambda s: f"{s['layer_bottom_m']:.3f}-{s['layer_top_m']:.3f} m, **{s['thickness_m']:.3f} m thick**"),
    ("porosity as settled (block volume)", lambda s: f"**{s['porosity']:.3f}**"),
    ("compaction: porosity between the plates", lambda s: compaction(s, lambda c:
        f"{c['porosity_when_plates_touched']:.3f} -> **{c['porosity']:.3f}** (target {c['target_porosity']})")),
    ("compaction: contacts and blocks' bonds at", lambda s: compaction(s, lambda c:
        f"E = {c['youngs_modulus_Pa'] / 1e6:.3g} MPa" if "youngs_modulus_Pa" in c else "the settling's modulus")),
    ("compaction: lid / floor pressure at bonding", lambda s: compaction(s, lambda c:
        f"{c['lid_pressure_at_bonding_Pa'] / 1e3:.1f} / {c['floor_pressure_at_bonding_Pa'] / 1e3:.1f} kPa")),
    ("released (bonded, plates gone): layer, porosity", lambda s: compaction(s, lambda c:
        f"{s['released']['layer_bottom_m']:.3f}-{s['released']['layer_top_m']:.3f} m, "
        f"{s['released']['thickness_m']:.3f} m thick, porosity {s['released']['porosity']:.3f}")),
    ("ice volume above water", lambda s: f"{100 * s['ice_volume_above_water_fraction']:.2f} %"),
    ("freeze-bonds / block contacts",
     lambda s: f"{s['freeze_bonds']} / {s['block_contacts']}, {s['mean_bonds_per_block_contact']:.1f} per contact"),
    ("confinement on the real area",
     lambda s: f"{s['confinement_mean_Pa'] / 1e3:.2f} kPa mean, {s['confinement_max_Pa'] / 1e3:.1f} kPa max"
               + (", median {:.2f}, 90th percentile {:.1f} kPa".format(s["confinement_percentiles_Pa"]["p50"] / 1e3,
                                                                   s["confinement_percentiles_Pa"]["p90"] / 1e3)
                  if "confinement_percentiles_Pa" in s else "")),
    ("block surface bonded (DEM bond area)",
     lambda s: f"{100 * s['bonded_surface_fraction']:.2f} %" if "bonded_surface_fraction" in s else "-"),
    ("c_f (heat balance)", lambda s: f"{s['area_correction']:.3f}"),
    ("freeze-bond strength on the bond area: effective (c_f x the set's)",
     lambda s: f"tensile {s.get('freeze_bond_effective_tensile_mean_Pa', s['freeze_bond_tensile_mean_Pa']) / 1e3:.2f} kPa, "
               f"shear {s.get('freeze_bond_effective_shear_mean_Pa', s['freeze_bond_shear_mean_Pa']) / 1e3:.1f} kPa"),
    ("particle-level (what the bonds break at)",
     lambda s: f"tensile {s['freeze_bond_tensile_mean_Pa'] / 1e3:.2f} kPa, shear {s['freeze_bond_shear_mean_Pa'] / 1e3:.1f} kPa"
               f" ({s.get('freeze_bond_particle_strengths', 'direct')})"),
    ("wall time, build + settle + compact + bond", lambda s: f"**{minutes(s['wall_s'])}** on {s['ranks']} rank{'s' if s['ranks'] > 1 else ''}"),
]


def compaction(summary, cell):
    c = summary.get("compaction", {"method": "none"})
    return cell(c) if c["method"] != "none" else "none"


def table(case):
    summaries = {}
    for shape in SHAPES:
        path = os.path.join(case, "results", f"summary_{shape}.json")
        if os.path.exists(path):
            summaries[shape] = json.load(open(path))
    if not summaries:
        sys.exit(f"resultsTable.py: no results/summary_<shape>.json in {case}")
    shapes = [s for s in SHAPES if s in summaries]
    lines = ["| | " + " | ".join(shapes) + " |", "|---|" + "---|" * len(shapes)]
    for label, cell in ROWS:
        lines.append(f"| {label} | " + " | ".join(cell(summaries[s]) for s in shapes) + " |")
    return "\n".join(lines)


def main():
    case = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__)))
    readme = os.path.join(case, "README.md")
    iceCases.write_readme_section(readme, "results table", table(case))


if __name__ == "__main__":
    main()
