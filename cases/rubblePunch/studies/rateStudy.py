#!/usr/bin/python3
"""Quasi-static check of the punch on a reduced keel: the keel of the tests (1.6 x 0.4 m, 0.25 m
of rubble, ends fixed, set 4h) punched 30 mm at the case's platen speed, half and a quarter of it;
writes rateStudy.csv (largest force and force at 10, 20, 30 mm at each speed) next to this script.

usage: studies/rateStudy.py [WORK] [BIN_DIR]   (default WORK /tmp/rubblePunchRate, BIN_DIR build/demModels)"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..", "..")
sys.path.insert(0, os.path.join(TOP, "tests", "integration"))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402
from ridgeSmall import build_keel, keel_file, ridge_case  # noqa: E402

work = sys.argv[1] if len(sys.argv) > 1 else "/tmp/rubblePunchRate"
bin_dir = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else os.path.join(TOP, "build", "demModels"))
os.makedirs(work, exist_ok=True)
if not os.path.exists(keel_file(work)):
    build_keel(work, bin_dir)
speed = float(iceCases.get_entry(os.path.join(HERE, "..", "constant", "ridgeProperties"), "test.speed"))
rows = ["speed_m_per_s,max_force_N,force_10mm_N,force_20mm_N,force_30mm_N,wall_s"]
for v in (speed, speed / 2, speed / 4):
    case = ridge_case("rubblePunch", os.path.join(work, f"v{v:g}"), work,
                      # Samples 10 um apart: the loop's blow-up check weighs the kinetic energy
                      # against the work of the sampled force, and a block's first impact on the
                      # platen lasts some 0.3 ms.
                      controls=(("maxTravel", 0.03), ("sampleInterval", 1e-5), ("writeInterval", 0.01),
                                ("checkpointInterval", 0.03)),
                      entries=(("test.speed", v),))
    wall = iceCases.run_app(os.path.join(bin_dir, "ridgeDEM"), case, 1, ["-stage", "all"], "log.ridgeDEM")
    c = {k: np.array(x) for k, x in iceCases.curve(case).items()}
    at = [np.interp(d, c["travel"], c["force"]) for d in (0.01, 0.02, 0.03)]
    rows.append(",".join(f"{x:.4g}" for x in (v, c["force"].max(), *at, wall)))
    print(rows[-1], flush=True)
iceCases.write_atomically(os.path.join(HERE, "rateStudy.csv"), "\n".join(rows) + "\n")
