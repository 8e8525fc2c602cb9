#!/usr/bin/python3
"""Keel-to-consolidated-layer bond (cases/keelBond, scenes.md section 8): pull-up and direct shear.

Writes to CASE/postProcessing/, each file atomically:
  keelBond.png  force minus the force at the start, as interface stress (force / (L B), kPa)
                against the CL's movement, both tests: the actuator's force and the part of it
                the keel-to-layer bonds carry (interfaceBondForce; with the keel held rigidly
                the rest is the CL's spheres ploughing into the keel's), with the field range
                of keelBondField.csv (max and mean of each year) drawn for the matching test;
  keelBond.csv  per test: peak force, force at the start, interface strength (kPa) from the
                actuator and from the bonds, field mean and max of each year, bonds broken.

usage: plotKeelBond.py CASE --field keelBondField.csv"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from iceCases import curve, finished, summary, write_atomically  # noqa: E402
from plotForceDisplacement import save_atomically  # noqa: E402

TESTS = {"pullUp": "tension", "directShear": "shear"}


def read_field(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(line for line in handle if not line.startswith("#")))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case")
    ap.add_argument("--field", required=True)
    a = ap.parse_args(argv)
    field = read_field(a.field)
    runs = {t: os.path.join(a.case, "runs", t) for t in TESTS
            if finished(os.path.join(a.case, "runs", t))}
    if not runs:
        sys.exit(f"plotKeelBond.py: no finished test in {a.case}/runs")

    fig, axes = plt.subplots(1, len(runs), figsize=(6.5 * len(runs), 4.5), squeeze=False)
    rows = []
    for ax, (test, run) in zip(axes[0], runs.items()):
        kind = TESTS[test]
        s, c = summary(run), curve(run)
        area = s["interface_area_m2"]
        mm = np.array(c["travel"]) * 1e3
        stress = (np.array(c["force"]) - s["force_at_start_N"]) / area * 1e-3
        bonds = "interfaceBondForce" in c
        ax.plot(mm, stress, color="0.5" if bonds else "k", lw=1.2, label="DEM, actuator's force")
        if bonds:
            bond_stress = (np.array(c["interfaceBondForce"]) - s["interface_bond_force_at_start_N"]) / area * 1e-3
            ax.plot(mm, bond_stress, color="k", lw=1.8, label="DEM, carried by the keel-to-CL bonds")
            top = max(bond_stress.max(), max(float(y[f"{kind}_max_kPa"]) for y in field))
            ax.set_ylim(min(0.0, bond_stress.min()) - 0.05 * top, 1.3 * top)
        for year, colour in zip(field, ("tab:blue", "tab:red")):
            mean, top = float(year[f"{kind}_mean_kPa"]), float(year[f"{kind}_max_kPa"])
            ax.axhspan(mean, top, color=colour, alpha=0.15)
            ax.axhline(mean, color=colour, ls="--", lw=1,
                       label=f"field {year['year']} (air {year['air_temperature_C']} C): mean {mean:g}, max {top:g} kPa")
            ax.axhline(top, color=colour, lw=1)
        ax.set_xlabel("CL movement (mm)")
        ax.set_ylabel("(force - force at start) / (L B)  (kPa)")
        strength = s.get("interface_bond_strength_Pa", s["interface_strength_Pa"])
        ax.set_title(f"{test} ({kind}): interface strength {strength * 1e-3:.1f} kPa"
                     + (" (bonds)" if bonds else ""))
        ax.legend(fontsize=7)
        row = {"test": test, "peak_force_N": round(s["peak_force_N"], 1),
               "force_at_start_N": round(s["force_at_start_N"], 1),
               "interface_area_m2": round(area, 4),
               "interface_strength_kPa": round(s["interface_strength_Pa"] * 1e-3, 2),
               "travel_at_peak_um": round(s["travel_at_peak_m"] * 1e6, 2),
               "interface_bond_strength_kPa": round(s.get("interface_bond_strength_Pa", float("nan")) * 1e-3, 2),
               "travel_at_interface_bond_peak_um": round(s.get("travel_at_interface_bond_peak_m", float("nan")) * 1e6, 2),
               "layer_keel_bonds_broken": s["layer_keel_bonds_broken"],
               "broken_tension": s["broken_by_mode"]["tension"], "broken_shear": s["broken_by_mode"]["shear"],
               "wall_s": round(s["wall_s"], 1)}
        for year in field:
            row[f"field_{year['year']}_mean_kPa"] = float(year[f"{kind}_mean_kPa"])
            row[f"field_{year['year']}_max_kPa"] = float(year[f"{kind}_max_kPa"])
        rows.append(row)
    out = os.path.join(a.case, "postProcessing")
    save_atomically(fig, os.path.join(out, "keelBond.png"))
    names = list(dict.fromkeys(k for r in rows for k in r))
    lines = [",".join(names)] + [",".join(str(r.get(k, "")) for k in names) for r in rows]
    write_atomically(os.path.join(out, "keelBond.csv"), "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
