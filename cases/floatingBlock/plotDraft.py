#!/usr/bin/python3
"""Draft and submerged volume fraction of the floating block against time.

    /usr/bin/python3 plotDraft.py --csv postProcessing/draft.csv \
        --summary postProcessing/summary.json --out postProcessing/draft.png

Top: the submerged share of the spheres' volume against rho_i/rho_w (the exact
equilibrium statement) and the geometric draft / block height against the
draft of the level lattice. Bottom: kinetic energy (log) and the sideways
drift of the centre of mass."""
import argparse
import csv
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--csv", required=True)
    ap.add_argument("--summary", required=True)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()

    with open(args.csv) as f:
        rows = list(csv.DictReader(f))
    c = {k: [float(r[k]) for r in rows] for k in rows[0]}
    s = json.load(open(args.summary))
    t = c["time"]
    x0, y0 = c["centreX"][0], c["centreY"][0]
    drift = [((x - x0) ** 2 + (y - y0) ** 2) ** 0.5 * 1e3 for x, y in zip(c["centreX"], c["centreY"])]

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    top.plot(t, c["submergedVolumeFraction"], label="submerged volume / sphere volume")
    top.plot(t, c["draftOverHeight"], label="draft / block height (geometric)")
    top.axhline(s["density_ratio"], color="k", ls="--", lw=0.8, label=f"rho_i/rho_w = {s['density_ratio']:.3f}")
    top.axhline(s["level_lattice_draft_m"] / s["height_m"], color="C1", ls=":", lw=1.0,
                label=f"level lattice draft / height = {s['level_lattice_draft_m'] / s['height_m']:.4f}")
    top.set_ylabel("fraction")
    top.set_ylim(0.0, max(1.4, max(c["draftOverHeight"]) * 1.05))
    top.legend(loc="upper right", fontsize=8)
    top.set_title(f"Floating block: {s['particles']} bonded ice spheres, {s['ranks']} rank(s); "
                  f"final submerged fraction {s['submerged_volume_fraction']:.4f}")

    peak = max(c["kineticEnergy"])
    bottom.semilogy(t, [max(k, 1e-12 * peak) for k in c["kineticEnergy"]], label="kinetic energy [J]")
    rest = s["rest_threshold_over_MgH"] * s["kinetic_energy_J"] / s["kinetic_energy_over_MgH"]
    bottom.axhline(rest, color="k", ls="--", lw=0.8, label="at-rest threshold")
    bottom.set_ylabel("kinetic energy [J]")
    bottom.set_xlabel("time [s]")
    right = bottom.twinx()
    right.plot(t, drift, color="C2", label="sideways drift [mm]")
    right.set_ylabel("sideways drift of the centre [mm]", color="C2")
    bottom.legend(loc="upper right", fontsize=8)

    fig.tight_layout()
    tmp = args.out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, args.out)


if __name__ == "__main__":
    main()
