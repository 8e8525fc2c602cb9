#!/usr/bin/python3
"""Ridge flexure at the cfd and vof levels against the hydrostatic level (physics.md section 6):
chosen runs of the matrix loaded in water that OpenFOAM solves (icePunchFoam, the case's cfd/
set-up) or in water and air with a moving surface (icePunchInterFoam, vof/), each beside the
same run in still water (the matrix's own run, made or reused by ridgeMatrix).

A cfd (vof) run is the matrix run's folder with cfd/ (vof/) over it
(runs/<resolution>-<level>/<run>/): the ridge is assembled in hydrostatic water (ridgeDEM -stage
assemble), the fluid mesh is made from the floor to the surface where it floats
(postProcessing/geometry.json; at vof on into the air), and the level's application loads it. A
finished run made from the same inputs is skipped (iceCases.prepared_run); an unfinished one
starts again (these runs have no checkpoint of their fluid).

Per run and level: failure force and travel, buoyancy share at the peak, the fluid's own share
beyond still-water buoyancy (drag, and pressure force less buoyancy, over the loading), broken
bonds, failure mode (postProcessing/failureAnalysis.py), wall time and particle-steps/s, and the
run's cost against the hydrostatic one. Writes runs/waterLevels_<resolution>/
waterLevels_<resolution>.{csv,md,png}; --publish runs nothing and copies them into results/ with
the README's table: the levels of --levels, which must be finished for every run, and any other
resolved level finished for every run (so publishing vof keeps the cfd rows where those runs are
here).

--keels iceStiff (default resolution only) loads the runs on the keels compacted at the ice's
stiffness (ridgeMatrix's KEEL_SETS; the case's default matrix since 2026-12-07) instead of the
softened ones the published levels were made on: runs/<resolution>-<level>-iceStiff/, tables
waterLevels_<resolution>_iceStiff.

Usage: studies/waterLevels.py [--resolution default|quick] [--keels softened|iceStiff] [--runs 6,14]
                              [--levels cfd,vof] [--jobs N] [--publish]
"""
import argparse
import concurrent.futures
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import ridgeMatrix  # noqa: E402
from ridgeMatrix import CASE, iceCases  # noqa: E402
import cfdRun  # noqa: E402  (postProcessing, on the path through ridgeMatrix)

os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")   # OpenFOAM's utilities and applications
# The resolved levels: the loading's application; the case's set-up is the folder of that name.
APPLICATIONS = {"cfd": "icePunchFoam", "vof": "icePunchInterFoam"}


def level_dir(run, resolution, level):
    return os.path.join(CASE, "runs", f"{resolution}-{level}{ridgeMatrix.keels_suffix()}",
                        os.path.basename(ridgeMatrix.run_dir(run, resolution)))


def prepare_resolved(run, resolution, level, folder):
    """The matrix run's folder with cfd/ (vof/) over it: OpenFOAM's controlDict, the loading's
    moved to system/loadingDict (the level's application reads it there)."""
    ridgeMatrix.prepare(run, resolution, folder)
    cfdRun.overlay(folder, os.path.join(CASE, level))
    if resolution == "quick":
        # The quick platen (0.2 m/s) crosses a force sample in about 64 DEM steps: the force is
        # sampled after whole coupling steps (the applications refuse a longer one).
        iceCases.set_entry(os.path.join(folder, "constant", "couplingProperties"), f"{level}.couplingInterval", 64)


def execute_resolved(run, resolution, level):
    target = iceCases.prepared_run(level_dir(run, resolution, level),
                                   lambda folder: prepare_resolved(run, resolution, level, folder),
                                   upstream=ridgeMatrix.upstream_files(run, resolution))
    if not iceCases.finished(target):
        app = APPLICATIONS[level]
        iceCases.run_app("ridgeDEM", target, 1, ["-stage", "assemble"], "log.ridgeDEM")
        cfdRun.mesh(target)
        iceCases.run_app(os.path.join(iceCases.BUILD, "coupling", app), target, 1, [], "log." + app)
    if not os.path.exists(os.path.join(target, "postProcessing", "failureAnalysis", "summary.json")):
        ridgeMatrix.analyse_failure(target)
    return target


def folders(run, resolution, levels):
    return {"hydrostatic": ridgeMatrix.run_dir(run, resolution),
            **{level: level_dir(run, resolution, level) for level in levels}}


def fluid_columns(fluid):
    """The table's columns of iceCases.fluid_force_figures over the loading; blanks at the
    hydrostatic level."""
    names = ("drag_mean_N", "dynamic_pressure_mean_N", "dynamic_pressure_std_N")
    return {name: round(fluid[name], 2) if fluid else "" for name in names}


def row(run, level, target):
    s = iceCases.summary(target)
    fa = json.load(open(os.path.join(target, "postProcessing", "failureAnalysis", "summary.json")))
    return {"run": run["run"], "keel_m": run["keel"], "bond_set": run["set"], "CL_cm": int(run["cl_cm"]),
            "water": level, "failure_force_kN": round(s["peak_force_N"] * 1e-3, 3),
            "travel_at_peak_mm": round(s["travel_at_peak_m"] * 1e3, 2),
            "buoyancy_share_at_peak_kN": round(s["buoyancy_share_at_peak_N"] * 1e-3, 3),
            **fluid_columns(iceCases.fluid_force_figures(iceCases.curve(target))),
            "broken_ice": s["broken_by_family"]["ice"], "broken_freeze": s["broken_by_family"]["freeze"],
            "failure_mode": fa.get("ridge_failure", {}).get("mode", "n/a"),
            "particles": s["particles"], "steps": s["steps"], "wall_s": round(s["wall_s"], 1),
            "particle_steps_per_s": round(s["particle_steps_per_s"], -3)}


def table(rows):
    columns = list(rows[0])
    csv_text = "\n".join([",".join(columns)] + [",".join(str(r[c]) for c in columns) for r in rows]) + "\n"
    lines = ["| run (keel, set, CL) | water | failure force [kN] at travel [mm] | buoyancy share at peak [kN] "
             "| drag, mean [N] | pressure less buoyancy: mean / std [N] | broken ice / freeze-bonds "
             "| failure mode | wall [s] (particle-steps/s) | cost against hydrostatic |", "|---|" + "---|" * 9]
    hydro = {r["run"]: r for r in rows if r["water"] == "hydrostatic"}
    for r in rows:
        fluid = "-" if r["drag_mean_N"] == "" else f"{r['drag_mean_N']:.1f}"
        dynamic = "-" if r["drag_mean_N"] == "" else f"{r['dynamic_pressure_mean_N']:.1f} / {r['dynamic_pressure_std_N']:.1f}"
        cost = f"{r['wall_s'] / hydro[r['run']]['wall_s']:.2f} x" if r["water"] != "hydrostatic" and r["run"] in hydro else ""
        lines.append(f"| {r['run']} ({r['keel_m']} m, {r['bond_set']}, {r['CL_cm']} cm) | {r['water']} "
                     f"| {r['failure_force_kN']:.2f} at {r['travel_at_peak_mm']:.1f} | {r['buoyancy_share_at_peak_kN']:.3f} "
                     f"| {fluid} | {dynamic} | {r['broken_ice']} / {r['broken_freeze']} | {r['failure_mode']} "
                     f"| {r['wall_s']:.0f} ({r['particle_steps_per_s']:.3g}) | {cost} |")
    return csv_text, "\n".join(lines) + "\n"


def plot(runs, resolution, levels, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(runs), figsize=(6 * len(runs), 4.5), squeeze=False)
    for ax, run in zip(axes[0], runs):
        for colour, (level, target) in zip(("tab:blue", "tab:red", "tab:green"), folders(run, resolution, levels).items()):
            c = iceCases.curve(target)
            mm = [t * 1e3 for t in c["travel"]]
            ax.plot(mm, [f * 1e-3 for f in c["force"]], color=colour, lw=1, label=f"{level}: platen force")
            ax.plot(mm, [f * 1e-3 for f in c["buoyancyShare"]], color=colour, ls="--", lw=1.2,
                    label=f"{level}: buoyancy share")
        ax.set_title(f"run {run['run']}: keel {run['keel']} m, {run['set']}, CL {int(run['cl_cm'])} cm")
        ax.set_xlabel("platen travel (mm)")
        ax.set_ylabel("force (kN)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    keels = "" if ridgeMatrix.KEELS == "softened" else f", {ridgeMatrix.KEELS} keels"
    fig.suptitle(f"Ridge flexure at the {', '.join(['hydrostatic', *levels])} levels ({resolution} resolution{keels})")
    iceCases.save_figure(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--resolution", choices=("quick", "default"), default="default")
    parser.add_argument("--runs", type=iceCases.comma_list(iceCases.whole_number(1)), default="6,14")
    parser.add_argument("--levels", type=iceCases.comma_list(iceCases.choice(tuple(APPLICATIONS))), default="cfd",
                        help="the resolved levels to run (default cfd)")
    parser.add_argument("--keels", choices=sorted(ridgeMatrix.KEEL_SETS), default="softened",
                        help="softened (the keels the published levels were made on) or iceStiff (default resolution)")
    parser.add_argument("--jobs", type=iceCases.whole_number(1), default=max(1, min(2, os.cpu_count() or 1)))
    parser.add_argument("--publish", action="store_true",
                        help="run nothing; copy the finished runs' table and plot into results/ and the README")
    args = parser.parse_args()
    ridgeMatrix.KEELS = args.keels
    ridgeMatrix.refuse_keels_at(args.resolution, parser)
    matrix = {r["run"]: r for r in ridgeMatrix.matrix()}
    unknown = [n for n in args.runs if n not in matrix]
    if unknown:
        parser.error(f"argument --runs: {unknown} not runs of ridgeMatrix.csv ({min(matrix)}-{max(matrix)})")
    runs = [matrix[n] for n in args.runs]
    levels = list(dict.fromkeys(args.levels))
    if args.publish:
        missing = [t for run in runs for t in folders(run, args.resolution, levels).values() if not iceCases.finished(t)]
        if missing:
            sys.exit("waterLevels.py --publish: not finished: " + ", ".join(missing))
        levels += [level for level in APPLICATIONS if level not in levels and all(
            iceCases.finished(level_dir(run, args.resolution, level)) for run in runs)]
        levels.sort(key=list(APPLICATIONS).index)
    else:
        jobs = [(ridgeMatrix.execute, run) for run in runs] + [
            (lambda r, res, lv=level: execute_resolved(r, res, lv), run) for level in levels for run in runs]
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            for future in [pool.submit(f, run, args.resolution) for f, run in jobs]:
                future.result()
    rows = [row(run, level, target) for run in runs for level, target in folders(run, args.resolution, levels).items()]
    csv_text, md = table(rows)
    name = "waterLevels_" + args.resolution + ridgeMatrix.keels_suffix().replace("-", "_")
    folder = os.path.join(CASE, "results") if args.publish else os.path.join(CASE, "runs", name)
    os.makedirs(folder, exist_ok=True)
    base = os.path.join(folder, name)
    iceCases.write_atomically(base + ".csv", csv_text)
    iceCases.write_atomically(base + ".md", md)
    plot(runs, args.resolution, levels, base + ".png")
    if args.publish:
        softened = args.keels == "softened"
        iceCases.write_readme_table(os.path.join(CASE, "README.md"),
                                    "ridge water table" + ("" if softened else " " + args.keels),
                                    "studies/waterLevels.py " + ("" if softened else "--keels " + args.keels + " ") + "--publish",
                                    f"results/{name}.csv", md)
    print(md, end="")


if __name__ == "__main__":
    main()
