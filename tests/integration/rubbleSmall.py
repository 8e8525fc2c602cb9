#!/usr/bin/python3
"""Reduced rubble beam (cases/rubbleBeam) checks that can fail:

1. one block rained alone (no compaction) floats at the Archimedes draft:
   submerged volume fraction rho_i / rho_w within 1 %, and comes to rest;
2. a small rubble beam settles; compacting it between plates reaches the
   target porosity exactly, the lid then backs off to near its hold pressure
   (the rubble springs back: porosity above the target), every particle and
   the ice volume kept, on 1 and 2 ranks alike (the backed-off porosity
   within 0.02: blocks rearranging under load are chaotic);
   freeze-bonding the same compacted state on 1 and 2 ranks gives the same
   bonds; the bonds made under the plates carry more confinement than those
   made where the same heap settled; every freeze-bond joins particles of
   different blocks that touch; the saved file holds every bond of the summary;
3. the settled rubble is not compacted against other inputs: -stage compact
   -shape empirical on a cuboid settle, or after the box changed, is refused
   naming the input, settled.h5 and the command that settles it anew; a
   compacted rubble is not bonded after the plates' speed changed (naming
   compacted.h5 and -stage compact), nor after the target porosity changed
   (the ice rained in: settled.h5 and -stage settle); with the inputs put back
   it compacts and bonds as before;
4. compacted with contacts ten times stiffer (compaction.youngsModulus), the
   same settled heap closes at the target, the stage records the contacts'
   modulus (compacted.h5 and compaction.json), and the lid needs several times
   the soft contacts' pressure at the same gap (postProcessing/compaction.json:
   overlaps between blocks when closed and after the hold);
5. the same stiff compaction allowed half the lid pressure it needed to close
   stops before the target with exit 3 (a run error: AppMain.C) and "out of reach", leaving its curve
   (postProcessing/compaction.csv) and no compacted.h5; the settling-levels
   study (cases/rubbleBeam/studies/settlingLevels.py) reads where the heap
   jammed from its log: above the target porosity, above the allowed pressure,
   the curve's last row.

usage: rubbleSmall.py CASE WORKDIR APP"""
import json
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "cases", "rubbleBeam",
                                "studies"))
import settlingLevels  # noqa: E402

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
iceCases.uncompacted(os.path.join(single, "constant", "rubbleProperties"), 0.6)
# The heave of a lone block decays slowly: wait until it has (1e-9 J per particle).
iceCases.set_entry(os.path.join(single, "constant", "rubbleProperties"), "settling.kineticEnergyThreshold", 1e-9)
iceCases.run_app(app, single, 1, ["-stage", "all"], "log.rubbleDEM")
s = iceCases.summary(single)
submerged = 1 - s["ice_volume_above_water_fraction"]
check(s["blocks"] == 1, f"one block ({s['blocks']})")
check(abs(submerged / (917 / 1000) - 1) < 0.01,
      f"submerged volume fraction {submerged:.4f} against rho_i/rho_w 0.917 (within 1 %)")
check(s["at_rest"], f"the block comes to rest (kinetic energy {s['kinetic_energy_per_particle_J']:.2e} J/particle)")

# 2. A small beam: settle once, compact on 1 and 2 ranks, bond the same compacted state on 1 and 2 ranks.
beam = small_case(os.path.join(work, "beam"), 1.0, 0.6, 0.2, 10, 30)
props = os.path.join(beam, "constant", "rubbleProperties")
target = float(iceCases.get_entry(props, "compaction.targetPorosity"))
iceCases.run_app(app, beam, 1, ["-stage", "settle"], "log.settle")


def particles(path):
    with h5py.File(path, "r") as f:
        return {"x": np.stack([np.array(f["particles"][k]) for k in ("x", "y", "z")], axis=1),
                "radius": np.array(f["particles"]["radius"]),
                "bottom": f.attrs.get("plateBottom"), "top": f.attrs.get("plateTop")}


def compaction_log(log):
    """The porosity when the plates closed, after the lid backed off, and the lid's pressure then."""
    line = [l for l in open(os.path.join(beam, log)) if l.startswith("Compacted in")][-1]
    m = re.search(r"-> (\S+), (\S+) after .* lid (\S+) Pa, floor", line)
    return {"closed": float(m.group(1)), "porosity": float(m.group(2)), "lid_Pa": float(m.group(3))}


settled = particles(os.path.join(beam, "DEM", "settled.h5"))
hold = float(iceCases.get_entry(props, "compaction.holdPressure"))
compacted = {}
for ranks in (2, 1):    # the 1-rank state stays for the bonds
    iceCases.run_app(app, beam, ranks, ["-stage", "compact"], f"log.compact_np{ranks}")
    compacted[ranks] = dict(particles(os.path.join(beam, "DEM", "compacted.h5")), **compaction_log(f"log.compact_np{ranks}"))
c1, c2 = compacted[1], compacted[2]
check(abs(c1["closed"] - target) <= 1e-6 and c1["porosity"] >= c1["closed"],
      f"compacted to porosity {c1['closed']:.4f} (target {target}), {c1['porosity']:.4f} after the lid backed off")
check(len(c1["radius"]) == len(settled["radius"]) and np.array_equal(c1["radius"], settled["radius"]),
      f"compaction keeps every particle and the ice volume ({len(c1['radius'])})")
inside = (c1["x"][:, 2] - c1["radius"] > c1["bottom"] - 0.01) & (c1["x"][:, 2] + c1["radius"] < c1["top"] + 0.01)
check(bool(np.all(inside)), f"every particle between the plates at z = {c1['bottom']:.3f}-{c1['top']:.3f} m")
check(c1["closed"] == c2["closed"] and abs(c1["porosity"] - c2["porosity"]) < 0.02,
      f"1 and 2 ranks: closed at the same gap, porosity after backing off {c1['porosity']:.4f}, {c2['porosity']:.4f}")
check(all(c["lid_Pa"] < 3 * hold for c in (c1, c2)),
      f"the lid backed off to about {hold:.0f} Pa on 1 and 2 ranks ({c1['lid_Pa']:.0f}, {c2['lid_Pa']:.0f} Pa)")
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
    results[ranks]["bondsAtBonding"] = np.loadtxt(os.path.join(beam, "postProcessing", "freezeBonds.csv"),
                                                  delimiter=",", skiprows=1, ndmin=2)
one, two = results[1], results[2]
check(one["freeze_bonds"] > 0, f"freeze-bonds created ({one['freeze_bonds']})")
check(one["freeze_bonds"] == two["freeze_bonds"],
      f"same freeze-bond count on 1 and 2 ranks ({one['freeze_bonds']}, {two['freeze_bonds']})")
check(one["freeze_bond_tensile_mean_Pa"] == two["freeze_bond_tensile_mean_Pa"],
      "same mean freeze-bond strength on 1 and 2 ranks")
check(abs(one["compaction"]["porosity"] - c1["porosity"]) < 1e-4 and one["released"]["porosity"] > 0,
      f"summary: compacted to {one['compaction']['porosity']:.4f}, released to {one['released']['porosity']:.4f}")
# The same settled heap bonded where it lay, in a copy without compaction.
loose = iceCases.copy_case(beam, os.path.join(work, "beamLoose"))
iceCases.set_entry(os.path.join(loose, "constant", "rubbleProperties"), "compaction.method", "none")
iceCases.add_entry(os.path.join(loose, "constant", "rubbleProperties"), "blocks.expectedPorosity", target)
iceCases.run_app(app, loose, 1, ["-stage", "settle"], "log.settle")
iceCases.run_app(app, loose, 1, ["-stage", "bond"], "log.bond")
uncompacted = iceCases.summary(loose)
check(one["confinement_mean_Pa"] > 2 * uncompacted["confinement_mean_Pa"],
      f"bonds made under the plates carry more confinement ({one['confinement_mean_Pa']:.0f} Pa mean, "
      f"{one['compaction']['lid_pressure_at_bonding_Pa']:.0f} Pa on the lid) than where the heap settled "
      f"({uncompacted['confinement_mean_Pa']:.0f} Pa)")
bonded = one["bondsAtBonding"]
check(bool(np.all((bonded[:, 2] > 0) == (bonded[:, 3] > 0))),
      "each bond's confinement is that of its measured contact force (zero exactly where the force is)")
f = one["file"]
check(len(f["tagA"]) == one["bonds"] == one["ice_bonds"] + one["freeze_bonds"],
      f"saved file holds every bond ({len(f['tagA'])})")
freeze = f["family"] == 1
a, b = f["tagA"][freeze] - 1, f["tagB"][freeze] - 1
check(bool(np.all(f["block"][a] != f["block"][b])), "every freeze-bond joins two different blocks")
# touching when bonded, under the plates (the saved file holds the released rubble)
with h5py.File(os.path.join(beam, "DEM", "compacted.h5"), "r") as c:
    xc = np.stack([np.array(c["particles"][k]) for k in ("x", "y", "z")], axis=1)
gap = np.linalg.norm(xc[a] - xc[b], axis=1) - (f["radius"][a] + f["radius"][b])
check(bool(np.all(gap <= 1e-12)), f"every freeze-bond joins particles that touched (largest gap {gap.max():.2e} m)")
ice = f["family"] == 0
check(bool(np.all(f["block"][f["tagA"][ice] - 1] == f["block"][f["tagB"][ice] - 1])),
      "every ice bond lies inside one block")


# 3. Stale settled and compacted rubble.
def refused(args, names):
    run = subprocess.run(["mpirun", "--allow-run-as-root", "-np", "1", app, "-case", beam] + args,
                         capture_output=True, text=True)
    text = run.stdout + run.stderr
    missing = [n for n in names if n not in text]
    check(run.returncode == 1 and not missing,
          f"{' '.join(args)}: exit {run.returncode}, names {names}" + (f", missing {missing}" if missing else ""))


refused(["-stage", "compact", "-shape", "empirical"], ["settled.h5", "block shape", "'cuboid'", "'empirical'", "-stage settle"])
width = iceCases.get_entry(props, "box.width")
iceCases.set_entry(props, "box.width", 0.7)
refused(["-stage", "compact"], ["settled.h5", "rubbleProperties/box.width", "-stage settle"])
iceCases.set_entry(props, "box.width", width)
speed = iceCases.get_entry(props, "compaction.speed")
iceCases.set_entry(props, "compaction.speed", 0.04)
refused(["-stage", "bond"], ["compacted.h5", "rubbleProperties/compaction.speed", "-stage compact"])
iceCases.set_entry(props, "compaction.speed", speed)
iceCases.set_entry(props, "compaction.targetPorosity", target + 0.05)   # another amount of ice rained in
refused(["-stage", "bond"], ["settled.h5", "porosity of a blocks.rubbleThickness layer", "-stage settle"])
iceCases.set_entry(props, "compaction.targetPorosity", target)
soft = json.load(open(os.path.join(beam, "postProcessing", "compaction.json")))
iceCases.run_app(app, beam, 1, ["-stage", "compact"], "log.compact_again")
iceCases.run_app(app, beam, 1, ["-stage", "bond"], "log.bond_again")
check(iceCases.summary(beam)["freeze_bonds"] == one["freeze_bonds"],
      "the box put back, the settled rubble compacts and bonds again as before")

# 4. The same settled heap compacted with contacts ten times stiffer.
stiff = iceCases.copy_case(beam, os.path.join(work, "beamStiff"))
shutil.copy(os.path.join(beam, "DEM", "settled.h5"), os.path.join(stiff, "DEM", "settled.h5"))
modulus = 10 * float(iceCases.get_entry(props, "settling.youngsModulus"))
iceCases.set_entry(os.path.join(stiff, "constant", "rubbleProperties"), "compaction.youngsModulus", modulus)
iceCases.set_entry(os.path.join(stiff, "constant", "rubbleProperties"), "compaction.maxPressure", 1e6)
iceCases.run_app(app, stiff, 1, ["-stage", "compact"], "log.compact")
hard = json.load(open(os.path.join(stiff, "postProcessing", "compaction.json")))
with h5py.File(os.path.join(stiff, "DEM", "compacted.h5"), "r") as f:
    saved_modulus = f.attrs.get("contactYoungsModulus")
check(hard["youngs_modulus_Pa"] == modulus == saved_modulus and soft["youngs_modulus_Pa"] == modulus / 10,
      f"the compaction's contact modulus is recorded: {saved_modulus} Pa in compacted.h5, "
      f"{hard['youngs_modulus_Pa']} in compaction.json (soft {soft['youngs_modulus_Pa']})")
check(abs(hard["porosity_when_closed"] - target) < 1e-9 and abs(soft["porosity_when_closed"] - target) < 1e-9,
      f"stiff contacts close at the target too ({hard['porosity_when_closed']})")
ratio = hard["lid_pressure_when_closed_Pa"] / soft["lid_pressure_when_closed_Pa"]
check(ratio > 2,
      f"at the same gap the stiff contacts need {ratio:.1f} times the lid pressure "
      f"({hard['lid_pressure_when_closed_Pa']:.0f} against {soft['lid_pressure_when_closed_Pa']:.0f} Pa; mean overlap "
      f"{1e3 * hard['overlaps_when_closed']['mean_overlap_m']:.2f} against "
      f"{1e3 * soft['overlaps_when_closed']['mean_overlap_m']:.2f} mm)")

# 5. Half the pressure the stiff contacts needed to close: the target is out of reach.
jammed = iceCases.copy_case(stiff, os.path.join(work, "beamJammed"))
shutil.copy(os.path.join(stiff, "DEM", "settled.h5"), os.path.join(jammed, "DEM", "settled.h5"))
allowed = 0.5 * hard["lid_pressure_when_closed_Pa"]
iceCases.set_entry(os.path.join(jammed, "constant", "rubbleProperties"), "compaction.maxPressure", allowed)
with open(os.path.join(jammed, "log.compact"), "w") as log:
    rc = subprocess.run(["mpirun", "--allow-run-as-root", "-np", "1", app, "-case", jammed, "-stage", "compact"],
                        stdout=log, stderr=subprocess.STDOUT).returncode
stop = settlingLevels.jam(jammed)
curve = np.genfromtxt(os.path.join(jammed, "postProcessing", "compaction.csv"), delimiter=",", names=True)
check(rc == 3 and "out of reach" in open(os.path.join(jammed, "log.compact")).read()
      and not os.path.exists(os.path.join(jammed, "DEM", "compacted.h5")),
      f"allowed {allowed:.0f} Pa, the compaction stops out of reach (exit {rc}) and saves no compacted.h5")
check(stop is not None and stop[0] > target and stop[1] > allowed
      and abs(stop[0] - curve["porosity"][-1]) < 1e-8 and abs(stop[1] / curve["lid_Pa"][-1] - 1) < 1e-8,
      f"the settling-levels study reads the jam: {stop} (porosity, Pa) against the target {target} and the "
      f"curve's last row ({curve['porosity'][-1]:.6f}, {curve['lid_Pa'][-1]:.1f} Pa)")
sys.exit(1 if failures else 0)
