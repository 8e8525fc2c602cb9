#!/usr/bin/python3
"""Regression guard (issue 20 item 5): three quick points whose figures and speed are kept in a
committed table, so that a change of the code that moves an answer beyond its seed scatter, or
slows a scene down, shows up in a fast test.

  point          case (application)                      figures                        seeds
  beam           levelIceBeam (iceBeamDEM), 400 particles,  elastic slope, first peak    packing 1-5
                 platen 0.2 m/s
  tension        freezeBondTension (freezeBondTensionDEM),  bond strength, peak force    none: the
                 tests 1-3 (25.2 kPa, 30 min)                                           packing is fixed
  floatingBlock  floatingBlock (floatingBlockDEM),          submerged volume fraction,   none: a lattice
                 hydrostatic, the first 2 s                 draft

  measure   runs every point (the beam at each seed of --seeds) in OUT/runs/, writes
            OUT/guard.csv: one row a point and seed (figures, wall time, particle-steps/s, load)
            and OUT/guard.md (per point and figure: seed 1's value, the seeds' mean and standard
            deviation, the tolerance the check uses)
  publish   copies OUT/guard.{csv,md} into results/ and the table into README.md
  check     runs each point at seed 1 in OUT/check/ and compares with results/guard.csv: each
            figure within its tolerance (2 standard deviations of the seeds where the point has
            them; 1e-6 relative where it is deterministic; a figure that moved at all is marked
            "moved" even within it), and its particle-steps/s at least half
            the committed (the machines are shared: a real slowdown, not the noise); exit 1 with
            the figures that moved

usage: regressionGuard.py measure [--out DIR] [--seeds 1,2,3,4,5] [--bin DIR]
       regressionGuard.py publish [--out DIR]
       regressionGuard.py check [--out DIR] [--bin DIR]
  --bin: the folder of the applications (default build/demModels)"""
import argparse
import csv
import io
import json
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402

DETERMINISTIC_TOLERANCE = 1e-6     # relative: the same code and compiler give the same bits
SCATTER_WIDTHS = 2                 # standard deviations of the seeds: 95 % of packings
SPEED_FLOOR = 0.5                  # of the committed particle-steps/s
BIN = os.path.join(iceCases.BUILD, "demModels")     # the applications (--bin)


def app(name):
    return os.path.join(BIN, name)


def run_beam(folder, seed):
    case = iceCases.copy_case(os.path.join(TOP, "cases", "levelIceBeam"), folder)
    props = os.path.join(case, "constant", "beamProperties")
    iceCases.set_entry(props, "packing.seed", seed)
    iceCases.set_entry(props, "platen.speed", 0.2)
    iceCases.set_entry(os.path.join(case, "system", "controlDict"), "writeInterval", 10)
    iceCases.run_app(app("iceBeamDEM"), case, 1, ["-particles", "400"], "log.run")
    s = iceCases.summary(case)
    return {"slope_N_per_m": s["elastic_slope_N_per_m"], "first_peak_N": s["first_peak_force_N"]}, s


def run_tension(folder, seed):
    case = iceCases.copy_case(os.path.join(TOP, "cases", "freezeBondTension"), folder)
    iceCases.run_app(app("freezeBondTensionDEM"), case, 1,
                     ["-label", "tests_1-3", "-pressure", "25200", "-time", "30"], "log.run")
    s = json.load(open(os.path.join(case, "postProcessing", "runs", "tests_1-3", "summary.json")))
    s["particle_steps_per_s"] = s["particles"] * s["steps"] / max(s["wall_s"], 1e-9)
    return {"strength_Pa": s["strength_Pa"], "peak_force_N": s["peak_force_N"]}, s


def run_floating_block(folder, seed):
    case = iceCases.copy_case(os.path.join(TOP, "cases", "floatingBlock"), folder)
    iceCases.set_entry(os.path.join(case, "system", "controlDict"), "endTime", 2)
    iceCases.run_app(app("floatingBlockDEM"), case, 1, [], "log.run")
    s = iceCases.summary(case)
    s["particle_steps_per_s"] = s["particles"] * s["steps"] / max(s["wall_s"], 1e-9)
    return {"submerged_fraction": s["submerged_volume_fraction"], "draft_m": s["draft_m"]}, s


# name: (run, seeded)
POINTS = {"beam": (run_beam, True), "tension": (run_tension, False), "floatingBlock": (run_floating_block, False)}


def run_point(name, seed, folder):
    run, _ = POINTS[name]
    start = time.time()
    figures, summary = run(folder, seed)
    return {"point": name, "seed": seed, **{f"figure:{k}": v for k, v in figures.items()},
            "wall_s": round(time.time() - start, 2),
            "particle_steps_per_s": round(summary["particle_steps_per_s"], -3),
            "load_average": round(os.getloadavg()[0], 2)}


def write_table(rows, path):
    fields = list(dict.fromkeys(k for r in rows for k in r))
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=fields, lineterminator="\n", restval="")
    writer.writeheader()
    writer.writerows(rows)
    iceCases.write_atomically(path, text.getvalue())


def read_table(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def tolerances(rows):
    """Per point and figure: seed 1's value, the seeds' mean and standard deviation, and the
    tolerance (absolute) of the check."""
    out = {}
    for name in POINTS:
        mine = [r for r in rows if r["point"] == name]
        for key in [k for k in mine[0] if k.startswith("figure:") and mine[0][k] != ""]:
            values = [float(r[key]) for r in mine]
            first = float(next(r for r in mine if int(r["seed"]) == 1)[key])
            sd = statistics.stdev(values) if len(values) > 1 else 0.0
            seeded = POINTS[name][1]
            tol = SCATTER_WIDTHS * sd if seeded else DETERMINISTIC_TOLERANCE * abs(first)
            out[(name, key[len("figure:"):])] = {"seed1": first, "mean": statistics.mean(values), "sd": sd,
                                                 "seeds": len(values), "tolerance": tol}
    return out


def markdown(rows):
    lines = ["| point | figure | seed 1 | seeds: mean / standard deviation | tolerance of the check | "
             "particle-steps/s (seed 1) |", "|---|---|---|---|---|---|"]
    speeds = {r["point"]: float(r["particle_steps_per_s"]) for r in rows if int(r["seed"]) == 1}
    for (name, figure), t in tolerances(rows).items():
        scatter = f"{t['mean']:.6g} / {t['sd']:.3g} ({t['seeds']} seeds)" if POINTS[name][1] else "deterministic"
        tol = (f"{SCATTER_WIDTHS} sd = {t['tolerance']:.3g}" if POINTS[name][1]
               else f"{DETERMINISTIC_TOLERANCE:g} relative")
        lines.append(f"| {name} | {figure} | {t['seed1']:.6g} | {scatter} | {tol} | {speeds[name]:.3g} |")
    return "\n".join(lines) + "\n"


def measure(out, seeds):
    rows = []
    for name, (_, seeded) in POINTS.items():
        for seed in (seeds if seeded else [1]):
            print(f"{name}, seed {seed} ...", flush=True)
            rows.append(run_point(name, seed, os.path.join(out, "runs", f"{name}-seed{seed}")))
    # A deterministic point twice: its figures must repeat to the bit, or it is not deterministic.
    for name, (_, seeded) in POINTS.items():
        if not seeded:
            again = run_point(name, 1, os.path.join(out, "runs", f"{name}-again"))
            first = next(r for r in rows if r["point"] == name)
            moved = [k for k in first if k.startswith("figure:") and first[k] != again[k]]
            if moved:
                sys.exit(f"regressionGuard.py: {name} is not deterministic: {moved} differ between two runs")
    write_table(rows, os.path.join(out, "guard.csv"))
    md = markdown(rows) + (f"\nMeasured {time.strftime('%Y-%m-%d %H:%M')} at revision {iceCases.git_revision()}, "
                           f"1 rank a point, load average {os.getloadavg()[0]:.1f} at the end.\n")
    iceCases.write_atomically(os.path.join(out, "guard.md"), md)
    print(md, end="")


def check(out):
    committed = read_table(os.path.join(HERE, "results", "guard.csv"))
    limits = tolerances(committed)
    speeds = {r["point"]: float(r["particle_steps_per_s"]) for r in committed if int(r["seed"]) == 1}
    failures = 0
    for name in POINTS:
        row = run_point(name, 1, os.path.join(out, "check", name))
        for key in [k for k in row if k.startswith("figure:")]:
            figure = key[len("figure:"):]
            t = limits[(name, figure)]
            value, difference = float(row[key]), float(row[key]) - t["seed1"]
            ok = abs(difference) <= t["tolerance"]
            failures += not ok
            same = abs(difference) <= DETERMINISTIC_TOLERANCE * abs(t["seed1"])
            print(f"{'ok  ' if ok else 'FAIL'} {name} {figure}: {value:.7g} against {t['seed1']:.7g} committed "
                  f"({'unchanged' if same else 'moved'}: difference {difference:+.3g}, tolerance {t['tolerance']:.3g})")
        speed = float(row["particle_steps_per_s"])
        ok = speed >= SPEED_FLOOR * speeds[name]
        failures += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {name} speed: {speed:.3g} particle-steps/s against {speeds[name]:.3g} "
              f"committed (at least {SPEED_FLOOR:g} of it; load average {row['load_average']})")
    return failures


def main():
    global BIN
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("action", choices=("measure", "publish", "check"))
    parser.add_argument("--out", default=os.path.join(HERE, "runs"))
    parser.add_argument("--seeds", type=iceCases.comma_list(iceCases.whole_number(1)), default="1,2,3,4,5")
    parser.add_argument("--bin", default=BIN)
    args = parser.parse_args()
    BIN = os.path.abspath(args.bin)
    if args.action == "measure":
        if 1 not in args.seeds:
            parser.error("argument --seeds: must hold 1 (the check runs seed 1)")
        measure(args.out, args.seeds)
    elif args.action == "publish":
        results = os.path.join(HERE, "results")
        iceCases.publish_files([os.path.join(args.out, f"guard.{ext}") for ext in ("csv", "md")], results)
        iceCases.write_readme_table(os.path.join(HERE, "README.md"), "guard table",
                                    "studies/regressionGuard/regressionGuard.py publish",
                                    "studies/regressionGuard/results/guard.csv",
                                    open(os.path.join(results, "guard.md")).read())
    else:
        sys.exit(1 if check(args.out) else 0)


if __name__ == "__main__":
    main()
