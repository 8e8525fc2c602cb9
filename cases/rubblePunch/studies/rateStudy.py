#!/usr/bin/python3
"""Quasi-static check of the punch on a reduced keel: the keel of the tests (1.6 x 0.4 m, 0.25 m
of rubble, ends fixed, set 4h) punched 30 mm at 0.05, 0.025 and 0.0125 m/s and at the 5 mm/s of
scenes.md section 6; writes rateStudy.csv (largest force, force at 10, 20, 30 mm as the mean
over +-2.5 mm, mean force over 5-30 mm, at each speed) next to this script.

usage: studies/rateStudy.py [-work WORK] [-bin BIN_DIR] [-speeds V ...]
       (default WORK /tmp/rubblePunchRate, BIN_DIR build/demModels)"""
import argparse
import csv
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..", "..")
sys.path.insert(0, os.path.join(TOP, "tests", "integration"))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402
from ridgeSmall import keel_file, ridge_case, small_keel_case  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("-work", default=os.path.join(HERE, "..", "runs", "rateStudy"),
                    help="the runs and rateStudy.csv (default ../runs/rateStudy)")
parser.add_argument("-publish", action="store_true",
                    help="run nothing; copy -work's rateStudy.csv into the committed studies/ and its table into the README")
parser.add_argument("-bin", default=os.path.join(TOP, "build", "demModels"))
parser.add_argument("-speeds", type=iceCases.positive_number, nargs="+",
                    default=[0.05, 0.025, 0.0125, 0.005])
args = parser.parse_args()


def readme_table(path):
    """The README's table of a rateStudy.csv: forces in N, wall time in s."""
    rows = list(csv.DictReader(open(path)))
    lines = ["| platen speed [m/s] | largest force | force at 10 mm | 20 mm | 30 mm | mean over 5-30 mm | wall [s] |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.0f |" % (
            r["speed_m_per_s"], *(float(r[k]) for k in ("max_force_N", "force_10mm_N", "force_20mm_N",
                                                        "force_30mm_N", "mean_force_5_30mm_N", "wall_s"))))
    return "\n".join(lines) + "\n"


if args.publish:
    iceCases.publish_files([os.path.join(args.work, "rateStudy.csv")], HERE)
    iceCases.write_readme_table(os.path.join(HERE, "..", "README.md"), "rate study table",
                                "studies/rateStudy.py -publish", "studies/rateStudy.csv",
                                readme_table(os.path.join(HERE, "rateStudy.csv")))
    sys.exit(0)
work = args.work
bin_dir = os.path.abspath(args.bin)
os.makedirs(work, exist_ok=True)
# the small keel, settled again unless it was made from the same inputs
keel = iceCases.prepared_run(os.path.join(work, "keel"), small_keel_case)
if not os.path.exists(keel_file(work)):
    iceCases.run_app(os.path.join(bin_dir, "rubbleDEM"), keel, 1, ["-stage", "settle"], "log.rubbleDEM")


def window_mean(c, lo, hi):
    inside = (c["travel"] >= lo) & (c["travel"] <= hi)
    return c["force"][inside].mean()


rows = ["speed_m_per_s,max_force_N,force_10mm_N,force_20mm_N,force_30mm_N,mean_force_5_30mm_N,wall_s"]
for v in args.speeds:
    case = ridge_case("rubblePunch", os.path.join(work, f"v{v:g}"), work,
                      # Samples 10 um apart: the loop's blow-up check weighs the kinetic energy
                      # against the work of the sampled force, and a block's first impact on the
                      # platen lasts some 0.3 ms.
                      controls=(("maxTravel", 0.03), ("sampleInterval", 1e-5), ("writeInterval", 0.01),
                                ("checkpointInterval", 0.03)),
                      entries=(("test.speed", v),))
    wall = iceCases.run_app(os.path.join(bin_dir, "ridgeDEM"), case, 1, ["-stage", "all"], "log.ridgeDEM")
    c = {k: np.array(x) for k, x in iceCases.curve(case).items()}
    at = [window_mean(c, d - 0.0025, d + 0.0025) for d in (0.01, 0.02, 0.03)]
    rows.append(",".join(f"{x:.4g}" for x in (v, c["force"].max(), *at, window_mean(c, 0.005, 0.03), wall)))
    print(rows[-1], flush=True)
iceCases.write_atomically(os.path.join(work, "rateStudy.csv"), "\n".join(rows) + "\n")
