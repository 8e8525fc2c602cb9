#!/usr/bin/python3
"""The README's table of the published hydrostatic punches, written from results/summary_<keel>.json,
results/beamPhase_<keel>.json and results/punchSummary.csv (./Allrun -publish calls it), so that the
figures a reader sees are those of the published runs.

usage: resultsTable.py [CASE_DIR]"""
import csv
import json
import os
import re
import sys

CASE = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(CASE, "..", "..", "postProcessing"))
import iceCases  # noqa: E402

KEELS = ("cuboid", "empirical")


def minutes(seconds):
    return f"{int(seconds // 60)} min {int(round(seconds % 60))} s"


def table(case):
    runs = {}
    for keel in KEELS:
        paths = [os.path.join(case, "results", f"{name}_{keel}.json") for name in ("summary", "beamPhase")]
        if all(os.path.exists(p) for p in paths):
            runs[keel] = [json.load(open(p)) for p in paths]
    if not runs:
        sys.exit(f"{case}/results: no summary_<keel>.json with its beamPhase_<keel>.json to tabulate")
    with open(os.path.join(case, "results", "punchSummary.csv"), newline="") as handle:
        means = {r["run"]: r for r in csv.DictReader(handle)}
    for keel in runs:
        runs[keel][0] = dict(runs[keel][0], **{k: float(v) for k, v in means[keel].items() if k.startswith("mean_")})
    keels = list(runs)
    lines = ["| | " + " | ".join(keels) + " |", "|---|" + "---|" * len(keels)]

    def row(label, cell):
        lines.append(f"| {label} | " + " | ".join(cell(*runs[k]) for k in keels) + " |")

    row("particles / freeze-bonds / c_f", lambda s, b: f"{s['particles']:,} / {s['freeze_bonds']} / "
        + re.search(r"c_f = ([\d.]+)", s["freeze_bond_set"]).group(1))
    for k in range(len(next(iter(runs.values()))[1].get("samples", []))):
        mm = next(iter(runs.values()))[1]["samples"][k]["travel_mm"]
        row(f"at {mm} mm: force / buoyancy share / bonds broken",
            lambda s, b: "{force_N:.0f} N / {buoyancy_share_N:.0f} N / {broken_bonds}".format(**b["samples"][k]))
    row("force minus buoyancy share, largest before 40 mm (the rubble's beam)",
        lambda s, b: f"**{b['rubble_share_peak_N']:.0f} N at {1e3 * b['rubble_share_peak_travel_m']:.1f} mm**")
    row("largest force (buoyancy share)", lambda s, b: f"{s['peak_force_N']:.0f} N at {1e3 * s['travel_at_peak_m']:.0f} mm "
        f"({s['buoyancy_share_at_peak_N']:.0f} N, {100 * s['buoyancy_share_at_peak_N'] / s['peak_force_N']:.0f} %)")
    row("mean force over 20-100 mm / mean buoyancy share", lambda s, b: f"{s['mean_force_20_100mm_N']:.0f} / "
        f"{s['mean_share_20_100mm_N']:.0f} N ({100 * s['mean_share_20_100mm_N'] / s['mean_force_20_100mm_N']:.0f} %)")

    def first(s, b):
        f = b["first_failure"]
        if not f:
            return "none"
        return (f"{1e3 * f['travel_m']:.1f} mm, {f['force_N']:.0f} N, {100 * f['from_load_line_m']:.0f} cm from mid-span, "
                f"{100 * f['height_in_keel']:.0f} % up, {f['mode']}")
    row("first freeze-bond failure", first)
    row("freeze-bonds broken at the end: tension / shear / twist / bending",
        lambda s, b: "{} / {} / {} / {} of {}".format(*(s["broken_by_mode"].get(m, 0) for m in ("tension", "shear", "twist", "bending")),
                                                     s["freeze_bonds"]) if "broken_by_mode" in s else f"{b['freeze_bonds_broken']}")
    row("wall time, 1 rank (particle-steps/s)", lambda s, b: f"{minutes(s['wall_s'])} ({s['particle_steps_per_s']:.3g})")
    return "\n".join(lines) + "\n"


def main():
    iceCases.write_readme_section(os.path.join(CASE, "README.md"), "punch table", table(CASE))


if __name__ == "__main__":
    main()
