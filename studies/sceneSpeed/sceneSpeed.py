#!/usr/bin/python3
"""The loading loops of the punch and of a ridge run against the bonded beam, per core (issue 17,
goal 1: within 1.3 times the beam's particle-steps/s, alone and two side by side).

Three scenes, each on one rank, measured on the stepping loop only (set-up excluded):

- the bonded beam: cases/levelIceBeam's 13,000-particle beam, --beam-steps steps from its start
  (iceBeamDEM -particles 13000 -steps N, the same run as the beam benchmark);
- the rubble punch: a window of --travel of platen travel from cases/rubblePunch/runs/cuboid (its
  saved ridge; the same window as studies/rankSpeedup and studies/waterLevels);
- ridge run 6: the same window from cases/ridgeFlexure/runs/default/run06_keel0.5_4h_CL10 (the softened
  keel's: ./Allrun -keels softened -runs 6).

"Alone" runs one scene at a time; "side by side" runs two copies of the same scene at once, one on
each core, as the ridge matrix and the punch's keels run (each copy's rate is listed, the row gives
their mean). Every scene is measured in each round (--rounds), alone and side by side, and the table
gives the median round; the ratio is the beam's particle-steps/s over the scene's in the same mode.
--bound-baseline also runs each pair side by side as before 2026-11-29, with Open MPI binding each
mpirun's rank to a core (its default, which put both on core 0; postProcessing/iceCases.py), in the
same round. The machine must be otherwise idle.

usage: sceneSpeed.py [--rounds 2] [--travel 0.002] [--beam-steps 2000] [--bound-baseline] [--out DIR]
                     [--publish]
  writes OUT/sceneSpeed.{json,md} (default runs/); --publish copies them into results/ and the
  table into this folder's README.md."""
import argparse
import concurrent.futures
import json
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(TOP, "studies", "waterLevels"))
import waterLevelChart  # noqa: E402
from waterLevelChart import CASES, iceCases  # noqa: E402

TARGET = 1.3    # issue 17: a scene's particle-steps/s within 1.3 times the beam's

SOURCES = {
    "punch": os.path.join(CASES, "rubblePunch", "runs", "cuboid"),
    "ridge": os.path.join(CASES, "ridgeFlexure", "runs", "default", waterLevelChart.RIDGE_RUN),
}
TITLES = {
    "beam": "bonded beam (levelIceBeam, 13,000 particles)",
    "punch": "rubble punch (cuboid keel, 5 mm/s)",
    "ridge": "ridge run 6 (default resolution, 0.05 m/s)",
}


def beam_rate(work, steps):
    """particle-steps/s of the beam's loop, and its particle count."""
    case = os.path.join(work, "case")
    if not os.path.isdir(case):
        iceCases.copy_case(os.path.join(CASES, "levelIceBeam"), case)
    iceCases.run_app("iceBeamDEM", case, 1, ["-particles", 13000, "-steps", steps], "log.run")
    s = iceCases.summary(case)
    return s["particle_steps_per_s"], s["particles"]


def window_rate(work, scene, travel):
    """particle-steps/s of the loading loop of a window of the scene's finished run."""
    waterLevelChart.loading_cost(work, scene, SOURCES[scene], "hydrostatic", travel, 1)
    s = iceCases.summary(os.path.join(work, f"{scene}-hydrostatic"))
    return s["particle_steps_per_s"], s["particles"]


def measure(work, scene, args):
    os.makedirs(work, exist_ok=True)
    if scene == "beam":
        return beam_rate(work, args.beam_steps)
    return window_rate(work, scene, args.travel)


BINDING = "OMPI_MCA_hwloc_base_binding_policy"


def side_by_side(out, scene, args, binding):
    """Two copies of the scene at once; each copy's rate. binding: Open MPI's binding policy."""
    before = os.environ[BINDING]
    os.environ[BINDING] = binding       # read by the mpiruns the two threads start
    try:
        with concurrent.futures.ThreadPoolExecutor(2) as pool:
            copies = [pool.submit(measure, os.path.join(out, "work", f"{scene}-side{c}"), scene, args) for c in (1, 2)]
            return [f.result()[0] for f in copies]
    finally:
        os.environ[BINDING] = before


def one_round(out, k, args):
    rows = {}
    for scene in ("beam", "punch", "ridge"):
        alone, particles = measure(os.path.join(out, "work", f"{scene}-alone"), scene, args)
        side = side_by_side(out, scene, args, "none")
        rows[scene] = {"particles": particles, "alone": alone, "side_by_side": side}
        line = f"round {k + 1}: {scene}: alone {alone:.3g}, side by side {side[0]:.3g} / {side[1]:.3g}"
        if args.bound_baseline:
            rows[scene]["side_by_side_bound"] = side_by_side(out, scene, args, "core")
            line += " (bound: {:.3g} / {:.3g})".format(*rows[scene]["side_by_side_bound"])
        print(line + " particle-steps/s", flush=True)
    return rows


def summarise(rounds):
    """Per scene the median round's rates (alone; mean of the two side-by-side copies) and the
    beam's over the scene's in each mode, round by round."""
    table = []
    for scene in ("beam", "punch", "ridge"):
        alone = [r[scene]["alone"] for r in rounds]
        side = [statistics.mean(r[scene]["side_by_side"]) for r in rounds]
        ratio_alone = [r["beam"]["alone"] / r[scene]["alone"] for r in rounds]
        ratio_side = [statistics.mean(r["beam"]["side_by_side"]) / statistics.mean(r[scene]["side_by_side"])
                      for r in rounds]
        table.append({"scene": scene, "title": TITLES[scene], "particles": rounds[0][scene]["particles"],
                      "alone_particle_steps_per_s": statistics.median(alone),
                      "side_by_side_particle_steps_per_s": statistics.median(side),
                      "beam_over_scene_alone": statistics.median(ratio_alone),
                      "beam_over_scene_side_by_side": statistics.median(ratio_side),
                      "rounds_alone": alone, "rounds_side_by_side": side})
        if "side_by_side_bound" in rounds[0][scene]:
            bound = [statistics.mean(r[scene]["side_by_side_bound"]) for r in rounds]
            table[-1]["side_by_side_bound_particle_steps_per_s"] = statistics.median(bound)
            table[-1]["unbound_over_bound"] = statistics.median(
                [statistics.mean(r[scene]["side_by_side"]) / statistics.mean(r[scene]["side_by_side_bound"])
                 for r in rounds])
    return table


def markdown(table, info):
    bound = "side_by_side_bound_particle_steps_per_s" in table[0]
    lines = ["| scene | particles | alone: particle-steps/s | beam / scene | side by side: particle-steps/s per copy "
             "| beam / scene |" + (" side by side, bound to cores (before) | unbound / bound |" if bound else ""),
             "|---|---|---|---|---|---|" + ("---|---|" if bound else "")]
    for r in table:
        mark = (lambda x: f"**{x:.2f}**" if r["scene"] != "beam" and x > TARGET else f"{x:.2f}")
        lines.append(f"| {r['title']} | {r['particles']:,} | {r['alone_particle_steps_per_s']:.3g} "
                     f"| {mark(r['beam_over_scene_alone'])} | {r['side_by_side_particle_steps_per_s']:.3g} "
                     f"| {mark(r['beam_over_scene_side_by_side'])} |"
                     + (f" {r['side_by_side_bound_particle_steps_per_s']:.3g} | {r['unbound_over_bound']:.2f} |"
                        if bound else ""))
    lines.append("")
    lines.append(f"Target: beam / scene at most {TARGET} (issue 17; bold where it is not met). Medians of "
                 f"{info['rounds']} rounds, one rank per run, loops only; the punch and ridge windows are "
                 f"{1e3 * info['travel']:g} mm of travel from their cases' finished runs, the beam "
                 f"{info['beam_steps']} steps. {info['date']}, load average {info['load_start']:.1f} at the start, "
                 f"{info['load_end']:.1f} at the end.")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=iceCases.whole_number(1), default=2)
    parser.add_argument("--travel", type=iceCases.positive_number, default=0.002)
    parser.add_argument("--beam-steps", type=iceCases.whole_number(100), default=2000)
    parser.add_argument("--bound-baseline", action="store_true",
                        help="also run each pair bound to cores, as every mpirun was before 2026-11-29")
    parser.add_argument("--out", default=os.path.join(HERE, "runs"))
    parser.add_argument("--publish", action="store_true")
    args = parser.parse_args()
    if args.publish:
        iceCases.publish_study(HERE, args.out, "sceneSpeed", ("json", "md"), "scene speed table", "json")
        return
    for scene, source in SOURCES.items():
        if not iceCases.finished(source):
            sys.exit(f"sceneSpeed.py: {source} has not finished: run its case first (README)")
    load_start = os.getloadavg()[0]
    rounds = [one_round(args.out, k, args) for k in range(args.rounds)]
    info = {"rounds": args.rounds, "travel": args.travel, "beam_steps": args.beam_steps,
            "bound_baseline": args.bound_baseline,
            "date": time.strftime("%Y-%m-%d %H:%M"), "load_start": load_start, "load_end": os.getloadavg()[0],
            "revision": iceCases.git_revision()}
    table = summarise(rounds)
    os.makedirs(args.out, exist_ok=True)
    iceCases.write_atomically(os.path.join(args.out, "sceneSpeed.json"),
                              json.dumps({"info": info, "table": table, "rounds": rounds}, indent=2) + "\n")
    md = markdown(table, info)
    iceCases.write_atomically(os.path.join(args.out, "sceneSpeed.md"), md)
    print(md, end="")


if __name__ == "__main__":
    main()
