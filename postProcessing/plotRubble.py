"""Settled, bonded rubble (cases/rubbleBeam): side and plan views coloured by
block, the water line, and histograms of the freeze-bonds' confinement and
strength. Run with Debian's /usr/bin/python3 (numpy, matplotlib, h5py)."""
import argparse
import csv
import json
import os

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--case", default=".")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    summary = json.load(open(os.path.join(a.case, "postProcessing", "summary.json")))
    with h5py.File(os.path.join(a.case, "DEM", "rubble.h5"), "r") as f:
        p = f["particles"]
        x, y, z = (np.array(p[k]) for k in ("x", "y", "z"))
        block, kind = np.array(p["block"]), np.array(p["type"])
    rows = list(csv.DictReader(open(os.path.join(a.case, "postProcessing", "freezeBonds.csv"))))
    confinement = np.array([float(r["confinement_Pa"]) for r in rows]) * 1e-3
    tensile = np.array([float(r["tensile_Pa"]) for r in rows]) * 1e-3
    shear = np.array([float(r["shear_Pa"]) for r in rows]) * 1e-3

    fig = plt.figure(figsize=(12, 8))
    colours = plt.cm.tab20(block % 20)
    side = fig.add_subplot(2, 2, (1, 2))
    side.scatter(x, z, s=4, c=colours)
    side.scatter(x[kind == 2], z[kind == 2], s=4, c="k", label="fixed to the box")
    side.axhline(summary["water_level_m"], color="tab:blue", lw=1, label="water surface")
    for level in (summary["layer_bottom_m"], summary["layer_top_m"]):
        side.axhline(level, color="grey", ls="--", lw=0.8)
    side.set_aspect("equal")
    side.set_xlabel("x (m)")
    side.set_ylabel("z (m)")
    side.set_title(f"{summary['blocks']} {summary['block_shape']} blocks, {summary['particles']} particles: "
                   f"thickness {summary['thickness_m']:.3f} m, porosity {summary['porosity']:.3f}, "
                   f"{100 * summary['ice_volume_above_water_fraction']:.1f} % of the ice above water")
    side.legend(loc="lower right", fontsize=8)

    hist = fig.add_subplot(2, 2, 3)
    hist.hist(confinement, bins=40, color="tab:grey")
    hist.set_xlabel("confinement on the real frozen area (kPa)")
    hist.set_ylabel("freeze-bonds")
    hist.set_title(f"{summary['freeze_bonds']} freeze-bonds, {summary['mean_bonds_per_block_contact']:.1f} per block contact")
    strength = fig.add_subplot(2, 2, 4)
    strength.hist([tensile, shear], bins=30, label=["tensile", "shear"])
    strength.set_xlabel(f"strength on the DEM bond area (kPa), c_f = {summary['area_correction']:.3f}")
    strength.legend()
    fig.tight_layout()
    fig.savefig(a.out + ".tmp.png", dpi=110)
    os.replace(a.out + ".tmp.png", a.out)


if __name__ == "__main__":
    main()
