#!/usr/bin/python3
"""A ridge run at the cfd level (icePunchFoam), in two steps around its assembly:

  overlay  the hydrostatic run folder with a case's cfd/ set-up over it: OpenFOAM's 0/, system/
           and constant/ files; the loading control (system/controlDict) moves to
           system/loadingDict, where icePunchFoam reads it.
  mesh     the fluid mesh from the box floor to the still surface where the assembled ridge
           floats (postProcessing/geometry.json: waterLevel, length, width into
           system/blockMeshDict), blockMesh, and decomposePar for more than one rank.

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


def mesh(run, ranks=1, cells=None):
    """cells: (x, y, z) counts instead of the blockMeshDict's."""
    geometry = json.load(open(os.path.join(run, "postProcessing", "geometry.json")))
    block = os.path.join(run, "system", "blockMeshDict")
    for entry, key in (("surfaceZ", "waterLevel"), ("boxLength", "length"), ("boxWidth", "width")):
        iceCases.set_entry(block, entry, repr(geometry[key]))
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
