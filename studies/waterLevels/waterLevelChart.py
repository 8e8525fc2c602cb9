#!/usr/bin/python3
"""Which water level does a scene need? (physics.md section 6; issue 19 item 4)

For the floating block, rubble settling, the rubble punch and a ridge run: each water level's
answer and its accuracy against the scene's check, from the committed results of the cases, beside
its cost, wall time per simulated second, measured here in one command: a short window of each
scene at each level, one after the other on 1 rank, so that every level sees the same machine.

  scene            check (committed results)                                   window timed here
  floating block   submerged volume fraction against rho_i/rho_w (Archimedes)  1 s of floating
  rubble settling  ice above water against 1 - rho_i/rho_w; porosity, depth    2 s of raining
  rubble punch     force against the hydrostatic level's, pressure noise       2 mm of travel, cuboid keel
  ridge run 6      failure force against the hydrostatic level's, noise        2 mm of travel, default resolution

Level `none` (no water): the floating block falls through, and the punch and ridge scenes are not
defined without the water that floats the keel (ridgeDEM refuses it), so `none` has no row but its
reason. Rubble settling has no `vof` level (the vof solver serves the floating block and the ridge
scenes' loading).

The windows start from the cases' own finished runs (the punch's runs/cuboid, runs/cuboid-cfd and
runs/cuboid-vof, the ridge's runs/default/run06..., runs/default-cfd/run06... and
runs/default-vof/run06..., their saved ridges), copied under runs/ here; run those first
(`cases/rubblePunch/Allrun [-water cfd|vof]`, `cases/ridgeFlexure/Allrun -water cfd|vof`). Cost
per simulated second: the loading or settling loop's own particle-steps/s where the application
reports it (set-up excluded), the wall clock of the whole run for the floating block.

usage: waterLevelChart.py [--out DIR] [--publish]
  writes OUT/waterLevels.{csv,md,png} (default runs/); --publish: into results/ and the table into
  this folder's README.md and the top README's."""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..")
CASES = os.path.join(TOP, "cases")
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
sys.path.insert(0, os.path.join(CASES, "rubbleBeam", "studies"))
import cfdRun  # noqa: E402
import iceCases  # noqa: E402
import settlingLevels  # noqa: E402

os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
RHO_RATIO = 917.0 / 1000.0
RIDGE_RUN = "run06_keel0.5_4h_CL10"
NONE_REASON = {"floating block": "no buoyancy: the block falls to the floor",
               "rubble settling": "no buoyancy: the blocks pile on the floor, no floating keel",
               "rubble punch": "not defined: the keel floats (ridgeDEM refuses waterLevel none)",
               "ridge run 6": "not defined: the keel floats (ridgeDEM refuses waterLevel none)"}


def load(path):
    return json.load(open(path))


# ---------------------------------------------------------------- the committed answers and checks

def floating_block_answers():
    rows = {}
    for level, folder in (("hydrostatic", "results"), ("cfd", "cfd/results"), ("vof", "vof/results")):
        s = load(os.path.join(CASES, "floatingBlock", folder, "summary.json"))
        rows[level] = {"answer": f"submerged fraction {s['submerged_volume_fraction']:.4f}",
                       "check": "Archimedes 0.917", "error": s["submerged_volume_fraction_error"],
                       "source": f"cases/floatingBlock/{folder}/summary.json"}
    return rows


def settling_answers():
    rows = {}
    table = os.path.join(CASES, "rubbleBeam", "results", "settlingLevels_cuboid.csv")
    for r in read_csv(table):
        above = float(r["ice_above_water"])
        rows[r["water"]] = {"answer": f"porosity {float(r['porosity']):.3f}, ice above water {100 * above:.2f} %",
                            "check": f"Archimedes {100 * (1 - RHO_RATIO):.1f} % above",
                            "error": (above - (1 - RHO_RATIO)) / (1 - RHO_RATIO),
                            "source": "cases/rubbleBeam/results/settlingLevels_cuboid.csv"}
    return rows


def punch_answers():
    rows = {}
    table = {r["run"]: r for r in read_csv(os.path.join(CASES, "rubblePunch", "results", "punchSummary.csv"))}
    base = float(table["cuboid"]["mean_force_20_100mm_N"])
    for level, run in (("hydrostatic", "cuboid"), ("cfd", "cuboid-cfd"), ("vof", "cuboid-vof")):
        r = table[run]
        mean = float(r["mean_force_20_100mm_N"])
        noise = f", pressure noise {float(r['dynamic_pressure_std_20_100mm_N']):.0f} N" if level != "hydrostatic" else ""
        if level == "vof":
            noise += f", level rise {float(r['level_rise_mm']):.1f} mm"
        rows[level] = {"answer": f"mean force 20-100 mm {mean:.0f} N, peak {float(r['peak_force_N']):.0f} N{noise}",
                       "check": "hydrostatic level's mean force",
                       "error": "reference" if level == "hydrostatic" else mean / base - 1,
                       "source": "cases/rubblePunch/results/punchSummary.csv"}
    return rows


def ridge_answers():
    rows = {}
    table = [r for r in read_csv(os.path.join(CASES, "ridgeFlexure", "results", "waterLevels_default.csv"))
             if r["run"] == "6"]
    base = next(float(r["failure_force_kN"]) for r in table if r["water"] == "hydrostatic")
    for r in table:
        force = float(r["failure_force_kN"])
        noise = f", pressure noise {float(r['dynamic_pressure_std_N']):.0f} N" if r["water"] != "hydrostatic" else ""
        rows[r["water"]] = {"answer": f"failure force {force:.2f} kN{noise}",
                            "check": "hydrostatic level's failure force",
                            "error": "reference" if r["water"] == "hydrostatic" else force / base - 1,
                            "source": "cases/ridgeFlexure/results/waterLevels_default.csv"}
    return rows


def read_csv(path):
    import csv
    with open(path) as f:
        return list(csv.DictReader(f))


# ---------------------------------------------------------------- the windows timed here

def copy_run(source, target, extra=("0",)):
    """A finished run's inputs and saved stages (not its outputs) in a fresh folder."""
    shutil.rmtree(target, ignore_errors=True)
    os.makedirs(target)
    skip = shutil.ignore_patterns("*.restart.*", "checkpoint*", "*.tmp")
    for sub in ("constant", "system", "DEM") + tuple(extra):
        if os.path.isdir(os.path.join(source, sub)):
            shutil.copytree(os.path.join(source, sub), os.path.join(target, sub), ignore=skip)
    iceCases.copy_common(target)
    return target


def floating_block_cost(work, level, end_time=1.0):
    folder = os.path.join(CASES, "floatingBlock", "" if level == "hydrostatic" else level)
    case = copy_run(folder, os.path.join(work, f"floatingBlock-{level}"))
    control = os.path.join(case, "system", "controlDict")
    iceCases.set_entry(control, "endTime", end_time)
    start = time.time()
    if level == "hydrostatic":
        iceCases.run_app("floatingBlockDEM", case, 1, [], "log.run")
    else:
        iceCases.set_entry(control, "writeInterval", end_time)
        with open(os.path.join(case, "log.Allrun"), "w") as log:
            subprocess.run([os.path.join(folder, "Allrun"), "-np", "1", "-case", case], check=True,
                           stdout=log, stderr=subprocess.STDOUT)
    return (time.time() - start) / end_time, "whole run"


def settling_cost(work, level, window=2.0):
    case = os.path.join(work, f"settling-{level}")
    iceCases.copy_case(os.path.join(CASES, "rubbleBeam"), case)
    props = os.path.join(case, "constant", "rubbleProperties")
    iceCases.set_entry(props, "settling.maxTime", window)
    iceCases.set_entry(props, "settling.minTime", window)
    if level == "cfd":
        settlingLevels.overlay_cfd(case)
        settlingLevels.settle_cfd(case, "cuboid")
    else:
        iceCases.run_app("rubbleDEM", case, 1, ["-stage", "settle"], "log.settle")
    return load(os.path.join(case, "postProcessing", "settling.json"))["wall_per_simulated_s"], "settling loop"


def loading_cost(work, name, source, level, travel=0.002, ranks=1):
    """Wall s per simulated s of a loading window (`travel` of the platen) started from the
    finished run `source` (its saved ridge), in a copy under work/, at a water level, on ranks."""
    if not iceCases.finished(source):
        raise RuntimeError(f"{source} has not finished: run its case first")
    case = copy_run(source, os.path.join(work, f"{name}-{level}" + (f"-np{ranks}" if ranks > 1 else "")))
    control = os.path.join(case, "system", "controlDict" if level == "hydrostatic" else "loadingDict")
    iceCases.set_entry(control, "maxTravel", travel)
    iceCases.set_entry(control, "rampTravel", travel / 2)   # the smooth start within the window
    if cfdRun.has_entry(control, "minTravel"):
        iceCases.set_entry(control, "minTravel", 0)
    os.makedirs(os.path.join(case, "postProcessing"), exist_ok=True)
    if level != "hydrostatic":
        if ranks > 1:
            raise ValueError(f"the {level} windows run on 1 rank (their meshes are not decomposed here)")
        app = {"cfd": "icePunchFoam", "vof": "icePunchInterFoam"}[level]
        iceCases.run_app(os.path.join(iceCases.BUILD, "coupling", app), case, 1, [], "log.run")
    else:
        iceCases.run_app("ridgeDEM", case, ranks, ["-stage", "load"], "log.run")
    s = iceCases.summary(case)
    return s["particles"] / s["particle_steps_per_s"] / s["dt"], "loading loop"


def level_suffix(level):
    """A case's run folder of a water level: runs/<name> (hydrostatic), runs/<name>-cfd, -vof."""
    return "" if level == "hydrostatic" else "-" + level


SCENES = [
    ("floating block", floating_block_answers, ("hydrostatic", "cfd", "vof"), floating_block_cost),
    ("rubble settling", settling_answers, ("hydrostatic", "cfd"), settling_cost),
    ("rubble punch", punch_answers, ("hydrostatic", "cfd", "vof"),
     lambda work, level: loading_cost(work, "punch", os.path.join(CASES, "rubblePunch", "runs",
                                                                  "cuboid" + level_suffix(level)), level)),
    ("ridge run 6", ridge_answers, ("hydrostatic", "cfd", "vof"),
     lambda work, level: loading_cost(work, "ridge", os.path.join(CASES, "ridgeFlexure", "runs",
                                                                  "default" + level_suffix(level), RIDGE_RUN), level)),
]


def measure(work):
    rows = []
    for scene, answers, levels, cost in SCENES:
        found = answers()
        rows.append({"scene": scene, "level": "none", "answer": NONE_REASON[scene], "check": "", "error": "",
                     "wall_per_simulated_s": "", "timed": "", "source": ""})
        for level in levels:
            print(f"{scene}, {level} ...", flush=True)
            seconds, what = cost(work, level)
            rows.append({"scene": scene, "level": level, **found[level],
                         "wall_per_simulated_s": round(seconds, 3), "timed": what})
    return rows


# ---------------------------------------------------------------- table and chart

COLUMNS = ("scene", "level", "answer", "check", "error", "wall_per_simulated_s", "timed", "source")


def table(rows):
    import csv
    import io
    out = io.StringIO()
    writer = csv.DictWriter(out, COLUMNS, lineterminator="\n")
    writer.writeheader()
    writer.writerows({k: (round(r[k], 5) if isinstance(r[k], float) else r[k]) for k in COLUMNS} for r in rows)
    lines = ["| scene | water level | answer | check | error | wall per simulated s (1 rank) |", "|---|---|---|---|---|---|"]
    for r in rows:
        error = f"{100 * r['error']:+.2f} %" if isinstance(r["error"], float) else r["error"]
        cost = f"{r['wall_per_simulated_s']:.3g} s ({r['timed']})" if r["wall_per_simulated_s"] != "" else "-"
        lines.append(f"| {r['scene']} | {r['level']} | {r['answer']} | {r['check']} | {error} | {cost} |")
    return out.getvalue(), "\n".join(lines) + "\n"


def plot(rows, path):
    """Per scene: each level's cost as a bar, its error against the scene's check written on it;
    levels without a run (none, vof not built) named where their bar would be."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    colours = {"none": "lightgrey", "hydrostatic": "tab:blue", "cfd": "tab:red", "vof": "tab:green"}
    scenes = [s[0] for s in SCENES]
    fig, axes = plt.subplots(1, len(scenes), figsize=(4.0 * len(scenes), 4.6), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        mine = [r for r in rows if r["scene"] == scene]
        top = max(r["wall_per_simulated_s"] for r in mine if r["wall_per_simulated_s"] != "")
        for x, r in enumerate(mine):
            if r["wall_per_simulated_s"] == "":
                ax.text(x, 0.05 * top, "none: no water" if r["level"] == "none" else "not built",
                        rotation=90, ha="center", va="bottom", fontsize=8, color="grey")
                continue
            ax.bar(x, r["wall_per_simulated_s"], color=colours[r["level"]], width=0.6)
            label = f"{100 * r['error']:+.2f} %" if isinstance(r["error"], float) else r["error"]
            ax.text(x, r["wall_per_simulated_s"] + 0.02 * top, label, ha="center", va="bottom", fontsize=8)
        ax.set_xticks(range(len(mine)), [r["level"] for r in mine], fontsize=8)
        ax.set_ylim(0, 1.15 * top)
        ax.set_xlim(-0.6, len(mine) - 0.4)
        ax.set_title(scene, fontsize=10)
        ax.set_ylabel("wall s per simulated s (1 rank)")
        check = next((r["check"] for r in mine if r["check"]), "")
        ax.set_xlabel(f"error against {check}", fontsize=8)
        ax.grid(alpha=0.3, axis="y")
    fig.suptitle("Water levels: cost per simulated second (bars) and error against each scene's check (labels)")
    iceCases.save_figure(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=os.path.join(HERE, "runs"))
    parser.add_argument("--publish", action="store_true",
                        help="run nothing; copy OUT's table and chart into results/ and the READMEs")
    args = parser.parse_args()
    if args.publish:
        results = os.path.join(HERE, "results")
        iceCases.publish_files([os.path.join(args.out, f"waterLevels.{ext}") for ext in ("csv", "md", "png")], results)
        md = open(os.path.join(results, "waterLevels.md")).read()
        for readme in (os.path.join(HERE, "README.md"), os.path.join(TOP, "README.md")):
            iceCases.write_readme_table(readme, "water level table", "studies/waterLevels/waterLevelChart.py --publish",
                                        "studies/waterLevels/results/waterLevels.csv", md)
        return
    os.makedirs(args.out, exist_ok=True)
    rows = measure(os.path.join(args.out, "windows"))
    csv_text, md = table(rows)
    load_average = os.getloadavg()[0]
    md += f"\nTimed {time.strftime('%Y-%m-%d %H:%M')}, load average {load_average:.1f} at the end.\n"
    iceCases.write_atomically(os.path.join(args.out, "waterLevels.csv"), csv_text)
    iceCases.write_atomically(os.path.join(args.out, "waterLevels.md"), md)
    plot(rows, os.path.join(args.out, "waterLevels.png"))
    print(md, end="")


if __name__ == "__main__":
    main()
