#!/usr/bin/python3
"""Calibration sweep of the three-point bending beams: runs the case for every
combination of thickness, platen speed and iceProperties entry values given,
and tabulates flexural strength against the targets.

    ./calibrate.py -thickness 0.10 0.15 0.20 -set bondFamilies.ice.breakN 0.002 0.0025 \
                   [-speeds 0.1 0.05] [-quick] [-ranks 1] [-jobs 2] [-label NAME]

Resumable (a finished run made from the same inputs is not rerun); the tables cover every run in
the output folder, so later invocations add rows. Writes (into -out, default ../runs/calibration; -publish copies them into studies/calibration/)
results.csv
and calibration/results.md: per run the values set, thickness, speed, failure
force, sigma_f, its error against the target, effective modulus, kinetic/elastic
energy at the peak, particles, steps and wall time; and per parameter set and
speed the largest |error| over the thicknesses run."""
import argparse
import concurrent.futures
import glob
import itertools
import json
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
case_dir = os.path.dirname(here)
sys.path.insert(0, os.path.join(here, "..", "..", "..", "postProcessing"))
import iceCases  # noqa: E402


def run_one(out, quick, thickness, speed, entries, ranks):
    name = "_".join([("quick" if quick else "std"), f"D{thickness}", f"v{speed}"]
                    + [f"{k.split('.')[-1]}{v}" for k, v in entries])
    args = ["-thickness", thickness, "-platenSpeed", speed] + (["-quick"] if quick else [])

    def prepare(folder):
        iceCases.copy_case(case_dir, folder)
        ice = os.path.join(folder, "constant", "iceProperties" + (".quick" if quick else ""))
        for key, value in entries:
            iceCases.set_entry(ice, key, value)
        json.dump(dict(entries), open(os.path.join(folder, "entries.json"), "w"))

    case = iceCases.prepared_run(os.path.join(out, name), prepare, settings=args)
    if iceCases.finished(case):
        return case
    iceCases.run_app("threePointBendingDEM", case, ranks, args, "log.threePointBendingDEM")
    return case


def load(case):
    s = iceCases.summary(case)
    entries = json.load(open(os.path.join(case, "entries.json")))
    return dict(s, entries=entries, case=os.path.basename(case))


def tables(runs):
    keys = sorted({k for r in runs for k in r["entries"]})
    head = ["resolution"] + keys + ["thickness_m", "speed_m_per_s", "failure_force_N", "sigma_f_kPa",
                                    "target_kPa", "error", "E_eff_GPa", "KE_over_elastic_at_peak",
                                    "particles", "steps", "wall_s"]
    rows = []
    for r in sorted(runs, key=lambda r: (r["resolution"], [str(r["entries"].get(k)) for k in keys],
                                         r["platen_speed_m_per_s"], r["thickness_m"])):
        rows.append([r["resolution"]] + [str(r["entries"].get(k, "")) for k in keys]
                    + [f"{r['thickness_m']:.2f}", f"{r['platen_speed_m_per_s']:g}",
                       f"{r['failure_force_N']:.1f}", f"{r['flexural_strength_Pa'] / 1e3:.1f}",
                       f"{r['target_strength_Pa'] / 1e3:.0f}", f"{r['strength_error']:+.4f}",
                       f"{r['effective_modulus_Pa'] / 1e9:.3f}", f"{r['kinetic_to_elastic_energy_at_peak']:.2g}",
                       str(r["particles"]), str(r["steps"]), f"{r['wall_s']:.0f}"])
    csv_text = "\n".join(",".join(row) for row in [head] + rows)
    md = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)] + ["| " + " | ".join(r) + " |" for r in rows]
    groups = {}
    for r in runs:
        key = (r["resolution"], tuple(str(r["entries"].get(k, "")) for k in keys), r["platen_speed_m_per_s"])
        groups.setdefault(key, []).append(r)
    md += ["", "| resolution | " + " | ".join(keys) + " | speed | thicknesses | largest error |",
           "|" + "---|" * (len(keys) + 4)]
    for key, group in sorted(groups.items()):
        worst = max(group, key=lambda r: abs(r["strength_error"]))
        md.append(f"| {key[0]} | " + " | ".join(key[1]) + f" | {key[2]:g} | "
                  + " ".join(f"{r['thickness_m']:.2f}" for r in sorted(group, key=lambda r: r["thickness_m"]))
                  + f" | {worst['strength_error']:+.1%} |")
    return csv_text + "\n", "\n".join(md) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-thickness", nargs="+", type=iceCases.positive_text, default=["0.10", "0.15", "0.20"])
    p.add_argument("-speeds", nargs="+", type=iceCases.positive_text, default=["0.1"])
    p.add_argument("-set", nargs="+", action="append", default=[], metavar=("ENTRY", "VALUE"),
                   help="an iceProperties entry (dotted path) and the values to try; repeatable")
    p.add_argument("-quick", action="store_true")
    p.add_argument("-ranks", type=iceCases.whole_number(1), default=1)
    p.add_argument("-jobs", type=iceCases.whole_number(1), default=2)
    p.add_argument("-out", default=os.path.join(here, "..", "runs", "calibration"))
    p.add_argument("-publish", action="store_true",
                   help="run nothing; copy the results in -out into the committed studies/calibration/")
    a = p.parse_args()
    if a.publish:
        iceCases.publish_files([os.path.join(a.out, f) for f in ("results.csv", "results.md")],
                               os.path.join(here, "calibration"))
        return
    os.makedirs(a.out, exist_ok=True)
    axes = [[(s[0], v) for v in s[1:]] for s in a.set]
    jobs = [(d, v, combo) for combo in itertools.product(*axes) for v in a.speeds for d in a.thickness]
    # Thickest first: the longest runs start early.
    jobs.sort(key=lambda j: -float(j[0]))
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        for f in [pool.submit(run_one, a.out, a.quick, d, v, combo, a.ranks) for d, v, combo in jobs]:
            f.result()
    runs = [load(os.path.dirname(os.path.dirname(s)))
            for s in sorted(glob.glob(os.path.join(a.out, "*", "postProcessing", "summary.json")))]
    csv_text, md = tables(runs)
    iceCases.write_atomically(os.path.join(a.out, "results.csv"), csv_text)
    iceCases.write_atomically(os.path.join(a.out, "results.md"), md)
    print(md)


if __name__ == "__main__":
    main()
