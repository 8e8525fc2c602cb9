#!/usr/bin/python3
"""The vof level's coupling-time limit, measured on this case: the floating
block run with the coupling time T_c (one fluid step per coupling step,
deltaT = T_c) and stabilityCheck no (the Courant limits not enforced), each in
a copy under runs/stability/; per T_c: the highest flow and interface Courant
numbers, whether alpha.water stayed within [0, 1] (to 1e-6), the submerged
fraction, whether the block came to rest and its heave over the last second.

    /usr/bin/python3 stabilityScan.py [--times-ms 20,40,60,80] [--end-time 8] [--out ../runs/stability/stability] [--publish]

Writes OUT.json and OUT.md (not tracked); --publish copies them into results/."""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "postProcessing"))
from iceCases import publish_files, write_atomically  # noqa: E402


def run(t_ms, end_time, dem_step=2.5e-5):
    case = os.path.join(here, "..", "runs", "stability", f"Tc{t_ms}ms")
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(case)
    for d in ("0", "constant", "system", "DEM"):
        shutil.copytree(os.path.join(here, d), os.path.join(case, d))
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    steps = round(t_ms * 1e-3 / dem_step)
    for f, entry, value in (("constant/couplingProperties", "couplingInterval", str(steps)),
                            ("constant/couplingProperties", "stabilityCheck", "no"),
                            ("system/controlDict", "deltaT", str(t_ms * 1e-3)),
                            ("system/controlDict", "endTime", str(end_time)),
                            ("system/controlDict", "writeInterval", str(end_time))):
        subprocess.run(["foamDictionary", "-entry", entry, "-set", value, os.path.join(case, f)],
                       check=True, stdout=subprocess.DEVNULL, env=env)
    start = time.time()
    ok = subprocess.run([os.path.join(here, "Allrun"), "-np", "1", "-case", case], env=env,
                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0
    wall = time.time() - start
    row = {"coupling_time_ms": t_ms, "completed": ok, "wall_s": round(wall, 1)}
    vof = os.path.join(case, "postProcessing", "vof.csv")
    if os.path.exists(vof):
        rows = list(csv.DictReader(open(vof)))
        row.update({
            "max_flow_courant": max(float(r["maxCo"]) for r in rows),
            "max_interface_courant": max(float(r["maxAlphaCo"]) for r in rows),
            "alpha_water_range": [min(float(r["alphaWaterMin"]) for r in rows),
                                  max(float(r["alphaWaterMax"]) for r in rows)],
        })
        row["alpha_bounded"] = row["alpha_water_range"][0] > -1e-6 and row["alpha_water_range"][1] < 1 + 1e-6
    summary = os.path.join(case, "postProcessing", "summary.json")
    if ok and os.path.exists(summary):
        s = json.load(open(summary))
        late = s["submerged_volume_fraction_range_last_s"]
        row.update({"submerged_volume_fraction": s["submerged_volume_fraction"], "at_rest": s["at_rest"],
                    "at_rest_since_s": s["at_rest_since_s"],
                    "submerged_fraction_swing_last_s": late[1] - late[0]})
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--times-ms", default="20,40,60,80")
    ap.add_argument("--end-time", type=float, default=8)
    ap.add_argument("--out", default=os.path.join(here, "..", "runs", "stability", "stability"),
                    help="OUT.json and OUT.md (default ../runs/stability/stability: not tracked)")
    ap.add_argument("--publish", action="store_true",
                    help="run nothing; copy OUT.json and OUT.md into results/ (committed)")
    args = ap.parse_args()
    if args.publish:
        publish_files([args.out + ".json", args.out + ".md"], os.path.join(here, "results"))
        return
    rows = []
    for t in [int(x) for x in args.times_ms.split(",")]:
        rows.append(run(t, args.end_time))
        print(json.dumps(rows[-1]), flush=True)
    write_atomically(args.out + ".json", json.dumps({"case": "floatingBlock/vof", "end_time_s": args.end_time,
                                                     "runs": rows}, indent=2) + "\n")
    lines = ["| T_c (ms) | max flow Co | max interface Co | alpha.water range | submerged fraction | at rest since (s) "
             "| swing over the last s |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        rng = r.get("alpha_water_range")
        lines.append(f"| {r['coupling_time_ms']} | {r.get('max_flow_courant', float('nan')):.3f} | "
                     f"{r.get('max_interface_courant', float('nan')):.3f} | "
                     f"{'%.2e .. %.6f' % tuple(rng) if rng else '-'} | "
                     f"{r.get('submerged_volume_fraction', float('nan')):.5f} | {r.get('at_rest_since_s')} | "
                     f"{r.get('submerged_fraction_swing_last_s', float('nan')):.2e} |")
    write_atomically(args.out + ".md", "\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
