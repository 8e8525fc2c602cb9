#!/usr/bin/python3
"""Scatter of the flexural strength over random packings: the case's calibrated inputs run for
every thickness with several packing seeds (constant/bendingProperties packing.seed).

    studies/seedScatter.py [-thickness 0.10 0.15 0.20] [-seeds 1 2 3] [-jobs 2] [-out DIR] [-publish]

A single packing is one sample of a random solid, as one laboratory beam is; the calibration
target is the regression through thousands of beams, so what should meet it is the mean over
packings. Resumable (a finished run made from the same inputs is skipped; iceCases.prepared_run). Runs go to runs/seedScatter_breakN<value>/
unless -out says otherwise, and so do seedScatter_breakN<value>.csv (per run) and .md (per run,
then per thickness: mean, sample standard deviation and the mean's error against the target),
named by the case's bondFamilies.ice.breakN. -publish runs nothing and writes the two tables into
the committed results/ folder instead; it refuses unless every run asked for is finished."""
import argparse
import concurrent.futures
import math
import os
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(CASE, "..", "..", "postProcessing"))
import iceCases  # noqa: E402


def run_one(out, thickness, seed):
    def prepare(folder):
        iceCases.copy_case(CASE, folder)
        iceCases.set_entry(os.path.join(folder, "constant", "bendingProperties"), "packing.seed", seed)

    case = iceCases.prepared_run(os.path.join(out, f"D{thickness}_seed{seed}"), prepare, settings=[thickness])
    if iceCases.finished(case):
        return case
    iceCases.run_app("threePointBendingDEM", case, 1, ["-thickness", thickness], "log.threePointBendingDEM")
    return case


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-thickness", nargs="+", type=iceCases.positive_text, default=["0.10", "0.15", "0.20"])
    p.add_argument("-seeds", nargs="+", type=iceCases.whole_number(0), default=[1, 2, 3])
    p.add_argument("-jobs", type=iceCases.whole_number(1), default=2)
    p.add_argument("-out", default=None)
    p.add_argument("-publish", action="store_true", help="run nothing; write the tables into results/")
    a = p.parse_args()
    label = "breakN" + iceCases.get_entry(os.path.join(CASE, "constant", "iceProperties"), "bondFamilies.ice.breakN")
    a.out = a.out or os.path.join(CASE, "runs", "seedScatter_" + label)
    os.makedirs(a.out, exist_ok=True)
    jobs = sorted(((d, s) for d in a.thickness for s in a.seeds), key=lambda j: -float(j[0]))
    if a.publish:
        missing = [os.path.join(a.out, f"D{d}_seed{s}") for d, s in jobs
                   if not iceCases.finished(os.path.join(a.out, f"D{d}_seed{s}"))]
        if missing:
            sys.exit("seedScatter: not published: not finished: " + ", ".join(missing))
        runs = {(d, s): iceCases.summary(os.path.join(a.out, f"D{d}_seed{s}")) for d, s in jobs}
    else:
        with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
            cases = {job: pool.submit(run_one, a.out, *job) for job in jobs}
            runs = {job: iceCases.summary(f.result()) for job, f in cases.items()}

    head = ["thickness_m", "seed", "particles", "failure_force_N", "sigma_f_kPa", "target_kPa", "error",
            "KE_over_elastic_at_peak", "steps", "wall_s"]
    rows = []
    for (d, seed), s in sorted(runs.items(), key=lambda kv: (float(kv[0][0]), kv[0][1])):
        rows.append([f"{float(d):.2f}", str(seed), str(s["particles"]), f"{s['failure_force_N']:.1f}",
                     f"{s['flexural_strength_Pa'] / 1e3:.1f}", f"{s['target_strength_Pa'] / 1e3:.0f}",
                     f"{s['strength_error']:+.4f}", f"{s['kinetic_to_elastic_energy_at_peak']:.2g}",
                     str(s["steps"]), f"{s['wall_s']:.0f}"])
    md = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)] + ["| " + " | ".join(r) + " |" for r in rows]
    md += ["", "| thickness_m | seeds | mean sigma_f [kPa] | std [kPa] | target [kPa] | error of the mean | "
           "largest single error |", "|---|---|---|---|---|---|---|"]
    for d in sorted({d for d, _ in runs}, key=float):
        group = [s for (dd, _), s in runs.items() if dd == d]
        strengths = [s["flexural_strength_Pa"] for s in group]
        target = group[0]["target_strength_Pa"]
        mean = statistics.fmean(strengths)
        std = statistics.stdev(strengths) if len(strengths) > 1 else math.nan
        worst = max((s["strength_error"] for s in group), key=abs)
        md.append(f"| {float(d):.2f} | {len(group)} | {mean / 1e3:.1f} | {std / 1e3:.1f} | {target / 1e3:.0f} | "
                  f"{mean / target - 1:+.1%} | {worst:+.1%} |")
    results = os.path.join(CASE, "results") if a.publish else a.out
    os.makedirs(results, exist_ok=True)
    iceCases.write_atomically(os.path.join(results, f"seedScatter_{label}.csv"),
                              "\n".join(",".join(r) for r in [head] + rows) + "\n")
    iceCases.write_atomically(os.path.join(results, f"seedScatter_{label}.md"), "\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
