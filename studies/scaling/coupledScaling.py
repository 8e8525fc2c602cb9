#!/usr/bin/python3
"""How the coupled settling's cost and memory grow with the particle count (issue 17, goal 5):
cases/settlingBed (ice spheres rising to a floating layer in water that iceFoam solves) widened so
that its release lattice holds about 1e4 and 1e5 spheres (the box, the lattice and the mesh grow
in x and y alike: the same 12 mm cells, the same 4 mm spheres, 12 layers), a short window of the
rise on 2 ranks (the fluid mesh decomposed as the case's decomposeParDict says). Per size: the
coupled run's wall time per particle-step (iceFoam's own "Coupled run" clock, from before the DEM
starts: the set-up of a lattice is small beside the window), and the peak resident memory of the
largest rank per particle of that rank; with a build of the coupling that reports it, the
exchange's own time (particles to the fluid ranks, locating, sums over the ranks, forces back) and
how many particles each rank held. The mesh is split across x, the way the layer is wide.
--baseline-build runs every size with another build's iceFoam too, in the same command, so that
the two can be compared on the same machine load.

usage: coupledScaling.py [--sizes 10000,100000] [--end-time 0.1] [--ranks 2] [--build DIR]
                         [--baseline-build DIR] [--out DIR] [--publish]
  writes OUT/coupledScaling.{json,md} (default runs/); --publish copies them into results/ and the
  table into this folder's README.md."""
import argparse
import csv
import json
import math
import os
import re
import shutil
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
sys.path.insert(0, os.path.join(TOP, "cases", "levelIceBeam", "studies"))
os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")   # OpenFOAM's, before benchmark copies the environment
import cfdRun  # noqa: E402
import iceCases  # noqa: E402
import benchmark  # noqa: E402  (the beam benchmark's timed run: wall and peak RSS)

CASE = os.path.join(TOP, "cases", "settlingBed")
CELL_MM = 12.0          # the case's cells (8 across its 96 mm box)
LAYERS = 12             # of the release lattice


def widened(n, target):
    """The settling bed with a release lattice of about `target` spheres, in folder n."""
    case = iceCases.copy_case(CASE, n)
    shutil.copytree(os.path.join(CASE, "0"), os.path.join(case, "0"))
    props = os.path.join(case, "constant", "couplingProperties")
    spacing = float(iceCases.get_entry(props, "demVariables.spacing"))
    diameter = float(iceCases.get_entry(props, "demVariables.diameter"))
    across = math.ceil(math.sqrt(target / LAYERS))           # lattice sites along x and y
    cells = math.ceil((across * spacing + diameter) * 1e3 / CELL_MM)
    width_mm = cells * CELL_MM
    iceCases.set_entry(props, "demVariables.width", width_mm * 1e-3)
    block = os.path.join(case, "system", "blockMeshDict")
    iceCases.set_entry(block, "vertices", f"( (0 0 0) ({width_mm:g} 0 0) ({width_mm:g} {width_mm:g} 0) (0 {width_mm:g} 0) "
                                          f"(0 0 96) ({width_mm:g} 0 96) ({width_mm:g} {width_mm:g} 96) (0 {width_mm:g} 96) )")
    iceCases.set_entry(block, "blocks", f"( hex (0 1 2 3 4 5 6 7) ({cells} {cells} 8) simpleGrading (1 1 1) )")
    return case


def released(case):
    """The spheres at the first time of postProcessing/particles.csv (iceFoam's trajectories)."""
    with open(os.path.join(case, "postProcessing", "particles.csv")) as f:
        rows = csv.DictReader(f)
        first = next(rows)["time"]
        return 1 + sum(1 for r in rows if r["time"] == first)


def run_size(ice_foam, target, args, label):
    """One widened settling bed run with this iceFoam; its row."""
    case = widened(os.path.join(args.out, f"settlingBed{target}_{label}"), target)
    iceCases.set_entry(os.path.join(case, "system", "controlDict"), "endTime", args.end_time)
    iceCases.set_entry(os.path.join(case, "system", "controlDict"), "writeInterval", args.end_time)
    cfdRun.foam("blockMesh", case)
    command = ["mpirun", "-np", str(args.ranks), "--oversubscribe", ice_foam, "-case", case]
    if args.ranks > 1:
        decompose = os.path.join(case, "system", "decomposeParDict")
        iceCases.set_entry(decompose, "numberOfSubdomains", args.ranks)
        iceCases.set_entry(decompose, "coeffs.n", f"({args.ranks} 1 1)")
        cfdRun.foam("decomposePar", case, "-force")
        command.append("-parallel")
    print(f"about {target} particles on {args.ranks} ranks, {label} build ...", flush=True)
    _, rss = benchmark.timed(command, case, "log.iceFoam")
    log = open(os.path.join(case, "log.iceFoam")).read()
    particles = released(case)
    wall = float(re.search(r"Coupled run: ([\d.e+-]+) s wall clock", log).group(1))
    dem_step = float(iceCases.get_entry(os.path.join(case, "constant", "couplingProperties"), "demVariables.demTimeStep"))
    particle_steps = particles * round(args.end_time / dem_step)
    cells = int(re.search(r"nCells: (\d+)", open(os.path.join(case, "log.blockMesh")).read()).group(1))
    row = {"particles": particles, "cells": cells, "ranks": args.ranks, "build": label, "simulated_s": args.end_time,
           "wall_s": round(wall, 1), "particle_steps_per_s": round(particle_steps / wall, -3),
           "ns_per_particle_step_per_rank": round(1e9 * args.ranks * wall / particle_steps, 1),
           "peak_rss_MiB_per_rank": round(rss, 1),
           "KiB_per_particle": round(1024 * rss * args.ranks / particles, 2)}
    exchange = re.search(r"Coupling exchange: ([\d.e+-]+) to ([\d.e+-]+) s of the wall clock.*"
                         r"at the end: (\d+) to (\d+) of (\d+)", log)
    if exchange:
        row.update({"exchange_s": [round(float(exchange.group(k)), 2) for k in (1, 2)],
                    "held_per_rank": [int(exchange.group(3)), int(exchange.group(4))]})
    print(json.dumps(row), flush=True)
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=iceCases.comma_list(iceCases.whole_number(100)), default="10000,100000")
    parser.add_argument("--end-time", type=iceCases.positive_number, default=0.1)
    parser.add_argument("--ranks", type=iceCases.whole_number(1), default=2)
    parser.add_argument("--build", default=iceCases.BUILD, help="the build whose iceFoam is measured")
    parser.add_argument("--baseline-build", help="another build to run every size with, for comparison")
    parser.add_argument("--out", default=os.path.join(HERE, "runs"))
    parser.add_argument("--publish", action="store_true")
    args = parser.parse_args()
    if args.publish:
        iceCases.publish_study(HERE, args.out, "coupledScaling", ("json", "md"), "coupled scaling table", "json")
        return
    builds = [("this", os.path.abspath(args.build))]
    if args.baseline_build:
        builds.insert(0, ("baseline", os.path.abspath(args.baseline_build)))
    rows = []
    for target in args.sizes:
        for label, build in builds:
            rows.append(run_size(os.path.join(build, "coupling", "iceFoam"), target, args, label))
    report = {"rows": rows, "load_average_at_end": os.getloadavg()[0], "date": time.strftime("%Y-%m-%d %H:%M"),
              "revision": iceCases.git_revision()}
    lines = ["| particles | fluid cells | build | particle-steps/s | ns per particle-step on a rank | exchange per rank [s] "
             "| particles held per rank | peak RSS per rank [MiB] | KiB per particle |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        held = "{:,} to {:,}".format(*r["held_per_rank"]) if "held_per_rank" in r else "all"
        exchange = "{:.1f} to {:.1f}".format(*r["exchange_s"]) if "exchange_s" in r else "-"
        lines.append(f"| {r['particles']:,} | {r['cells']:,} | {r['build']} | {r['particle_steps_per_s']:.3g} "
                     f"| {r['ns_per_particle_step_per_rank']:.0f} | {exchange} | {held} | {r['peak_rss_MiB_per_rank']:.0f} "
                     f"| {r['KiB_per_particle']:.1f} |")
    report["builds"] = {label: os.path.relpath(build, TOP) for label, build in builds}
    md = "\n".join(lines) + (f"\n\n{args.end_time:g} s of the rise on {args.ranks} ranks (iceFoam, coupling every 100 DEM "
                             f"steps, the mesh split across x), {report['date']}, load average {report['load_average_at_end']:.1f} at the end.\n")
    iceCases.write_study_outputs(args.out, "coupledScaling", {"json": json.dumps(report, indent=2) + "\n", "md": md})
    print(md, end="")


if __name__ == "__main__":
    main()
