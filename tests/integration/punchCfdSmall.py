#!/usr/bin/python3
"""Rubble punch at the cfd water level (icePunchFoam; cases/rubblePunch, ./Allrun -water cfd) on
the small keel of ridgeSmall.py (1.6 x 0.4 m, 489 particles, free ends).

usage: punchCfdSmall.py STEP WORK DEM_BIN_DIR CFD_BIN_DIR
  punch     the same punch in hydrostatic water (ridgeDEM) and at the cfd level on 1 and 2 ranks:
            (a) the cfd run's buoyancy share equals rho_w g times the rise of the ice's submerged
                volume that this script computes from the VTK frames (ridgeSmall.py's check);
            (b) before the first bond breaks, the cfd platen force agrees with the hydrostatic
                one within the water's dynamic forces that differ between the levels (added
                mass of the accelerating ice, drag; bound below);
            (c) 2 ranks give the 1-rank force before any bond breaks (relative 1e-8)
  badInput  ridgeDEM loading at waterLevel cfd; icePunchFoam without a mesh, with a mesh whose top
            is not the water surface, with a coupling interval longer than a force sample:
            a message naming the file or entry, non-zero exit"""
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import ridgeSmall  # noqa: E402
from ridgeSmall import LENGTH, WIDTH, RHO_W, G, check, iceCases  # noqa: E402

CFD = os.path.join(ridgeSmall.CASES, "rubblePunch", "cfd")
TRAVEL = 0.012          # m: the ramp (5 mm) and 7 mm at full speed
# Freeze-bonds at their ultimate strength: the 4h set's first bond breaks within 0.3 mm of
# travel, before the water's effects can be told apart; these hold for several mm.
CONTROLS = (("maxTravel", TRAVEL), ("writeInterval", 0.002), ("checkpointInterval", 0.02),
            ("stopAfterHalfLoad", "no"))
ENTRIES = (("test.settleTime", 0.05), ("ends.fixedLength", 0))


def env():
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                OMPI_MCA_mpi_yield_when_idle="1",
                WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))


def ultimate_freeze_bonds(case):
    iceCases.set_entry(os.path.join(case, "constant", "freezeBondProperties"), "fixedSetCoeffs.set", "ultimate")


def hydrostatic_case(work, name):
    case = ridgeSmall.ridge_case("rubblePunch", os.path.join(work, name), work, CONTROLS, ENTRIES)
    ultimate_freeze_bonds(case)
    return case


def cfd_case(work, name):
    """The punch with cfd/ over it, as Allrun -water cfd makes it."""
    case = hydrostatic_case(work, name)
    os.rename(os.path.join(case, "system", "controlDict"), os.path.join(case, "system", "loadingDict"))
    shutil.copytree(os.path.join(CFD, "0"), os.path.join(case, "0"))
    for sub in ("system", "constant"):
        for f in os.listdir(os.path.join(CFD, sub)):
            shutil.copy(os.path.join(CFD, sub, f), os.path.join(case, sub, f))
    return case


def foam(cmd, case, log):
    with open(os.path.join(case, log), "w") as out:
        return subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT, env=env()).returncode


def mesh(case, ranks, cells=(8, 2, 5)):
    """The water from the floor to where the assembled ridge floats, cells about 0.2 m."""
    g = json.load(open(os.path.join(case, "postProcessing", "geometry.json")))
    block = os.path.join(case, "system", "blockMeshDict")
    for entry, value in (("surfaceZ", repr(g["waterLevel"])), ("boxLength", LENGTH), ("boxWidth", WIDTH),
                         ("cellsX", cells[0]), ("cellsY", cells[1]), ("cellsZ", cells[2])):
        iceCases.set_entry(block, entry, value)
    if foam(["blockMesh", "-case", case], case, "log.blockMesh") != 0:
        raise RuntimeError(f"blockMesh failed in {case}")
    if ranks > 1:
        decompose = os.path.join(case, "system", "decomposeParDict")
        iceCases.set_entry(decompose, "numberOfSubdomains", ranks)
        iceCases.set_entry(decompose, "coeffs.n", f"({ranks} 1 1)")
        if foam(["decomposePar", "-force", "-case", case], case, "log.decomposePar") != 0:
            raise RuntimeError(f"decomposePar failed in {case}")


def run_cfd(dem_bin, cfd_bin, case, ranks):
    iceCases.run_app(os.path.join(dem_bin, "ridgeDEM"), case, 1, ["-stage", "assemble"], "log.ridgeDEM")
    mesh(case, ranks)
    args = ["-parallel"] if ranks > 1 else []
    return iceCases.run_app(os.path.join(cfd_bin, "icePunchFoam"), case, ranks, args, "log.icePunchFoam")


def before_first_break(c):
    broken = np.array(c["brokenBonds"])
    return int(np.argmax(broken > 0)) if broken.max() > 0 else len(broken)


def punch(work, dem_bin, cfd_bin):
    hydro = hydrostatic_case(work, "cfdRef_hydrostatic")
    iceCases.run_app(os.path.join(dem_bin, "ridgeDEM"), hydro, 1, ["-stage", "all"], "log.ridgeDEM")
    cfd1 = cfd_case(work, "cfd_np1")
    wall1 = run_cfd(dem_bin, cfd_bin, cfd1, 1)
    cfd2 = cfd_case(work, "cfd_np2")
    wall2 = run_cfd(dem_bin, cfd_bin, cfd2, 2)
    print(f"wall: cfd 1 rank {wall1:.0f} s, 2 ranks {wall2:.0f} s")

    level = json.load(open(os.path.join(cfd1, "postProcessing", "geometry.json")))["waterLevel"]
    # (a) The share's definition at the cfd level.
    ridgeSmall.check_buoyancy_share(cfd1, level)

    # (b) The levels differ in the water's dynamic forces only: buoyancy is rho_w g V_cap in both
    # (cfd: the hydrostatic part of -V grad p). Bound on the difference at each sample:
    #   added mass: the hydrostatic level gives each sphere C_a rho_w V_sub (C_a 0.5), the cfd
    #     level none of its own; the whole free keel accelerates with the platen's smooth start,
    #     a = v/tau exp(-t/tau) (tau = rampTravel / v): C_a rho_w V_sub a;
    #   drag: the keel moving down at the platen's speed v as a plate of its plan area,
    #     0.5 rho_w C_d L B v^2 with C_d = 2 (a flat plate broadside; the porous keel less);
    #   and 5 % of the force for the rest (drag laws, dynamic pressure of the flow through the
    #     rubble, fluid-fraction jumps as spheres cross cell faces).
    h, c = iceCases.curve(hydro), iceCases.curve(cfd1)
    ramp, speed = 0.005, 0.05
    tau = ramp / speed
    n = min(before_first_break(h), before_first_break(c), len(h["travel"]), len(c["travel"]))
    check(n >= 10, f"{n} force samples before the first break in both runs (at least 10)")
    travel_h, travel_c = np.array(h["travel"]), np.array(c["travel"])
    start = h["time"][0] - (travel_h[0] and 0)
    worst, worst_at = -1.0, 0.0
    for k in range(n):
        t = c["time"][k]
        if travel_c[k] > travel_h[n - 1]:
            break
        f_h = float(np.interp(travel_c[k], travel_h[:n], np.array(h["force"][:n])))
        elapsed = t - (c["time"][0] - ridgeSmall_sample_elapsed(c))
        accel = speed / tau * math.exp(-elapsed / tau)
        bound = 0.5 * RHO_W * c["submergedVolume"][k] * accel + 0.5 * RHO_W * 2.0 * LENGTH * WIDTH * speed ** 2 \
            + 0.05 * abs(f_h)
        ratio = abs(c["force"][k] - f_h) / bound
        if ratio > worst:
            worst, worst_at = ratio, travel_c[k]
    check(0.0 <= worst <= 1.0,
          f"cfd force within the bound of the hydrostatic force before the first break (worst "
          f"{worst:.2f} of the bound at {worst_at * 1e3:.2f} mm; {n} samples to "
          f"{travel_h[n - 1] * 1e3:.1f} mm)")
    del start

    # (c) Ranks.
    c2 = iceCases.curve(cfd2)
    m = min(before_first_break(c), before_first_break(c2))
    diff = max(abs(a - b) / max(abs(a), 1e-300) for a, b in zip(c["force"][1:m], c2["force"][1:m]))
    same_times = all(abs(a - b) < 1e-12 for a, b in zip(c["time"][:m], c2["time"][:m]))
    check(m >= 10 and same_times and diff <= 1e-8,
          f"2 ranks give the 1-rank force before the first break: largest relative difference "
          f"{diff:.1e} over {m} samples (limit 1e-8)")


def ridgeSmall_sample_elapsed(c):
    """Loading time at the first sample, from its travel: travel(t) = v (t - tau (1 - e^-t/tau))."""
    ramp, speed = 0.005, 0.05
    tau = ramp / speed
    target = c["travel"][0]
    lo, hi = 0.0, 1.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if speed * (mid - tau * (1 - math.exp(-mid / tau))) < target:
            lo = mid
        else:
            hi = mid
    return lo


def bad_input(work, dem_bin, cfd_bin):
    def expect(name, cmd, case, words):
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env())
        out = r.stdout
        check(r.returncode != 0 and all(w in out for w in words),
              f"{name}: exit {r.returncode}, message names {words}: "
              + next((line for line in out.splitlines() if words[-1] in line), out[-300:]).strip())

    ridge_dem = os.path.join(dem_bin, "ridgeDEM")
    app = os.path.join(cfd_bin, "icePunchFoam")
    mpi = ["mpirun", "-np", "1", "--oversubscribe"]

    case = cfd_case(os.path.join(work, "bad"), "ridgeDEMLoadsCfd")
    expect("ridgeDEM -stage all at waterLevel cfd", mpi + [ridge_dem, "-case", case, "-stage", "all"], case,
           ["couplingProperties", "waterLevel", "icePunchFoam"])

    case = cfd_case(os.path.join(work, "bad"), "noMesh")
    iceCases.run_app(ridge_dem, case, 1, ["-stage", "assemble"], "log.ridgeDEM")
    expect("icePunchFoam without a mesh", mpi + [app, "-case", case], case,
           ["constant/polyMesh", "blockMesh"])

    mesh(case, 1)
    iceCases.set_entry(os.path.join(case, "constant", "couplingProperties"), "cfd.couplingInterval", 1000)
    expect("coupling interval longer than a force sample", mpi + [app, "-case", case], case,
           ["couplingProperties", "couplingInterval", "sampleInterval"])

    iceCases.set_entry(os.path.join(case, "constant", "couplingProperties"), "cfd.couplingInterval", 84)
    iceCases.set_entry(os.path.join(case, "system", "blockMeshDict"), "surfaceZ", 0.95)
    foam(["blockMesh", "-case", case], case, "log.blockMesh")
    expect("mesh top above the water surface", mpi + [app, "-case", case], case,
           ["blockMeshDict", "geometry.json", "surface"])


def main():
    os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")   # OpenFOAM's etc files
    step, work = sys.argv[1], sys.argv[2]
    dem_bin, cfd_bin = os.path.abspath(sys.argv[3]), os.path.abspath(sys.argv[4])
    if not os.path.exists(ridgeSmall.keel_file(work)):
        sys.exit(f"punchCfdSmall.py: the small keel {ridgeSmall.keel_file(work)} is missing (ridgeSmall.py keel)")
    if step == "punch":
        punch(work, dem_bin, cfd_bin)
    elif step == "badInput":
        bad_input(work, dem_bin, cfd_bin)
    else:
        sys.exit(f"punchCfdSmall.py: unknown step {step}")
    sys.exit(1 if ridgeSmall.failures else 0)


if __name__ == "__main__":
    main()
