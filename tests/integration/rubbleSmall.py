#!/usr/bin/python3
"""Reduced rubble beam (cases/rubbleBeam) checks that can fail:

1. one block rained alone floats at the Archimedes draft: submerged volume
   fraction rho_i / rho_w within 1 %, and comes to rest;
2. a small rubble beam settles to rest; freeze-bonding the same settled state
   on 1 and 2 ranks gives the same bonds; every freeze-bond joins particles of
   different blocks that touch; the saved file holds every bond of the summary;
3. the settled rubble is not bonded against other inputs: -stage bond -shape
   empirical on a cuboid settle, or after the box changed, is refused naming
   the input, settled.h5 and the command that settles it anew; with the box
   put back it bonds as before.

usage: rubbleSmall.py CASE WORKDIR APP"""
import json
import os
import subprocess
import sys

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


def small_case(path, length, width, thickness, max_time, tilt):
    return iceCases.small_rubble_case(case, path, length, width, thickness, max_time, tilt)


# 1. One block alone.
single = small_case(os.path.join(work, "singleBlock"), 0.6, 0.5, 0.005, 12, 0)
# The heave of a lone block decays slowly: wait until it has (1e-9 J per particle).
iceCases.set_entry(os.path.join(single, "constant", "rubbleProperties"), "settling.kineticEnergyThreshold", 1e-9)
iceCases.run_app(app, single, 1, ["-stage", "all"], "log.rubbleDEM")
s = iceCases.summary(single)
submerged = 1 - s["ice_volume_above_water_fraction"]
check(s["blocks"] == 1, f"one block ({s['blocks']})")
check(abs(submerged / (917 / 1000) - 1) < 0.01,
      f"submerged volume fraction {submerged:.4f} against rho_i/rho_w 0.917 (within 1 %)")
check(s["at_rest"], f"the block comes to rest (kinetic energy {s['kinetic_energy_per_particle_J']:.2e} J/particle)")

# 2. A small beam: settle once, bond the same settled state on 1 and 2 ranks.
beam = small_case(os.path.join(work, "beam"), 1.0, 0.6, 0.2, 10, 30)
iceCases.run_app(app, beam, 1, ["-stage", "settle"], "log.settle")
results = {}
for ranks in (1, 2):
    iceCases.run_app(app, beam, ranks, ["-stage", "bond"], f"log.bond_np{ranks}")
    results[ranks] = iceCases.summary(beam)
    with h5py.File(os.path.join(beam, "DEM", "rubble.h5"), "r") as f:
        results[ranks]["file"] = {
            "x": np.stack([np.array(f["particles"][k]) for k in ("x", "y", "z")], axis=1),
            "radius": np.array(f["particles"]["radius"]),
            "block": np.array(f["particles"]["block"]).astype(int),
            "tagA": np.array(f["bonds"]["tagA"]).astype(int),
            "tagB": np.array(f["bonds"]["tagB"]).astype(int),
            "family": np.array(f["bonds"]["family"]).astype(int),
            "tensile": np.array(f["bonds"]["tensileStrength"]),
        }
one, two = results[1], results[2]
check(one["freeze_bonds"] > 0, f"freeze-bonds created ({one['freeze_bonds']})")
check(one["freeze_bonds"] == two["freeze_bonds"],
      f"same freeze-bond count on 1 and 2 ranks ({one['freeze_bonds']}, {two['freeze_bonds']})")
check(one["freeze_bond_tensile_mean_Pa"] == two["freeze_bond_tensile_mean_Pa"],
      "same mean freeze-bond strength on 1 and 2 ranks")
f = one["file"]
check(len(f["tagA"]) == one["bonds"] == one["ice_bonds"] + one["freeze_bonds"],
      f"saved file holds every bond ({len(f['tagA'])})")
freeze = f["family"] == 1
a, b = f["tagA"][freeze] - 1, f["tagB"][freeze] - 1
check(bool(np.all(f["block"][a] != f["block"][b])), "every freeze-bond joins two different blocks")
gap = np.linalg.norm(f["x"][a] - f["x"][b], axis=1) - (f["radius"][a] + f["radius"][b])
check(bool(np.all(gap <= 1e-12)), f"every freeze-bond joins touching particles (largest gap {gap.max():.2e} m)")
ice = f["family"] == 0
check(bool(np.all(f["block"][f["tagA"][ice] - 1] == f["block"][f["tagB"][ice] - 1])),
      "every ice bond lies inside one block")


# 3. Stale settled rubble.
def refused(args, names):
    run = subprocess.run(["mpirun", "--allow-run-as-root", "-np", "1", app, "-case", beam] + args,
                         capture_output=True, text=True)
    text = run.stdout + run.stderr
    missing = [n for n in names if n not in text]
    check(run.returncode == 1 and not missing,
          f"{' '.join(args)}: exit {run.returncode}, names {names}" + (f", missing {missing}" if missing else ""))


refused(["-stage", "bond", "-shape", "empirical"], ["settled.h5", "block shape", "'cuboid'", "'empirical'", "-stage settle"])
props = os.path.join(beam, "constant", "rubbleProperties")
width = iceCases.get_entry(props, "box.width")
iceCases.set_entry(props, "box.width", 0.7)
refused(["-stage", "bond"], ["settled.h5", "rubbleProperties/box.width", "-stage settle"])
iceCases.set_entry(props, "box.width", width)
iceCases.run_app(app, beam, 1, ["-stage", "bond"], "log.bond_again")
check(iceCases.summary(beam)["freeze_bonds"] == one["freeze_bonds"],
      "the box put back, the settled rubble bonds again as before")
sys.exit(1 if failures else 0)
