"""A self-contained scratch copy of a case that still finds what the case in the
source tree finds by its relative paths (../.. is the top). Used by the smoke tests
(tests/cases/runSmoke.py) and by bin/reproduce.

The copy lives in a mirror of the project, WORK/NAME/:
  WORK/NAME/cases/CASE      the case (files git tracks or would add)
  WORK/NAME/cases/common    shared dictionaries, if the project has them
  WORK/NAME/cases/OTHER     sibling cases the case reads (others)
  WORK/NAME/{build,postProcessing,bin,tests,studies}  links to the build and the sources
  WORK/shared               link to the project's ../shared (made here if missing)
Nothing is written into the source tree."""
import os
import shutil
import subprocess


def case_files(top, folder):
    """Paths (relative to top) of a folder's files that git tracks or would add; all files without git."""
    try:
        out = subprocess.run(["git", "-C", top, "ls-files", "-z", "--cached", "--others", "--exclude-standard",
                              "--", folder], check=True, capture_output=True).stdout
        return [p for p in out.decode().split("\0") if p and os.path.isfile(os.path.join(top, p))]
    except (OSError, subprocess.CalledProcessError):
        return [os.path.relpath(os.path.join(d, f), top)
                for d, _, files in os.walk(os.path.join(top, folder)) for f in files]


def copy_folder(top, folder, mirror, skip=()):
    """Copies the folder's files into the mirror (but those under a skipped subfolder
    of the folder, e.g. results); returns their paths there."""
    copied = []
    for rel in case_files(top, folder):
        inner = os.path.relpath(rel, folder).split(os.sep)[0]
        if inner in skip:
            continue
        dest = os.path.join(mirror, rel)
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        shutil.copy2(os.path.join(top, rel), dest)
        copied.append(dest)
    return copied


def make_mirror(source, build, work, case, name=None, others=(), skip=()):
    """A fresh mirror WORK/NAME of the project holding cases/CASE, cases/common and
    cases/OTHER...; returns (path of the case copy, paths of every copied file)."""
    source = os.path.abspath(source)
    mirror = os.path.join(work, name or case)
    shutil.rmtree(mirror, ignore_errors=True)
    copied = []
    for folder in [case, "common", *others]:
        if os.path.isdir(os.path.join(source, "cases", folder)):
            copied += copy_folder(source, os.path.join("cases", folder), mirror, skip)
    for link, target in (("build", build), ("postProcessing", "postProcessing"), ("bin", "bin"), ("tests", "tests"),
                         ("studies", "studies")):
        os.symlink(os.path.join(source, target), os.path.join(mirror, link))
    shared = os.path.join(work, "shared")
    if not os.path.lexists(shared) and os.path.isdir(os.path.join(source, "..", "shared")):
        os.symlink(os.path.realpath(os.path.join(source, "..", "shared")), shared)
    return os.path.join(mirror, "cases", case), copied
