#!/usr/bin/python3
"""Cost of the settlingBed scene (5,292 ice spheres rising to a floating layer)
at the three water levels, and with OpenFOAM's DPMFoam, in one run on one
machine:

  none         settlingBedDEM -hydrodynamics none          (no water: the ice falls)
  hydrostatic  settlingBedDEM -hydrodynamics hydrostatic   (buoyancy + drag, WaterForces)
  cfd          iceFoam                                     (the water solved, CFD-DEM)
  DPMFoam      Debian's DPMFoam, pairCollision, same mesh, particles, time step
               (only --short seconds: its collisions cost far more)

Each run is timed (wall clock, and the CPU time of the run's processes, which
other users of a shared machine disturb less); cfd is also run for --short
seconds, to set beside DPMFoam over the same interval.

Usage: benchmark.py [--long 2] [--short 0.05] [--ranks 1] [--publish]
Writes runs/benchmark/benchmark.json (atomically) and prints a markdown table for README.md;
the run directories are runs/benchmark/<run>/. --publish runs nothing and copies
runs/benchmark/benchmark.json into the committed studies/benchmark.json.
"""
import argparse
import csv
import json
import os
import random
import resource
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.dirname(HERE)
OUT = os.path.join(CASE, "runs", "benchmark")
sys.path.insert(0, os.path.join(CASE, "..", "..", "postProcessing"))
from iceCases import (BUILD, copy_case, copy_common, get_entry, positive_number, publish_files, run_app,  # noqa: E402
                      set_entry, whole_number, write_atomically)

ICEFOAM = os.path.join(BUILD, "coupling", "iceFoam")
DEM_APP = os.path.join(BUILD, "coupling", "settlingBedDEM")
DPMFOAM = shutil.which("DPMFoam") or "/usr/bin/DPMFoam"
os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")


def number(path, dotted):
    return float(get_entry(path, dotted).split()[-1])


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(action):
    cpu0, wall0 = children_cpu(), time.time()
    action()
    return time.time() - wall0, children_cpu() - cpu0


def prepare_iceFoam_case(name, end_time):
    case = copy_case(CASE, os.path.join(OUT, name))
    shutil.copytree(os.path.join(CASE, "0"), os.path.join(case, "0"))
    set_entry(os.path.join(case, "system", "controlDict"), "endTime", end_time)
    subprocess.run(["blockMesh", "-case", case], check=True, stdout=subprocess.DEVNULL)
    return case


def lattice_positions(props):
    """The release lattice of DEM/in.settlingBed, jittered the same way (another random sequence)."""
    d, s, w = (number(props, "demVariables." + k) for k in ("diameter", "spacing", "width"))
    lo, hi = number(props, "demVariables.releaseBottom"), number(props, "demVariables.releaseTop")
    rows = [s / 2 + s * k for k in range(int(w / s) + 1) if d / 2 <= s / 2 + s * k <= w - d / 2]
    layers = [s / 2 + s * k for k in range(int(hi / s) + 1) if lo <= s / 2 + s * k <= hi]
    rng = random.Random(86028157)
    jitter = lambda: rng.uniform(-1.5e-4, 1.5e-4)  # noqa: E731
    return [(x + jitter(), y + jitter(), z + jitter()) for z in layers for y in rows for x in rows]


def prepare_dpm_case(end_time):
    case = os.path.join(OUT, "DPMFoam")
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(os.path.join(CASE, "dpmFoam"), case)
    copy_common(case)
    shutil.copy(os.path.join(CASE, "system", "blockMeshDict"), os.path.join(case, "system"))
    shutil.copy(os.path.join(CASE, "constant", "g"), os.path.join(case, "constant"))
    points = lattice_positions(os.path.join(CASE, "constant", "couplingProperties"))
    with open(os.path.join(case, "constant", "kinematicCloudPositions"), "w") as f:
        f.write("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class vectorField;\n"
                "    location \"constant\";\n    object kinematicCloudPositions;\n}\n")
        f.write(f"{len(points)}\n(\n" + "".join(f"({x:.9g} {y:.9g} {z:.9g})\n" for x, y, z in points) + ")\n")
    set_entry(os.path.join(case, "system", "controlDict"), "endTime", end_time)
    subprocess.run(["blockMesh", "-case", case], check=True, stdout=subprocess.DEVNULL)
    return case, len(points)


def mean_height_iceFoam(case):
    last, total, n = None, 0.0, 0
    with open(os.path.join(case, "postProcessing", "particles.csv")) as f:
        for r in csv.DictReader(f):
            if r["time"] != last:
                last, total, n = r["time"], 0.0, 0
            total += float(r["z"])
            n += 1
    return total / n, n


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--long", type=positive_number, default=2.0, help="simulated s for none, hydrostatic, cfd")
    ap.add_argument("--short", type=positive_number, default=0.05, help="simulated s for DPMFoam (and cfd beside it)")
    ap.add_argument("--ranks", type=whole_number(1), default=1)
    ap.add_argument("--publish", action="store_true", help="run nothing; copy runs/benchmark/benchmark.json into studies/")
    a = ap.parse_args()
    if a.publish:
        publish_files([os.path.join(OUT, "benchmark.json")], HERE)
        return 0
    for exe in (ICEFOAM, DEM_APP):
        if not os.access(exe, os.X_OK):
            sys.exit(f"{exe} not built: run bin/build")
    props = os.path.join(CASE, "constant", "couplingProperties")
    result = {"ranks": a.ranks, "load_average_start": os.getloadavg()[0], "runs": {}}

    def record(name, simulated, wall, cpu, **extra):
        result["runs"][name] = {"simulated_s": simulated, "wall_s": wall, "cpu_s": cpu,
                                "wall_s_per_simulated_s": wall / simulated,
                                "cpu_s_per_simulated_s": cpu / simulated, **extra}
        print(f"{name:>14}: {simulated:g} s simulated in {wall:.1f} s wall, {cpu:.1f} s CPU "
              f"({wall / simulated:.1f} s wall per simulated s)", flush=True)

    for level in ("none", "hydrostatic"):
        case = prepare_iceFoam_case(level, a.long)
        wall, cpu = timed(lambda: run_app(DEM_APP, case, a.ranks, ["-hydrodynamics", level], "log.settlingBedDEM"))
        s = json.load(open(os.path.join(case, "postProcessing", f"settlingBedDEM_{level}.json")))
        record(level, a.long, wall, cpu, particles=s["particles"], mean_height_m=s["mean_height_m"])

    for name, end in (("cfd", a.long), ("cfd_short", a.short)):
        case = prepare_iceFoam_case(name, end)
        wall, cpu = timed(lambda: run_app(ICEFOAM, case, a.ranks, [], "log.iceFoam"))
        height, n = mean_height_iceFoam(case)
        record(name, end, wall, cpu, particles=n, mean_height_m=height)

    case, n = prepare_dpm_case(a.short)
    wall, cpu = timed(lambda: run_app(DPMFOAM, case, a.ranks, [], "log.DPMFoam"))
    record("DPMFoam_short", a.short, wall, cpu, particles=n)

    runs = result["runs"]
    per = lambda k, q="wall": runs[k][f"{q}_s_per_simulated_s"]  # noqa: E731
    result["cfd_over_hydrostatic_wall"] = per("cfd") / per("hydrostatic")
    result["cfd_over_hydrostatic_cpu"] = per("cfd", "cpu") / per("hydrostatic", "cpu")
    result["hydrostatic_over_none_wall"] = per("hydrostatic") / per("none")
    result["DPMFoam_over_cfd_same_interval_wall"] = per("DPMFoam_short") / per("cfd_short")
    result["DPMFoam_over_cfd_same_interval_cpu"] = per("DPMFoam_short", "cpu") / per("cfd_short", "cpu")
    result["load_average_end"] = os.getloadavg()[0]
    os.makedirs(OUT, exist_ok=True)
    write_atomically(os.path.join(OUT, "benchmark.json"), json.dumps(result, indent=2) + "\n")

    print("\n| run | simulated (s) | wall (s) | CPU (s) | wall s per simulated s | CPU s per simulated s |")
    print("|---|---|---|---|---|---|")
    for k, r in runs.items():
        print(f"| {k} | {r['simulated_s']:g} | {r['wall_s']:.1f} | {r['cpu_s']:.1f} | "
              f"{r['wall_s_per_simulated_s']:.1f} | {r['cpu_s_per_simulated_s']:.1f} |")
    print(f"\ncfd / hydrostatic per simulated second: {result['cfd_over_hydrostatic_wall']:.2f} (wall), "
          f"{result['cfd_over_hydrostatic_cpu']:.2f} (CPU); DPMFoam / cfd over the first {a.short:g} s: "
          f"{result['DPMFoam_over_cfd_same_interval_wall']:.1f} (wall), "
          f"{result['DPMFoam_over_cfd_same_interval_cpu']:.1f} (CPU); load average "
          f"{result['load_average_start']:.1f} -> {result['load_average_end']:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
