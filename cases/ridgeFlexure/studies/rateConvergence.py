#!/usr/bin/python3
"""Rate convergence of the ridge flexure test (physics.md section 7): one run of the matrix at
several platen speeds; the force should converge as the speed falls.

Each speed (and consolidated-layer packing seed) is a copy of the run under
runs/rate_<resolution>/runNN_v<speed>[_seedS]/ (finished ones are skipped, killed ones resume, both
only when made from the same inputs: iceCases.prepared_run).
Writes runs/rate_<resolution>/rateConvergence_<resolution>_runNN.csv and .md (per run: peak force, travel at
peak, the force averaged over +-1 mm at fixed travels, the kinetic to bond-energy ratio at the
peak, wall time; per speed with several seeds: the mean peak and its spread, which is the scale of
the fracture's chaos against which a rate effect must be judged) and a plot of force against
speed (.png). --publish runs nothing and writes them into the committed results/ folder
instead, and the table into the README ("rate convergence table"); it refuses unless every speed
and seed asked for is finished.

Usage: studies/rateConvergence.py [--resolution quick|default] [--run 6] [--speeds 0.2,0.1,0.05]
                                  [--seeds 1] [--jobs N] [--publish]
"""
import argparse
import concurrent.futures
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import ridgeMatrix  # noqa: E402
from ridgeMatrix import CASE, iceCases  # noqa: E402


TRAVELS_MM = (10, 20, 30, 40, 50)


def speed_dir(run, resolution, speed, seed):
    return os.path.join(CASE, "runs", "rate_" + resolution,
                        "run%02d_v%g%s" % (run["run"], speed, "" if seed == 1 else "_seed%d" % seed))


def prepare(run, resolution, speed, seed, folder):
    ridgeMatrix.prepare(run, resolution, folder)
    iceCases.set_entry(os.path.join(folder, "constant", "ridgeProperties"), "test.speed", speed)
    iceCases.set_entry(os.path.join(folder, "constant", "ridgeProperties"), "consolidatedLayer.seed", seed)


def execute(run, resolution, speed, seed):
    target = iceCases.prepared_run(speed_dir(run, resolution, speed, seed),
                                   lambda folder: prepare(run, resolution, speed, seed, folder),
                                   upstream=ridgeMatrix.upstream_files(run, resolution))
    if iceCases.finished(target):
        return target
    resume = os.path.exists(os.path.join(target, "DEM", "checkpoint"))
    iceCases.run_app("ridgeDEM", target, 1, ["-stage", "all"] + (["-resume"] if resume else []),
                     log_name="log.ridgeDEM")
    return target


def force_at(curve, travel_mm):
    """Mean force (kN) over +-1 mm of travel around travel_mm; '' past the curve's end."""
    near = [f for d, f in zip(curve["travel"], curve["force"]) if abs(d * 1e3 - travel_mm) <= 1.0]
    return round(sum(near) / len(near) * 1e-3, 3) if near else ""


def row(target, speed, seed):
    s = iceCases.summary(target)
    c = iceCases.curve(target)
    k = max(range(len(c["force"])), key=lambda i: c["force"][i])
    bond_energy = c["bondEnergy"][k]
    return {
        "speed_m_per_s": speed,
        "seed": seed,
        "peak_force_kN": round(s["peak_force_N"] * 1e-3, 3),
        "travel_at_peak_mm": round(s["travel_at_peak_m"] * 1e3, 2),
        **{"force_at_%dmm_kN" % d: force_at(c, d) for d in TRAVELS_MM},
        "kinetic_to_bond_energy_at_peak": round(c["kineticEnergy"][k] / bond_energy, 4) if bond_energy > 0 else "n/a",
        "broken_bonds": s["broken_bonds"],
        "wall_s": round(s["wall_s"], 1),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--resolution", choices=("quick", "default"), default="quick")
    parser.add_argument("--run", type=iceCases.whole_number(1), default=6)
    parser.add_argument("--speeds", type=iceCases.comma_list(iceCases.positive_number), default="0.2,0.1,0.05,0.025")
    parser.add_argument("--seeds", type=iceCases.comma_list(iceCases.whole_number(0)), default="1",
                        help="consolidated-layer packing seeds, e.g. 1,2,3")
    parser.add_argument("--jobs", type=iceCases.whole_number(1), default=max(1, min(2, os.cpu_count() or 1)))
    parser.add_argument("--publish", action="store_true",
                        help="run nothing; write the table of the finished runs into results/")
    args = parser.parse_args()
    speeds = sorted(args.speeds, reverse=True)
    seeds = args.seeds
    runs = {r["run"]: r for r in ridgeMatrix.matrix()}
    if args.run not in runs:
        parser.error(f"argument --run: {args.run} is not a run of ridgeMatrix.csv ({min(runs)}-{max(runs)})")
    run = runs[args.run]
    jobs = [(v, seed) for v in speeds for seed in seeds]
    if args.publish:
        missing = [speed_dir(run, args.resolution, v, seed) for v, seed in jobs
                   if not iceCases.finished(speed_dir(run, args.resolution, v, seed))]
        if missing:
            sys.exit("rateConvergence: not published: not finished: " + ", ".join(missing))
    else:
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            list(pool.map(lambda job: execute(run, args.resolution, *job), jobs))
    # Every run of the folder, so that seeds added later join the table.
    rows = []
    for v in speeds:
        for seed in sorted({seed for vv, seed in jobs if vv == v} | set(
                s for s in range(1, 100) if os.path.exists(os.path.join(
                    speed_dir(run, args.resolution, v, s), "postProcessing", "summary.json")))):
            rows.append(row(speed_dir(run, args.resolution, v, seed), v, seed))

    folder = os.path.join(CASE, "results") if args.publish else os.path.join(CASE, "runs", "rate_" + args.resolution)
    base = os.path.join(folder, "rateConvergence_%s_run%02d" % (args.resolution, args.run))
    os.makedirs(os.path.dirname(base), exist_ok=True)
    columns = list(rows[0].keys())
    iceCases.write_atomically(base + ".csv", "\n".join(
        [",".join(columns)] + [",".join(str(r[c]) for c in columns) for r in rows]) + "\n")
    md = ["Run %d (keel %s m, set %s, CL %d cm), %s resolution" % (
        run["run"], run["keel"], run["set"], run["cl_cm"], args.resolution), "",
        "| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    md += ["| " + " | ".join(str(r[c]) for c in columns) + " |" for r in rows]
    md += ["", "| speed_m_per_s | runs | mean peak [kN] | peak range [kN] | mean force at 30 mm [kN] |",
           "|---|---|---|---|---|"]
    for v in speeds:
        group = [r for r in rows if r["speed_m_per_s"] == v]
        peaks = [r["peak_force_kN"] for r in group]
        at30 = [r["force_at_30mm_kN"] for r in group if r["force_at_30mm_kN"] != ""]
        md.append("| %g | %d | %.3f | %.3f-%.3f | %s |" % (
            v, len(group), sum(peaks) / len(peaks), min(peaks), max(peaks),
            "%.3f" % (sum(at30) / len(at30)) if at30 else "-"))
    iceCases.write_atomically(base + ".md", "\n".join(md) + "\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogx([r["speed_m_per_s"] for r in rows], [r["peak_force_kN"] for r in rows], "o",
                label="peak (each seed)")
    for d in TRAVELS_MM[1:4]:
        pts = [(r["speed_m_per_s"], r["force_at_%dmm_kN" % d]) for r in rows if r["force_at_%dmm_kN" % d] != ""]
        ax.semilogx([p[0] for p in pts], [p[1] for p in pts], ".-", label="force at %d mm" % d)
    ax.set_xlabel("platen speed (m/s)")
    ax.set_ylabel("force (kN)")
    ax.legend(fontsize=8)
    ax.set_title("Ridge flexure run %d (%s): force against speed" % (run["run"], args.resolution))
    ax.grid(True, which="both", alpha=0.3)
    iceCases.save_figure(fig, base + ".png", dpi=120)
    if args.publish:
        iceCases.write_readme_table(os.path.join(CASE, "README.md"), "rate convergence table",
                                    "studies/rateConvergence.py --publish", "results/%s.md" % os.path.basename(base),
                                    "\n".join(md))
    print(open(base + ".md").read())


if __name__ == "__main__":
    main()
