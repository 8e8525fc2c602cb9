#!/usr/bin/python3
"""The rubble settled at the cfd level against the hydrostatic level (physics.md section 6, issue 19
item 1): the same blocks (same seed) rained into water that OpenFOAM solves (iceRubbleFoam, the
case's cfd/ set-up) and into still water (rubbleDEM), each then compacted and bonded by rubbleDEM in
still water as the case does, so that the keels of the punch and the ridges can start from either.

A run is a copy of this case (runs/settling-<level>-<shape>/); the cfd one has cfd/ over it and a
fluid mesh of the box from the floor to the still surface (boxLength, boxWidth from
constant/rubbleProperties, surfaceZ from hydrostatic.surfaceLevel). A finished run made from the
same inputs is reused (iceCases.prepared_run); an unfinished cfd settling starts again (it has no
checkpoint of its fluid).

Per level: settling time, at rest, thickness, porosity, ice above water, the water's vertical force
on the settled ice against its weight (cfd), wall time, wall time per simulated second and
particle-steps/s of the settling; after compaction and bonding: porosity, the lid's pressure when
the plates closed, freeze-bonds. A heap that jams before the compaction's target (rubbleDEM stops:
"out of reach") is reported where it jammed and under what pressure, and is not bonded. The plot
gives the ice's volume fraction against height for both settled layers and the lid's pressure
against porosity as the plates close on each heap. Writes
runs/settlingLevels_<shape>.{csv,md,png}; --publish runs nothing and copies them into results/ with
the README's table.

usage: settlingLevels.py [--shape cuboid|empirical] [--jobs N] [--publish]"""
import argparse
import concurrent.futures
import json
import os
import re
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(CASE, "..", "..", "postProcessing"))
import cfdRun  # noqa: E402
import iceCases  # noqa: E402

os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")   # OpenFOAM's utilities and iceRubbleFoam
LEVELS = ("hydrostatic", "cfd")
CFD_MIN_TIME = 10.0     # s of settling at least, at the cfd level (prepare, below)


def run_dir(level, shape):
    return os.path.join(CASE, "runs", f"settling-{level}-{shape}")


def overlay_cfd(folder):
    """cfd/ over a copy of a rubble case, the box's dimensions and the surface in its fluid mesh."""
    for sub in ("0", "constant", "system"):
        shutil.copytree(os.path.join(CASE, "cfd", sub), os.path.join(folder, sub), dirs_exist_ok=True)
    props = os.path.join(folder, "constant", "rubbleProperties")
    block = os.path.join(folder, "system", "blockMeshDict")
    for entry, source in (("boxLength", (props, "box.length")), ("boxWidth", (props, "box.width")),
                          ("surfaceZ", (os.path.join(folder, "constant", "couplingProperties"),
                                        "hydrostatic.surfaceLevel"))):
        iceCases.set_entry(block, entry, iceCases.get_entry(*source))


def settle_cfd(folder, shape, ranks=1, app=None):
    """The settling in iceRubbleFoam (app: another build's) on the case copy `folder` (its mesh
    made here)."""
    cfdRun.foam("blockMesh", folder)
    if ranks > 1:
        decompose = os.path.join(folder, "system", "decomposeParDict")
        iceCases.set_entry(decompose, "numberOfSubdomains", ranks)
        iceCases.set_entry(decompose, "coeffs.n", f"({ranks} 1 1)")
        cfdRun.foam("decomposePar", folder, "-force")
    args = ["-shape", shape] + (["-parallel"] if ranks > 1 else [])
    iceCases.run_app(app or os.path.join(iceCases.BUILD, "coupling", "iceRubbleFoam"), folder, ranks, args,
                     "log.iceRubbleFoam")


def execute(level, shape):
    def prepare(folder):
        iceCases.copy_case(CASE, folder)
        if level == "cfd":
            overlay_cfd(folder)
            # The kinetic-energy rule alone stopped it at 4.0 s with the heap still creeping: its
            # ice 9.4 % above water against Archimedes' 8.3 % and the water's force 1 % short of the
            # weight (2026-11-28); held at least as long as the hydrostatic settling takes (9.9 s).
            iceCases.set_entry(os.path.join(folder, "constant", "rubbleProperties"), "settling.minTime", CFD_MIN_TIME)

    target = iceCases.prepared_run(run_dir(level, shape), prepare, settings=[shape])
    if done(target):
        return target
    # A settled heap of this folder's inputs is kept (rubbleDEM -stage compact checks its provenance):
    # the cfd settling has no checkpoint of its fluid and is the expensive part.
    if not settled(target):
        if level == "cfd":
            settle_cfd(target, shape)
        else:
            iceCases.run_app("rubbleDEM", target, 1, ["-stage", "settle", "-shape", shape], "log.settle")
    try:
        iceCases.run_app("rubbleDEM", target, 1, ["-stage", "compact", "-shape", shape], "log.compact")
    except RuntimeError:
        if jam(target) is None:
            raise
        print(f"{target}: the compaction's target is out of reach for this heap (log.compact): "
              "reported as jammed, not bonded", flush=True)
        return target
    iceCases.run_app("rubbleDEM", target, 1, ["-stage", "bond", "-shape", shape], "log.bond")
    return target


JAM = re.compile(r"compaction stopped at porosity (\S+) \(plates \S+ m apart\) with (\S+) Pa on the lid")


def jam(target):
    """Where the heap jammed before the compaction's target (porosity, lid pressure in Pa, from
    rubbleDEM's message in log.compact), or None if its compaction did not stop that way."""
    log = os.path.join(target, "log.compact")
    match = JAM.search(open(log).read()) if os.path.exists(log) else None
    return (float(match.group(1)), float(match.group(2))) if match else None


def settled(target):
    """Whether the run folder holds its settled heap (its summary and DEM/settled.h5)."""
    return (os.path.exists(os.path.join(target, "postProcessing", "settling.json"))
            and os.path.exists(os.path.join(target, "DEM", "settled.h5")))


def done(target):
    """Compacted and bonded, or settled and jammed on the way to the compaction's target."""
    return iceCases.finished(target) or (settled(target) and jam(target) is not None)


def settling(target):
    return json.load(open(os.path.join(target, "postProcessing", "settling.json")))


def compaction_figures(target):
    """The porosity and the lid's pressure when the plates closed on the target (or where the heap
    jammed), the porosity after the hold, at which the freeze-bonds were made, and their number
    ("" when the heap jammed and was not bonded)."""
    if iceCases.finished(target):
        b = iceCases.summary(target)
        closed = json.load(open(os.path.join(target, "postProcessing", "compaction.json")))
        return {"compaction": "reached", "closed_porosity": round(closed["porosity_when_closed"], 4),
                "lid_pressure_kPa": round(closed["lid_pressure_when_closed_Pa"] / 1e3, 2),
                "compacted_porosity": round(b["compaction"]["porosity"], 4),
                "freeze_bonds": b["freeze_bonds"]}
    porosity, pressure = jam(target)
    return {"compaction": "jammed", "closed_porosity": round(porosity, 4),
            "lid_pressure_kPa": round(pressure / 1e3, 2), "compacted_porosity": "", "freeze_bonds": ""}


def row(level, target):
    s = settling(target)
    fluid = s.get("fluidForceZ_N")
    return {"water": level, "settled_time_s": round(s["settled_time_s"], 2), "at_rest": s["at_rest"],
            "thickness_m": round(s["thickness_m"], 4), "porosity": round(s["porosity"], 4),
            "ice_above_water": round(s["ice_volume_above_water_fraction"], 4),
            "freeboard_m": round(s["freeboard_m"], 4),
            "fluid_force_over_weight": round(fluid / s["weight_N"], 4) if fluid is not None else "",
            "drag_N": round(s["dragZ_N"], 2) if fluid is not None else "",
            "particles": s["particles"], "steps": s["steps"], "wall_s": round(s["wall_s"], 1),
            "wall_per_simulated_s": round(s["wall_per_simulated_s"], 2),
            "particle_steps_per_s": round(s["particle_steps_per_s"], -3), **compaction_figures(target)}


def table(rows):
    columns = list(rows[0])
    csv_text = "\n".join([",".join(columns)] + [",".join(str(r[c]) for c in columns) for r in rows]) + "\n"
    lines = ["| water | settled after [s] | thickness [m] | porosity | ice above water | water's force / weight "
             "| settling wall [s] (per simulated s) | particle-steps/s | plates closed: porosity, lid pressure "
             "| bonded at porosity, freeze-bonds |",
             "|---|" + "---|" * 9]
    for r in rows:
        ratio = "-" if r["fluid_force_over_weight"] == "" else f"{r['fluid_force_over_weight']:.4f}"
        reached = r["compaction"] == "reached"
        closed = (f"{r['closed_porosity']:.3f}, {r['lid_pressure_kPa']:.1f} kPa" if reached
                  else f"jammed at {r['closed_porosity']:.3f} under {r['lid_pressure_kPa']:.0f} kPa")
        bonded = f"{r['compacted_porosity']:.3f}, {r['freeze_bonds']}" if reached else "not bonded"
        lines.append(f"| {r['water']} | {r['settled_time_s']:.1f}{'' if r['at_rest'] else ' (NOT at rest)'} "
                     f"| {r['thickness_m']:.3f} | {r['porosity']:.3f} | {100 * r['ice_above_water']:.2f} % "
                     f"| {ratio} | {r['wall_s']:.0f} ({r['wall_per_simulated_s']:.1f}) "
                     f"| {r['particle_steps_per_s']:.3g} | {closed} | {bonded} |")
    return csv_text, "\n".join(lines) + "\n"


def ice_fraction_profile(target, bins):
    """The settled spheres' volume per height bin over the box's volume there (DEM/settled.h5)."""
    import h5py
    import numpy as np
    props = os.path.join(target, "constant", "rubbleProperties")
    area = float(iceCases.get_entry(props, "box.length")) * float(iceCases.get_entry(props, "box.width"))
    with h5py.File(os.path.join(target, "DEM", "settled.h5"), "r") as f:
        z, r = f["particles"]["z"][()], f["particles"]["radius"][()]
    volume, _ = np.histogram(z, bins=bins, weights=4.0 / 3.0 * np.pi * r ** 3)
    return volume / (area * np.diff(bins))


def plot(shape, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    bins = np.linspace(0.0, 1.25, 26)     # 5 cm: about a sphere diameter
    fig, (ax, squeeze) = plt.subplots(1, 2, figsize=(11, 5))
    for colour, level in zip(("tab:blue", "tab:red"), LEVELS):
        target = run_dir(level, shape)
        ax.plot(ice_fraction_profile(target, bins), 0.5 * (bins[1:] + bins[:-1]), color=colour,
                label=f"{level}: porosity {settling(target)['porosity']:.3f}")
    ax.axhline(float(iceCases.get_entry(os.path.join(CASE, "cfd", "constant", "couplingProperties"),
                                        "hydrostatic.surfaceLevel")), color="k", ls="--", lw=1, label="water surface")
    ax.set_xlabel("sphere volume fraction in the box")
    ax.set_ylabel("height above the box floor (m)")
    ax.set_title(f"Settled rubble ({shape}) at both water levels")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    for colour, level in zip(("tab:blue", "tab:red"), LEVELS):
        curve = os.path.join(run_dir(level, shape), "postProcessing", "compaction.csv")
        if os.path.exists(curve):
            c = np.genfromtxt(curve, delimiter=",", names=True)
            squeeze.semilogy(c["porosity"], np.maximum(c["lid_Pa"], 1.0) / 1e3, color=colour, label=level)
    props = os.path.join(CASE, "constant", "rubbleProperties")
    squeeze.axvline(float(iceCases.get_entry(props, "compaction.targetPorosity")), color="k", ls="--", lw=1,
                    label="target porosity")
    squeeze.axhline(float(iceCases.get_entry(props, "compaction.maxPressure")) / 1e3, color="k", ls=":", lw=1,
                    label="maxPressure")
    squeeze.invert_xaxis()
    squeeze.set_xlabel("porosity between the plates (closing: left to right)")
    squeeze.set_ylabel("lid pressure (kPa)")
    squeeze.set_title("Compaction at the ice's stiffness")
    squeeze.grid(alpha=0.3, which="both")
    squeeze.legend(fontsize=8)
    iceCases.save_figure(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--shape", choices=("cuboid", "empirical"), default="cuboid")
    parser.add_argument("--jobs", type=iceCases.whole_number(1), default=max(1, min(2, os.cpu_count() or 1)))
    parser.add_argument("--publish", action="store_true",
                        help="run nothing; copy the finished runs' table and plot into results/ and the README")
    args = parser.parse_args()
    if args.publish:
        missing = [run_dir(level, args.shape) for level in LEVELS if not done(run_dir(level, args.shape))]
        if missing:
            sys.exit("settlingLevels.py --publish: not finished: " + ", ".join(missing))
    else:
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            for future in [pool.submit(execute, level, args.shape) for level in LEVELS]:
                future.result()
    rows = [row(level, run_dir(level, args.shape)) for level in LEVELS]
    csv_text, md = table(rows)
    folder = os.path.join(CASE, "results") if args.publish else os.path.join(CASE, "runs")
    base = os.path.join(folder, f"settlingLevels_{args.shape}")
    iceCases.write_atomically(base + ".csv", csv_text)
    iceCases.write_atomically(base + ".md", md)
    plot(args.shape, base + ".png")
    if args.publish:
        iceCases.write_readme_table(os.path.join(CASE, "README.md"), "settling water table",
                                    "studies/settlingLevels.py --publish", f"results/settlingLevels_{args.shape}.csv", md)
    print(md, end="")


if __name__ == "__main__":
    main()
