#!/usr/bin/python3
"""Rubble punch at the cfd water level (icePunchFoam; cases/rubblePunch, ./Allrun -water cfd), or
at the vof level (icePunchInterFoam, ./Allrun -water vof), on the small keel of ridgeSmall.py
(1.6 x 0.4 m, 489 particles, free ends).

usage: punchCfdSmall.py STEP WORK DEM_BIN_DIR CFD_BIN_DIR [cfd|vof]
  punch     the same punch in hydrostatic water (ridgeDEM) and at the level on 1 and 2 ranks:
            (a) the cfd run's buoyancy share equals rho_w g times the rise of the ice's submerged
                volume that this script computes from the VTK frames (ridgeSmall.py's check);
            (b) before the first bond breaks, the cfd platen force agrees with the hydrostatic
                one within the water's dynamic forces that differ between the levels (added
                mass of the accelerating ice, drag; bound below);
            (c) 2 ranks give the 1-rank force before any bond breaks (relative 5e-3: the DEM's
                own rank-order sums of contact forces, see RANKS_LIMIT)
            and at the vof level
            (d) the water's volume is kept; the level's rise over the box's area is the ice under
                water as the cells hold it (postProcessing/vof.csv), and it follows the ice's
                geometric submergence (the caps under the surface)
  badInput  ridgeDEM loading at the level; the app without a mesh, with a coupling interval
            longer than a force sample, with inertia scaling; cfd: a mesh whose top is not the
            water surface; vof: a water surface outside the mesh, vof/initialLevel given, no
            0/alpha.water, a coupling interval that holds the spheres' buoyancy past their heave
            limit: a message naming the file or entry, non-zero exit"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import ridgeSmall  # noqa: E402
from ridgeSmall import LENGTH, WIDTH, RHO_W, check, iceCases  # noqa: E402
import cfdRun  # noqa: E402  (postProcessing, on the path through ridgeSmall)

# Per level: the case's set-up over the hydrostatic case, the application, the cells of the small
# box (x, y, z: at vof, z below the case's 4 cm surface band), the platen's travel.
LEVELS = {
    # cells of about 0.2 m; past the first break (2.8 mm), not below rampTravel (5 mm)
    "cfd": dict(setup=os.path.join(ridgeSmall.CASES, "rubblePunch", "cfd"), app="icePunchFoam",
                cells=(8, 2, 5), travel=0.005),
    # 20 mm: the level's rise against the ice pushed under needs the ice to cross the surface's cells
    "vof": dict(setup=os.path.join(ridgeSmall.CASES, "rubblePunch", "vof"), app="icePunchInterFoam",
                cells=(8, 2, 4), travel=0.02),
}
TRAVEL = LEVELS["cfd"]["travel"]
# Freeze-bonds at their ultimate strength: the 4h set's first bond breaks within 0.3 mm of
# travel, before the water's effects can be told apart; these hold for 2.8 mm (30 samples).
CONTROLS = (("maxTravel", TRAVEL), ("writeInterval", 0.001), ("checkpointInterval", 0.02),
            ("stopAfterHalfLoad", "no"))
# The platen speed is the test's own (the case's may change): the bounds below and the refused
# coupling interval were worked out for 0.05 m/s.
SPEED = 0.05                        # m/s
ENTRIES = (("test.settleTime", 0.05), ("ends.fixedLength", 0), ("test.speed", SPEED))
RAMP = float(iceCases.get_entry(os.path.join(ridgeSmall.CASES, "rubblePunch", "system", "controlDict"), "rampTravel"))
TAU = RAMP / SPEED                  # s: the platen's smooth start (PlatenLoadingControl::travelAt)
# 1 against 2 ranks: LIGGGHTS sums the frictional contact forces of the rubble in rank order, so
# the DEM alone differs already: the hydrostatic level on this keel and case by up to 3.3e-4
# (relative) before its first break (measured; ridgeFlexureSmall accepts 1e-4 for the same
# reason), and the contact spikes amplify it; 1e-8 is out of reach for this scene at either
# level. The limit still catches a coupling that loses or doubles fluid forces at the ranks'
# boundary: one 55 mm sphere's buoyancy (0.8 N) is 2-10 % of the force here.
RANKS_LIMIT = 5e-3
EARLY_SAMPLES, EARLY_LIMIT = 8, 1e-5


def env():
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                OMPI_MCA_mpi_yield_when_idle="1",
                WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))


def ultimate_freeze_bonds(case):
    iceCases.set_entry(os.path.join(case, "constant", "freezeBondProperties"), "fixedSetCoeffs.set", "ultimate")


def hydrostatic_case(work, name, where=None):
    """The small keel's punch (WORK/keel) in where/name (where: WORK)."""
    case = ridgeSmall.ridge_case("rubblePunch", os.path.join(where or work, name), work, CONTROLS, ENTRIES)
    ultimate_freeze_bonds(case)
    return case


def resolved_case(work, name, level, where=None):
    """The punch with cfd/ (vof/) over it, as Allrun -water cfd (vof) makes it."""
    case = hydrostatic_case(work, name, where)
    cfdRun.overlay(case, LEVELS[level]["setup"])
    iceCases.set_entry(os.path.join(case, "system", "loadingDict"), "maxTravel", LEVELS[level]["travel"])
    return case


def foam(cmd, case, log):
    with open(os.path.join(case, log), "w") as out:
        return subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT, env=env()).returncode


def run_resolved(dem_bin, cfd_bin, case, ranks, level, assembled=None):
    """Assembles (or takes the ridge of the case `assembled`), meshes, punches."""
    if assembled:
        for f in ("DEM/ridge.h5", "postProcessing/geometry.json"):
            os.makedirs(os.path.dirname(os.path.join(case, f)), exist_ok=True)
            shutil.copy(os.path.join(assembled, f), os.path.join(case, f))
    else:
        iceCases.run_app(os.path.join(dem_bin, "ridgeDEM"), case, 1, ["-stage", "assemble"], "log.ridgeDEM")
    cfdRun.mesh(case, ranks, cells=LEVELS[level]["cells"])
    args = ["-parallel"] if ranks > 1 else []
    app = LEVELS[level]["app"]
    return iceCases.run_app(os.path.join(cfd_bin, app), case, ranks, args, "log." + app)


def before_first_break(c):
    broken = np.array(c["brokenBonds"])
    return int(np.argmax(broken > 0)) if broken.max() > 0 else len(broken)


def punch(work, dem_bin, cfd_bin, water):
    hydro = hydrostatic_case(work, f"{water}Ref_hydrostatic")
    iceCases.set_entry(os.path.join(hydro, "system", "controlDict"), "maxTravel", LEVELS[water]["travel"])
    iceCases.run_app(os.path.join(dem_bin, "ridgeDEM"), hydro, 1, ["-stage", "all"], "log.ridgeDEM")
    cfd1 = resolved_case(work, f"{water}_np1", water)
    wall1 = run_resolved(dem_bin, cfd_bin, cfd1, 1, water)
    cfd2 = resolved_case(work, f"{water}_np2", water)
    wall2 = run_resolved(dem_bin, cfd_bin, cfd2, 2, water, assembled=cfd1)
    print(f"wall: {water} 1 rank {wall1:.0f} s, 2 ranks {wall2:.0f} s")

    level = json.load(open(os.path.join(cfd1, "postProcessing", "geometry.json")))["waterLevel"]
    # (a) The share's definition (caps under the still surface where the ridge floated).
    ridgeSmall.check_buoyancy_share(cfd1, level)

    # (b) Buoyancy is rho_w g V_cap at both levels (cfd: the hydrostatic part of -V grad p); they
    # differ in the water's dynamic forces. Single samples cannot be compared: the force is a
    # train of contact spikes (the hydrostatic force jumps by several newtons from one 0.2 mm
    # sample to the next); their mean before the first break can. Bound on the difference of
    # the means, from the physics:
    #   added mass: the hydrostatic level gives each sphere C_a rho_w V_sub (C_a 0.5), the cfd
    #     level none of its own; at most the whole free keel accelerates with the platen's
    #     smooth start, a = v/tau exp(-t/tau) (tau = rampTravel / v): mean of C_a rho_w V_sub a;
    #   drag: the keel moving down at the platen's speed v(t) as a plate of its plan area,
    #     0.5 rho_w C_d L B v^2 with C_d = 2 (a flat plate broadside; a porous keel less);
    #   the means' own scatter: 3 standard errors of the hydrostatic mean (the sample-to-sample
    #     scatter of the spikes over sqrt(samples));
    #   vof: the level's rise lifts the ice by rho_w g A dh at most (A the box's area; dh the
    #     highest rise before the first break).
    h, c = iceCases.curve(hydro), iceCases.curve(cfd1)
    n = min(before_first_break(h), before_first_break(c))
    check(n >= 10, f"{n} force samples before the first break in both runs (at least 10)")
    f_h, f_c = np.array(h["force"][:n]), np.array(c["force"][:n])
    elapsed = np.array([loading_time(d) for d in c["travel"][:n]])
    accel = SPEED / TAU * np.exp(-elapsed / TAU)
    speed = SPEED * (1 - np.exp(-elapsed / TAU))
    added_mass = float(np.mean(0.5 * RHO_W * np.array(c["submergedVolume"][:n]) * accel))
    drag = float(np.mean(0.5 * RHO_W * 2.0 * LENGTH * WIDTH * speed ** 2))
    scatter = 3 * float(np.std(np.diff(f_h)) / math.sqrt(2) / math.sqrt(n))
    rise = 0.0
    if water == "vof":
        rise = RHO_W * ridgeSmall.G * LENGTH * WIDTH * max(0.0, max(c["waterLevel"][:n]) - c["waterLevel"][0])
    bound = added_mass + drag + scatter + rise
    difference = float(f_c.mean() - f_h.mean())
    check(abs(difference) <= bound,
          f"mean platen force before the first break ({n} samples, to {c['travel'][n - 1] * 1e3:.1f} mm): "
          f"{water} {f_c.mean():.2f} N, hydrostatic {f_h.mean():.2f} N, difference {difference:.2f} N within "
          f"{bound:.2f} N (added mass {added_mass:.2f} + drag {drag:.2f} + 3 standard errors {scatter:.2f}"
          f" + level's rise {rise:.2f})")
    share_h, share_c = h["buoyancyShare"][n - 1], c["buoyancyShare"][n - 1]
    if water == "vof":
        # The ice under the moving surface (the still level's share misses the rise).
        share_c = RHO_W * ridgeSmall.G * (c["iceSubmergedVolume"][n - 1] - c["iceSubmergedVolume"][0])
    check(abs(share_c - share_h) <= 0.1 * abs(share_h),
          f"buoyancy share at {c['travel'][n - 1] * 1e3:.1f} mm: {water} {share_c:.2f} N, hydrostatic "
          f"{share_h:.2f} N (within 10 %: the same ice pushed under by the same platen)")

    # (c) Ranks. The first samples agree to the coupled exchange's round-off; then the rubble's
    # contact chatter amplifies it (about tenfold every 0.2 mm since the freeze-bonds bear with the
    # ice's modulus in compression), so single samples part before the first break while their
    # mean does not (statistically equal, as after a chaotic event), over the first 5 mm (the
    # vof run goes on to 20 mm: its means there parted by 9 %, its level's rise by 0.2 %).
    # At vof the water's force is compared: the rank-local DIC preconditioner of the pressure and
    # interface solves parts it by 2-9e-6 from the first step (measured), which the platen's
    # small contact forces magnify.
    c2 = iceCases.curve(cfd2)
    m = min(before_first_break(c), before_first_break(c2), sum(t <= LEVELS["cfd"]["travel"] for t in c["travel"]))
    same_times = all(abs(a - b) < 1e-12 for a, b in zip(c["time"][:m], c2["time"][:m]))
    early_column, early_limit = ("pressureForceZ", 1e-4) if water == "vof" else ("force", EARLY_LIMIT)
    early = max(abs(a - b) / abs(a) for a, b in zip(c[early_column][:EARLY_SAMPLES], c2[early_column][:EARLY_SAMPLES])
                if a != 0)
    check(m >= 10 and same_times and early <= early_limit,
          f"2 ranks give the 1-rank {early_column} over the first {EARLY_SAMPLES} samples: largest relative "
          f"difference {early:.1e} (limit {early_limit:g})")
    mean1, mean2 = float(np.mean(c["force"][:m])), float(np.mean(c2["force"][:m]))
    check(abs(mean2 / mean1 - 1) <= RANKS_LIMIT,
          f"2 ranks give the 1-rank mean force before the first break: {mean2:.4f} N against {mean1:.4f} N "
          f"over {m} samples ({100 * (mean2 / mean1 - 1):+.2f} %, limit {100 * RANKS_LIMIT:g} %)")
    if water == "vof":
        check_level_rise(cfd1)


# (d) The water's volume is kept to round-off (1e-15 measured; a coarse surface cell that the
# rubble fills lost 5 % in 0.7 s, the reason for the case's 4 cm band). The box's area times the
# level's rise is the ice under water as the cells hold it, sum alpha.water (1 - eps) V, which
# VOF conserves. The cells place the ice against the surface to their resolution only (vertical
# sharing over 4 cm cells), so the rise follows the caps' submergence with a lag: measured on
# this keel, 0.78 of it at 30 mm of travel, 0.27 with the cfd level's 0.3 m smoothing.
VOLUME_LIMIT = 1e-10
RISE_SHARE_LOW = 0.5


def check_level_rise(case):
    with open(os.path.join(case, "postProcessing", "vof.csv")) as f:
        rows = list(csv.DictReader(f))
    v = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    worst = float(np.max(np.abs(v["waterVolumeChange"])))
    check(worst <= VOLUME_LIMIT, f"water volume kept: largest relative change {worst:.1e} over {len(rows)} "
          f"coupling steps (limit {VOLUME_LIMIT:g})")
    rise_volume = LENGTH * WIDTH * (v["level"] - v["level"][0])
    held = v["cellSubmergedVolume"] - v["cellSubmergedVolume"][0]
    mismatch = float(np.max(np.abs(rise_volume - held)))
    check(mismatch <= 1e-9, f"box area x level rise = ice under water in the cells: largest difference "
          f"{mismatch:.1e} m3 (limit 1e-9) on a rise of {rise_volume[-1] * 1e6:.0f} cm3")
    caps = v["submergedVolume"][-1] - v["submergedVolume"][0]
    share = rise_volume[-1] / caps
    check(caps > 0 and RISE_SHARE_LOW <= share <= 1.02,
          f"the level's rise holds {share:.2f} of the ice pushed under (caps: {caps * 1e6:.0f} cm3) after "
          f"{LEVELS['vof']['travel'] * 1e3:.0f} mm (between {RISE_SHARE_LOW} and 1.02)")


def loading_time(travel):
    """Time since the platen started at this travel: travel = v (t - tau (1 - exp(-t/tau)))."""
    lo, hi = 0.0, 10.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if SPEED * (mid - TAU * (1 - math.exp(-mid / TAU))) < travel:
            lo = mid
        else:
            hi = mid
    return lo


def bad_input(work, dem_bin, cfd_bin, water):
    def expect(name, cmd, case, words):
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env())
        out = r.stdout
        check(r.returncode != 0 and all(w in out for w in words),
              f"{name}: exit {r.returncode}, message names {words}: "
              + next((line for line in out.splitlines() if words[-1] in line), out[-300:]).strip())

    ridge_dem = os.path.join(dem_bin, "ridgeDEM")
    name = LEVELS[water]["app"]
    app = os.path.join(cfd_bin, name)
    mpi = ["mpirun", "-np", "1", "--oversubscribe"]
    coupling = lambda c: os.path.join(c, "constant", "couplingProperties")  # noqa: E731

    bad = os.path.join(work, f"bad_{water}")
    case = resolved_case(work, "ridgeDEMLoads", water, bad)
    expect(f"ridgeDEM -stage all at waterLevel {water}", mpi + [ridge_dem, "-case", case, "-stage", "all"], case,
           ["couplingProperties", "waterLevel", name])

    case = resolved_case(work, "noMesh", water, bad)
    iceCases.run_app(ridge_dem, case, 1, ["-stage", "assemble"], "log.ridgeDEM")
    expect(f"{name} without a mesh", mpi + [app, "-case", case], case, ["constant/polyMesh", "blockMesh"])

    cfdRun.mesh(case, 1, cells=LEVELS[water]["cells"])
    iceCases.set_entry(coupling(case), f"{water}.couplingInterval", 1000)
    expect("coupling interval longer than a force sample", mpi + [app, "-case", case], case,
           ["couplingProperties", "couplingInterval", "sampleInterval"])

    iceCases.set_entry(coupling(case), f"{water}.couplingInterval", 84)
    props = os.path.join(case, "constant", "ridgeProperties")
    iceCases.set_entry(props, "test.inertiaScaling", 10)
    expect(f"inertia scaling at the {water} level", mpi + [app, "-case", case], case,
           ["ridgeProperties", "test.inertiaScaling", f"not allowed at the {water} level"])
    iceCases.set_entry(props, "test.inertiaScaling", 1)
    block = os.path.join(case, "system", "blockMeshDict")
    if water == "cfd":
        iceCases.set_entry(block, "surfaceZ", 0.95)
        foam(["blockMesh", "-case", case], case, "log.blockMesh")
        expect("mesh top above the water surface", mpi + [app, "-case", case], case,
               ["blockMeshDict", "geometry.json", "surface"])
        return
    # vof: the air above must hold the surface; the level comes from the ridge, not the dictionary;
    # the water fraction's file; the spheres' heave against the coupling time (a force sample of
    # 5 mm lets a 71 ms coupling step pass the sampling check).
    top = float(iceCases.get_entry(block, "top"))
    iceCases.set_entry(block, "top", top - 0.25)
    foam(["blockMesh", "-case", case], case, "log.blockMesh")
    expect("water surface above the mesh", mpi + [app, "-case", case], case,
           ["blockMeshDict", "geometry.json", "not inside the fluid mesh"])
    iceCases.set_entry(block, "top", top)
    foam(["blockMesh", "-case", case], case, "log.blockMesh")
    text = open(coupling(case)).read()
    open(coupling(case), "w").write(text.replace("    couplingInterval", "    initialLevel 0.9;\n    couplingInterval", 1))
    expect("vof/initialLevel given", mpi + [app, "-case", case], case, ["couplingProperties", "initialLevel", "geometry.json"])
    open(coupling(case), "w").write(text)
    os.replace(os.path.join(case, "0", "alpha.water"), os.path.join(case, "alpha.water.away"))
    expect("no 0/alpha.water", mpi + [app, "-case", case], case, ["alpha.water", "hydrodynamics vof"])
    os.replace(os.path.join(case, "alpha.water.away"), os.path.join(case, "0", "alpha.water"))
    for entry in ("writeInterval", "sampleInterval"):
        iceCases.set_entry(os.path.join(case, "system", "loadingDict"), entry, 0.005)
    iceCases.set_entry(coupling(case), "vof.couplingInterval", 3000)
    expect("coupling time past the spheres' heave limit", mpi + [app, "-case", case], case,
           ["couplingProperties", "couplingInterval", "heaves at"])


def main():
    os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")   # OpenFOAM's etc files
    step, work = sys.argv[1], sys.argv[2]
    dem_bin, cfd_bin = os.path.abspath(sys.argv[3]), os.path.abspath(sys.argv[4])
    water = sys.argv[5] if len(sys.argv) > 5 else "cfd"
    if water not in LEVELS:
        sys.exit(f"punchCfdSmall.py: unknown level {water} (cfd|vof)")
    if not os.path.exists(ridgeSmall.keel_file(work)):
        sys.exit(f"punchCfdSmall.py: the small keel {ridgeSmall.keel_file(work)} is missing (ridgeSmall.py keel)")
    if step == "punch":
        punch(work, dem_bin, cfd_bin, water)
    elif step == "badInput":
        bad_input(work, dem_bin, cfd_bin, water)
    else:
        sys.exit(f"punchCfdSmall.py: unknown step {step}")
    sys.exit(1 if ridgeSmall.failures else 0)


if __name__ == "__main__":
    main()
