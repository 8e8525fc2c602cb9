#!/usr/bin/python3
"""Where a quasi-static answer stops being quasi-static (issue 20, item 4c): the loading rate against
the kinetic energy the run carries, and what it does to the answer, for three scenes:

  level-ice beam   1,200 particles, clamped, speeds 0.025-0.4 m/s, run here; figure: the elastic
                   slope, against the slowest run's
  ridge run 6      quick resolution, 0.005-0.2 m/s, three packings at 0.025 and 0.05 m/s: the runs
                   of cases/ridgeFlexure/studies/rateConvergence.py (runs/rate_quick; run it
                   first); figure: the failure force, against the slowest run's
  rubble punch     the reduced keel of cases/rubblePunch/studies/rateStudy.py (runs/rateStudy),
                   0.005-0.05 m/s; figures: the mean force over 5-30 mm and the largest force,
                   against the slowest run's

The kinetic energy is each run's own measure: its median over the loading of the kinetic energy
over the platen's work (kinetic_to_work_ratio; the limit the program enforces on inertia-scaled
runs is 5e-4) and the kinetic over the bonds' elastic energy near the peak.

usage: rateMap.py [--speeds 0.4,0.2,0.1,0.05,0.025] [--jobs 2] [--out DIR] [--publish]
  writes OUT/rateMap.{csv,md,png} (default runs/); --publish copies them into results/ and the
  table into this folder's README.md."""
import argparse
import concurrent.futures
import csv
import glob
import io
import json
import os
import re
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402

KINETIC_LIMIT = 5e-4    # the program's limit on inertia-scaled runs (demModels/core/material/InertiaScaling.H)


def beam_point(out, speed):
    case = iceCases.copy_case(os.path.join(TOP, "cases", "levelIceBeam"), os.path.join(out, f"beam_v{speed:g}"))
    iceCases.set_entry(os.path.join(case, "system", "controlDict"), "writeInterval", 10)   # no frames
    iceCases.run_app("iceBeamDEM", case, 1, ["-particles", 1200, "-platenSpeed", speed], "log.run")
    s = iceCases.summary(case)
    # The elastic slope, not the first peak: at 0.025 m/s the centre crack's drop is too small for
    # the first-peak rule, which then takes a later event (36 mm of travel against 20 mm).
    return {"scene": "level-ice beam (elastic slope)", "speed_m_per_s": speed, "seed": 1,
            "figure": s["elastic_slope_N_per_m"], "kinetic_to_work": s["kinetic_to_work_ratio"],
            "kinetic_to_elastic_near_peak": s["kinetic_to_elastic_energy_near_peak"]}


def ridge_points():
    rows = []
    for f in glob.glob(os.path.join(TOP, "cases", "ridgeFlexure", "runs", "rate_quick", "run06_v*", "postProcessing",
                                     "summary.json")):
        name = f.split(os.sep)[-3]
        seed = re.search(r"_seed(\d+)", name)
        s = json.load(open(f))
        rows.append({"scene": "ridge run 6, quick (failure force)", "speed_m_per_s": s["platen_speed_m_per_s"],
                     "seed": int(seed.group(1)) if seed else 1, "figure": s["peak_force_N"],
                     "kinetic_to_work": s["kinetic_to_work_ratio"],
                     "kinetic_to_elastic_near_peak": s["kinetic_to_elastic_energy_near_peak"]})
    if not rows:
        sys.exit("rateMap.py: no runs in cases/ridgeFlexure/runs/rate_quick: run studies/rateConvergence.py there first")
    return rows


def punch_points():
    folder = os.path.join(TOP, "cases", "rubblePunch", "runs", "rateStudy")
    if not os.path.exists(os.path.join(folder, "rateStudy.csv")):
        sys.exit("rateMap.py: no cases/rubblePunch/runs/rateStudy/rateStudy.csv: run studies/rateStudy.py there first")
    rows = []
    for r in csv.DictReader(open(os.path.join(folder, "rateStudy.csv"))):
        speed = float(r["speed_m_per_s"])
        s = json.load(open(os.path.join(folder, f"v{speed:g}", "postProcessing", "summary.json")))
        for label, key in (("mean force 5-30 mm", "mean_force_5_30mm_N"), ("largest force", "max_force_N")):
            rows.append({"scene": f"rubble punch, reduced ({label})", "speed_m_per_s": speed, "seed": 1,
                         "figure": float(r[key]), "kinetic_to_work": s["kinetic_to_work_ratio"],
                         "kinetic_to_elastic_near_peak": s["kinetic_to_elastic_energy_near_peak"]})
    return rows


def with_changes(rows):
    """Each figure against its scene's slowest run (the first seed there)."""
    for scene in {r["scene"] for r in rows}:
        mine = [r for r in rows if r["scene"] == scene]
        slowest = min(mine, key=lambda r: (r["speed_m_per_s"], r["seed"]))
        for r in mine:
            r["change"] = r["figure"] / slowest["figure"] - 1
    return sorted(rows, key=lambda r: (r["scene"], -r["speed_m_per_s"], r["seed"]))


def table(rows):
    out = io.StringIO()
    writer = csv.DictWriter(out, list(rows[0]), lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    lines = ["| scene (figure) | speed [m/s] | seed | figure | change against the slowest | kinetic / work (median) "
             "| kinetic / elastic near the peak |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['scene']} | {r['speed_m_per_s']:g} | {r['seed']} | {r['figure']:.4g} | {100 * r['change']:+.1f} % "
                     f"| {r['kinetic_to_work']:.2e} | {r['kinetic_to_elastic_near_peak']:.2e} |")
    return out.getvalue(), "\n".join(lines) + "\n"


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    markers = ["o", "s", "^", "D"]
    for k, scene in enumerate(sorted({r["scene"] for r in rows})):
        mine = [r for r in rows if r["scene"] == scene]
        ax.scatter([r["kinetic_to_work"] for r in mine], [100 * r["change"] for r in mine], marker=markers[k % 4],
                   s=45, label=scene)
        for r in mine:
            ax.annotate(f"{r['speed_m_per_s']:g}", (r["kinetic_to_work"], 100 * r["change"]), fontsize=6,
                        textcoords="offset points", xytext=(3, 3))
    ax.axvline(KINETIC_LIMIT, color="k", ls="--", lw=1, label=f"limit on inertia-scaled runs ({KINETIC_LIMIT:g})")
    ax.axhline(0, color="grey", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("symlog", linthresh=10)
    ax.set_xlabel("kinetic energy / platen work, median over the loading")
    ax.set_ylabel("figure's change against the slowest run (%)")
    ax.set_title("Loading rate: kinetic energy against the answer (labels: platen speed, m/s)", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    iceCases.save_figure(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--speeds", type=iceCases.comma_list(iceCases.positive_number), default="0.4,0.2,0.1,0.05,0.025")
    parser.add_argument("--jobs", type=iceCases.whole_number(1), default=2)
    parser.add_argument("--out", default=os.path.join(HERE, "runs"))
    parser.add_argument("--publish", action="store_true")
    args = parser.parse_args()
    if args.publish:
        iceCases.publish_study(HERE, args.out, "rateMap", ("csv", "md", "png"), "rate map table", "csv")
        return
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        beam = list(pool.map(lambda v: beam_point(os.path.join(args.out, "rate"), v), args.speeds))
    rows = with_changes(beam + ridge_points() + punch_points())
    csv_text, md = table(rows)
    md += f"\n{time.strftime('%Y-%m-%d %H:%M')}, revision {iceCases.git_revision()}.\n"
    iceCases.write_study_outputs(args.out, "rateMap", {"csv": csv_text, "md": md})
    plot(rows, os.path.join(args.out, "rateMap.png"))
    print(md, end="")


if __name__ == "__main__":
    main()
