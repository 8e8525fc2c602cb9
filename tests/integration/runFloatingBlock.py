#!/usr/bin/python3
"""Copies the floating-block case into a work folder, makes it small, runs it.

usage: runFloatingBlock.py CASE WORKDIR NP APP"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402

case, work, ranks, app = sys.argv[1:]
iceCases.copy_case(case, work)
# 3 x 3 spheres in 2 layers released half-way to its draft: at rest within 15 s.
iceCases.set_entry(os.path.join(work, "constant", "blockProperties"), "block.spheres", "(3 3 2)")
iceCases.set_entry(os.path.join(work, "constant", "blockProperties"), "block.releaseDepth", "0.05")
iceCases.set_entry(os.path.join(work, "system", "controlDict"), "endTime", "15")
iceCases.set_entry(os.path.join(work, "system", "controlDict"), "writeInterval", "2")
iceCases.run_app(app, work, int(ranks), [], "log.floatingBlockDEM")
print("".join(open(os.path.join(work, "log.floatingBlockDEM")).readlines()[-2:]), end="")
