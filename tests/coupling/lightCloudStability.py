#!/usr/bin/python3
"""Stability and momentum conservation of the drag exchange with light
particles (ice, rho_p/rho_f = 0.917): a periodic box filled with a cloud of
ice spheres (fluid fraction 0.476) set moving at v0 through still water
(tests/coupling/lightCloud). Every particle and the fluid must end at the
common velocity v0 phi rho_p / (phi rho_p + alpha rho_f) that momentum
conservation leaves. At a coupling time of 28 ms the explicit exchange
diverges (iceFoam refuses it; forced, it blows up) while the semi-implicit
one relaxes; at 10 ms both relax.

Usage: lightCloudStability.py CASE_SOURCE WORK_DIR ICEFOAM"""
import csv
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
from iceCases import copy_common  # noqa: E402


def run(src, work, app, name, changes):
    case = os.path.join(work, name)
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    for sub in ("0", "constant", "system", "DEM"):
        shutil.copytree(os.path.join(src, sub), os.path.join(case, sub))
    copy_common(case)
    for file, entry, value in changes:
        subprocess.run(["foamDictionary", "-entry", entry, "-set", str(value), os.path.join(case, file)],
                       check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["blockMesh", "-case", case], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(case, "log.iceFoam"), "w") as log:
        rc = subprocess.run([app, "-case", case], stdout=log, stderr=subprocess.STDOUT).returncode
    speeds = {}
    path = os.path.join(case, "postProcessing", "particles.csv")
    if os.path.exists(path):
        with open(path) as f:
            for r in csv.DictReader(f):
                t = float(r["time"])
                speeds.setdefault(t, []).append(float(r["vx"]))
    return rc, case, speeds


def main():
    src, work, app = sys.argv[1:4]
    v0, rho_p, rho_f, d, spacing = 0.01, 917.0, 1000.0, 2e-3, 2e-3
    phi = math.pi / 6 * d ** 3 / spacing ** 3
    v_mix = v0 * phi * rho_p / (phi * rho_p + (1 - phi) * rho_f)
    props, control = "constant/couplingProperties", "system/controlDict"
    step28 = [(props, "couplingInterval", 28), (control, "deltaT", 0.028)]
    step10 = [(props, "couplingInterval", 10), (control, "deltaT", 0.01)]
    failures = []

    def relaxes(name, changes):
        rc, case, speeds = run(src, work, app, name, changes)
        if rc != 0:
            failures.append(f"{name}: iceFoam failed (exit {rc}), see {case}/log.iceFoam")
            return
        final = speeds[max(speeds)]
        worst = max(abs(v - v_mix) for v in final) / v_mix
        peak = max(abs(v) for vs in speeds.values() for v in vs)
        print(f"{name}: every particle ends at {v_mix:.8f} m/s within {worst:.1e} (relative); "
              f"fastest ever {peak:.5f} m/s")
        if worst > 1e-6:
            failures.append(f"{name}: momentum not conserved, particles {worst:.2e} off {v_mix} m/s")
        if peak > v0 * (1 + 1e-9):
            failures.append(f"{name}: a particle went faster ({peak}) than the initial {v0} m/s")

    relaxes("semiImplicit_28ms", step28)
    relaxes("explicit_10ms", step10 + [(props, "momentumCoupling", "explicit")])
    relaxes("semiImplicit_10ms", step10)

    rc, case, _ = run(src, work, app, "explicit_28ms_refused", step28 + [(props, "momentumCoupling", "explicit")])
    log = open(os.path.join(case, "log.iceFoam")).read()
    said = "the drag exchange is unstable with momentumCoupling explicit" in log
    print(f"explicit_28ms_refused: exit {rc}, {'says' if said else 'does NOT say'} the exchange is unstable")
    if rc == 0 or not said:
        failures.append("explicit_28ms_refused: not refused with the stability message")

    rc, case, speeds = run(src, work, app, "explicit_28ms_forced",
                           step28 + [(props, "momentumCoupling", "explicit"), (props, "stabilityCheck", "no")])
    peak = max(abs(v) for vs in speeds.values() for v in vs) if speeds else 0.0
    print(f"explicit_28ms_forced: exit {rc}, fastest particle {peak:.4f} m/s ({peak / v0:.0f} v0)")
    if peak < 10 * v0:
        failures.append(f"explicit_28ms_forced: did not diverge (fastest {peak} m/s)")

    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
