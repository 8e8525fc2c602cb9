#!/usr/bin/python3
"""Every case's Allrun (and ./Allrun, and the Allcleans that take options) is
strict about its command line: each bad command line below exits with status 2,
names the option on stderr with the usage line, and leaves the copy of the
project it ran in unchanged (it refused before writing or deleting anything);
each good one passes the checks (ALLRUN_CHECK_ONLY=1: the Allrun stops after
them with status 0). No application is run or needed: the copy has no build/,
and its bin/installDependencies and bin/build only leave a mark.

The copy (the files git tracks or would add under cases/ and bin/, and
./Allrun) is made in a temporary folder, never in the source tree.

usage: allrunOptions.py --source TOP"""
import argparse
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from runSmoke import case_files  # noqa: E402

# Bad command lines of every Allrun: (arguments, the option stderr must name).
COMMON_BAD = [
    (["-np", "0"], "-np"),
    (["-np"], "-np"),
    (["-np", "x"], "-np"),
    (["-np", "-smoke"], "-np"),
    (["-np", "2abc"], "-np"),
    (["-bogus"], "-bogus"),
    (["-smoke", "extra"], "extra"),
]

# script (relative to the top): (its own bad command lines, good command lines)
SCRIPTS = {
    "Allrun": ([(["-particles", "0"], "-particles"), (["-platenSpeed", "abc"], "-platenSpeed")],
               []),
    "cases/levelIceBeam/Allrun": (
        [(["-particles", "0"], "-particles"), (["-particles", "19"], "-particles"),
         (["-particles", "400abc"], "-particles"), (["-platenSpeed", "abc"], "-platenSpeed"),
         (["-platenSpeed", "0"], "-platenSpeed"), (["-platenSpeed", "-1"], "-platenSpeed"),
         (["-steps", "1e3"], "-steps"), (["-steps"], "-steps"), (["-np", "65"], "-np")],
        [[], ["-smoke"], ["-np", "1", "-particles", "400", "-platenSpeed", "0.2", "-steps", "100", "-resume"], ["-publish"]]),
    "cases/threePointBending/Allrun": (
        [(["-platenSpeed", "abc"], "-platenSpeed"), (["-steps", "0"], "-steps"),
         (["-thickness", "0.1"], "-thickness"), (["-quick", "1"], "1")],
        [[], ["-smoke"], ["-quick", "-np", "1", "-platenSpeed", "0.1", "-steps", "10"], ["-publish"]]),
    "cases/floatingBlock/Allrun": (
        [(["-level", "x"], "-level"), (["-level"], "-level"), (["-level", "cfd", "-np", "0"], "-np"),
         (["-water", "sph"], "-water"), (["-water"], "-water")],
        [[], ["-level", "cfd", "-smoke", "-np", "1"], ["-level", "hydrostatic", "-np", "2"], ["-level", "cfd", "-publish"],
         ["-water", "vof", "-smoke", "-np", "1"], ["-water", "vof", "-publish"], ["-level", "vof", "-np", "2"]]),
    "cases/floatingBlock/cfd/Allrun": (
        [(["-case"], "-case"), (["-case", "/nonexistent/case"], "-case")],
        [[], ["-smoke"], ["-np", "2", "-case", "."], ["-publish"]]),
    "cases/floatingBlock/vof/Allrun": (
        [(["-case"], "-case"), (["-case", "/nonexistent/case"], "-case")],
        [[], ["-smoke"], ["-np", "2", "-case", "."], ["-publish"]]),
    "cases/freezeBondShear/Allrun": ([], [[], ["-smoke"], ["-publish"]]),
    "cases/freezeBondTension/Allrun": ([], [[], ["-np", "1", "-smoke"], ["-publish"]]),
    "cases/keelBond/Allrun": ([(["-resume", "1"], "1"), (["-keels", "iceStiff", "-smoke"], "-keels"), (["-keels", "x"], "-keels")],
                              [[], ["-np", "1", "-resume", "-smoke"], ["-publish"], ["-keels", "softened", "-publish"]]),
    "cases/packedBed/Allrun": (
        [(["-only", "x"], "-only"), (["-only"], "-only"), (["-case", "-smoke"], "-case")],
        [[], ["-smoke"], ["-only", "fluidisation", "-np", "2"], ["-only", "all"], ["-only", "fixed", "-publish"]]),
    "cases/ridgeFlexure/Allrun": (
        [(["-jobs", "0"], "-jobs"), (["-jobs", "x"], "-jobs"), (["-runs", "0"], "-runs"),
         (["-runs", "1,17"], "-runs"), (["-runs", "a"], "-runs"), (["-runs", "1,,2"], "-runs"),
         (["-runs"], "-runs"), (["-water", "x"], "-water"), (["-smoke", "-water", "cfd"], "-smoke"),
         (["-speed", "0"], "-speed"), (["-speed", "0.1m/s"], "-speed"), (["-speed", "0.1", "-publish"], "-speed"),
         (["-speed", "0.1", "-water", "cfd"], "-speed"), (["-resolution", "fine"], "-resolution"),
         (["-resolution"], "-resolution"), (["-keels", "iceStiff", "-quick"], "-keels"),
         (["-keels", "iceStiff", "-quick", "-water", "vof"], "-keels")],
        [[], ["-smoke"], ["-quick", "-jobs", "2", "-runs", "1,2,5"], ["-quick", "-runs", "6", "-speed", "0.05"],
         ["-resolution", "default", "-runs", "6", "-speed", "0.025", "-jobs", "1"],
         ["-quick", "-publish"], ["-keels", "softened", "-publish"], ["-keels", "softened", "-smoke"], ["-keels", "iceStiff", "-water", "vof", "-runs", "6"],
         ["-water", "cfd", "-runs", "6,14", "-publish"]]),
    "cases/ridgeDesignMap/Allrun": (
        [(["-jobs", "0"], "-jobs"), (["-data"], "-data"), (["-data", "foo=bar.csv"], "-data"),
         (["-data", "freezeBondSets"], "-data"), (["-data", "freezeBondSets=/no/such.csv"], "/no/such.csv"),
         (["-quick", "1"], "1")],
        [[], ["-smoke"], ["-quick", "-jobs", "2", "-resume"], ["-data", "freezeBondSets=/etc/hostname"]]),
    "cases/rubbleBeam/Allrun": (
        [(["-shape", "x"], "-shape"), (["-shape"], "-shape")],
        [[], ["-smoke"], ["-shape", "empirical", "-resume", "-np", "1"], ["-publish"]]),
    "cases/rubblePunch/Allrun": (
        [(["-keels", "x"], "-keels"), (["-keels", ""], "-keels"), (["-water", "x"], "-water"),
         (["-water", "cfd", "-resume"], "-resume"), (["-keelSeed", "1"], "-keelSeed"),
         (["-keelSeed", "2x"], "-keelSeed"), (["-keelSeed"], "-keelSeed"), (["-smoke", "-keelSeed", "2"], "-keelSeed"),
         (["-keelSeed", "3", "-publish"], "-keelSeed")],
        [[], ["-smoke"], ["-keels", "cuboid empirical", "-water", "cfd", "-rateStudy", "-np", "2"],
         ["-keels", "cuboid", "-keelSeed", "2", "-np", "1"],
         ["-keels", "empirical", "-resume"], ["-keels", "cuboid", "-water", "cfd", "-publish"]]),
    "cases/settlingBed/Allrun": (
        [(["-level", "x"], "-level"), (["-endTime", "0"], "-endTime"), (["-endTime", "abc"], "-endTime")],
        [[], ["-smoke"], ["-level", "none", "-endTime", "0.5", "-np", "2"]]),
    "cases/sphereSettling/Allrun": (
        [(["-case"], "-case"), (["-case", "/nonexistent/case"], "-case")],
        [[], ["-smoke"], ["-np", "2", "-case", "."]]),
    "cases/tenCateSettling/Allrun": (
        [(["--only", "E5"], "--only"), (["--only"], "--only"), (["--only", "E1,"], "--only"),
         (["--endTime", "0"], "--endTime"), (["--iceFoam", "x"], "--iceFoam")],
        [[], ["-smoke"], ["--only", "E1,E4", "--endTime", "0.6"]]),
}

# Allcleans that take options (they delete: a bad command line must delete nothing).
ALLCLEANS = {
    "cases/ridgeFlexure/Allclean": [(["-bogus"], "-bogus"), (["-keels", "x"], "x")],
    "cases/rubblePunch/Allclean": [(["-bogus"], "-bogus")],
    "cases/ridgeDesignMap/Allclean": [(["-bogus"], "-bogus"), (["-keels", "x"], "x")],
    "cases/packedBed/Allclean": [(["-bogus"], "-bogus"), (["a", "b"], "one case folder")],
    "cases/sphereSettling/Allclean": [(["-bogus"], "-bogus")],
    "cases/floatingBlock/cfd/Allclean": [(["-bogus"], "-bogus")],
    "cases/floatingBlock/vof/Allclean": [(["-bogus"], "-bogus")],
}

STUB = "#!/bin/bash\ntouch \"$(dirname \"${BASH_SOURCE[0]}\")/../STUB_RAN\"\n"


def snapshot(top):
    """A digest of every path, size and modification time under top."""
    h = hashlib.sha1()
    for d, dirs, files in sorted(os.walk(top)):
        dirs.sort()
        for name in sorted(dirs + files):
            p = os.path.join(d, name)
            st = os.lstat(p)
            h.update(f"{os.path.relpath(p, top)} {st.st_size} {st.st_mtime_ns}\n".encode())
    return h.hexdigest()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True, help="the project's top folder")
    a = ap.parse_args()
    start = time.time()
    work = tempfile.mkdtemp(prefix="allrunOptions.")
    failures, checked = [], 0
    try:
        for rel in case_files(a.source, "cases") + case_files(a.source, "bin") + ["Allrun"]:
            dest = os.path.join(work, rel)
            os.makedirs(os.path.dirname(dest), exist_ok=True)
            shutil.copy2(os.path.join(a.source, rel), dest)
        for stub in ("bin/installDependencies", "bin/build"):
            with open(os.path.join(work, stub), "w") as f:
                f.write(STUB)
        before = snapshot(work)
        env = {k: v for k, v in os.environ.items() if k != "ALLRUN_CHECK_ONLY"}

        def run(script, args, check_only):
            path = os.path.join(work, script)
            e = dict(env, ALLRUN_CHECK_ONLY="1") if check_only else env
            try:
                return subprocess.run([path, *args], cwd=os.path.dirname(path), env=e, capture_output=True,
                                      text=True, timeout=20)
            except subprocess.TimeoutExpired:
                return subprocess.CompletedProcess([path, *args], 124, "", "timed out after 20 s")

        for script, bad in [(s, COMMON_BAD + own) for s, (own, _) in SCRIPTS.items()] + list(ALLCLEANS.items()):
            for args, option in bad:
                checked += 1
                line = f"{script} {' '.join(repr(x) if not x or ' ' in x else x for x in args)}"
                r = run(script, args, check_only=False)
                problems = []
                if r.returncode != 2:
                    problems.append(f"exit status {r.returncode}, not 2")
                if option not in r.stderr:
                    problems.append(f"stderr does not name {option}")
                if "usage:" not in r.stderr:
                    problems.append("stderr has no usage line")
                if snapshot(work) != before:
                    problems.append("the copy changed (it wrote or deleted something before refusing)")
                    before = snapshot(work)
                if problems:
                    failures.append(f"{line}: {'; '.join(problems)}\n    stderr: {r.stderr.strip()}")
        for script, (_, good) in SCRIPTS.items():
            for args in good:
                checked += 1
                r = run(script, args, check_only=True)
                if r.returncode != 0 or snapshot(work) != before:
                    failures.append(f"{script} {' '.join(args)} (ALLRUN_CHECK_ONLY=1): exit status "
                                    f"{r.returncode}{'' if snapshot(work) == before else ', the copy changed'}"
                                    f"\n    stderr: {r.stderr.strip()}")
                    before = snapshot(work)
        # Every case's Allrun is in the table.
        for rel in case_files(a.source, "cases"):
            if os.path.basename(rel) == "Allrun" and rel not in SCRIPTS:
                failures.append(f"{rel}: not in this test's table (add its bad command lines)")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    for f in failures:
        print(f"FAIL {f}")
    print(f"{'FAIL' if failures else 'ok  '} allrunOptions: {checked} command lines, {len(failures)} failed, "
          f"{time.time() - start:.1f} s")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
