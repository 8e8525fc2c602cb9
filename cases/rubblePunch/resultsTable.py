#!/usr/bin/python3
"""The README's tables of the published punches, written from results/summary_<keel>.json,
results/beamPhase_<keel>.json and results/punchSummary.csv (./Allrun -publish calls it), so that the
figures a reader sees are those of the published runs: the hydrostatic punches ("punch table"), and
each keel at the hydrostatic level beside the cfd and vof levels where those are published
("punch water table").

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
        runs[keel][0] = dict(runs[keel][0], **{k: float(v) for k, v in means[keel].items() if k.startswith("mean_") and v != ""})
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


# A keel's hydrostatic punch of the keel it had before (the row run "<keel>-previousKeel" of
# punchSummary.csv, summary_<keel>-previousKeel.json), kept while its resolved levels are still on it.
PREVIOUS = "previousKeel"


def water_table(case):
    """Each keel at the hydrostatic level and the cfd and vof levels published, side by side, from
    results/punchSummary.csv (with the hydrostatic punch of the keel before, where it is kept: a
    row says which keel each column was punched on); None when no keel has a resolved level
    published."""
    with open(os.path.join(case, "results", "punchSummary.csv"), newline="") as handle:
        rows = {r["run"]: r for r in csv.DictReader(handle)}
    names = [n for k in KEELS if k in rows and (f"{k}-cfd" in rows or f"{k}-vof" in rows)
             for n in (k, f"{k}-{PREVIOUS}", f"{k}-cfd", f"{k}-vof") if n in rows]
    if not names:
        return None

    def heading(name):
        keel = name.split("-")[0]
        return f"{keel} {rows[name]['water']}" + (", previous keel" if name.endswith(PREVIOUS) else "")

    lines = ["| | " + " | ".join(heading(n) for n in names) + " |", "|---|" + "---|" * len(names)]

    def row(label, cell):
        lines.append(f"| {label} | " + " | ".join(cell(rows[n]) for n in names) + " |")

    def number(r, key):
        return float(r[key])

    def keel(r):    # which keel a level was punched on: the published levels need not share one
        s = json.load(open(os.path.join(case, "results", f"summary_{r['run']}.json")))
        return f"{s['keel_thickness_m']:.3f} m, {s['freeze_bonds']} freeze-bonds"

    row("keel: thickness, freeze-bonds", keel)
    row("platen speed [m/s]", lambda r: f"{number(r, 'platen_speed_m_per_s'):g}")
    row("largest platen force", lambda r: f"{number(r, 'peak_force_N'):.0f} N at {number(r, 'travel_at_peak_mm'):.1f} mm")
    row("buoyancy share at that sample", lambda r: f"{number(r, 'buoyancy_share_at_peak_N'):.0f} N")
    row("mean force / buoyancy share over 20-100 mm",
        lambda r: f"{number(r, 'mean_force_20_100mm_N'):.0f} / {number(r, 'mean_share_20_100mm_N'):.0f} N")
    for at in (50, 80, 100):
        row(f"force / buoyancy share at {at} mm",
            lambda r, at=at: f"{number(r, f'force_{at}mm_N'):.0f} / {number(r, f'share_{at}mm_N'):.0f} N")
    row("drag on the keel, mean over 20-100 mm", lambda r: f"{number(r, 'drag_mean_20_100mm_N'):.2f} N"
        if r.get("drag_mean_20_100mm_N") else "-")
    row("pressure force less buoyancy over 20-100 mm: mean / standard deviation",
        lambda r: f"{number(r, 'dynamic_pressure_mean_20_100mm_N'):.1f} / {number(r, 'dynamic_pressure_std_20_100mm_N'):.1f} N"
        if r.get("dynamic_pressure_mean_20_100mm_N") else "-")
    row("vof: buoyancy share from the level's rise, platen included: mean over 20-100 mm / at 100 mm",
        lambda r: f"{number(r, 'mean_levelRiseShare_20_100mm_N'):.0f} / {number(r, 'levelRiseShare_100mm_N'):.0f} N"
        if r.get("mean_levelRiseShare_20_100mm_N") else "-")
    row("vof: the ice's share under the moving surface: mean over 20-100 mm / at 100 mm",
        lambda r: f"{number(r, 'mean_iceShareMovingSurface_20_100mm_N'):.0f} / {number(r, 'iceShareMovingSurface_100mm_N'):.0f} N"
        if r.get("mean_iceShareMovingSurface_20_100mm_N") else "-")
    row("vof: the level's rise at the end", lambda r: f"{number(r, 'level_rise_mm'):.1f} mm" if r.get("level_rise_mm") else "-")
    row("broken freeze-bonds at 100 mm: tension / shear / twist / bending",
        lambda r: " / ".join(r[f"broken_{m}"] for m in ("tension", "shear", "twist", "bending")))
    row("wall time, 1 rank (particle-steps/s)",
        lambda r: f"{minutes(number(r, 'wall_s'))} ({number(r, 'particle_steps_per_s'):.3g})")
    return "\n".join(lines) + "\n"


def main():
    readme = os.path.join(CASE, "README.md")
    iceCases.write_readme_section(readme, "punch table", table(CASE))
    water = water_table(CASE)
    if water:
        iceCases.write_readme_section(readme, "punch water table", water)


if __name__ == "__main__":
    main()
