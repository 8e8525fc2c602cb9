#!/usr/bin/python3
"""A ridge run at the cfd level (icePunchFoam) or the vof level (icePunchInterFoam), in two
steps around its assembly:

  overlay  the hydrostatic run folder with a case's cfd/ (or vof/) set-up over it: OpenFOAM's 0/,
           system/ and constant/ files; the loading control (system/controlDict) moves to
           system/loadingDict, where icePunchFoam and icePunchInterFoam read it.
  mesh     the fluid mesh from the box floor to the still surface where the assembled ridge
           floats (postProcessing/geometry.json: waterLevel, length, width into
           system/blockMeshDict; for a box without end walls, ends that reach past every sphere
           of DEM/ridge.h5; a vof mesh, with airHeight, goes on to top = surface + airHeight, its fine
           band from zFine = surface - fineDepth),
           blockMesh, and decomposePar for more than one rank.

Used by ../cases/rubblePunch/Allrun, ../cases/ridgeFlexure/studies/waterLevels.py and the cfd
punch tests.

usage: cfdRun.py overlay RUN CFD_DIR
       cfdRun.py mesh RUN [--ranks N]"""
import argparse
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import iceCases  # noqa: E402


def foam(utility, run, *args):
    """An OpenFOAM utility on the run, its output in run/log.<utility>; raises naming the log."""
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    log = os.path.join(run, "log." + utility)
    with open(log, "w") as out:
        if subprocess.run([utility, "-case", run, *args], stdout=out, stderr=subprocess.STDOUT, env=env).returncode:
            raise RuntimeError(f"{utility} failed on {run}: see {log}")


def overlay(run, cfd):
    os.replace(os.path.join(run, "system", "controlDict"), os.path.join(run, "system", "loadingDict"))
    for sub in ("0", "constant", "system"):
        shutil.copytree(os.path.join(cfd, sub), os.path.join(run, sub), dirs_exist_ok=True)


def particle_reach(run):
    """The lowest and highest x that the assembled ridge's spheres reach (DEM/ridge.h5)."""
    import h5py
    with h5py.File(os.path.join(run, "DEM", "ridge.h5"), "r") as f:
        x, r = (f["particles"][k][()] for k in ("x", "radius"))
    return float((x - r).min()), float((x + r).max())


def has_entry(path, dotted):
    try:
        iceCases.get_entry(path, dotted)
        return True
    except KeyError:
        return False


def mesh(run, ranks=1, cells=None):
    """cells: (x, y, z) counts instead of the blockMeshDict's. A blockMeshDict with xMin/xMax
    (a box without end walls) gets the box's ends, or the reach of the spheres beyond them;
    one with boxLength, the box's length."""
    geometry = json.load(open(os.path.join(run, "postProcessing", "geometry.json")))
    block = os.path.join(run, "system", "blockMeshDict")
    for entry, key in (("surfaceZ", "waterLevel"), ("boxWidth", "width")):
        iceCases.set_entry(block, entry, repr(geometry[key]))
    if has_entry(block, "airHeight"):
        level = geometry["waterLevel"]
        iceCases.set_entry(block, "top", repr(level + float(iceCases.get_entry(block, "airHeight"))))
        iceCases.set_entry(block, "zFine", repr(level - float(iceCases.get_entry(block, "fineDepth"))))
    if has_entry(block, "xMin"):
        low, high = particle_reach(run)
        iceCases.set_entry(block, "xMin", repr(min(geometry["x0"], low)))
        iceCases.set_entry(block, "xMax", repr(max(geometry["x0"] + geometry["length"], high)))
    else:
        iceCases.set_entry(block, "boxLength", repr(geometry["length"]))
    for entry, count in zip(("cellsX", "cellsY", "cellsZ"), cells or ()):
        iceCases.set_entry(block, entry, count)
    foam("blockMesh", run)
    if ranks > 1:
        decompose = os.path.join(run, "system", "decomposeParDict")
        iceCases.set_entry(decompose, "numberOfSubdomains", ranks)
        iceCases.set_entry(decompose, "coeffs.n", f"({ranks} 1 1)")
        foam("decomposePar", run, "-force")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("action", choices=("overlay", "mesh"))
    parser.add_argument("run")
    parser.add_argument("cfd", nargs="?", help="overlay: the case's cfd/ folder")
    parser.add_argument("--ranks", type=iceCases.whole_number(1), default=1)
    args = parser.parse_args()
    if (args.action == "overlay") != (args.cfd is not None):
        parser.error("overlay takes RUN and CFD_DIR; mesh takes RUN")
    try:
        if args.action == "overlay":
            overlay(args.run, args.cfd)
        else:
            mesh(args.run, args.ranks)
    except (RuntimeError, OSError, KeyError) as error:
        sys.exit(f"cfdRun.py: {error}")


if __name__ == "__main__":
    main()
