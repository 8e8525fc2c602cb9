#!/usr/bin/python3
"""Speed of the bonded-ice model, in one run on one core each:

1. iceBeamDEM: the bonded beam (bonds in fix external, contacts in LIGGGHTS);
2. the same packing, platen and contacts in plain LIGGGHTS, no bonds
   (the `liggghts` binary on the scene's own input script);
3. Yade's cohesive-frictional bonded model (CohFrictMat, ScGeom6D,
   Law2_ScGeom6D_CohFrictPhys_CohesionMoment) on the same packing, time step,
   pads and platen.

    ./benchmark.py [-particles 13000] [-steps 2000] [-repeats 3] [-out DIR] [-publish]

The bonded and the plain run alternate -repeats times (the machine is shared
and its speed drifts: a pair run back to back sees the same machine); each
model's row gives its median loop time, and the cost ratio is the median of
the pairs' ratios, with their range. Yade runs once.

Needs Debian's Yade besides the project's own packages: apt-get install yade.

Reports particle-steps per second of the stepping loop (set-up excluded), the
ratios, and peak resident memory (/usr/bin/time -v). Writes benchmark.json (for
programs) and benchmark.md (for the README) into -out (default ../runs/benchmark);
-publish runs nothing and copies those two into the committed studies/benchmark/."""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "postProcessing"))
import iceCases  # noqa: E402

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1")


def timed(cmd, cwd, log):
    """Runs cmd under /usr/bin/time -v; returns (wall s, peak RSS MiB)."""
    timing = os.path.join(cwd, log + ".time")
    start = time.time()
    with open(os.path.join(cwd, log), "w") as out:
        r = subprocess.run(["/usr/bin/time", "-v", "-o", timing, *cmd], cwd=cwd, stdout=out,
                           stderr=subprocess.STDOUT, env=ENV)
    wall = time.time() - start
    if r.returncode != 0:
        raise RuntimeError(f"{cmd} failed, see {os.path.join(cwd, log)}")
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", open(timing).read()).group(1))
    return wall, rss / 1024.0


def run_bonded(app, case, particles, steps, ranks=1):
    """The bonded beam (iceBeamDEM) on `ranks` ranks; peak RSS: the largest rank's."""
    _, rss = timed(["mpirun", "-np", str(ranks), "--oversubscribe", app, "-case", case, "-particles", str(particles),
                    "-steps", str(steps)], case, "log.bonded")
    s = iceCases.summary(case)
    return {"model": "iceBeamDEM bonded (this project)", "particles": s["particles"], "bonds": s["bonds"],
            "steps": s["steps"], "dt": s["dt"], "loop_wall_s": s["loop_wall_s"],
            "particle_steps_per_s": s["particle_steps_per_s"], "peak_rss_MiB": rss}


def run_granular(script, case, dt):
    """The same packing, platen and contacts in plain LIGGGHTS, no bonds."""
    _, rss = timed(["liggghts", "-in", script, "-log", os.path.join(case, "log.liggghts.granular")], case,
                   "log.granular")
    loop = re.search(r"Loop time of ([\d.e+-]+) on \d+ procs for (\d+) steps with (\d+) atoms",
                     open(os.path.join(case, "log.granular")).read())
    wall, steps, atoms = float(loop.group(1)), int(loop.group(2)), int(loop.group(3))
    return {"model": "LIGGGHTS 3.8 granular contacts, no bonds", "particles": atoms, "bonds": 0,
            "steps": steps, "dt": dt, "loop_wall_s": wall,
            "particle_steps_per_s": atoms * steps / wall, "peak_rss_MiB": rss}


def median_run(runs):
    """The run with the median loop time (the lower middle one of an even count)."""
    return sorted(runs, key=lambda r: r["loop_wall_s"])[(len(runs) - 1) // 2]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-particles", type=iceCases.whole_number(20), default=13000)
    p.add_argument("-steps", type=iceCases.whole_number(1), default=2000)
    p.add_argument("-repeats", type=iceCases.whole_number(1), default=3, help="bonded/plain pairs run back to back")
    p.add_argument("-out", default=os.path.join(here, "..", "runs", "benchmark"))
    p.add_argument("-publish", action="store_true", help="run nothing; copy -out's benchmark.json and .md into studies/benchmark/")
    p.add_argument("-noYade", action="store_true",
                   help="the bonded and plain pairs only (no Yade installed); not for -publish")
    a = p.parse_args()
    if a.publish:
        iceCases.publish_files([os.path.join(a.out, n) for n in ("benchmark.json", "benchmark.md")],
                               os.path.join(here, "benchmark"))
        return
    if shutil.which("yade") is None and not a.noYade:
        sys.exit("benchmark.py: Yade is not installed; run: apt-get install yade (or -noYade: the bonded and plain pairs only)")
    load_start = os.getloadavg()[0]   # the machine may be shared: timings are only comparable at low load
    case = iceCases.copy_case(os.path.join(here, ".."), os.path.join(a.out, "case"))
    app = os.path.join(iceCases.BUILD, "demModels", "iceBeamDEM")
    bench = os.path.join(case, "DEM", "in.benchmarkGranular")
    with open(bench, "w") as f:
        f.write(f"include {case}/DEM/variables.generated\ninclude {case}/DEM/in.levelIceBeam\n"
                f"thermo 0\nrun {a.steps}\n")
    bonded_runs, granular_runs = [], []
    for _ in range(a.repeats):
        bonded_runs.append(run_bonded(app, case, a.particles, a.steps))
        granular_runs.append(run_granular(bench, case, bonded_runs[-1]["dt"]))
    pair_ratios = [g["particle_steps_per_s"] / b["particle_steps_per_s"] for b, g in zip(bonded_runs, granular_runs)]
    results = [median_run(bonded_runs), median_run(granular_runs)]
    if a.noYade:
        ratio = statistics.median(pair_ratios)
        print(f"bonded cost over plain LIGGGHTS per particle-step: {ratio:.2f} (pairs {', '.join(f'{r:.2f}' for r in pair_ratios)}); "
              f"bonded {results[0]['particle_steps_per_s']:.3g}, plain {results[1]['particle_steps_per_s']:.3g} particle-steps/s; "
              f"load {load_start:.1f} -> {os.getloadavg()[0]:.1f}")
        return

    # 3. Yade CohFrictMat bonded
    yade_json = os.path.join(case, "yade.json")
    _, rss = timed(["yade", "-j1", "-n", "-x", os.path.join(here, "yadeBondedBeam.py"),
                    os.path.join(case, "DEM", "packing.data"), str(a.steps), repr(results[0]["dt"]), yade_json],
                   case, "log.yade")
    y = json.load(open(yade_json))
    results.append({"model": f"Yade {y['version']} CohFrictMat bonded", "particles": y["particles"],
                    "bonds": y["bonds"], "steps": y["steps"], "dt": y["dt"], "loop_wall_s": y["loop_wall_s"],
                    "particle_steps_per_s": y["particle_steps_per_s"], "peak_rss_MiB": rss})

    bonded, granular, yade = results
    report = {
        "machine": os.uname().nodename, "cores_used": 1, "date": time.strftime("%Y-%m-%d %H:%M"),
        "cores": os.cpu_count(), "load_average_1min_start": load_start, "load_average_1min_end": os.getloadavg()[0],
        "results": results,
        "repeats": a.repeats,
        "bonded_cost_over_granular": statistics.median(pair_ratios),
        "bonded_cost_over_granular_pairs": pair_ratios,
        "bonded_speedup_over_yade": bonded["particle_steps_per_s"] / yade["particle_steps_per_s"],
    }
    os.makedirs(a.out, exist_ok=True)
    iceCases.write_atomically(os.path.join(a.out, "benchmark.json"), json.dumps(report, indent=2) + "\n")
    lines = ["| model | particles | bonds | steps | loop wall [s] | particle-steps/s (1 core) | peak RSS [MiB] |",
             "|---|---|---|---|---|---|---|"]
    for r in results:
        lines.append(f"| {r['model']} | {r['particles']} | {r['bonds']} | {r['steps']} | {r['loop_wall_s']:.1f} | "
                     f"{r['particle_steps_per_s']:.3g} | {r['peak_rss_MiB']:.0f} |")
    lines.append("")
    lines.append(f"Bonded cost per particle-step / plain granular: {report['bonded_cost_over_granular']:.2f} "
                 f"(limit 2.5; median of {a.repeats} interleaved pairs, "
                 f"{min(pair_ratios):.2f}-{max(pair_ratios):.2f}). Bonded speed / Yade: {report['bonded_speedup_over_yade']:.2f}. "
                 f"Machine load (1-minute average) {report['load_average_1min_start']:.1f} at the start, "
                 f"{report['load_average_1min_end']:.1f} at the end, on {report['cores']} cores.")
    iceCases.write_atomically(os.path.join(a.out, "benchmark.md"), "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
