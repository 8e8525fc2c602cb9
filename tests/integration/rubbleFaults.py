#!/usr/bin/python3
"""A rubble settling (cases/rubbleBeam, reduced) SIGKILLed three times, each a random moment
(seeded: ICEDEM_FAULT_SEED, default 1) after it wrote a new settling checkpoint, and resumed each
time with -resume, ends with the uninterrupted settling's rubble to the last bit: every particle's
position, velocity and spin and every bond's history in DEM/settled.h5, and the settled time; its
settling.json counts the wall time the killed runs had spent up to the checkpoint it resumed from.

usage: rubbleFaults.py CASE WORKDIR APP"""
import json
import os
import random
import shutil
import sys
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402

case, work, app = sys.argv[1:]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def small(name):
    shutil.rmtree(os.path.join(work, name), ignore_errors=True)   # no stage of an earlier run
    path = iceCases.small_rubble_case(case, os.path.join(work, name), 1.0, 0.6, 0.2, 6, 30,
                                      {"settling.checkpointInterval": 0.25, "settling.minTime": 6})
    iceCases.uncompacted(os.path.join(path, "constant", "rubbleProperties"), 0.6)    # settling only
    return path


whole = small("whole")
iceCases.run_app(app, whole, 1, ["-stage", "settle"], "log.settle")

killed = small("killed")
checkpoint = os.path.join(killed, "DEM", "settling.checkpoint.h5")
pick = random.Random(int(os.environ.get("ICEDEM_FAULT_SEED", "1")))
delays = []
killed_runs_started = time.monotonic()
for attempt in range(3):
    delays.append(pick.uniform(0.0, 0.01))    # the small settling runs at tens of thousands of steps a second
    iceCases.kill_after_new_checkpoint(app, killed, ["-stage", "settle"] + (["-resume"] if attempt else []),
                                       checkpoint, f"log.settle.{attempt}", delays[-1])
killed_runs_wall = time.monotonic() - killed_runs_started
settled = os.path.join(killed, "DEM", "settled.h5")
check(not os.path.exists(settled),
      f"killed three times, {', '.join(f'{d:.3f}' for d in delays)} s after a new checkpoint each, before it settled")
iceCases.run_app(app, killed, 1, ["-stage", "settle", "-resume"], "log.settle.final")
log = open(os.path.join(killed, "log.settle.final")).read()
check("Resuming the settling from" in log, "the last run resumed from the checkpoint")
# The wall time counts the killed runs' settling up to the checkpoint resumed from, not just the resume's.
settling = json.load(open(os.path.join(killed, "postProcessing", "settling.json")))
before, total = settling.get("wall_before_resume_s", 0.0), settling.get("wall_s", 0.0)
check(0.0 < before <= killed_runs_wall and total > before,
      f"wall_s {total:.3g} s includes {before:.3g} s before the resume (the killed runs took {killed_runs_wall:.3g} s)")

with h5py.File(os.path.join(whole, "DEM", "settled.h5"), "r") as a, h5py.File(settled, "r") as b:
    check(a.attrs["time"] == b.attrs["time"], f"settled at the same time ({a.attrs['time']:.6g} s, {b.attrs['time']:.6g} s)")
    for group in ("particles", "bonds"):
        for name in a[group]:
            x, y = np.array(a[group][name]), np.array(b[group][name])
            check(x.shape == y.shape and np.array_equal(x, y),
                  f"{group}/{name}: " + ("identical" if x.shape == y.shape and np.array_equal(x, y)
                                         else f"DIFFERENT (largest difference {np.max(np.abs(x - y)):.3g})"))
sys.exit(1 if failures else 0)
