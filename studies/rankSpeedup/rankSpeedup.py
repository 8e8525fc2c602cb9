#!/usr/bin/python3
"""The 2-rank speed-up of the punch and a ridge run (issue 17, goal 3: at least 1.8), measured on
the loading loop of each: a window of platen travel from the case's own finished run (its saved
ridge; the same windows as studies/waterLevels), on 1 and on 2 ranks, alternated --pairs times so
that each pair sees the same machine. The speed-up of a pair is the 1-rank loop's wall time per
simulated second over the 2-rank one's; the table gives each pair and the median.

usage: rankSpeedup.py [--pairs 2] [--travel 0.002] [--out DIR] [--publish]
  writes OUT/rankSpeedup.{json,md} (default runs/); --publish copies them into results/ and the
  table into this folder's README.md."""
import argparse
import json
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(TOP, "studies", "waterLevels"))
import waterLevelChart  # noqa: E402
from waterLevelChart import CASES, iceCases  # noqa: E402

SCENES = [
    ("rubble punch (cuboid keel, 7,069 particles, 5 mm/s)", "punch", os.path.join(CASES, "rubblePunch", "runs", "cuboid")),
    ("ridge run 6 (default resolution, 9,269 particles, 0.05 m/s)", "ridge",
     os.path.join(CASES, "ridgeFlexure", "runs", "default", waterLevelChart.RIDGE_RUN)),
]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pairs", type=iceCases.whole_number(1), default=2)
    parser.add_argument("--travel", type=iceCases.positive_number, default=0.002)
    parser.add_argument("--out", default=os.path.join(HERE, "runs"))
    parser.add_argument("--publish", action="store_true")
    args = parser.parse_args()
    if args.publish:
        iceCases.publish_study(HERE, args.out, "rankSpeedup", ("json", "md"), "rank speed-up table", "json")
        return
    work = os.path.join(args.out, "windows")
    rows = []
    for title, name, source in SCENES:
        pairs = []
        for k in range(args.pairs):
            one = waterLevelChart.loading_cost(work, name, source, "hydrostatic", args.travel, 1)[0]
            two = waterLevelChart.loading_cost(work, name, source, "hydrostatic", args.travel, 2)[0]
            pairs.append({"one_rank_wall_per_simulated_s": round(one, 2), "two_ranks_wall_per_simulated_s": round(two, 2),
                          "speedup": round(one / two, 3)})
            print(title, json.dumps(pairs[-1]), flush=True)
        rows.append({"scene": title, "pairs": pairs, "median_speedup": statistics.median(p["speedup"] for p in pairs)})
    report = {"rows": rows, "travel_m": args.travel, "target": 1.8, "load_average_at_end": os.getloadavg()[0],
              "date": time.strftime("%Y-%m-%d %H:%M"), "revision": iceCases.git_revision()}
    lines = ["| scene | 1 rank (wall s per simulated s) | 2 ranks | speed-up | median |", "|---|---|---|---|---|"]
    for r in rows:
        for k, p in enumerate(r["pairs"]):
            median = f"**{r['median_speedup']:.2f}**" if k == 0 else ""
            lines.append(f"| {r['scene'] if k == 0 else ''} | {p['one_rank_wall_per_simulated_s']:.1f} "
                         f"| {p['two_ranks_wall_per_simulated_s']:.1f} | {p['speedup']:.2f} | {median} |")
    md = "\n".join(lines) + (f"\n\nTarget 1.8 (issue 17). Loading loops of {1e3 * args.travel:g} mm of travel, "
                             f"{report['date']}, load average {report['load_average_at_end']:.1f} at the end.\n")
    iceCases.write_study_outputs(args.out, "rankSpeedup", {"json": json.dumps(report, indent=2) + "\n", "md": md})
    print(md, end="")


if __name__ == "__main__":
    main()
