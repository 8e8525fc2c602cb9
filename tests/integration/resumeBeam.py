#!/usr/bin/python3
"""A run stopped part-way (as if killed while writing its next checkpoint: a
newer LIGGGHTS restart and a half-written one lie beside the last complete
checkpoint) and resumed gives the answer of the uninterrupted run to the last
bit: the same force curve and time axis, peak and broken bonds, and a wall time that counts the
stopped run's up to the checkpoint (wall_before_resume_s). Before that,
a resume against other inputs (another platen speed on the command line,
another breakN) is refused with a message naming the input and the
checkpoint, and leaves the checkpoint as it was.

usage: resumeBeam.py CASE WORKDIR APP"""
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402

case, work, app = sys.argv[1:4]
args = ["-particles", "400", "-platenSpeed", "0.2"]

whole = iceCases.copy_case(case, os.path.join(work, "whole"))
iceCases.run_app(app, whole, 1, args, "log.iceBeamDEM")
stopped = iceCases.copy_case(case, os.path.join(work, "stoppedAndResumed"))
iceCases.run_app(app, stopped, 1, args + ["-steps", "9000"], "log.iceBeamDEM.1")
checkpoint = os.path.join(stopped, "DEM", "checkpoint")
restarts = [f for f in os.listdir(checkpoint) if f.startswith("liggghts.restart")]
if len(restarts) != 1:
    sys.exit(f"FAIL: expected one LIGGGHTS restart in {checkpoint}, found {restarts}")
stopped_wall = iceCases.summary(stopped)["wall_s"]
newer_step = int(restarts[0].rsplit(".", 1)[1]) + 1400
shutil.copy(os.path.join(checkpoint, restarts[0]), os.path.join(checkpoint, f"liggghts.restart.{newer_step}"))
with open(os.path.join(checkpoint, "liggghts.restart.tmp"), "wb") as f:
    f.write(b"LammpS RestartFile half writ")


def refused(extra_args, names):
    """The resume is refused: exit 1, a message naming each of `names`, the checkpoint untouched."""
    before = {f: open(os.path.join(checkpoint, f), "rb").read() for f in os.listdir(checkpoint)}
    run = subprocess.run(["mpirun", "--allow-run-as-root", "-np", "1", app, "-case", stopped] + extra_args,
                         capture_output=True, text=True)
    text = run.stdout + run.stderr
    after = {f: open(os.path.join(checkpoint, f), "rb").read() for f in os.listdir(checkpoint)}
    missing = [n for n in names if n not in text]
    ok = run.returncode == 1 and not missing and before == after
    print(("ok   " if ok else "FAIL ") + f"{' '.join(extra_args)}: exit {run.returncode}, names {names}"
          + (f", missing {missing}" if missing else "") + ("" if before == after else ", checkpoint CHANGED"))
    return ok


refusals_ok = refused(["-particles", "400", "-platenSpeed", "0.1", "-resume"],
                      ["iceBeamDEM.checkpoint", "command line -platenSpeed", "'0.2'", "'0.1'", "without -resume"])
ice = os.path.join(stopped, "constant", "iceProperties")
breakN = iceCases.get_entry(ice, "bondFamilies.ice.breakN")
iceCases.set_entry(ice, "bondFamilies.ice.breakN", 0.002)
refusals_ok &= refused(args + ["-resume"], ["iceBeamDEM.checkpoint", "iceProperties/bondFamilies.ice.breakN"])
iceCases.set_entry(ice, "bondFamilies.ice.breakN", breakN)
iceCases.run_app(app, stopped, 1, args + ["-resume"], "log.iceBeamDEM.2")

a, b = iceCases.curve(whole), iceCases.curve(stopped)
sa, sb = iceCases.summary(whole), iceCases.summary(stopped)
failed = [] if refusals_ok else ["a resume against changed inputs was not refused as it should be"]
if a["time"] != b["time"]:
    failed.append("the resumed run's time axis differs")
differing = [k for k, (x, y) in enumerate(zip(a["force"], b["force"])) if x != y]
if differing:
    failed.append(f"{len(differing)} force samples differ, the first at sample {differing[0]}")
if sa["peak_force_N"] != sb["peak_force_N"]:
    failed.append(f"peak {sa['peak_force_N']} != {sb['peak_force_N']}")
na, nb = sa["crack_pattern"]["broken_bonds"], sb["crack_pattern"]["broken_bonds"]
if na != nb:
    failed.append(f"broken bonds {na} vs {nb}")
before, total = sb.get("wall_before_resume_s", 0.0), sb.get("wall_s", 0.0)
if not (0.0 < before <= stopped_wall and total > before):
    failed.append(f"the resumed run's wall_s {total:.3g} s should include the {before:.3g} s before the resume,"
                  f" more than 0 and at most the stopped run's {stopped_wall:.3g} s")
left = sorted(f for f in os.listdir(checkpoint) if f.startswith("liggghts.restart"))
if len(left) > 1:
    failed.append(f"stale restarts left in the checkpoint: {left}")
print(f"uninterrupted: {len(a['time'])} samples, peak {sa['peak_force_N']:.6g} N, {na} broken; "
      f"stopped at 9000 steps, a newer restart and a half-written one beside the checkpoint, and resumed: {len(b['time'])} samples, peak {sb['peak_force_N']:.6g} N, {nb} broken")
for f in failed:
    print("FAIL:", f)
print(f"{0 if failed else 1} passed, {1 if failed else 0} failed")
sys.exit(1 if failed else 0)
