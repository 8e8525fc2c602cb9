#!/usr/bin/python3
"""Does the way the rubble is settled change the settled rubble?

Raining only has to produce the right geometry, so rubbleDEM settles with
softened contacts and bonds (a longer time step) and stronger hysteretic
damping (constant/rubbleProperties, settling). This study settles the same
blocks (same seed) in a reduced box with the case's choices and with stiffer
contacts and weaker damping, and tabulates porosity, thickness and the ice
above water, and the freeze-bonds made where the heap came to rest (no compaction: it would set
the porosity whatever the heap was), so that the choices can be judged. Each settled heap is one
random outcome: differences of a few per cent between variants are the
scatter of the heap itself (compare two seeds).

usage: settlingSensitivity.py [--length 1.2] [--np 1]
Writes studies/settlingSensitivity.{csv,md} next to this script."""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "postProcessing"))
import iceCases  # noqa: E402

UNCOMPACTED_POROSITY = 0.6   # the ice rained in: a rubbleThickness layer at the settled heap's porosity
VARIANTS = [
    # name, settling youngsModulus, dampingAlpha, seed
    ("case (E 2e6, alpha 0.3)", 2e6, 0.3, 1),
    ("stiffer (E 8e6, alpha 0.3)", 8e6, 0.3, 1),
    ("case, another seed", 2e6, 0.3, 2),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--length", type=iceCases.positive_number, default=1.2)
    ap.add_argument("--np", type=iceCases.whole_number(1), default=1)
    ap.add_argument("--out", default=os.path.join(HERE, "..", "runs", "settlingSensitivity"))
    ap.add_argument("--publish", action="store_true",
                    help="run nothing; copy the tables in --out into the committed studies/ "
                         "and the table into the README")
    a = ap.parse_args()
    if a.publish:
        iceCases.publish_files([os.path.join(a.out, f) for f in ("settlingSensitivity.csv", "settlingSensitivity.md")],
                               HERE)
        iceCases.write_readme_table(os.path.join(HERE, "..", "README.md"), "settling invariance table",
                                    "studies/settlingSensitivity.py --publish", "studies/settlingSensitivity.md",
                                    open(os.path.join(HERE, "settlingSensitivity.md")).read())
        return
    case = os.path.dirname(HERE)
    rows = []
    for k, (name, modulus, alpha, seed) in enumerate(VARIANTS):
        def prepare(folder, modulus=modulus, alpha=alpha, seed=seed):
            iceCases.copy_case(case, folder)
            props = os.path.join(folder, "constant", "rubbleProperties")
            iceCases.set_entry(props, "box.length", a.length)
            iceCases.set_entry(props, "settling.youngsModulus", modulus)
            iceCases.set_entry(props, "settling.dampingAlpha", alpha)
            iceCases.set_entry(props, "blocks.seed", seed)
            # the heap as it settles, bonded where it came to rest: what the settling's softening
            # could change (compaction afterwards sets the porosity whatever the heap was)
            iceCases.uncompacted(props, UNCOMPACTED_POROSITY)

        # resumable: a finished variant made from the same inputs and rank count is kept
        work = iceCases.prepared_run(os.path.join(a.out, f"variant{k}"), prepare, settings=[a.np])
        if not iceCases.finished(work):
            print(f"{name} ...", flush=True)
            iceCases.run_app("rubbleDEM", work, a.np, [], "log.rubbleDEM")
        s = iceCases.summary(work)
        rows.append((name, s))
    header = "variant,settled_time_s,at_rest,thickness_m,porosity,ice_above_water,freeze_bonds,steps,settling_wall_s"
    lines = [header] + [
        f"{n},{s['settled_time_s']:.2f},{s['at_rest']},{s['thickness_m']:.3f},{s['porosity']:.3f},"
        f"{s['ice_volume_above_water_fraction']:.4f},{s['freeze_bonds']},{s['steps']},{s['settling_wall_s']:.0f}"
        for n, s in rows]
    iceCases.write_atomically(os.path.join(a.out, "settlingSensitivity.csv"), "\n".join(lines) + "\n")
    md = ["| variant | settled after (s) | thickness (m) | porosity | ice above water | freeze-bonds | settling wall (s) |",
          "|---|---|---|---|---|---|---|"]
    md += [f"| {n} | {s['settled_time_s']:.1f} | {s['thickness_m']:.3f} | {s['porosity']:.3f} | "
           f"{100 * s['ice_volume_above_water_fraction']:.2f} % | {s['freeze_bonds']} | {s['settling_wall_s']:.0f} |"
           for n, s in rows]
    iceCases.write_atomically(os.path.join(a.out, "settlingSensitivity.md"), "\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
