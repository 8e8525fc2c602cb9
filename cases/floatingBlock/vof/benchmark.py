#!/usr/bin/python3
"""Cost of the vof level against the cfd level on the floating block: the
same block, the same coupling (5 ms, 200 DEM steps) and end time, 1 rank,
in copies under runs/benchmark/; cfd and vof run back to back, --pairs times,
so that both see the same load on this shared machine. Wall clock per
simulated second of each, the ratio of each pair and its median.

    /usr/bin/python3 benchmark.py [--end-time 3] [--pairs 3] [--out ../runs/benchmark/benchmark] [--publish]

Writes OUT.json and OUT.md (not tracked); --publish copies them into results/."""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "postProcessing"))
from iceCases import publish_files, write_atomically  # noqa: E402


def run(level, end_time, k):
    src = os.path.join(here, "..", level)
    case = os.path.join(here, "..", "runs", "benchmark", f"{level}{k}")
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    for d in ("0", "constant", "system", "DEM"):
        shutil.copytree(os.path.join(src, d), os.path.join(case, d))
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    for entry, value in (("endTime", str(end_time)), ("writeInterval", str(end_time))):
        subprocess.run(["foamDictionary", "-entry", entry, "-set", value, os.path.join(case, "system", "controlDict")],
                       check=True, stdout=subprocess.DEVNULL, env=env)
    start = time.time()
    subprocess.run([os.path.join(src, "Allrun"), "-np", "1", "-case", case], env=env, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return (time.time() - start) / end_time


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--end-time", type=float, default=3)
    ap.add_argument("--pairs", type=int, default=3)
    ap.add_argument("--out", default=os.path.join(here, "..", "runs", "benchmark", "benchmark"),
                    help="OUT.json and OUT.md (default ../runs/benchmark/benchmark: not tracked)")
    ap.add_argument("--publish", action="store_true",
                    help="run nothing; copy OUT.json and OUT.md into results/ (committed)")
    args = ap.parse_args()
    if args.publish:
        publish_files([args.out + ".json", args.out + ".md"], os.path.join(here, "results"))
        return
    pairs = []
    for k in range(args.pairs):
        cfd = run("cfd", args.end_time, k)
        vof = run("vof", args.end_time, k)
        pairs.append({"cfd_wall_s_per_simulated_s": round(cfd, 3), "vof_wall_s_per_simulated_s": round(vof, 3),
                      "ratio": round(vof / cfd, 3)})
        print(json.dumps(pairs[-1]), flush=True)
    ratios = [p["ratio"] for p in pairs]
    s = {"case": "floatingBlock", "end_time_s": args.end_time, "ranks": 1,
         "load_average_at_end": os.getloadavg()[0], "pairs": pairs, "median_ratio": statistics.median(ratios),
         "bar": 2.0, "within_bar": statistics.median(ratios) <= 2.0,
         "date": time.strftime("%Y-%m-%d %H:%M")}
    write_atomically(args.out + ".json", json.dumps(s, indent=2) + "\n")
    lines = ["| pair | cfd (s per simulated s) | vof (s per simulated s) | vof / cfd |", "|---|---|---|---|"]
    lines += [f"| {i + 1} | {p['cfd_wall_s_per_simulated_s']:.2f} | {p['vof_wall_s_per_simulated_s']:.2f} | "
              f"{p['ratio']:.2f} |" for i, p in enumerate(pairs)]
    lines.append(f"\nMedian vof / cfd: {s['median_ratio']:.2f} (bar 2), {s['date']}, "
                 f"load average {s['load_average_at_end']:.1f} at the end.")
    write_atomically(args.out + ".md", "\n".join(lines) + "\n")
    print(lines[-1].strip())
    return 0


if __name__ == "__main__":
    sys.exit(main())
