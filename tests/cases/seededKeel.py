#!/usr/bin/python3
"""rubblePunch/Allrun -keelSeed N never reuses another packing's keel built from other inputs.

In a temporary copy of the project (cases/, bin/, postProcessing/; no build: rubbleDEM and
ridgeDEM are stubs that leave a mark and fail):

1. keels/cuboid-seed2 built from other inputs (its constant/ says blocks.seed 3, a stage
   DEM/settled.h5 beside it): ./Allrun -keels cuboid -keelSeed 2 exits 1 naming the folder
   and what to do, runs no application, and leaves the stage and its inputs as they were.
2. The same folder with no stage: its constant/ is replaced by keels/cuboid's with
   blocks.seed 2 and the keel is built (the stub rubbleDEM is called).

usage: seededKeel.py --source TOP"""
import argparse
import filecmp
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from runSmoke import case_files  # noqa: E402

STUB = "#!/bin/bash\ntouch \"$(dirname \"${BASH_SOURCE[0]}\")/STUB_RAN\"\nexit 99\n"


def copy_project(source, work):
    for rel in case_files(source, "cases") + case_files(source, "bin") + case_files(source, "postProcessing"):
        dest = os.path.join(work, rel)
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        shutil.copy2(os.path.join(source, rel), dest, follow_symlinks=False)
    stubs = os.path.join(work, "stubs")
    os.makedirs(stubs)
    for app in ("rubbleDEM", "ridgeDEM"):
        with open(os.path.join(stubs, app), "w") as f:
            f.write(STUB)
        os.chmod(os.path.join(stubs, app), 0o755)
    return stubs


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True, help="the project's top folder")
    a = ap.parse_args()
    sys.path.insert(0, os.path.join(a.source, "postProcessing"))
    import iceCases

    def seed_of(rubble_properties):
        return iceCases.get_entry(rubble_properties, "blocks.seed").strip()

    work = tempfile.mkdtemp(prefix="seededKeel.")
    failures = []
    try:
        stubs = copy_project(a.source, work)
        case = os.path.join(work, "cases", "rubblePunch")
        seeded = os.path.join(case, "keels", "cuboid-seed2")
        props = os.path.join(seeded, "constant", "rubbleProperties")
        os.makedirs(os.path.join(seeded, "DEM"))
        shutil.copytree(os.path.join(case, "keels", "cuboid", "constant"), os.path.join(seeded, "constant"))
        text = open(props).read()
        assert text.count("seed                1;") == 1, "keels/cuboid's blocks.seed line changed: update this test"
        open(props, "w").write(text.replace("seed                1;", "seed                3;"))
        stage = os.path.join(seeded, "DEM", "settled.h5")
        with open(stage, "w") as f:
            f.write("a keel rained from seed 3\n")
        kept = os.path.join(work, "kept")
        shutil.copytree(seeded, kept)
        env = dict(os.environ, ICE_BIN=stubs, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
        command = ["./Allrun", "-np", "1", "-keels", "cuboid", "-keelSeed", "2"]

        r = subprocess.run(command, cwd=case, env=env, capture_output=True, text=True, timeout=60)
        if r.returncode != 1:
            failures.append(f"1: exit status {r.returncode}, not 1")
        for words in ("keels/cuboid-seed2 was built from other inputs", "remove keels/cuboid-seed2"):
            if words not in r.stderr:
                failures.append(f"1: stderr does not say '{words}'")
        if os.path.exists(os.path.join(stubs, "STUB_RAN")):
            failures.append("1: an application ran")
        if filecmp.dircmp(seeded, kept).diff_files or not filecmp.cmp(stage, os.path.join(kept, "DEM", "settled.h5"),
                                                                       shallow=False) \
                or not filecmp.cmp(props, os.path.join(kept, "constant", "rubbleProperties"), shallow=False):
            failures.append("1: the other packing's stage or inputs changed")
        if os.path.exists(os.path.join(case, "runs", "cuboid-seed2")):
            failures.append("1: a punch run folder was made")

        os.remove(stage)
        r2 = subprocess.run(command, cwd=case, env=env, capture_output=True, text=True, timeout=60)
        if r2.returncode == 0:
            failures.append("2: exit status 0 with a failing rubbleDEM")
        if not os.path.exists(os.path.join(stubs, "STUB_RAN")):
            failures.append("2: the keel was not built (rubbleDEM not called)")
        if seed_of(props) != "2":
            failures.append(f"2: keels/cuboid-seed2's blocks.seed is {seed_of(props)}, not 2")
        if failures:
            print("stderr of 1:", r.stderr, "stderr of 2:", r2.stderr, sep="\n")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    for f in failures:
        print("FAIL", f)
    print("seededKeel: %s" % ("failed" if failures else "both cases as expected"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
