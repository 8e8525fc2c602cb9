#!/usr/bin/python3
"""Runs the four Ten Cate et al. (2002) settling experiments (oils E1-E4 of
../../shared/data/tenCate2002.csv) with iceFoam, each in runs/<name>, and writes
postProcessing/summary.json and postProcessing/terminalVelocities.csv: the
simulated settling velocity (median over the sphere's path from 30 to 80 mm
above the bottom: robust to the dips when it crosses cell faces), the
Schiller-Naumann terminal velocity in unbounded fluid, and the measured one.

Usage: runExperiments.py [--iceFoam PATH] [--only E1,E4] [--endTime T]"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
from iceCases import copy_common, positive_text, write_atomically  # noqa: E402

DIAMETER, RHO_P, G = 0.015, 1120.0, 9.81


def unbounded_terminal_velocity(rho_f, mu):
    nu = mu / rho_f
    lo, hi = 0.0, 10.0
    for _ in range(200):
        v = 0.5 * (lo + hi)
        re = v * DIAMETER / nu
        drag = 0.5 * rho_f * max(0.44 * re, 24 * (1 + 0.15 * re ** 0.687)) * nu / DIAMETER \
            * math.pi * DIAMETER ** 2 / 4 * v
        lo, hi = (v, hi) if drag < (RHO_P - rho_f) * math.pi / 6 * DIAMETER ** 3 * G else (lo, v)
    return 0.5 * (lo + hi)


def experiments():
    with open(os.path.join(os.path.dirname(TOP), "shared", "data", "tenCate2002.csv")) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def run(exp, app, end_time):
    case = os.path.join(HERE, "runs", exp["experiment"])
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    for sub in ("0", "constant", "system", "DEM"):
        shutil.copytree(os.path.join(HERE, sub), os.path.join(case, sub))
    copy_common(case)
    rho_f, mu = float(exp["rho_f"]), float(exp["mu_f_Pa_s"])
    transport = os.path.join(case, "constant", "transportProperties")
    for entry, value in (("rho", rho_f), ("nu", mu / rho_f)):
        subprocess.run(["foamDictionary", "-entry", entry, "-set", repr(value), transport],
                       check=True, stdout=subprocess.DEVNULL)
    if end_time:
        subprocess.run(["foamDictionary", "-entry", "endTime", "-set", str(end_time),
                        os.path.join(case, "system", "controlDict")], check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["blockMesh", "-case", case], check=True, stdout=subprocess.DEVNULL)
    start = time.time()
    with open(os.path.join(case, "log.iceFoam"), "w") as log:
        if subprocess.run([app, "-case", case], stdout=log, stderr=subprocess.STDOUT).returncode != 0:
            raise RuntimeError(f"iceFoam failed, see {case}/log.iceFoam")
    wall = time.time() - start
    with open(os.path.join(case, "postProcessing", "particles.csv")) as f:
        rows = [(float(r["z"]), -float(r["vz"])) for r in csv.DictReader(f)]
    window = sorted(v for z, v in rows if 0.03 <= z <= 0.08)
    if not window:
        raise RuntimeError(f"{exp['experiment']}: the sphere never passed 30-80 mm (run longer)")
    median = window[len(window) // 2]
    return {
        "experiment": exp["experiment"],
        "Re_measured": float(exp["Re"]),
        "u_measured_m_s": float(exp["u_terminal_m_s"]),
        "u_iceFoam_m_s": median,
        "u_iceFoam_min_m_s": window[0],
        "u_iceFoam_max_m_s": window[-1],
        "u_SchillerNaumann_unbounded_m_s": unbounded_terminal_velocity(rho_f, mu),
        "iceFoam_vs_measured": median / float(exp["u_terminal_m_s"]) - 1,
        "wall_s": wall,
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--iceFoam", default=os.path.join(TOP, "build", "coupling", "iceFoam"))
    ap.add_argument("--only", default="", help="comma-separated experiments (E1,E4; default: all)")
    ap.add_argument("--endTime", type=positive_text, default=None, help="simulated seconds (default: controlDict's)")
    a = ap.parse_args()
    os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    names = [e["experiment"] for e in experiments()]
    if a.only and any(n not in names for n in a.only.split(",")):
        ap.error(f"argument --only: needs experiments of {','.join(names)} separated by commas, got '{a.only}'")
    chosen = [e for e in experiments() if not a.only or e["experiment"] in a.only.split(",")]
    results = [run(e, a.iceFoam, a.endTime) for e in chosen]
    out = os.path.join(HERE, "postProcessing")
    os.makedirs(out, exist_ok=True)
    keys = list(results[0])
    write_atomically(os.path.join(out, "terminalVelocities.csv"),
                     ",".join(keys) + "\n" + "".join(",".join(str(r[k]) for k in keys) + "\n" for r in results))
    summary = {
        "experiments": results,
        "particles": 1, "bonds": 0,
        "steps": None, "dt": 1e-4, "ranks": 1,
        "wall_s": sum(r["wall_s"] for r in results),
    }
    write_atomically(os.path.join(out, "summary.json"), json.dumps(summary, indent=2) + "\n")
    print("experiment  Re    measured  iceFoam (min-max)          SN unbounded  iceFoam/measured")
    for r in results:
        print(f"{r['experiment']:10s} {r['Re_measured']:5.1f}  {r['u_measured_m_s']:.3f}     "
              f"{r['u_iceFoam_m_s']:.4f} ({r['u_iceFoam_min_m_s']:.4f}-{r['u_iceFoam_max_m_s']:.4f})  "
              f"{r['u_SchillerNaumann_unbounded_m_s']:.4f}        {100 * r['iceFoam_vs_measured']:+.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
