#!/usr/bin/python3
"""Where the drag exchange of the cfd level fails (issue 20, item 4b): the coupling time against the
momentum-coupling scheme (explicit, semiImplicit) and the cell size over the particle diameter, on
tests/coupling/lightCloud (a periodic box of 2 mm ice spheres on a 2 mm lattice, fluid fraction
0.476, set moving at 10 mm/s through still water; momentum conservation fixes the velocity every
particle and the water must end at). Each point runs 30 coupling steps with the check off
(stabilityCheck no): stable (every particle within 1e-6 of that velocity), slow (still relaxing,
within 1 %), or unstable (further off, growing, or stopped); and once with the check on, to read
the longest coupling time the check allows (its refusal names it) or that it lets the point run.

usage: couplingMap.py [--times 5,10,16,20,22,24,28,40,60,100] [--cells 12,8,6,4] [--out DIR] [--publish]
  times in ms; cells across the 24 mm box (2, 3, 4, 6 mm: 1, 1.5, 2, 3 particle diameters);
  writes OUT/couplingMap.{csv,md,png} (default runs/); --publish copies them into results/ and the
  table into this folder's README.md."""
import argparse
import csv
import io
import math
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402

SOURCE = os.path.join(TOP, "tests", "coupling", "lightCloud")
BOX_MM, DIAMETER_MM = 24.0, 2.0
V0, RHO_P, RHO_F = 0.01, 917.0, 1000.0
SCHEMES = ("explicit", "semiImplicit")
STEPS = 30


def common_velocity():
    phi = math.pi / 6
    return V0 * phi * RHO_P / (phi * RHO_P + (1 - phi) * RHO_F)


def run(out, scheme, t_ms, cells, check):
    case = os.path.join(out, f"{scheme}_{t_ms:g}ms_{cells}cells" + ("_checked" if check else ""))
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    for sub in ("0", "constant", "system", "DEM"):
        shutil.copytree(os.path.join(SOURCE, sub), os.path.join(case, sub))
    iceCases.copy_common(case)
    props, control = os.path.join(case, "constant", "couplingProperties"), os.path.join(case, "system", "controlDict")
    iceCases.set_entry(props, "momentumCoupling", scheme)
    iceCases.set_entry(props, "couplingInterval", round(t_ms))     # DEM steps of 1 ms
    iceCases.set_entry(props, "stabilityCheck", "yes" if check else "no")
    iceCases.set_entry(control, "deltaT", t_ms * 1e-3)
    iceCases.set_entry(control, "endTime", STEPS * t_ms * 1e-3)
    iceCases.set_entry(os.path.join(case, "system", "blockMeshDict"), "blocks",
                       f"( hex (0 1 2 3 4 5 6 7) ({cells} {cells} {cells}) simpleGrading (1 1 1) )")
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    subprocess.run(["blockMesh", "-case", case], check=True, stdout=subprocess.DEVNULL, env=env)
    with open(os.path.join(case, "log.iceFoam"), "w") as log:
        rc = subprocess.run([os.path.join(iceCases.BUILD, "coupling", "iceFoam"), "-case", case], stdout=log,
                            stderr=subprocess.STDOUT, env=env).returncode
    return rc, case


def final_deviation(case):
    speeds = {}
    path = os.path.join(case, "postProcessing", "particles.csv")
    if not os.path.exists(path):
        return math.inf
    with open(path) as f:
        for r in csv.DictReader(f):
            speeds.setdefault(float(r["time"]), []).append(float(r["vx"]))
    v = common_velocity()
    return max(abs(x - v) for x in speeds[max(speeds)]) / v


def point(out, scheme, t_ms, cells):
    rc, case = run(out, scheme, t_ms, cells, check=False)
    deviation = final_deviation(case) if rc == 0 else math.inf
    outcome = "stable" if deviation < 1e-6 else "slow" if deviation < 1e-2 else "unstable"
    rc_checked, checked = run(out, scheme, t_ms, cells, check=True)
    said = re.search(r"Stable up to a coupling time of ([\d.e+-]+) s", open(os.path.join(checked, "log.iceFoam")).read())
    return {"scheme": scheme, "coupling_time_ms": t_ms, "cells_across": cells,
            "cell_over_diameter": round(BOX_MM / cells / DIAMETER_MM, 3), "outcome": outcome,
            "final_deviation": deviation if math.isfinite(deviation) else "",
            "check": "refused" if rc_checked != 0 else "runs",
            "check_limit_ms": round(1e3 * float(said.group(1)), 2) if said else ""}


def table(rows):
    out = io.StringIO()
    writer = csv.DictWriter(out, list(rows[0]), lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    times = sorted({r["coupling_time_ms"] for r in rows})
    lines = ["| scheme | cell / diameter | " + " | ".join(f"{t:g} ms" for t in times) + " | check's limit |",
             "|---|---|" + "---|" * (len(times) + 1)]
    short = {"stable": "ok", "slow": "slow", "unstable": "**X**"}
    for scheme in SCHEMES:
        for ratio in sorted({r["cell_over_diameter"] for r in rows}, reverse=True):
            mine = {r["coupling_time_ms"]: r for r in rows if r["scheme"] == scheme and r["cell_over_diameter"] == ratio}
            cells = [short[mine[t]["outcome"]] + (" (refused)" if mine[t]["check"] == "refused" else "") for t in times]
            limits = sorted({r["check_limit_ms"] for r in mine.values() if r["check_limit_ms"] != ""})
            lines.append(f"| {scheme} | {ratio:g} | " + " | ".join(cells) + " | "
                         + (", ".join(f"{x:g} ms" for x in limits) or "none hit") + " |")
    return out.getvalue(), "\n".join(lines) + "\n"


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), sharey=True)
    style = {"stable": ("o", "tab:green"), "slow": ("o", "gold"), "unstable": ("x", "tab:red")}
    for ax, scheme in zip(axes, SCHEMES):
        mine = [r for r in rows if r["scheme"] == scheme]
        for r in mine:
            marker, colour = style[r["outcome"]]
            ax.scatter(r["coupling_time_ms"], r["cell_over_diameter"], marker=marker, color=colour, s=60, zorder=3)
            if r["check"] == "refused":
                ax.scatter(r["coupling_time_ms"], r["cell_over_diameter"], marker="s", facecolors="none",
                           edgecolors="k", s=160, zorder=2)
        for limit in sorted({r["check_limit_ms"] for r in mine if r["check_limit_ms"] != ""}):
            ax.axvline(limit, color="k", ls="--", lw=1)
        ax.set_xscale("log")
        ax.set_title(scheme, fontsize=10)
        ax.set_xlabel("coupling time (ms)")
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("cell size / particle diameter")
    for label, (marker, colour) in style.items():
        axes[1].scatter([], [], marker=marker, color=colour, label=label)
    axes[1].scatter([], [], marker="s", facecolors="none", edgecolors="k", label="refused by stabilityCheck")
    axes[1].plot([], [], "k--", lw=1, label="the check's longest coupling time")
    axes[1].legend(fontsize=7)
    fig.suptitle("Drag exchange of the cfd level, light cloud (30 coupling steps, check off)", fontsize=10)
    iceCases.save_figure(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--times", type=iceCases.comma_list(iceCases.positive_number), default="5,10,16,20,22,24,28,40,60,100")
    parser.add_argument("--cells", type=iceCases.comma_list(iceCases.whole_number(2)), default="12,8,6,4")
    parser.add_argument("--out", default=os.path.join(HERE, "runs"))
    parser.add_argument("--publish", action="store_true")
    args = parser.parse_args()
    if args.publish:
        iceCases.publish_study(HERE, args.out, "couplingMap", ("csv", "md", "png"), "coupling map table", "csv")
        return
    work = os.path.join(args.out, "coupling")
    rows = [point(work, s, t, c) for s in SCHEMES for c in args.cells for t in args.times]
    csv_text, md = table(rows)
    md += f"\n{time.strftime('%Y-%m-%d %H:%M')}, revision {iceCases.git_revision()}.\n"
    iceCases.write_study_outputs(args.out, "couplingMap", {"csv": csv_text, "md": md})
    plot(rows, os.path.join(args.out, "couplingMap.png"))
    print(md, end="")


if __name__ == "__main__":
    main()
