#!/usr/bin/python3
"""bin/caseCommon.sh's inputs_fingerprint (what a case's run folders record as madeFrom) follows
a case's dictionaries and the files they #include, recursively, and nothing else: editing a file
of cases/common that the case does not include keeps its finished runs; editing one it includes,
directly or through another, or the case itself, or the run's own settings, makes them anew.
On a scratch copy (a case and a common/ folder beside it), then on the real keelBond case; and
iceCases.prepared_run, the same test for the study scripts' run folders.

usage: inputsFingerprint.py --source TOP"""
import argparse
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

def fingerprint(top, case, *paths, words=()):
    script = f'source "{top}/bin/caseCommon.sh"; inputs_fingerprint "$@"'
    result = subprocess.run(["bash", "-c", script, "fingerprint", *paths, "--", *words], cwd=case,
                            capture_output=True, text=True, check=True)
    return result.stdout.strip()


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def check_prepared_run(top):
    """iceCases.prepared_run, the study scripts' test of "already done": a run folder is reused
    only when prepared again from the same dictionaries, includes, settings and upstream files."""
    sys.path.insert(0, os.path.join(top, "postProcessing"))
    import iceCases
    with tempfile.TemporaryDirectory() as scratch:
        runs = os.path.join(scratch, "runs")
        common = os.path.join(runs, "common")    # where copy_common puts it for a run folder in runs/
        write(os.path.join(common, "ice"), "breakN 1e-3;\n")
        write(os.path.join(common, "otherCalibration"), "slope 2.4;\n")
        keel = os.path.join(scratch, "keel.h5")
        write(keel, "\0keel one")
        target = os.path.join(runs, "run1")

        def prepare(speed):
            def make(folder):
                write(os.path.join(folder, "constant", "iceProperties"), '#include "../../common/ice"\n')
                write(os.path.join(folder, "system", "controlDict"), "speed %s;\n" % speed)
            return make

        def made_again(speed, settings=("-thickness", "0.1")):
            """Prepares the run as a study would; whether it was made anew (a finished run's summary gone)."""
            marker = os.path.join(target, "postProcessing", "summary.json")
            if os.path.isdir(target):
                write(marker, "{}")
            iceCases.prepared_run(target, prepare(speed), settings=list(settings), upstream=[keel])
            check(not os.path.exists(target + ".preparing"), "no scratch folder left beside the run")
            return not os.path.exists(marker)

        check(made_again(0.05), "a new run folder is made")
        check(not made_again(0.05), "the same inputs: the finished run is reused")
        write(os.path.join(common, "otherCalibration"), "slope 1.9;\n")
        check(not made_again(0.05), "a common file the run does not include edited: reused")
        write(os.path.join(common, "ice"), "breakN 2e-3;\n")
        check(made_again(0.05), "an included common file edited: made again")
        check(made_again(0.025), "another entry set by the study (speed): made again")
        check(made_again(0.025, settings=("-thickness", "0.15")), "another application argument: made again")
        write(keel, "\0keel two")
        check(made_again(0.025, settings=("-thickness", "0.15")), "the upstream keel changed: made again")
        os.remove(os.path.join(target, "madeFrom"))
        check(made_again(0.025, settings=("-thickness", "0.15")), "a run folder without a madeFrom record: made again")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--source", required=True)
    top = os.path.abspath(ap.parse_args().source)
    with tempfile.TemporaryDirectory() as scratch:
        case = os.path.join(scratch, "cases", "myCase")
        common = os.path.join(scratch, "cases", "common")
        write(os.path.join(case, "constant", "iceProperties"), 'bonds\n{\n    #include "../../common/ice"\n}\n')
        write(os.path.join(case, "system", "controlDict"), "maxTravel 0.1;\n")
        write(os.path.join(common, "ice"), '#include "iceModulus"\nbreakN 1e-3;\n')
        write(os.path.join(common, "iceModulus"), "youngsModulus 5.4e8;\n")
        write(os.path.join(common, "otherCalibration"), "slope 2.4;\n")
        base = fingerprint(top, case, "constant", "system", words=("speed=0.005",))
        check(len(base) == 16, f"a 16-digit fingerprint ({base})")
        steps = [
            ("otherCalibration", os.path.join(common, "otherCalibration"), "slope 1.9;\n", False),
            ("common/ice (included)", os.path.join(common, "ice"), '#include "iceModulus"\nbreakN 2e-3;\n', True),
            ("common/iceModulus (included by the included)", os.path.join(common, "iceModulus"),
             "youngsModulus 1.95e8;\n", True),
            ("the case's controlDict", os.path.join(case, "system", "controlDict"), "maxTravel 0.2;\n", True),
        ]
        before = base
        for name, path, text, changes in steps:
            write(path, text)
            now = fingerprint(top, case, "constant", "system", words=("speed=0.005",))
            check((now != before) == changes, f"{name} edited: the fingerprint {'changes' if changes else 'stays'} "
                                               f"({before} -> {now})")
            before = now
        other = fingerprint(top, case, "constant", "system", words=("speed=0.05",))
        check(other != before, f"another speed, another fingerprint ({before} -> {other})")

    check_prepared_run(top)

    listed = subprocess.run([sys.executable, os.path.join(top, "postProcessing", "inputFiles.py"), "constant", "system",
                             "DEM/in.ridge"], cwd=os.path.join(top, "cases", "keelBond"), capture_output=True,
                            text=True, check=True).stdout.split()
    check("../common/freezeBondCalibrationCompliant" in listed and "../common/freezeBondProperties" in listed
          and not any("freezeBondCalibrationRidge" in p for p in listed),
          f"keelBond's inputs include the calibration it includes, not the ridge's: {', '.join(listed)}")
    finish()


if __name__ == "__main__":
    main()
