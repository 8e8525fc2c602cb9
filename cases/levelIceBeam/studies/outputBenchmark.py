#!/usr/bin/python3
"""What the ParaView frames cost: the same beam run three times in one command, with
vtkFormat ascii, with vtkFormat binary, and with the frames off (writeInterval beyond the
largest travel: only the frames at the start and at the end), all else equal (same packing, same ranks;
the physics is bit for bit the same, which the peak force checks).

    ./outputBenchmark.py [-particles 13000] [-ranks 2] [-out DIR] [-publish | -report]

Reports, for each: bytes and files under VTK/ (frames and their .pvd), the frames written,
the run's wall time, and the frames' share of it two ways: measured inside the run (the
summary's frames_wall_s: gathering the particles and bonds, writing the .vtp and .pvd files
and the breakage and curve files rewritten with each frame, over wall_s), and as the
difference from the run without frames (noisier on a shared machine: the three runs do not
see the same load). Writes outputBenchmark.json (for programs) and outputBenchmark.md (for
the README) into -out (default ../runs/outputBenchmark); -publish runs nothing and copies
those two into the committed studies/outputBenchmark/; -report runs nothing and writes the
.md again from the .json."""
import argparse
import json
import os
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "postProcessing"))
import iceCases  # noqa: E402

VARIANTS = (  # name, vtkFormat, writeInterval (None: the case's)
    ("ascii", "ascii", None),
    ("binary", "binary", None),
    ("off", "binary", 1e3),
)
OUTPUTS = ("outputBenchmark.json", "outputBenchmark.md")


def folder_bytes(folder):
    files = [os.path.join(folder, f) for f in os.listdir(folder)] if os.path.isdir(folder) else []
    return sum(os.path.getsize(f) for f in files), len(files)


def run_variant(out, name, vtk_format, write_interval, particles, ranks):
    case = iceCases.copy_case(os.path.join(here, ".."), os.path.join(out, name))
    control = os.path.join(case, "system", "controlDict")
    iceCases.set_entry(control, "vtkFormat", vtk_format)
    if write_interval is not None:
        iceCases.set_entry(control, "writeInterval", write_interval)
    load = os.getloadavg()[0]
    wall = iceCases.run_app("iceBeamDEM", case, ranks, ["-particles", particles], "log.iceBeamDEM")
    s = iceCases.summary(case)
    vtk_bytes, vtk_files = folder_bytes(os.path.join(case, "VTK"))
    return {
        "variant": name, "vtkFormat": vtk_format, "particles": s["particles"], "bonds": s["bonds"],
        "ranks": s["ranks"], "steps": s["steps"], "frames": s["frames"], "vtk_bytes": vtk_bytes,
        "vtk_files": vtk_files, "wall_s": s["wall_s"], "process_wall_s": wall,
        "frames_wall_s": s["frames_wall_s"], "frames_share_of_wall": s["frames_wall_s"] / s["wall_s"],
        "peak_force_N": s["peak_force_N"], "load_average_1min_start": load,
    }


def markdown(report):
    r = {v["variant"]: v for v in report["runs"]}
    lines = ["| frames | VTK bytes | files | frames written | wall [s] | frames' wall [s] | frames' share of wall "
             "| wall outside the frames [s] | load at start |",
             "|---|---|---|---|---|---|---|---|---|"]
    for v in report["runs"]:
        lines.append(f"| {v['variant']} | {v['vtk_bytes'] / 1e6:.1f} MB | {v['vtk_files']} | {v['frames']} | "
                     f"{v['wall_s']:.1f} | {v['frames_wall_s']:.2f} | {100 * v['frames_share_of_wall']:.2f} % | "
                     f"{v['wall_s'] - v['frames_wall_s']:.1f} | {v['load_average_1min_start']:.1f} |")
    outside = [v["wall_s"] - v["frames_wall_s"] for v in report["runs"]]
    lines.append("")
    lines.append(
        f"{r['ascii']['particles']} particles, {r['ascii']['bonds']} bonds, {r['ascii']['ranks']} rank(s), "
        f"{report['date']}, {report['cores']} cores. Binary writes {report['binary_bytes_over_ascii']:.3f} of "
        f"ascii's bytes (1/{1 / report['binary_bytes_over_ascii']:.1f}). The frames' share of the wall time, "
        f"measured inside the run: binary {100 * r['binary']['frames_share_of_wall']:.2f} %, ascii "
        f"{100 * r['ascii']['frames_share_of_wall']:.2f} %. As the difference from the run without frames it is "
        f"binary {100 * report['binary_share_by_difference']:.1f} %, ascii "
        f"{100 * report['ascii_share_by_difference']:.1f} %, which measures the machine more than the frames "
        f"where the runs saw different loads: their time outside the frames ranged from {min(outside):.0f} to "
        f"{max(outside):.0f} s. Peak force "
        + ", ".join(f"{v['variant']} {v['peak_force_N'] / 1e3:.6g} kN" for v in report["runs"])
        + (" (the same run)." if report["same_peak_force"] else " (NOT the same run)."))
    return "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-particles", type=iceCases.whole_number(20), default=13000)
    p.add_argument("-ranks", type=iceCases.whole_number(1), default=2)
    p.add_argument("-out", default=os.path.join(here, "..", "runs", "outputBenchmark"))
    p.add_argument("-publish", action="store_true",
                   help="run nothing; copy -out's outputBenchmark.json and .md into studies/outputBenchmark/")
    p.add_argument("-report", action="store_true",
                   help="run nothing; write -out's outputBenchmark.md again from its outputBenchmark.json")
    a = p.parse_args()
    if a.report:
        report = json.load(open(os.path.join(a.out, OUTPUTS[0])))
        iceCases.write_atomically(os.path.join(a.out, OUTPUTS[1]), markdown(report))
        print(markdown(report), end="")
        return
    if a.publish:
        iceCases.publish_files([os.path.join(a.out, n) for n in OUTPUTS], os.path.join(here, "outputBenchmark"))
        return
    runs = [run_variant(a.out, name, fmt, interval, a.particles, a.ranks) for name, fmt, interval in VARIANTS]
    r = {v["variant"]: v for v in runs}
    report = {
        "machine": os.uname().nodename, "cores": os.cpu_count(), "date": time.strftime("%Y-%m-%d %H:%M"),
        "load_average_1min_end": os.getloadavg()[0],
        "runs": runs,
        "binary_bytes_over_ascii": r["binary"]["vtk_bytes"] / r["ascii"]["vtk_bytes"],
        "binary_share_by_difference": (r["binary"]["wall_s"] - r["off"]["wall_s"]) / r["binary"]["wall_s"],
        "ascii_share_by_difference": (r["ascii"]["wall_s"] - r["off"]["wall_s"]) / r["ascii"]["wall_s"],
        "same_peak_force": len({v["peak_force_N"] for v in runs}) == 1,
    }
    os.makedirs(a.out, exist_ok=True)
    iceCases.write_atomically(os.path.join(a.out, OUTPUTS[0]), json.dumps(report, indent=2) + "\n")
    iceCases.write_atomically(os.path.join(a.out, OUTPUTS[1]), markdown(report))
    print(markdown(report), end="")


if __name__ == "__main__":
    main()
