#!/usr/bin/python3
"""A run stopped part-way (as if killed) and resumed from its checkpoint gives
the answer of the uninterrupted run: every force sample up to the checkpoint
identical, the time axis continued, the curve the same length, the peak force
identical and the broken bonds within 2 %.

usage: resumeBeam.py CASE WORKDIR APP"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402

case, work, app = sys.argv[1:4]
args = ["-particles", "400", "-platenSpeed", "0.2"]

whole = iceCases.copy_case(case, os.path.join(work, "whole"))
iceCases.run_app(app, whole, 1, args, "log.iceBeamDEM")
stopped = iceCases.copy_case(case, os.path.join(work, "stoppedAndResumed"))
iceCases.run_app(app, stopped, 1, args + ["-steps", "9000"], "log.iceBeamDEM.1")
iceCases.run_app(app, stopped, 1, args + ["-resume"], "log.iceBeamDEM.2")

a, b = iceCases.curve(whole), iceCases.curve(stopped)
sa, sb = iceCases.summary(whole), iceCases.summary(stopped)
checkpoint_rows = 600   # checkpointInterval / sampleInterval = 100 samples; 9000 steps = 642 samples
failed = []
if a["force"][:checkpoint_rows] != b["force"][:checkpoint_rows]:
    failed.append("force samples before the checkpoint differ")
if a["time"] != b["time"]:
    failed.append("the resumed run's time axis differs")
if sa["peak_force_N"] != sb["peak_force_N"]:
    failed.append(f"peak {sa['peak_force_N']} != {sb['peak_force_N']}")
na, nb = sa["crack_pattern"]["broken_bonds"], sb["crack_pattern"]["broken_bonds"]
if abs(na - nb) > 0.02 * na:
    failed.append(f"broken bonds {na} vs {nb}")
print(f"uninterrupted: {len(a['time'])} samples, peak {sa['peak_force_N']:.6g} N, {na} broken; "
      f"stopped at 9000 steps and resumed: {len(b['time'])} samples, peak {sb['peak_force_N']:.6g} N, {nb} broken")
for f in failed:
    print("FAIL:", f)
print(f"{0 if failed else 1} passed, {1 if failed else 0} failed")
sys.exit(1 if failed else 0)
