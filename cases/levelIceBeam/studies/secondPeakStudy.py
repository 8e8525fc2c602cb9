#!/usr/bin/python3
"""What sets the second load peak of the side-loaded beam (the arch the two
halves form between the rigid end pads after the centre crack)? Reruns the
calibrated beam with one contact or damping parameter changed at a time and
reports the first (centre-crack) peak, the highest load and their ratio.

    ./secondPeakStudy.py [-particles 1200] [-platenSpeed 0.1] [-seeds 1 2] [-jobs 1]
                         [-variants base mu0.1 ...]

Resumable: a finished run made from the same inputs is not repeated. Writes
(into -out, default ../runs/secondPeakStudy; -publish copies them into studies/secondPeakStudy/)
results.csv and results.md (mean over the seeds per variant)."""
import argparse
import concurrent.futures
import csv
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "postProcessing"))
import iceCases  # noqa: E402

ICE = "constant/iceProperties"
# name: [(file, entry, value)], each a change from the calibrated case.
VARIANTS = {
    "base": [],
    "mu0.1": [(ICE, "material.frictionCoefficient", "0.1")],
    "mu0.2": [(ICE, "material.frictionCoefficient", "0.2")],
    "mu0.5": [(ICE, "material.frictionCoefficient", "0.5")],
    "muR0.01": [(ICE, "material.rollingFrictionCoefficient", "0.01")],
    "muR0.2": [(ICE, "material.rollingFrictionCoefficient", "0.2")],
    "alpha0.01": [(ICE, "damping.hystereticCoeffs.alpha", "0.01")],
    "beta1.5": [(ICE, "bondFamilies.ice.beta", "1.5")],
}


def run_one(name, seed, out, particles, speed):
    def prepare(folder):
        iceCases.copy_case(os.path.join(here, ".."), folder)
        for relative, entry, value in VARIANTS[name]:
            iceCases.set_entry(os.path.join(folder, relative), entry, value)
        iceCases.set_entry(os.path.join(folder, "constant", "beamProperties"), "packing.seed", seed)

    args = ["-particles", particles, "-platenSpeed", speed]
    case = iceCases.prepared_run(os.path.join(out, f"{name}_seed{seed}"), prepare, settings=args)
    if not iceCases.finished(case):
        iceCases.run_app("iceBeamDEM", case, 1, args, "log.iceBeamDEM")
    s = iceCases.summary(case)
    return {
        "variant": name, "seed": seed,
        "slope_MN_per_m": s["elastic_slope_N_per_m"] / 1e6,
        "first_peak_kN": s["first_peak_force_N"] / 1e3,
        "highest_kN": s["peak_force_N"] / 1e3,
        "ratio": s["peak_force_N"] / s["first_peak_force_N"],
        "travel_at_highest_mm": 1e3 * s["travel_at_peak_m"],
        "wall_s": s["wall_s"],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("-particles", type=iceCases.whole_text(20), default="1200")
    parser.add_argument("-platenSpeed", type=iceCases.positive_text, default="0.1")
    parser.add_argument("-seeds", nargs="+", type=iceCases.whole_text(0), default=["1", "2"])
    parser.add_argument("-jobs", type=iceCases.whole_number(1), default=1)
    parser.add_argument("-variants", nargs="+", default=list(VARIANTS))
    parser.add_argument("-out", default=os.path.join(here, "..", "runs", "secondPeakStudy"))
    parser.add_argument("-publish", action="store_true",
                        help="run nothing; copy the results in -out into the committed studies/secondPeakStudy/ "
                             "and the table into the README")
    args = parser.parse_args()
    if args.publish:
        iceCases.publish_files([os.path.join(args.out, f) for f in ("results.csv", "results.md")],
                               os.path.join(here, "secondPeakStudy"))
        iceCases.write_readme_table(os.path.join(here, "..", "README.md"), "second peak table",
                                    "studies/secondPeakStudy.py -publish", "studies/secondPeakStudy/results.md",
                                    open(os.path.join(here, "secondPeakStudy", "results.md")).read())
        return
    unknown = [v for v in args.variants if v not in VARIANTS]
    if unknown:
        sys.exit(f"secondPeakStudy: unknown variant(s) {unknown}; allowed: {list(VARIANTS)}")

    out = args.out
    os.makedirs(out, exist_ok=True)
    work = [(v, s) for v in args.variants for s in args.seeds]
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        rows = list(pool.map(lambda w: run_one(w[0], w[1], out, args.particles, args.platenSpeed), work))

    keys = list(rows[0])
    with open(os.path.join(out, "results.csv.tmp"), "w", newline="") as f:
        writer = csv.DictWriter(f, keys)
        writer.writeheader()
        writer.writerows(rows)
    os.replace(os.path.join(out, "results.csv.tmp"), os.path.join(out, "results.csv"))

    lines = [f"{args.particles} particles, platen {args.platenSpeed} m/s, mean over seeds {' '.join(args.seeds)}",
             "", "| variant | slope [MN/m] | first peak [kN] | highest load [kN] | highest / first |",
             "|---|---|---|---|---|"]
    for v in args.variants:
        mine = [r for r in rows if r["variant"] == v]
        mean = {k: sum(r[k] for r in mine) / len(mine) for k in ("slope_MN_per_m", "first_peak_kN", "highest_kN", "ratio")}
        lines.append(f"| {v} | {mean['slope_MN_per_m']:.2f} | {mean['first_peak_kN']:.1f} | "
                     f"{mean['highest_kN']:.1f} | {mean['ratio']:.2f} |")
    iceCases.write_atomically(os.path.join(out, "results.md"), "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
