"""Helpers for studies that run many variants of a case: copy a case, set
dictionary entries by their dotted path (as foamDictionary -entry -set does),
run an application under mpirun, and read the results.

Used by the sweep, speed-study and benchmark scripts with Debian's
/usr/bin/python3."""
import csv
import json
import os
import re
import shutil
import subprocess
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(TOP), "shared")
BUILD = os.path.join(TOP, "build")


def _block_span(text, start, name):
    """(open, close) indices of the braces of sub-dictionary `name` in text[start:close]."""
    pattern = re.compile(r"(^|[\s;{}])" + re.escape(name) + r"\s*\{", re.M)
    depth_ok = None
    for m in pattern.finditer(text, start):
        # accept only matches at brace depth 0 relative to `start`
        depth = text.count("{", start, m.start()) - text.count("}", start, m.start())
        if depth == 0:
            depth_ok = m
            break
    if depth_ok is None:
        raise KeyError(name)
    open_brace = depth_ok.end() - 1
    depth = 0
    for k in range(open_brace, len(text)):
        if text[k] == "{":
            depth += 1
        elif text[k] == "}":
            depth -= 1
            if depth == 0:
                return open_brace, k
    raise ValueError(f"unclosed dictionary {name}")


def _entry_value_span(text, dotted, path):
    *dicts, key = dotted.split(".")
    start, end = 0, len(text)
    for name in dicts:
        open_brace, close_brace = _block_span(text[:end], start, name)
        start, end = open_brace + 1, close_brace
    pattern = re.compile(r"(^|[\s;{])(" + re.escape(key) + r")(\s+)([^;{}]*);", re.M)
    for m in pattern.finditer(text, start, end):
        depth = text.count("{", start, m.start()) - text.count("}", start, m.start())
        if depth == 0:
            return m.start(4), m.end(4)
    raise KeyError(f"{dotted} not found in {path}")


def get_entry(path, dotted):
    """The value text of `a.b.key value;` in an OpenFOAM dictionary file."""
    text = open(path).read()
    begin, end = _entry_value_span(text, dotted, path)
    return text[begin:end]


def set_entry(path, dotted, value):
    """Sets `a.b.key value;` in an OpenFOAM dictionary file (the entry must exist)."""
    text = open(path).read()
    begin, end = _entry_value_span(text, dotted, path)
    open(path, "w").write(text[:begin] + str(value) + text[end:])


def copy_case(source, target):
    shutil.rmtree(target, ignore_errors=True)
    os.makedirs(target)
    for sub in ("constant", "system", "DEM"):
        if os.path.isdir(os.path.join(source, sub)):
            shutil.copytree(os.path.join(source, sub), os.path.join(target, sub))
    for generated in ("DEM/packing.data", "DEM/platen.stl"):
        p = os.path.join(target, generated)
        if os.path.exists(p):
            os.remove(p)
    return target


def small_rubble_case(source, path, length, width, thickness, max_time, tilt, entries=None):
    """A reduced copy of a rubble case (cases/rubbleBeam): a shorter box, a
    thinner layer, a shorter settling; `entries` sets further dotted entries
    of its rubbleProperties."""
    copy_case(source, path)
    props = os.path.join(path, "constant", "rubbleProperties")
    set_entry(props, "box.length", length)
    set_entry(props, "box.width", width)
    set_entry(props, "blocks.rubbleThickness", thickness)
    set_entry(props, "settling.maxTime", max_time)
    set_entry(props, "settling.maxTilt", tilt)
    for entry, value in (entries or {}).items():
        set_entry(props, entry, value)
    return path


def run_app(app, case, ranks=1, args=(), log_name="log.run"):
    """Runs an application on a case; returns the wall time in s. Raises on failure."""
    # yield_when_idle: ranks that wait do not busy-spin a shared core (2 ranks on 2 busy cores).
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_mpi_yield_when_idle="1")
    exe = os.path.join(BUILD, "demModels", app) if not os.path.isabs(app) else app
    cmd = ["mpirun", "-np", str(ranks), "--oversubscribe", exe, "-case", case, *map(str, args)]
    start = time.time()
    with open(os.path.join(case, log_name), "w") as log:
        result = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    if result.returncode != 0:
        tail = open(os.path.join(case, log_name)).read()[-2000:]
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{tail}")
    return time.time() - start


def summary(case):
    return json.load(open(os.path.join(case, "postProcessing", "summary.json")))


def curve(case):
    with open(os.path.join(case, "postProcessing", "platenForce.csv")) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def residual_strength(case, window=0.03):
    """Mean force over `window` m of travel after the peak, as a fraction of the peak."""
    c, s = curve(case), summary(case)
    d0 = s["travel_at_peak_m"]
    values = [f for d, f in zip(c["displacement"], c["force"]) if d0 < d <= d0 + window]
    return sum(values) / len(values) / s["peak_force_N"] if values else float("nan")


def write_atomically(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)
