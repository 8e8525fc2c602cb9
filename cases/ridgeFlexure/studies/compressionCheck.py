#!/usr/bin/python3
"""Why compliant freeze-bonds need the ice's modulus in compression (README, "Compliant
freeze-bonds"): one quick ridge run (run 3: 0.5 m keel, 2 min set, 15 cm CL) loaded with
its freeze-bonds at the reference punch's 2.81 MPa, as stiff in compression as in tension
or not, and with the damping and the time step changed, to show which of them the blow-up
follows.

A bonded pair has no contact (IceBondForces): a compliant bond in compression lets its
particles interpenetrate, and when it breaks the ice-stiff contact takes over at that
overlap. Every variant has particleStrengths direct (the set's c_f x laboratory strengths
on the bonds), so that only the named entry changes; maxParticleSpeed is off, so that a
blow-up runs to its end and its figures can be read.

Writes runs/compressionCheck/compressionCheck.{csv,md}; --publish copies them into results/
and the table into ../README.md ("Compliant freeze-bonds").

Usage: studies/compressionCheck.py [--jobs N] [--publish]
"""
import argparse
import concurrent.futures
import csv
import io
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(CASE)), "postProcessing"))
sys.path.insert(0, HERE)
import iceCases  # noqa: E402
import ridgeMatrix  # noqa: E402

OUT = os.path.join(CASE, "runs", "compressionCheck")
ICE = 5.4e8
FREEZE = 2.80775e6

# name: (what it shows, {(file, entry): value})
VARIANTS = {
    "compliant": ("2.81 MPa in tension and compression", {}),
    "compliantHalfStep": ("the same, half the time step", {("iceProperties", "timeStep.factor"): 0.1}),
    "compliantUndamped": ("the same, no damping", {("iceProperties", "damping.model"): "none"}),
    "compliantUndampedHalfStep": ("the same, no damping, half the time step",
                                  {("iceProperties", "damping.model"): "none",
                                   ("iceProperties", "timeStep.factor"): 0.1}),
    "tenTimesStiffer": ("54 MPa in tension and compression",
                        {("iceProperties", "bondFamilies.freeze.youngsModulus"): 5.4e7,
                         ("iceProperties", "bondFamilies.freeze.compressionModulus"): 5.4e7}),
    "compliantIceInCompression": ("2.81 MPa, the ice's 540 MPa in compression (the case's)",
                                  {("iceProperties", "bondFamilies.freeze.compressionModulus"): ICE}),
}
COLUMNS = ["variant", "freeze_bonds", "peak_kN", "travel_at_peak_mm", "max_travel_mm", "max_kinetic_energy_J",
           "travel_at_max_kinetic_mm", "broken_bonds", "outcome"]


RUN = 3


def prepare(name, target):
    run = next(r for r in ridgeMatrix.matrix() if r["run"] == RUN)
    ridgeMatrix.prepare(run, "quick", target)
    files = {n: os.path.join(target, d, n) for d, n in (("constant", "iceProperties"),
                                                        ("constant", "freezeBondProperties"),
                                                        ("system", "controlDict"))}
    iceCases.set_entry(files["freezeBondProperties"], "particleStrengths", "direct")
    iceCases.set_entry(files["controlDict"], "maxParticleSpeed", 0)
    iceCases.set_entry(files["iceProperties"], "bondFamilies.freeze.compressionModulus", FREEZE)
    for (name_, entry), value in VARIANTS[name][1].items():
        iceCases.set_entry(files[name_], entry, value)


def execute(name):
    """The variant's row; a run that stopped on an error (a blown-up one that lost a particle) is
    read from the force curve it wrote before stopping, with the application's message."""
    run = next(r for r in ridgeMatrix.matrix() if r["run"] == RUN)
    target = iceCases.prepared_run(os.path.join(OUT, name), lambda folder: prepare(name, folder),
                                   upstream=ridgeMatrix.upstream_files(run, "quick"))
    stopped = ""
    if not iceCases.finished(target):
        try:
            iceCases.run_app(os.path.join(iceCases.TOP, "build", "demModels", "ridgeDEM"), target, 1,
                             ["-stage", "all"], "log.ridgeDEM")
        except RuntimeError as error:
            stopped = iceCases.fatal_message(error)
    return row(name, target, stopped)


def row(name, target, stopped):
    curve = iceCases.curve(target)
    force, travel, kinetic = curve["force"], curve["travel"], curve["kineticEnergy"]
    peak = max(range(len(force)), key=force.__getitem__)
    k = max(range(len(kinetic)), key=kinetic.__getitem__)
    blown = kinetic[k] > 100.0
    return {"variant": name, "freeze_bonds": VARIANTS[name][0],
            "peak_kN": round(force[peak] * 1e-3, 2), "travel_at_peak_mm": round(travel[peak] * 1e3, 1),
            "max_travel_mm": round(max(travel) * 1e3, 1), "max_kinetic_energy_J": round(kinetic[k], 1),
            "travel_at_max_kinetic_mm": round(travel[k] * 1e3, 1), "broken_bonds": int(curve["brokenBonds"][-1]),
            "outcome": ("blew up" if blown else "failed as a ridge") + (f" (stopped: {stopped})" if stopped else "")}


def write(rows):
    os.makedirs(OUT, exist_ok=True)
    base = os.path.join(OUT, "compressionCheck")
    table = io.StringIO()
    writer = csv.DictWriter(table, COLUMNS, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    iceCases.write_atomically(base + ".csv", table.getvalue())
    md = ["Quick ridge run 3 (0.5 m keel, 2 min set, 15 cm CL), particleStrengths direct, clamped ends, "
          "`studies/compressionCheck.py`. A run 'blew up' where its kinetic energy passed 100 J (a failing "
          "ridge stays under 10 J here).", "",
          "| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    md += ["| " + " | ".join(str(r[c]) for c in COLUMNS) + " |" for r in rows]
    iceCases.write_atomically(base + ".md", "\n".join(md) + "\n")
    return base


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=iceCases.whole_number(1), default=2)
    parser.add_argument("--publish", action="store_true", help="copy the finished study's table into results/")
    args = parser.parse_args()
    base = os.path.join(OUT, "compressionCheck")
    if args.publish:
        iceCases.publish_files([base + ".csv", base + ".md"], os.path.join(CASE, "results"))
        iceCases.write_readme_section(os.path.join(CASE, "README.md"), "compressionCheck table",
                                      open(os.path.join(CASE, "results", "compressionCheck.md")).read())
        return
    keel = iceCases.keel_file(ridgeMatrix.keel_case({"keel": "0.5"}, "quick"))
    if not os.path.exists(keel):
        sys.exit(f"compressionCheck: {keel} is missing: build the quick keels first (./Allrun -quick does)")
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        rows = list(pool.map(execute, VARIANTS))
    print(open(write(rows) + ".md").read())


if __name__ == "__main__":
    main()
