#!/usr/bin/python3
"""Reduced punch on a compacted and on an uncompacted keel: the same settled heap of
../rubbleBeam's blocks in a 1.6 x 0.4 m box, 0.3 m of rubble with the ice of porosity 0.40,
compacted between plates (rubbleDEM -stage compact) or not, bonded by ridgeDEM, punched at
0.05 m/s for 60 mm with fixed ends. Prints each run's peak, travel at the peak, broken bonds,
and the assembly's touching pairs and freeze-bonds (from its log).

usage: studies/compactionPunch.py [--work DIR]   (default runs/compactionPunch; about 2 min on 2 idle cores)"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "postProcessing"))
import iceCases  # noqa: E402

CASE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def keel(work):
    path = iceCases.prepared_run(
        os.path.join(work, "keel"),
        lambda folder: iceCases.small_rubble_case(os.path.join(CASE, "..", "rubbleBeam"), folder, 1.6, 0.4, 0.3, 6, 15,
                                                  {"compaction.targetPorosity": 0.40, "settling.minTime": 1}))
    if not os.path.exists(os.path.join(path, "DEM", "compacted.h5")):
        iceCases.run_app("rubbleDEM", path, 1, ["-stage", "settle"], "log.settle")
        iceCases.run_app("rubbleDEM", path, 1, ["-stage", "compact"], "log.compact")
    return path


def punch(work, keel_dir, stage_file):
    stage = os.path.join(keel_dir, "DEM", stage_file)

    def prepare(folder):
        iceCases.copy_case(CASE, folder)
        props = os.path.join(folder, "constant", "ridgeProperties")
        text = open(props).read()
        open(props, "w").write(text.replace("\nconsolidatedLayer", "\nbox\n{\n    length 1.6;\n    width 0.4;\n}\n\nconsolidatedLayer", 1))
        iceCases.set_entry(props, "keel.settledRubble", '"%s"' % stage)
        for entry, value in (("test.settleTime", 0.05), ("ends.fixedLength", 0.1), ("test.speed", 0.05)):
            iceCases.set_entry(props, entry, value)
        iceCases.set_entry(os.path.join(folder, "system", "controlDict"), "maxTravel", 0.06)

    run = iceCases.prepared_run(os.path.join(work, stage_file.split(".")[0]), prepare, upstream=[stage])
    if not iceCases.finished(run):
        iceCases.run_app("ridgeDEM", run, 1, ["-stage", "all"], "log.ridgeDEM")
    s = iceCases.summary(run)
    log = open(os.path.join(run, "log.ridgeDEM")).read()
    pairs = re.search(r"touching pairs between blocks (\d+) -> (\d+)", log)
    bonds = re.search(r"(\d+) freeze-bonds \(", log)
    print("%-10s peak %.1f N at %.1f mm, %d bonds broken; touching pairs %s -> %s at stiffening, %s freeze-bonds"
          % (stage_file, s["peak_force_N"], 1e3 * s["travel_at_peak_m"], s["broken_bonds"],
             pairs.group(1), pairs.group(2), bonds.group(1)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--work", default=os.path.join(CASE, "runs", "compactionPunch"))
    args = parser.parse_args()
    k = keel(args.work)
    for stage_file in ("compacted.h5", "settled.h5"):
        punch(args.work, k, stage_file)


if __name__ == "__main__":
    main()
