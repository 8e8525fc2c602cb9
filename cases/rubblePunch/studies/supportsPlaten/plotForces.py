#!/usr/bin/python3
"""The platen force, its buoyancy share and the rest (the rubble's) against travel for each
finished point of this study (runs/<point>/.../runs/cuboid/postProcessing/platenForce.csv), one
panel per point: results/forces.png.

usage: plotForces.py [STUDY_FOLDER]"""
import csv
import glob
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def curves(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    col = {k: [float(r[k]) for r in rows] for k in ("travel", "force", "buoyancyShare")}
    col["rubble"] = [f - b for f, b in zip(col["force"], col["buoyancyShare"])]
    return col


def main(folder):
    runs = sorted(glob.glob(os.path.join(folder, "runs", "*", "mirror", "cases", "rubblePunch", "runs", "cuboid",
                                         "postProcessing", "summary.json")))
    if not runs:
        sys.exit(f"plotForces.py: no finished point in {folder}/runs")
    fig, axes = plt.subplots(1, len(runs), figsize=(5.5 * len(runs), 4), sharey=True, squeeze=False)
    for ax, summary in zip(axes[0], runs):
        point = summary.split(os.sep + "runs" + os.sep)[1].split(os.sep)[0]
        c = curves(os.path.join(os.path.dirname(summary), "platenForce.csv"))
        mm = [1e3 * t for t in c["travel"]]
        ax.plot(mm, c["force"], lw=0.6, label="platen force")
        ax.plot(mm, c["buoyancyShare"], lw=1.2, label="buoyancy share (the ice pushed under)")
        ax.plot(mm, c["rubble"], lw=0.6, label="the rest: the rubble's")
        ax.axhline(0, color="k", lw=0.4)
        ax.set_title(point.replace("_", ", "), fontsize=9)
        ax.set_xlabel("platen travel [mm]")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("force [N]")
    axes[0][0].legend(fontsize=7)
    fig.suptitle("Rubble punch, cuboid keel, 5 mm/s: the end supports", fontsize=10)
    fig.tight_layout()
    out = os.path.join(folder, "results", "forces.png")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=80)
    os.replace(tmp, out)
    print("plotForces.py:", out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__)))
