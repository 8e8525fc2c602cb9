#!/usr/bin/python3
"""The platen force, its buoyancy share and the rest (the rubble's) against travel for each
finished point of this study (runs/<point>/.../runs/cuboid), drawn by the case's own
plotPunch.plot_forces: results/forces.png.

usage: plotForces.py [STUDY_FOLDER]"""
import glob
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "..", "postProcessing"))
import plotPunch  # noqa: E402


def main(folder):
    summaries = sorted(glob.glob(os.path.join(folder, "runs", "*", "mirror", "cases", "rubblePunch", "runs", "cuboid",
                                              "postProcessing", "summary.json")))
    if not summaries:
        sys.exit(f"plotForces.py: no finished point in {folder}/runs")
    # point name (runs/<point>/...) -> its punch run folder
    runs = {os.path.relpath(s, os.path.join(folder, "runs")).split(os.sep)[0]: os.path.dirname(os.path.dirname(s))
            for s in summaries}
    out = os.path.join(folder, "results", "forces.png")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    plotPunch.plot_forces(runs, out)
    print("plotForces.py:", out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else HERE)
