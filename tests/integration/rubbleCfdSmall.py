#!/usr/bin/python3
"""Rubble settling at the cfd water level (iceRubbleFoam; cases/rubbleBeam, ./Allrun -water cfd)
on a reduced box (1.0 x 0.6 m, 0.2 m of rubble, about 600 particles, 5 x 3 x 5 fluid cells).

usage: rubbleCfdSmall.py STEP WORK DEM_BIN_DIR CFD_BIN_DIR
  settle    (a) the settled ice floats as Archimedes says: its share above the still surface is
                1 - rho_s/rho_w within 0.5 points, and the water's vertical force on it, averaged
                over the last second, is its weight within 2 % (the resolved pressure jitters by
                some 4 % from one sample to the next: fluid-fraction jumps, coupling/README.md);
            (b) rubbleDEM compacts the rubble settled at cfd (-stage compact) to its target, as it
                does one settled in still water: the saved stage is the hydrostatic one's format;
            (c) a rubble settled at cfd is not compacted after the water's inputs changed
                (cfd.couplingInterval): refused naming settled.h5 and the entry
  ranks     the first 0.2 s of the same settling on 1 and 2 ranks (the fluid mesh decomposed), the
            lowest blocks in the water: every sphere within 1e-7 m and 1e-5 m/s (measured
            1.5e-9 m, 7.5e-8 m/s; 1.2e-12 m after 0.1 s: round-off that the blocks' landing then
            amplifies, to 8e-7 m by 0.3 s); the same settling in still water (rubbleDEM) is
            bit-identical
  badInput  rubbleDEM settling at waterLevel cfd, iceRubbleFoam at waterLevel hydrostatic, without
            a fluid mesh, and with a mesh whose top is not the water surface: a message naming the
            file or entry and the application to use, non-zero exit"""
import json
import os
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
sys.path.insert(0, os.path.join(TOP, "tests", "cases"))
sys.path.insert(0, os.path.join(TOP, "cases", "rubbleBeam", "studies"))
import iceCases  # noqa: E402
import settlingLevels  # noqa: E402
from checks import check, finish  # noqa: E402

CASE = os.path.join(TOP, "cases", "rubbleBeam")
CELLS = (("cellsX", 5), ("cellsY", 3))     # cells of 0.2 x 0.2 x 0.18 m, larger than the spheres
RHO_W = 1000.0
WINDOW = 0.2        # s of settling compared on 1 and 2 ranks


def small_cfd_case(path, max_time, entries):
    iceCases.small_rubble_case(CASE, path, 1.0, 0.6, 0.2, max_time, 30, entries)
    settlingLevels.overlay_cfd(path)
    for entry, count in CELLS:
        iceCases.set_entry(os.path.join(path, "system", "blockMeshDict"), entry, count)
    return path


def env():
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                OMPI_MCA_orte_execute_quiet="1",
                WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))


def refused(command, case, log, *needles):
    """Runs a command that must fail; checks the exit status and that its output names each needle."""
    out = subprocess.run(command, cwd=case, env=env(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    text = out.stdout
    missing = [n for n in needles if n not in text]
    check(out.returncode != 0 and not missing,
          f"{log}: exit {out.returncode}, names {list(needles)}" + (f" (missing {missing}: {text[-600:]})" if missing else ""))


def settle(work, dem_bin, cfd_bin):
    run = small_cfd_case(os.path.join(work, "settle"), 5.0,
                         {"settling.minTime": 3.0, "settling.kineticEnergyThreshold": 1e-7,
                          "compaction.targetPorosity": 0.45, "compaction.speed": 0.1, "compaction.holdTime": 0.2})
    settlingLevels.settle_cfd(run, "cuboid", app=os.path.join(cfd_bin, "iceRubbleFoam"))
    s = json.load(open(os.path.join(run, "postProcessing", "settling.json")))
    with h5py.File(os.path.join(run, "DEM", "settled.h5"), "r") as f:
        density = f["particles"]["density"][()]
    archimedes = 1.0 - float(np.mean(density)) / RHO_W
    above = s["ice_volume_above_water_fraction"]
    check(s["water"] == "cfd", f"settled at the cfd level ({s['water']})")
    check(abs(above - archimedes) < 0.005,
          f"ice above water {100 * above:.2f} % against Archimedes' {100 * archimedes:.2f} % (within 0.5 points)")
    ratio = s["fluidForceZ_N"] / s["weight_N"]
    check(abs(ratio - 1) < 0.02, f"the water's vertical force over the last second {s['fluidForceZ_N']:.1f} N "
          f"(sample std {s['fluidForceZ_std_N']:.1f} N) against the weight {s['weight_N']:.1f} N: {ratio:.4f} (within 2 %)")
    check(abs(s["dragZ_N"]) < 0.01 * s["weight_N"], f"drag on the ice at rest {s['dragZ_N']:.2f} N (under 1 % of the weight)")

    # (b) the hydrostatic stages take it
    iceCases.run_app(os.path.join(dem_bin, "rubbleDEM"), run, 1, ["-stage", "compact", "-shape", "cuboid"], "log.compact")
    with h5py.File(os.path.join(run, "DEM", "compacted.h5"), "r") as f:
        compacted = len(f["particles"]["x"][()])
    log = open(os.path.join(run, "log.compact")).read()
    check(compacted == s["particles"] and "0.45" in log,
          f"rubbleDEM -stage compact took the rubble settled at cfd: {compacted} particles compacted to 0.45")

    # (c) stale: the water's inputs changed
    coupling = os.path.join(run, "constant", "couplingProperties")
    iceCases.set_entry(coupling, "cfd.couplingInterval", 20)
    refused(["mpirun", "-np", "1", os.path.join(dem_bin, "rubbleDEM"), "-case", run, "-stage", "compact"], run,
            "compact after cfd.couplingInterval changed", "settled.h5", "couplingInterval")


def positions(run):
    with h5py.File(os.path.join(run, "DEM", "settled.h5"), "r") as f:
        return np.array([f["particles"][k][()] for k in ("x", "y", "z", "vx", "vy", "vz")])


def ranks(work, dem_bin, cfd_bin):
    cfd, still = {}, {}
    for n in (1, 2):
        run = small_cfd_case(os.path.join(work, f"ranks{n}"), WINDOW, {"settling.minTime": 0.1})
        settlingLevels.settle_cfd(run, "cuboid", n, app=os.path.join(cfd_bin, "iceRubbleFoam"))
        cfd[n] = positions(run)
        plain = iceCases.small_rubble_case(CASE, os.path.join(work, f"stillRanks{n}"), 1.0, 0.6, 0.2, WINDOW, 30,
                                           {"settling.minTime": 0.1})
        iceCases.run_app(os.path.join(dem_bin, "rubbleDEM"), plain, n, ["-stage", "settle"], "log.settle")
        still[n] = positions(plain)
    d = np.abs(cfd[1] - cfd[2])
    check(d[:3].max() < 1e-7 and d[3:].max() < 1e-5,
          f"cfd, 1 against 2 ranks after {WINDOW} s: positions within {d[:3].max():.2e} m, velocities {d[3:].max():.2e} m/s")
    check(np.array_equal(still[1], still[2]), f"still water, 1 against 2 ranks after {WINDOW} s: bit-identical")


def bad_input(work, dem_bin, cfd_bin):
    rubble_foam = os.path.join(cfd_bin, "iceRubbleFoam")
    run = small_cfd_case(os.path.join(work, "bad"), 0.1, {"settling.minTime": 0.05})
    refused(["mpirun", "-np", "1", os.path.join(dem_bin, "rubbleDEM"), "-case", run, "-stage", "settle"], run,
            "rubbleDEM settling at cfd", "couplingProperties", "waterLevel", "iceRubbleFoam")
    refused([rubble_foam, "-case", run], run, "iceRubbleFoam without a mesh", "blockMesh", "points")
    block = os.path.join(run, "system", "blockMeshDict")
    iceCases.set_entry(block, "surfaceZ", 0.8)
    settlingLevels.cfdRun.foam("blockMesh", run)
    refused([rubble_foam, "-case", run], run, "iceRubbleFoam with a mesh below the surface", "0.8", "surfaceLevel")
    iceCases.set_entry(block, "surfaceZ", 0.9)
    settlingLevels.cfdRun.foam("blockMesh", run)
    iceCases.set_entry(os.path.join(run, "constant", "couplingProperties"), "waterLevel", "hydrostatic")
    refused([rubble_foam, "-case", run], run, "iceRubbleFoam at waterLevel hydrostatic", "waterLevel", "rubbleDEM")


def main():
    step, work, dem_bin, cfd_bin = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    {"settle": settle, "ranks": ranks, "badInput": bad_input}[step](work, dem_bin, cfd_bin)
    finish()


if __name__ == "__main__":
    main()
