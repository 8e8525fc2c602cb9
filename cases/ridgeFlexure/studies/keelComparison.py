#!/usr/bin/python3
"""The ridge matrix on the softened keels (./Allrun -keels softened) beside the matrix on the keels
compacted at the ice's stiffness (the case's since 2026-12-07): what each ridge was bonded under and
what it carried.

For every run of the default matrix finished in both runs/default/ and runs/default-iceStiff/:
the load on the floor plate when the bonds were made, the freeze-bonds (all, and between layer and
keel), the mean and largest confinement of the freeze-bonds (the contact force on the bond's real
area, ridgeDEM's log), the failure force and the keel's contribution (failure force less the layer
alone's), from the two published tables (results/ridgeMatrix_default_softened.csv and
results/ridgeMatrix_default_iceStiff.csv).

Writes results/ridgeMatrix_keelComparison.csv and .md and the README section
"ridgeMatrix keel comparison".

usage: studies/keelComparison.py [--case DIR]   (DIR: the ridgeFlexure case, this script's by default)"""
import argparse
import csv
import json
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(CASE)), "postProcessing"))
import iceCases  # noqa: E402

SETS = (("softened", "default", "ridgeMatrix_default_softened.csv"),
        ("iceStiff", "default-iceStiff", "ridgeMatrix_default_iceStiff.csv"))
NUMBER = r"([-+0-9.eE]+)"


def assembly_state(run_folder):
    """What the bonds of a run were made under: its postProcessing/assembly.json (since 2026-11-29),
    else the assembly lines of its log (None where it has neither: a resumed run's log is of its
    resume only)."""
    made = os.path.join(run_folder, "postProcessing", "assembly.json")
    if os.path.exists(made):
        with open(made) as f:
            a = json.load(f)
        return {"floor_plate_kPa": round(a["floor_plate_Pa"] * 1e-3, 3), "freeze_bonds": a["freeze_bonds"],
                "layer_keel_bonds": a["freeze_bonds_layer_keel"],
                "confinement_mean_kPa": round(a["confinement_mean_Pa"] * 1e-3, 1),
                "confinement_max_kPa": round(a["confinement_max_Pa"] * 1e-3, 0),
                "layer_rise_mm": round(a["layer_rise_during_stiffening_m"] * 1e3, 2)}
    log = os.path.join(run_folder, "log.ridgeDEM")
    if not os.path.exists(log):
        return None
    text = open(log).read()
    plates = re.search(r"held between plates at z = .*?: " + NUMBER + " Pa on the floor plate", text)
    bonds = re.search(r"Bonds: \d+ ice bonds \(blocks and layer\), (\d+) freeze-bonds \((\d+) between layer and keel\); "
                      r"confinement " + NUMBER + r" kPa mean, " + NUMBER + " kPa max", text)
    # "moved X mm down" since 2026-11-29; before, a layer that sank "moved -X mm up".
    rise = re.search(r"assembly.layerHold balanced\): moved " + NUMBER + " mm (up|down)", text)
    if not (plates and bonds):
        return None
    return {"floor_plate_kPa": round(float(plates.group(1)) * 1e-3, 3), "freeze_bonds": int(bonds.group(1)),
            "layer_keel_bonds": int(bonds.group(2)), "confinement_mean_kPa": round(float(bonds.group(3)), 1),
            "confinement_max_kPa": round(float(bonds.group(4)), 0),
            "layer_rise_mm": round(float(rise.group(1)) * (1 if rise.group(2) == "up" else -1), 2) if rise else 0.0}


def published(case, name):
    path = os.path.join(case, "results", name)
    with open(path, newline="") as f:
        return {int(r["run"]): r for r in csv.DictReader(f)}


def rows(case):
    tables = {keels: published(case, table) for keels, _, table in SETS}
    out = []
    for run in sorted(set.intersection(*(set(t) for t in tables.values()))):
        row = {"run": run}
        for keels, folder, _ in SETS:
            r = tables[keels][run]
            if keels == "softened":
                row.update({"keel_m": r["keel_m"], "bond_set": r["bond_set"], "CL_cm": r["CL_cm"]})
            target = os.path.join(case, "runs", folder,
                                  "run%02d_keel%s_%s_CL%s" % (run, r["keel_m"], r["bond_set"], r["CL_cm"]))
            state = assembly_state(target) or {}
            for key in ("floor_plate_kPa", "freeze_bonds", "layer_keel_bonds", "confinement_mean_kPa",
                        "confinement_max_kPa", "layer_rise_mm"):
                row[f"{key}_{keels}"] = state.get(key, "")
            row[f"depth_m_{keels}"] = r["depth_m"]
            row[f"failure_force_kN_{keels}"] = r["failure_force_kN"]
            row[f"keel_contribution_kN_{keels}"] = r["keel_contribution_kN"]
            row[f"failure_mode_{keels}"] = r["failure_mode"].split(";")[0]
        out.append(row)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", default=CASE, help="the ridgeFlexure case folder (default: %(default)s)")
    case = os.path.abspath(parser.parse_args().case)
    table = rows(case)
    if not table:
        sys.exit("keelComparison: no run published in both results/ridgeMatrix_default_softened.csv and "
                 "results/ridgeMatrix_default_iceStiff.csv (./Allrun -keels softened and ./Allrun, each then -publish)")
    base = os.path.join(case, "results", "ridgeMatrix_keelComparison")
    columns = list(table[0].keys())
    lines = [",".join(columns)] + [",".join('"%s"' % r[c] if "mode" in c else str(r[c]) for c in columns) for r in table]
    iceCases.write_atomically(base + ".csv", "\n".join(lines) + "\n")
    shown = [("run", "run"), ("keel_m", "keel [m]"), ("bond_set", "set"), ("CL_cm", "CL [cm]"),
             ("floor_plate_kPa", "floor plate at bonding [kPa]"), ("confinement_mean_kPa", "confinement mean [kPa]"),
             ("freeze_bonds", "freeze-bonds"), ("layer_keel_bonds", "of them layer-keel"),
             ("layer_rise_mm", "layer rose [mm]"), ("depth_m", "depth [m]"), ("failure_force_kN", "failure force [kN]"),
             ("keel_contribution_kN", "keel's contribution [kN]"), ("failure_mode", "mode")]
    md = ["From `results/ridgeMatrix_default_softened.csv` (softened keels) and `results/ridgeMatrix_default_iceStiff.csv`"
          " (keels at the ice's stiffness), and what each run's bonds were made under (its"
          " `postProcessing/assembly.json`, or the assembly lines of its log). Each cell: softened / iceStiff.",
          "", "| " + " | ".join(label for _, label in shown) + " |", "|" + "---|" * len(shown)]
    for r in table:
        cells = []
        for key, _ in shown:
            if key in r:
                cells.append(str(r[key]))
            else:
                cells.append("%s / %s" % (r[f"{key}_softened"], r[f"{key}_iceStiff"]))
        md.append("| " + " | ".join(cells) + " |")
    text = "\n".join(md)
    iceCases.write_atomically(base + ".md", text + "\n")
    iceCases.write_readme_table(os.path.join(case, "README.md"), "ridgeMatrix keel comparison",
                                "studies/keelComparison.py", "results/ridgeMatrix_keelComparison.csv", text)
    print("Written: %s.csv, %s.md and README.md's section" % (base, base))


if __name__ == "__main__":
    main()
