#!/usr/bin/python3
"""Where the bonded ice's explicit time step fails (issue 20, item 4a): the level-ice beam of
cases/levelIceBeam at 1,200 particles (the resolution of its parametric studies, 0.1 m/s) run to
its end at time-step factors up to and past the program's limit, for each damping model of
physics.md (hysteretic alpha 0.1, the case's; viscous damping ratio 0.05; none). A point past the
limit runs only with timeStep.refuseUnsafe no (cases/common/iceProperties), which exists for this
study; the program then warns and its blow-up check (system/controlDict blowUpFactor: the kinetic
energy over the platen's work) stops a run that goes unstable, with the time and step.

Per point: stable (the run's highest load) or unstable (when the blow-up check stopped it); per
damping model the smallest unstable factor beside the program's limit (the largest factor it
accepts, from its own log) and the case's default 0.25. The small pack's counterpart is the unit
test BondDynamics.ProgramLimitSitsBelowMeasuredInstability*.

usage: stabilityMap.py [--factors 0.25,0.3,...] [--jobs 2] [--out DIR] [--publish]
  writes OUT/stabilityMap.{csv,md,png} (default runs/); --publish copies them into results/ and the
  table into this folder's README.md."""
import argparse
import concurrent.futures
import csv
import io
import os
import re
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402

PARTICLES = 1200
DAMPING = {"hysteretic": None, "viscous": ("damping.viscousCoeffs.dampingRatio", 0.05), "none": None}
DEFAULT_FACTOR = 0.25


def run_point(out, damping, factor):
    case = iceCases.copy_case(os.path.join(TOP, "cases", "levelIceBeam"), os.path.join(out, f"{damping}_{factor:g}"))
    props = os.path.join(case, "constant", "iceProperties")
    iceCases.set_entry(props, "timeStep.factor", factor)
    iceCases.add_entry(props, "timeStep.refuseUnsafe", "no")
    iceCases.set_entry(props, "damping.model", damping)
    if DAMPING[damping]:
        iceCases.add_entry(props, *DAMPING[damping])
    iceCases.set_entry(os.path.join(case, "system", "controlDict"), "writeInterval", 10)   # no frames
    try:
        iceCases.run_app("iceBeamDEM", case, 1, ["-particles", PARTICLES], "log.run")
        outcome, detail = "stable", f"{iceCases.summary(case)['peak_force_N'] / 1e3:.1f} kN"
    except RuntimeError:
        log = open(os.path.join(case, "log.run")).read()
        blow = re.search(r"at time ([\d.e+-]+) s, step (\d+): the run is unstable", log)
        outcome, detail = ("unstable", f"t = {float(blow.group(1)) * 1e3:.1f} ms, step {blow.group(2)}") if blow \
            else ("failed", iceCases.fatal_message(log))
    step = re.search(r"Time step ([\d.e+-]+) s \(limit ([\d.e+-]+) s", open(os.path.join(case, "log.run")).read())
    limit_factor = factor * float(step.group(2)) / float(step.group(1))
    return {"damping": damping, "factor": factor, "outcome": outcome, "detail": detail,
            "program_limit_factor": round(limit_factor, 4)}


def table(rows):
    out = io.StringIO()
    writer = csv.DictWriter(out, list(rows[0]), lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    factors = sorted({r["factor"] for r in rows})
    lines = ["| damping | " + " | ".join(f"{f:g}" for f in factors) + " | smallest unstable factor | program's limit |",
             "|---|" + "---|" * (len(factors) + 2)]
    for damping in DAMPING:
        mine = {r["factor"]: r for r in rows if r["damping"] == damping}
        cells = [("**stable** " if mine[f]["outcome"] == "stable" else "**" + mine[f]["outcome"] + "** ")
                 + mine[f]["detail"] if f in mine else "" for f in factors]
        unstable = [f for f in factors if f in mine and mine[f]["outcome"] == "unstable"]
        limit = next(iter(mine.values()))["program_limit_factor"]
        lines.append(f"| {damping} | " + " | ".join(cells) + f" | {min(unstable):g} |" if unstable else
                     f"| {damping} | " + " | ".join(cells) + " | none tried |")
        lines[-1] += f" {limit:.3f} |"
    return out.getvalue(), "\n".join(lines) + "\n"


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 4.0))
    names = list(DAMPING)
    for r in rows:
        y = names.index(r["damping"])
        style = {"stable": ("o", "tab:green"), "unstable": ("x", "tab:red")}.get(r["outcome"], ("s", "grey"))
        ax.scatter(r["factor"], y, marker=style[0], color=style[1], s=70, zorder=3)
    limit = rows[0]["program_limit_factor"]
    ax.axvline(limit, color="k", lw=1.5, label=f"program's limit {limit:.3f} (refused above, by default)")
    ax.axvline(DEFAULT_FACTOR, color="tab:blue", ls=":", lw=1.5, label=f"default {DEFAULT_FACTOR}")
    ax.scatter([], [], marker="o", color="tab:green", label="stable (ran to its end)")
    ax.scatter([], [], marker="x", color="tab:red", label="unstable (stopped by the blow-up check)")
    ax.set_yticks(range(len(names)), names)
    ax.set_ylim(-0.6, len(names) - 0.4)
    ax.set_xlabel("time-step factor c (dt = c D_min sqrt(rho / E_max))")
    ax.set_title(f"Level-ice beam, {PARTICLES:,} particles: where the time step fails", fontsize=10)
    ax.grid(alpha=0.3, axis="x")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)
    iceCases.save_figure(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--factors", type=iceCases.comma_list(iceCases.positive_number),
                        default="0.25,0.3,0.35,0.375,0.4,0.45,0.5,0.6,0.8")
    parser.add_argument("--jobs", type=iceCases.whole_number(1), default=2)
    parser.add_argument("--out", default=os.path.join(HERE, "runs"))
    parser.add_argument("--publish", action="store_true")
    args = parser.parse_args()
    if args.publish:
        iceCases.publish_study(HERE, args.out, "stabilityMap", ("csv", "md", "png"), "stability map table", "csv")
        return
    points = [(d, f) for d in DAMPING for f in args.factors]
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        rows = list(pool.map(lambda p: run_point(os.path.join(args.out, "points"), *p), points))
    csv_text, md = table(rows)
    md += f"\n{time.strftime('%Y-%m-%d %H:%M')}, revision {iceCases.git_revision()}.\n"
    iceCases.write_study_outputs(args.out, "stabilityMap", {"csv": csv_text, "md": md})
    plot(rows, os.path.join(args.out, "stabilityMap.png"))
    print(md, end="")


if __name__ == "__main__":
    main()
