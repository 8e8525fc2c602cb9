#!/usr/bin/python3
"""Smoke test of one case: runs a copy of cases/CASE through its own ./Allrun
with the given options, then checks the exit status and that each expected
output file exists, is not empty and (if text) holds no nan, and that every
file the copy got from the source tree is still byte-identical (a run writes
only untracked places: postProcessing/, runs/, a study's output folder; results/
changes only through ./Allrun -publish).

The copy lives in a mirror of the project, WORK/NAME/, so that the Allrun finds
what it finds in the source tree by its relative paths (../.. is the top):
  WORK/NAME/cases/CASE      the case (files git tracks or would add; no results)
  WORK/NAME/cases/common    shared dictionaries, if the project has them
  WORK/NAME/cases/OTHER     sibling cases the case reads (--with)
  WORK/NAME/{build,postProcessing,bin,tests,studies}  links to the build and the sources
  WORK/shared               link to the project's ../shared (made by CMake)
Nothing is written into the source tree.

usage: runSmoke.py --source TOP --build BUILD --work WORK --case CASE [--name NAME]
                   [--with OTHER ...] [--expect GLOB ...] -- ALLRUN_OPTIONS..."""
import argparse
import glob
import hashlib
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
from caseMirror import case_files, make_mirror  # noqa: E402,F401 (case_files: for allrunOptions.py)

NAN = re.compile(rb"(?<![A-Za-z_])[-+]?nan(?![A-Za-z_])", re.I)


def digest(path):
    """The file's SHA-256, or a word saying why there is none."""
    if not os.path.isfile(path):
        return "missing"
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def check_output(case, pattern):
    """A message for each problem with the files matching pattern (relative to the case)."""
    paths = sorted(glob.glob(os.path.join(case, pattern)))
    if not paths:
        return [f"{pattern}: missing"]
    problems = []
    for path in paths:
        rel = os.path.relpath(path, case)
        data = open(path, "rb").read()
        if not data:
            problems.append(f"{rel}: empty")
        elif b"\0" not in data[:4096] and NAN.search(data):
            line = data[:NAN.search(data).start()].count(b"\n") + 1
            problems.append(f"{rel}: nan at line {line}")
    return problems


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--case", required=True)
    ap.add_argument("--name", help="of the test and its folder (default: the case's)")
    ap.add_argument("--with", dest="others", nargs="*", default=[])
    ap.add_argument("--expect", nargs="*", default=[])
    ap.add_argument("options", nargs="*")
    a = ap.parse_args()
    name = a.case
    mirror = os.path.join(a.work, a.name or name)
    case, copied = make_mirror(a.source, a.build, a.work, name, a.name, a.others)
    before = {path: digest(path) for path in copied}
    allrun = os.path.join(case, "Allrun")
    if not os.access(allrun, os.X_OK):
        sys.exit(f"smoke {name}: cases/{name}/Allrun missing or not executable")

    cmd = [allrun, *a.options]
    print(f"smoke {name}: {' '.join(['./Allrun', *a.options])} in {case}", flush=True)
    start = time.time()
    with open(os.path.join(mirror, "log.Allrun"), "w") as log:
        rc = subprocess.run(cmd, cwd=case, stdout=log, stderr=subprocess.STDOUT).returncode
    output = open(os.path.join(mirror, "log.Allrun"), errors="replace").read()
    print(output[-3000:], end="")
    print(f"smoke {name}: ./Allrun exited {rc} after {time.time() - start:.1f} s (log {mirror}/log.Allrun)")
    problems = [f"./Allrun {' '.join(a.options)} exited {rc}"] if rc else []
    for pattern in a.expect:
        problems += check_output(case, pattern)
    for path, hash_before in before.items():
        hash_after = digest(path)
        if hash_after != hash_before:
            problems.append(f"{os.path.relpath(path, mirror)}: a file of the source tree "
                            f"{'removed' if hash_after == 'missing' else 'changed'} by the run")
    for p in problems:
        print(f"FAIL smoke {name}: {p}")
    if not problems:
        print(f"ok   smoke {name}: {len(a.expect)} output file pattern(s) present, non-empty, no nan; "
              f"{len(before)} source file(s) unchanged")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
