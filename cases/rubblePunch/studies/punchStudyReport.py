#!/usr/bin/python3
"""The report of a punch study (here: supportsPlaten, bondSets, supportsEmpirical; or
studies/rubblePunchInertia): the platen
force, its buoyancy share and the rest (the rubble's) against travel for each finished point
(STUDY_FOLDER/runs/<point>/.../runs/<keel>), drawn by the case's own plotPunch.plot_forces into
STUDY_FOLDER/results/forces.png, and the study's README table (between `<!-- study table -->`
and `<!-- end study table -->`) generated from STUDY_FOLDER/results/table.csv, which
studies/runStudy.py writes.

usage: punchStudyReport.py STUDY_FOLDER [NAME=RUN_FOLDER ...]
  NAME=RUN_FOLDER  a finished punch outside the study drawn beside its points, e.g. the case's
                   published clamped punch: clamped=cases/rubblePunch/runs/empirical"""
import csv
import glob
import json
import math
import os
import shlex
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "postProcessing"))
import iceCases  # noqa: E402
import plotPunch  # noqa: E402

# figure of the study dictionaries here -> (column heading, scale, decimals)
COLUMNS = {
    "peakForce": ("largest force [N]", 1, 0),
    "travelAtPeak": ("at travel [mm]", 1e3, 1),
    "buoyancyAtPeak": ("buoyancy share there [N]", 1, 0),
    "supportReactionAtPeak": ("support reaction there [N]", 1, 0),
    "rubbleSharePeak": ("force less buoyancy, largest [N]", 1, 0),
    "brokenBonds": ("broken bonds at the end", 1, 0),
    "brokenBeforePeak": ("broken before the peak", 1, 0),
    "brokenInShear": ("broken in shear", 1, 0),
    "tensionShare": ("broken in tension [%]", 100, 0),
    "firstFailureTravel": ("first freeze-bond failure: travel [mm]", 1e3, 1),
    "firstFailureForce": ("force there [N]", 1, 0),
    "firstFailureFromLoadLine": ("from the load line [m]", 1, 2),
    "firstFailureHeight": ("height in keel", 1, 2),
    "bottomCentreTensionShare": ("bottom-centre tension, first 10", 1, 1),
    "kineticToWork": ("kinetic energy / platen work", 1, 4),
    "n_steps": ("steps", 1, 0),
    "wall_s": ("wall [s]", 1, 0),
}


def finished_runs(folder):
    """{point: its punch run folder} of the points whose run finished (one keel's punch per point)."""
    summaries = sorted(glob.glob(os.path.join(folder, "runs", "*", "mirror", "cases", "rubblePunch", "runs", "*",
                                              "postProcessing", "summary.json")))
    return {os.path.relpath(s, os.path.join(folder, "runs")).split(os.sep)[0]: os.path.dirname(os.path.dirname(s))
            for s in summaries if json.load(open(s)).get("complete")}


def table_markdown(rows, knobs):
    """The README table of the study's rows: its knobs, then each figure it has, in COLUMNS' order."""
    figures = [name for name in COLUMNS if name in rows[0]]
    lines = ["| " + " | ".join(knobs + ["status"] + [COLUMNS[f][0] for f in figures]) + " |",
             "|" + "---|" * (len(knobs) + 1 + len(figures))]
    for row in rows:
        cells = [row[k] for k in knobs] + [row["status"]]
        for name in figures:
            _, scale, decimals = COLUMNS[name]
            value = float(row[name]) if row[name] not in ("", None) else math.nan
            cells.append("-" if math.isnan(value) else f"{value * scale:.{decimals}f}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(folder, beside):
    runs = finished_runs(folder)
    if not runs:
        sys.exit(f"punchStudyReport.py: no finished point in {folder}/runs")
    for pair in beside:
        name, _, run = pair.partition("=")
        summary = os.path.join(run, "postProcessing", "summary.json")
        if not name or not os.path.isfile(summary) or not json.load(open(summary)).get("complete"):
            sys.exit(f"punchStudyReport.py: '{pair}': needs NAME=RUN_FOLDER of a finished punch ({summary})")
        runs[name] = run
    out = os.path.join(folder, "results", "forces.png")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    plotPunch.plot_forces(runs, out)
    print("punchStudyReport.py:", out)

    source = os.path.join(folder, "results", "table.csv")
    if not os.path.isfile(source):
        sys.exit(f"punchStudyReport.py: {source} missing (studies/runStudy.py writes it)")
    with open(source, newline="") as f:
        rows = list(csv.DictReader(f))
    header = list(rows[0])
    knobs = header[1:header.index("status")]
    study = os.path.relpath(os.path.abspath(folder), iceCases.TOP)
    iceCases.write_readme_table(os.path.join(folder, "README.md"), "study table",
                                " ".join(["cases/rubblePunch/studies/punchStudyReport.py", study]
                                         + [shlex.quote(b) for b in beside]),
                                "results/table.csv", table_markdown(rows, knobs))


if __name__ == "__main__":
    if len(sys.argv) < 2 or not os.path.isfile(os.path.join(sys.argv[1], "studyDict")):
        sys.exit("usage: punchStudyReport.py STUDY_FOLDER [NAME=RUN_FOLDER ...] (STUDY_FOLDER holds a "
                 "studyDict, e.g. supportsPlaten)")
    main(sys.argv[1], sys.argv[2:])
