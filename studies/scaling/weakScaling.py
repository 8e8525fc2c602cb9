#!/usr/bin/python3
"""How the bonded DEM's cost and memory grow with the particle count (issue 17, goal 5): the
level-ice beam of cases/levelIceBeam packed with 1e4, 1e5 and 1e6 particles (iceBeamDEM
-particles N: the same beam, finer spheres), a fixed number of loading steps on 2 ranks. Per size:
the loading loop's particle-steps/s (set-up excluded) and its cost per particle-step, the set-up's
wall time (packing, bonds, LIGGGHTS start), and the peak resident memory of the largest rank
(/usr/bin/time on mpirun) per particle of that rank.

usage: weakScaling.py [--sizes 10000,100000,1000000] [--steps 800] [--ranks 2] [--out DIR] [--publish]
  writes OUT/weakScaling.{json,md} (default runs/); --publish copies them into results/ and the
  table into this folder's README.md."""
import argparse
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
sys.path.insert(0, os.path.join(TOP, "cases", "levelIceBeam", "studies"))
import iceCases  # noqa: E402
import benchmark  # noqa: E402  (the beam benchmark's timed run of iceBeamDEM)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=iceCases.comma_list(iceCases.whole_number(20)), default="10000,100000,1000000")
    parser.add_argument("--steps", type=iceCases.whole_number(1), default=800)   # two force samples at 1e6
    parser.add_argument("--ranks", type=iceCases.whole_number(1), default=2)
    parser.add_argument("--out", default=os.path.join(HERE, "runs"))
    parser.add_argument("--publish", action="store_true")
    args = parser.parse_args()
    if args.publish:
        iceCases.publish_study(HERE, args.out, "weakScaling", ("json", "md"), "weak scaling table", "json")
        return
    app = os.path.join(iceCases.BUILD, "demModels", "iceBeamDEM")
    rows = []
    for n in args.sizes:
        case = iceCases.copy_case(os.path.join(TOP, "cases", "levelIceBeam"), os.path.join(args.out, f"beam{n}"))
        # the platen on the beam from the first step: every step of the window loads it
        iceCases.set_entry(os.path.join(case, "constant", "beamProperties"), "platen.initialGap", 0)
        print(f"{n} particles on {args.ranks} ranks ...", flush=True)
        start = time.time()
        r = benchmark.run_bonded(app, case, n, args.steps, args.ranks)
        wall = time.time() - start
        rows.append({"particles": r["particles"], "bonds": r["bonds"], "steps": r["steps"], "ranks": args.ranks,
                     "loop_wall_s": round(r["loop_wall_s"], 2), "setup_wall_s": round(wall - r["loop_wall_s"], 1),
                     "particle_steps_per_s": round(r["particle_steps_per_s"], -3),
                     "ns_per_particle_step_per_rank": round(1e9 * args.ranks / r["particle_steps_per_s"], 1),
                     "peak_rss_MiB_per_rank": round(r["peak_rss_MiB"], 1),
                     "KiB_per_particle": round(1024 * r["peak_rss_MiB"] * args.ranks / r["particles"], 2)})
        print(json.dumps(rows[-1]), flush=True)
    report = {"rows": rows, "load_average_at_end": os.getloadavg()[0], "date": time.strftime("%Y-%m-%d %H:%M"),
              "revision": iceCases.git_revision()}
    lines = ["| particles | bonds | loop: particle-steps/s | ns per particle-step on a rank | set-up [s] "
             "| peak RSS per rank [MiB] | KiB per particle |", "|---|---|---|---|---|---|---|"]
    lines += [f"| {r['particles']:,} | {r['bonds']:,} | {r['particle_steps_per_s']:.3g} | {r['ns_per_particle_step_per_rank']:.0f} "
              f"| {r['setup_wall_s']:.0f} | {r['peak_rss_MiB_per_rank']:.0f} | {r['KiB_per_particle']:.1f} |" for r in rows]
    md = "\n".join(lines) + (f"\n\n{args.steps} loading steps on {args.ranks} ranks, {report['date']}, "
                             f"load average {report['load_average_at_end']:.1f} at the end.\n")
    iceCases.write_study_outputs(args.out, "weakScaling", {"json": json.dumps(report, indent=2) + "\n", "md": md})
    print(md, end="")


if __name__ == "__main__":
    main()
