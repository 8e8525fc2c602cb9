#!/usr/bin/python3
"""Copies a beam case's inputs into a work folder and runs iceBeamDEM there.

usage: runBeamCase.py CASE WORKDIR NP APP [app options...]"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402

case, work, ranks, app, *options = sys.argv[1:]
iceCases.copy_case(case, work)
iceCases.run_app(app, work, int(ranks), options, "log.iceBeamDEM")
print("".join(open(os.path.join(work, "log.iceBeamDEM")).readlines()[-3:]), end="")
