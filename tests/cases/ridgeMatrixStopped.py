#!/usr/bin/python3
"""studies/ridgeMatrix.py keeps a ridge run that the application stopped after its failure (its
load had fallen to 90 % of its peak or less, e.g. a blow-up caught by maxParticleSpeed) and
refuses one stopped before it or killed; a subset of runs shares the whole matrix's layers alone: on
synthetic run folders (a summary saying "complete": false with
the application's reason, and a force curve), no application run.

usage: ridgeMatrixStopped.py --source TOP"""
import argparse
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

def run_folder(root, name, forces, summary):
    folder = os.path.join(root, name, "postProcessing")
    os.makedirs(folder)
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump(summary, f)
    with open(os.path.join(folder, "platenForce.csv"), "w") as f:
        f.write("time,travel,force\n")
        f.writelines(f"{0.1 * k},{0.001 * k},{force}\n" for k, force in enumerate(forces))
    return os.path.dirname(folder)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--source", required=True)
    top = os.path.abspath(ap.parse_args().source)
    sys.path.insert(0, os.path.join(top, "cases", "ridgeFlexure", "studies"))
    sys.argv = sys.argv[:1]
    import ridgeMatrix

    reason = "stopped by an error: particle 3957 moves at 13.1 m/s, faster than maxParticleSpeed 10 m/s: the run has blown up"
    stopped = {"complete": False, "reason": reason, "application": "ridgeDEM"}
    with tempfile.TemporaryDirectory() as root:
        after = run_folder(root, "after", [0, 5e3, 10.7e3, 9.5e3, 8.7e3], stopped)
        before = run_folder(root, "before", [0, 5e3, 10.7e3, 10.1e3], stopped)
        finished = run_folder(root, "finished", [0, 5e3, 10.7e3, 4e3], {"complete": True, "peak_force_N": 10.7e3})
        killed = run_folder(root, "killed", [0, 5e3, 10.7e3, 2e3], {"complete": False})
        # What a run killed after its peak leaves (default-iceStiff run 16 on 2026-11-28 was published
        # from it as "stopped" until 2026-11-29): the reason written when loading began.
        killed_after_peak = run_folder(root, "killedAfterPeak", [0, 5e3, 16.2e3, 10.2e3], {
            "complete": False, "application": "ridgeDEM", "steps": 0,
            "reason": "in the making: ridgeDEM started it and has not finished; if it was killed, `-resume` continues it"})
        check(ridgeMatrix.stopped_after_failure(after) == reason,
              "stopped at 81 % of its peak: kept, with the application's reason")
        check(ridgeMatrix.stopped_after_failure(before) is None, "stopped at 94 % of its peak: not a result")
        check(ridgeMatrix.stopped_after_failure(finished) is None, "a finished run is no stopped run")
        check(ridgeMatrix.stopped_after_failure(killed) is None, "a run without a reason (killed) is no stopped run")
        check(ridgeMatrix.stopped_after_failure(killed_after_peak) is None,
              "a run killed after its peak (still 'in the making') is no stopped run: it is resumed")
        check(abs(ridgeMatrix.counted_until(after) - 0.3) < 1e-12,
              "a stopped run's breaks are counted up to the sample before the one it stopped in (0.3 s)")
        check(ridgeMatrix.counted_until(finished) is None, "a finished run's breaks are all counted")
        analysis = os.path.join(finished, "postProcessing", "failureAnalysis")
        os.makedirs(analysis)
        record = os.path.join(finished, "postProcessing", "breakage.h5")
        for path, when in ((os.path.join(analysis, "summary.json"), 1000), (record, 2000)):
            open(path, "w").close()
            os.utime(path, (when, when))
        check(not ridgeMatrix.failure_analysed(finished),
              "a failure analysis older than the run's breakage record (killed, analysed, resumed) is made again")
        os.utime(record, (500, 500))
        check(ridgeMatrix.failure_analysed(finished), "one newer than the record stands")
    rows = ridgeMatrix.matrix()
    alone_all = {r["cl_cm"]: r["set"] for r in ridgeMatrix.layers_alone(rows)}
    alone_16 = {r["cl_cm"]: r["set"] for r in ridgeMatrix.layers_alone([r for r in rows if r["run"] == 16])}
    check(alone_16 == {10.0: alone_all[10.0]} and alone_all[10.0] != rows[15]["set"],
          f"-runs 16 asks for the layer alone the whole matrix made (CL 10 cm, set {alone_16.get(10.0)}), "
          "not one under run 16's set, which would make the shared layer again")
    finish()


if __name__ == "__main__":
    main()
