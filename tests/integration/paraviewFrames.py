#!/usr/bin/python3
"""ParaView opens every series of a small beam run, in both vtkFormats.

Runs the 400-particle beam twice, vtkFormat binary and ascii (1 rank, 0.2 m/s: the same run,
bit for bit), has ParaView's pvpython read every .pvd series of each (paraviewReadSeries.py)
and checks what it read: the series' times are the .pvd's, the particles' point arrays and the
bonds' cell arrays are all there with a tuple a particle or bond, every number is finite, the
broken bonds are short lines where they broke, and the binary run reads back the same numbers
as the ascii one (to the ascii's 10 significant digits). pvpython needs no display for reading.

usage: paraviewFrames.py CASE WORK APP PVPYTHON"""
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "postProcessing"))
import iceCases  # noqa: E402
import vtpFile  # noqa: E402

PARTICLE_ARRAYS = {"radius": 1, "velocity": 3, "force": 3, "tag": 1, "bondCount": 1, "fixed": 1}
BOND_ARRAYS = {"family": 1, "state": 1, "mode": 1, "breakTime": 1}

failures = []


def check(condition, what):
    print(("ok    " if condition else "FAIL  ") + what)
    if not condition:
        failures.append(what)


def run(case, work, app, vtk_format):
    run_dir = os.path.join(work, vtk_format)
    iceCases.copy_case(case, run_dir)
    iceCases.set_entry(os.path.join(run_dir, "system", "controlDict"), "vtkFormat", vtk_format)
    iceCases.run_app(app, run_dir, 1, ["-particles", 400, "-platenSpeed", 0.2], "log.iceBeamDEM")
    return run_dir


def read_with_paraview(pvpython, run_dir):
    out = os.path.join(run_dir, "paraview")
    result = subprocess.run([pvpython, os.path.join(HERE, "paraviewReadSeries.py"), run_dir, out],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            env=dict(os.environ, DISPLAY=""))
    messages = [l for l in result.stdout.splitlines() if "ERROR" in l or "Warning" in l]
    check(result.returncode == 0 and not messages,
          f"{run_dir}: pvpython read the series without errors or warnings (exit {result.returncode}"
          + (", " + "; ".join(messages[:3]) if messages else "") + ")")
    if result.returncode != 0:
        print(result.stdout[-3000:])
        return {}
    report = json.load(open(os.path.join(out, "report.json")))
    return {name: dict(np.load(os.path.join(out, name + ".npz"))) for name in report["series"]}


def frames(series):
    return range(len(series["times"]))


def check_run(run_dir, read):
    label = os.path.basename(run_dir)
    summary = iceCases.summary(run_dir)
    check(sorted(read) == ["bonds", "particles"], f"{label}: ParaView found the series {sorted(read)}")
    for name, series in read.items():
        pvd_times = [t for t, _ in vtpFile.read_pvd(os.path.join(run_dir, "VTK", name + ".pvd"))]
        check(len(pvd_times) >= 3 and np.allclose(series["times"], pvd_times, rtol=1e-12, atol=0),
              f"{label}/{name}: {len(series['times'])} times in ParaView, {len(pvd_times)} in the .pvd")

    particles, bonds = read["particles"], read["bonds"]
    n, nBonds = summary["particles"], summary["bonds"]
    for k in frames(particles):
        arrays = {a.split("/")[2]: v for a, v in particles.items() if a.startswith(f"{k}/point/")}
        good = (str(particles[f"{k}/class"]) == "vtkPolyData" and int(particles[f"{k}/verts"]) == n
                and particles[f"{k}/points"].shape == (n, 3) and np.all(np.isfinite(particles[f"{k}/points"]))
                and set(arrays) == set(PARTICLE_ARRAYS)
                and all(v.shape == ((n,) if PARTICLE_ARRAYS[a] == 1 else (n, 3)) for a, v in arrays.items())
                and all(np.all(np.isfinite(v)) for v in arrays.values()))
        if not good or k == len(particles["times"]) - 1:
            check(good, f"{label}/particles time {k}: {n} points and vertices, arrays "
                        f"{sorted((a, v.shape) for a, v in arrays.items())}, all finite")
    broken_lengths = []
    for k in frames(bonds):
        arrays = {a.split("/")[2]: v for a, v in bonds.items() if a.startswith(f"{k}/cell/")}
        lines = int(bonds[f"{k}/lines"])
        good = (lines == nBonds and set(arrays) == set(BOND_ARRAYS)
                and all(v.shape == (lines,) for v in arrays.values())
                and all(np.all(np.isfinite(v)) for v in arrays.values())
                and np.all(np.isfinite(bonds[f"{k}/points"])))
        if not good or k == len(bonds["times"]) - 1:
            check(good, f"{label}/bonds time {k}: {lines} lines of {nBonds} bonds, arrays "
                        f"{sorted((a, v.shape) for a, v in arrays.items())}, all finite")
        ends = line_ends(bonds, k)
        broken = arrays["state"] == 1
        broken_lengths += np.linalg.norm(ends[broken, 1] - ends[broken, 0], axis=1).tolist()
    last = len(bonds["times"]) - 1
    check_numpy_reader(run_dir, read, label)
    broken_at_end = int(np.sum(bonds[f"{last}/cell/state"] == 1))
    diameter = 2 * float(np.max(particles["0/point/radius"]))
    check(broken_at_end > 0 and max(broken_lengths) < 1.5 * diameter,
          f"{label}: {broken_at_end} broken bonds at the last frame, drawn where they broke: the longest "
          f"{max(broken_lengths or [0]):.4f} m < 1.5 particle diameters ({1.5 * diameter:.4f} m)")


def check_numpy_reader(run_dir, read, label):
    """postProcessing/vtpFile.py reads the last frame of each series as ParaView does."""
    for name, series in read.items():
        k = len(series["times"]) - 1
        piece = vtpFile.read_vtp(vtpFile.read_pvd(os.path.join(run_dir, "VTK", name + ".pvd"))[k][1])
        ours = {"points": piece.points, **{"point/" + a: v for a, v in piece.point_data.items()},
                **{"cell/" + a: v for a, v in piece.cell_data.items()}}
        theirs = {key.split("/", 1)[1]: v for key, v in series.items()
                  if key.startswith(f"{k}/") and key.split("/", 1)[1].split("/")[0] in ("points", "point", "cell")}
        same = set(ours) == set(theirs) and all(
            np.allclose(ours[a], theirs[a], rtol=1e-15, atol=0) for a in ours)
        check(same, f"{label}/{name}: vtpFile.py reads the last frame as ParaView does ({sorted(ours)})")


def line_ends(bonds, k):
    """lines x 2 x 3: each line's two points (ascii writes them in order, binary shares them)."""
    points = bonds[f"{k}/points"]
    connectivity = bonds.get(f"{k}/lineConnectivity", np.arange(len(points)))
    return points[connectivity].reshape(-1, 2, 3)


def check_same_numbers(binary, ascii_):
    for name in ("particles", "bonds"):
        b, a = binary[name], ascii_[name]
        # The bonds' points differ (binary shares them between lines): their lines' ends are compared.
        own_layout = ("/points", "/lineConnectivity") if name == "bonds" else ()
        shared = set(a) - {"times"} - {k for k in a if own_layout and k.endswith(own_layout)}
        check(set(b) >= shared and np.array_equal(b["times"], a["times"]),
              f"{name}: the same times and arrays in both formats")
        worst, differ = 0.0, []
        for key in sorted(shared & set(b)):
            values = a[key]
            if values.dtype.kind == "f":
                scale = float(np.max(np.abs(values))) if values.size else 1.0
                worst = max(worst, float(np.max(np.abs(b[key] - values), initial=0)) / max(scale, 1e-300))
            elif not np.array_equal(b[key], values):
                differ.append(key)
        for k in frames(a):
            ascii_ends, binary_ends = line_ends(a, k), line_ends(b, k)
            scale = float(np.max(np.abs(ascii_ends))) if ascii_ends.size else 1.0
            worst = max(worst, float(np.max(np.abs(binary_ends - ascii_ends), initial=0)) / scale)
        check(not differ, f"{name}: counts and whole-number arrays equal in both formats {differ[:5]}")
        check(worst < 1e-9, f"{name}: binary and ascii read back the same numbers "
                            f"(largest difference {worst:.1e} of the array's largest value)")


def main():
    case, work, app, pvpython = sys.argv[1:]
    runs = {f: run(case, work, app, f) for f in ("binary", "ascii")}
    read = {}
    for f, run_dir in runs.items():
        read[f] = read_with_paraview(pvpython, run_dir)
        if read[f]:
            check_run(run_dir, read[f])
    if read["binary"] and read["ascii"]:
        check_same_numbers(read["binary"], read["ascii"])
    sizes = {f: sum(os.path.getsize(os.path.join(d, "VTK", x)) for x in os.listdir(os.path.join(d, "VTK")))
             for f, d in runs.items()}
    print(f"VTK bytes: ascii {sizes['ascii']}, binary {sizes['binary']} "
          f"({sizes['binary'] / sizes['ascii']:.3f} of ascii)")
    if failures:
        sys.exit(f"paraviewFrames.py: {len(failures)} check(s) failed")


main()
