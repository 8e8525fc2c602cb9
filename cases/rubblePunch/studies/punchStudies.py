#!/usr/bin/python3
"""Why a punched rubble does or does not bend as a beam, and how its peak moves with the
freeze-bond set and the porosity: reduced punches (issue 18, scenes.md section 6).

One reduced keel: ../rubbleBeam's cuboid blocks in a 1.6 x 0.4 m box, 0.3 m of rubble (the ice
of porosity 0.40 rained in), settled once, then compacted between plates (rubbleDEM -stage
compact) to each target porosity. Each punch is a copy of this case on that box (ridgeDEM -stage
all), 60 mm of travel; its first freeze-bond failures come from postProcessing/beamPhase.py.

  cause   one cause at a time, at fixed particle strengths (the compliant calibration's 4 h pair,
          put on the bonds directly) and 0.05 m/s: the keel (settled / compacted to 0.35), the
          freeze-bonds' modulus (the ice's 195 MPa / c_f x the ice's 38.4 MPa / the reference
          punch's 2.81 MPa) and the ends (clamped / simple): 12 punches.
  sweep   the case's own freeze-bonds (2.81 MPa, strengths calibrated at that modulus) at
          0.05 m/s: the sets 2 min / 4 h / ultimate on the settled heap and on the keel compacted
          to 0.35, and the 4 h set on keels compacted to 0.30 / 0.40 / 0.45 (each keel's porosity
          at bonding is reported: a compacted heap springs back when the lid backs off), and on
          keels compacted to 0.30-0.45 whose lid holds the target gap while they are bonded
          ("held": the freeze-bonds made while the compaction's pressure acts).
  compaction  a reduced heap of the case's width (1.6 x 0.94 m) closed towards 0.30 with the
          contacts and the blocks' bonds at 2 MPa (the settling's), 20 MPa and the ice's 195 MPa,
          and at 195 MPa with 37 mm spheres in 3 layers, until the lid needs 100 kPa: the
          compaction curves, the overlaps between blocks, the blocks' tilts (4 heaps, no punch).
  porosity  the 4 h set punched on heaps of that width compacted to 0.45 / 0.55 / 0.65 at 2 and
          195 MPa (the assembly starting from the keel's modulus); a target the ice-stiff
          heap cannot reach is a table row with the jam's message.
  stiffkeel  the case's own cuboid keel compacted with the ice's stiffness to 0.45 (it jams near
          0.435 under 100 kPa; the reduced heaps, 1.8 block layers thick, at 0.60) and punched
          as the case does (100 mm, its area correction) at 0.05 and the laboratory's 0.005 m/s,
          beside the case's published punch (the case's keel since 2026-11-28; before, the
          settling's softened contacts compacted it to 0.35).

Writes WORK/<study>.csv, .md (the table) and .png (force against travel, first failures
marked). --publish copies the three into ../results/ as punchStudy_<study>.* and the table
into ../README.md (its generated block "punchStudy <study> table").

usage: studies/punchStudies.py {cause,sweep,compaction,porosity,stiffkeel} [--work DIR] [--jobs N] [--publish]
       (default WORK runs/punchStudies; each about 6 min on 2 cores)"""
import argparse
import concurrent.futures
import json
import os
import re
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.dirname(HERE)
TOP = os.path.abspath(os.path.join(CASE, "..", ".."))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402
from beamPhase import first_failures  # noqa: E402

ICE_MODULUS = 1.95e8
FREEZE_MODULI = {"ice 195 MPa": 1.95e8, "c_f x ice 38.4 MPa": 0.197 * 1.95e8, "k_n 51 MPa/m: 2.81 MPa": 2.80775e6}
BOX = (1.6, 0.4, 0.3)               # m: length, width, rubble thickness
TRAVEL = 0.06                       # m
ICE_POROSITY = 0.40                 # the ice of a BOX[2] layer at this porosity is rained in
# The reduced keels' compaction unless a point says otherwise: the settling's softened contacts and
# a 50 kPa limit on the lid, as ../rubbleBeam had them when these studies were made (the case's
# keels since compact at the ice's stiffness under up to 100 kPa).
RUBBLE_PROPERTIES = os.path.join(TOP, "cases", "rubbleBeam", "constant", "rubbleProperties")
SETTLING_MODULUS = float(iceCases.get_entry(RUBBLE_PROPERTIES, "settling.youngsModulus"))
STUDY_MAX_PRESSURE = 50e3


def calibrated_4h_particle_strengths():
    """(T_p, S_p) the compliant calibration gives the 4 h set (its dictionary's derived table)."""
    path = os.path.join(TOP, "cases", "common", "freezeBondCalibrationCompliant")
    for line in open(path):
        words = line.split()
        if words[:2] == ["4h", "sets"]:
            i = words.index("particle")
            return float(words[i + 1]) * 1e3, float(words[i + 3]) * 1e3
    raise RuntimeError(f"{path}: no '4h sets' row in its derived table")


def settled_keel(work):
    def prepare(folder):
        iceCases.small_rubble_case(os.path.join(TOP, "cases", "rubbleBeam"), folder, *BOX, 6, 15,
                                   {"settling.minTime": 1})
        iceCases.uncompacted(os.path.join(folder, "constant", "rubbleProperties"), ICE_POROSITY)

    keel = iceCases.prepared_run(os.path.join(work, "keels", "settled"), prepare)
    if not os.path.exists(os.path.join(keel, "DEM", "settled.h5")):
        iceCases.run_app("rubbleDEM", keel, 1, ["-stage", "settle"], "log.settle")
    return os.path.join(keel, "DEM", "settled.h5")


FINE_BLOCKS = {"blocks.particleDiameter": 0.037, "blocks.layers": 3}     # the same 0.1 m blocks, smoother faces


def keel_folder(work, porosity, held=False, modulus=None, box=BOX, max_pressure=None, fine=False):
    return os.path.join(work, "keels", f"compacted{porosity:g}" + ("held" if held else "")
                        + (f"_E{modulus:g}" if modulus else "") + (f"_w{box[1]:g}" if box != BOX else "")
                        + (f"_p{max_pressure:g}" if max_pressure else "") + ("_fine" if fine else ""))


def block_tilts(stage):
    """Each block's tilt (degrees): the angle between its thinnest axis (of its spheres' centres) and z."""
    import h5py
    import numpy as np
    with h5py.File(stage, "r") as f:
        p = f["particles"]
        x = np.stack([p["x"][:], p["y"][:], p["z"][:]], axis=1)
        block = p["block"][:].astype(int)
    tilts = []
    for b in np.unique(block):
        y = x[block == b] - x[block == b].mean(axis=0)
        thinnest = np.linalg.eigh(y.T @ y)[1][:, 0]
        tilts.append(np.degrees(np.arccos(min(1.0, abs(thinnest[2])))))
    return np.array(tilts)


def settle_and_compact(keel):
    """(keel's DEM/compacted.h5, None), settled and compacted unless it is there; (None, the
    application's message) where it could not be compacted."""
    stage = os.path.join(keel, "DEM", "compacted.h5")
    if not os.path.exists(stage):
        try:
            if not os.path.exists(os.path.join(keel, "DEM", "settled.h5")):
                iceCases.run_app("rubbleDEM", keel, 1, ["-stage", "settle"], "log.settle")
            iceCases.run_app("rubbleDEM", keel, 1, ["-stage", "compact"], "log.compact")
        except RuntimeError as error:
            return None, iceCases.fatal_message(error)
    return stage, None


def compacted_keel(work, porosity, held=False, modulus=None, box=BOX, max_pressure=None, fine=False):
    """A keel of the same ice as the settled heap (a rubbleThickness layer at porosity 0.40), rained
    in and compacted between plates to `porosity`: (stage file, its summary) or (None, the reason).
    held: the lid does not back off to the case's holdPressure but holds the target gap, so that
    the freeze-bonds are made at the target porosity while the compaction's pressure still acts
    (the reference method), not after the rubble sprang back.
    modulus: the contacts' and blocks' Young's modulus from compaction on (None: the settling's).
    box: (length, width, thickness of the ice at porosity 0.40); max_pressure: the lid's (None: 50 kPa)."""
    # with plates the ice rained in is that of a rubbleThickness layer at the target porosity
    thickness = box[2] * (1 - ICE_POROSITY) / (1 - porosity)
    entries = {"settling.minTime": 1, "compaction.targetPorosity": porosity,
               "compaction.maxPressure": f"{max_pressure or STUDY_MAX_PRESSURE:g}",
               "compaction.youngsModulus": f"{modulus or SETTLING_MODULUS:g}"}
    if fine:
        entries.update(FINE_BLOCKS)
    if held:
        entries["compaction.holdPressure"] = 0.99 * STUDY_MAX_PRESSURE

    def prepare(folder):
        iceCases.small_rubble_case(os.path.join(TOP, "cases", "rubbleBeam"), folder, box[0], box[1], thickness, 6, 15,
                                   entries)

    keel = iceCases.prepared_run(keel_folder(work, porosity, held, modulus, box, max_pressure, fine), prepare)
    stage, refused = settle_and_compact(keel)
    if refused:
        return None, refused
    c = json.load(open(os.path.join(keel, "postProcessing", "compaction.json")))
    return stage, {"settled": c["porosity_when_plates_touched"], "closed": c["porosity_when_closed"] or 0.0,
                   "held": c["porosity_after_hold"], "compaction": c}


def punch(run, stage, speed, freeze_modulus=None, fixed_strengths=None, bond_set=None, support="clamped",
          keel_modulus=None, box=BOX):
    """A reduced punch in `run`; returns its figures (summary + beamPhase)."""
    def prepare(folder):
        iceCases.copy_case(CASE, folder)
        props = os.path.join(folder, "constant", "ridgeProperties")
        text = open(props).read()
        open(props, "w").write(text.replace(
            "\nconsolidatedLayer", "\nbox\n{\n    length %g;\n    width %g;\n}\n\nconsolidatedLayer" % box[:2], 1))
        iceCases.set_entry(props, "keel.settledRubble", '"%s"' % stage)
        for entry, value in (("test.settleTime", 0.05), ("ends.fixedLength", 0.1), ("ends.endSupport", support),
                             ("test.speed", speed)):
            iceCases.set_entry(props, entry, value)
        iceCases.set_entry(os.path.join(folder, "system", "controlDict"), "maxTravel", TRAVEL)
        bonds = os.path.join(folder, "constant", "freezeBondProperties")
        if freeze_modulus:
            iceCases.set_entry(os.path.join(folder, "constant", "iceProperties"), "bondFamilies.freeze.youngsModulus",
                               f"{freeze_modulus:g}")
        if fixed_strengths:
            # the same particle-level pair on every bond whatever the modulus: direct, c_f 1
            iceCases.set_entry(bonds, "particleStrengths", "direct")
            iceCases.set_entry(bonds, "areaCorrection.value", 1)
            iceCases.set_entry(bonds, "fixedSetCoeffs.sets.4h.tensile", f"{fixed_strengths[0]:g}")
            iceCases.set_entry(bonds, "fixedSetCoeffs.sets.4h.shear", f"{fixed_strengths[1]:g}")
        if bond_set:
            iceCases.set_entry(bonds, "fixedSetCoeffs.set", bond_set)
        # the assembly starts from the contacts the keel came to rest with
        iceCases.set_entry(props, "assembly.youngsModulus", f"{keel_modulus or SETTLING_MODULUS:g}")

    run = iceCases.prepared_run(run, prepare, upstream=[stage])
    if not iceCases.finished(run):
        iceCases.run_app("ridgeDEM", run, 1, ["-stage", "all"], "log.ridgeDEM")
    return figures(run)


def figures(run):
    s = iceCases.summary(run)
    f = first_failures(run)
    first = f["first_failure"] or {}
    return {"peak_N": s["peak_force_N"], "travel_at_peak_mm": 1e3 * s["travel_at_peak_m"],
            "freeze_bonds": s.get("freeze_bonds"), "broken_bonds": s["broken_bonds"],
            "first_travel_mm": 1e3 * first["travel_m"] if first else None,
            "first_force_N": first.get("force_N"), "first_rise": first.get("force_rise"),
            "first_from_load_cm": 100 * first["from_load_line_m"] if first else None,
            "first_height": first.get("height_in_keel"), "first_mode": first.get("mode"),
            "bottom_centre_tension_share": f.get("bottom_centre_tension_share_of_first_n"),
            "wall_s": s.get("wall_s")}


def cause_points(work):
    strengths = calibrated_4h_particle_strengths()
    settled = settled_keel(work)
    compacted, info = compacted_keel(work, 0.35)
    if compacted is None:
        raise RuntimeError(f"the reduced keel does not compact to 0.35: {info}")
    points = []
    for keel_name, stage in (("settled", settled), ("compacted 0.35", compacted)):
        for modulus_name, modulus in FREEZE_MODULI.items():
            for support in ("clamped", "simple"):
                name = f"{keel_name.split()[0]}_E{modulus:.3g}_{support}"
                points.append(({"keel": keel_name, "freeze-bond modulus": modulus_name, "ends": support},
                               dict(run=os.path.join(work, "cause", name), stage=stage, speed=0.05,
                                    freeze_modulus=modulus, fixed_strengths=strengths, support=support)))
    return points, {"fixed particle strengths T_p / S_p (kPa)": "%.1f / %.1f" % (strengths[0] / 1e3, strengths[1] / 1e3)}


def sweep_points(work):
    points = []
    keels = {}
    for porosity in (0.30, 0.35, 0.40, 0.45):
        keels[porosity] = compacted_keel(work, porosity)
    settled = settled_keel(work)
    for bond_set in ("2min", "4h", "ultimate"):
        points.append(({"set": bond_set, "keel": "settled"},
                       dict(run=os.path.join(work, "sweep", f"settled_{bond_set}"), stage=settled, speed=0.05,
                            bond_set=bond_set)))
        points.append(({"set": bond_set, "keel": "compacted to 0.35"},
                       dict(run=os.path.join(work, "sweep", f"set_{bond_set}"), stage=keels[0.35][0], speed=0.05,
                            bond_set=bond_set)))
    for porosity, (stage, info) in keels.items():
        row = {"set": "4h", "keel": f"compacted to {porosity:g}"}
        if stage is None:
            points.append((row, {"refused": info}))
        elif porosity != 0.35:
            points.append((row, dict(run=os.path.join(work, "sweep", f"porosity_{porosity:g}"), stage=stage,
                                     speed=0.05)))
    held = {porosity: compacted_keel(work, porosity, held=True) for porosity in (0.30, 0.35, 0.40, 0.45)}
    for porosity, (stage, info) in held.items():
        row = {"set": "4h", "keel": f"compacted to {porosity:g}, held"}
        points.append((row, {"refused": info} if stage is None else
                       dict(run=os.path.join(work, "sweep", f"porosity_{porosity:g}_held"), stage=stage, speed=0.05)))
    extra = {f"keel compacted to {p:g}": ("settled %.3f, closed to %.3f, %.3f held at the hold pressure when bonded"
                                          % (info["settled"], info["closed"], info["held"]))
             if stage else f"refused: {info}" for p, (stage, info) in keels.items()}
    extra.update({f"keel compacted to {p:g}, held": ("settled %.3f, closed to %.3f, %.3f with the lid holding the gap "
                                                     "when bonded" % (info["settled"], info["closed"], info["held"]))
                  if stage else f"refused: {info}" for p, (stage, info) in held.items()})
    return points, extra


WIDE_BOX = (1.6, 0.94, 0.3)         # the case's width: the reduced box's 0.4 m jams blocks of up to 0.26 m
CURVE_MODULI = (2e6, 2e7, 1.95e8)   # Pa: the settling's, ten times it, the ice's
CURVE_TARGET, CURVE_MAX_PRESSURE = 0.30, 100e3


def read_compaction_curve(keel):
    """(porosity, lid pressure) arrays of a keel's postProcessing/compaction.csv, closing phase only."""
    import numpy as np
    data = np.genfromtxt(os.path.join(keel, "postProcessing", "compaction.csv"), delimiter=",", names=True)
    closed = np.argmin(data["gap"]) + 1     # then the hold, the lid backing off
    return data["porosity"][:closed], data["lid_Pa"][:closed]


def compaction_study(work, jobs):
    """Each modulus's heap closed towards porosity 0.30 until its lid needs CURVE_MAX_PRESSURE: the
    porosity against the lid's pressure, and the overlaps between blocks it takes; at the ice's
    modulus also with 37 mm spheres in 3 layers (the same blocks with smoother faces)."""
    import numpy as np
    args = [dict(work=work, porosity=CURVE_TARGET, modulus=m, box=WIDE_BOX, max_pressure=CURVE_MAX_PRESSURE)
            for m in CURVE_MODULI]
    args.append(dict(args[-1], fine=True))
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        outcomes = list(pool.map(lambda kw: compacted_keel(**kw), args))
    rows = []
    for kw, (stage, info) in zip(args, outcomes):
        keel = keel_folder(**kw)
        porosity, lid = read_compaction_curve(keel)
        settled_tilts = block_tilts(os.path.join(keel, "DEM", "settled.h5"))
        row = {"modulus_MPa": kw["modulus"] / 1e6,
               "particles_mm": 1e3 * (FINE_BLOCKS["blocks.particleDiameter"] if kw.get("fine") else 0.055),
               "settled": porosity[0], "settled_tilt_median_deg": float(np.median(settled_tilts)),
               "settled_tilted_over_30_share": float(np.mean(settled_tilts > 30))}
        for pressure in (1e3, 10e3, 50e3):
            reached = porosity[lid <= pressure]
            row[f"porosity_at_{pressure / 1e3:g}kPa"] = reached.min() if len(reached) else None
        if stage:
            c = info["compaction"]
            row.update(reached=c["porosity_when_closed"], lid_kPa=c["lid_pressure_when_closed_Pa"] / 1e3,
                       mean_overlap_mm=1e3 * c["overlaps_when_closed"]["mean_overlap_m"],
                       max_overlap_mm=1e3 * c["overlaps_when_closed"]["max_overlap_m"],
                       after_hold=c["porosity_after_hold"], stopped="")
            tilts = block_tilts(stage)
            row.update(compacted_tilt_median_deg=float(np.median(tilts)),
                       compacted_tilted_over_30_share=float(np.mean(tilts > 30)))
        else:
            m = re.search(r"overlap ([\d.e+-]+) um", info)
            row.update(reached=porosity.min(), lid_kPa=lid.max() / 1e3,
                       mean_overlap_mm=float(m.group(1)) / 1e3 if m else None, max_overlap_mm=None,
                       after_hold=None, stopped="jammed", compacted_tilt_median_deg=None,
                       compacted_tilted_over_30_share=None)
        rows.append((row, keel))
        print(row, flush=True)
    return rows


def porosity_points(work):
    """The 4 h set punched on heaps of the case's width compacted to 0.45 / 0.55 / 0.65 with contacts at
    the settling's softened 2 MPa and at the ice's 195 MPa (the assembly starting from the same)."""
    points, extra = [], {}
    for modulus in (2e6, 1.95e8):
        for porosity in (0.45, 0.55, 0.65):
            stage, info = compacted_keel(work, porosity, modulus=modulus, box=WIDE_BOX, max_pressure=CURVE_MAX_PRESSURE)
            row = {"contacts E (MPa)": f"{modulus / 1e6:g}", "keel": f"compacted to {porosity:g}"}
            if stage is None:
                points.append((row, {"refused": info}))
                extra[f"E {modulus / 1e6:g} MPa, {porosity:g}"] = f"refused: {info}"
                continue
            c = info["compaction"]
            extra[f"E {modulus / 1e6:g} MPa, {porosity:g}"] = (
                "settled %.3f, closed to %.3f under %.1f kPa (mean overlap %.2f mm), %.3f after the hold at 500 Pa"
                % (info["settled"], info["closed"], c["lid_pressure_when_closed_Pa"] / 1e3,
                   1e3 * c["overlaps_when_closed"]["mean_overlap_m"], info["held"]))
            points.append((row, dict(run=os.path.join(work, "porosity", f"E{modulus:g}_{porosity:g}"), stage=stage,
                                     speed=0.05, keel_modulus=modulus, box=WIDE_BOX)))
    return points, extra


STIFF_KEEL = {"modulus": 1.95e8, "porosity": 0.45, "max_pressure": 100e3}


def full_keel(work, modulus, porosity, max_pressure):
    """The case's cuboid keel (keels/cuboid's dictionaries, its box and its ice) compacted to `porosity`
    with the contacts and the blocks' bonds at `modulus`: (stage, compaction.json) or (None, the reason)."""
    def prepare(folder):
        os.makedirs(os.path.join(folder, "DEM"))
        shutil.copytree(os.path.join(CASE, "keels", "cuboid", "constant"), os.path.join(folder, "constant"))
        shutil.copy(os.path.join(TOP, "cases", "rubbleBeam", "DEM", "in.rubbleBeam"), os.path.join(folder, "DEM"))
        props = os.path.join(folder, "constant", "rubbleProperties")
        # the case's ice (that of a rubbleThickness layer at its own target), compacted to another porosity
        ice = float(iceCases.get_entry(props, "blocks.rubbleThickness")) * (
            1 - float(iceCases.get_entry(props, "compaction.targetPorosity")))
        iceCases.set_entry(props, "blocks.rubbleThickness", f"{ice / (1 - porosity):.6g}")
        iceCases.set_entry(props, "compaction.targetPorosity", porosity)
        iceCases.set_entry(props, "compaction.maxPressure", f"{max_pressure:g}")
        iceCases.set_entry(props, "compaction.youngsModulus", f"{modulus:g}")

    keel = iceCases.prepared_run(os.path.join(work, "keels", f"cuboid_E{modulus:g}_{porosity:g}"), prepare)
    stage, refused = settle_and_compact(keel)
    if refused:
        return None, refused
    return stage, json.load(open(os.path.join(keel, "postProcessing", "compaction.json")))


def full_punch(run, stage, speed, keel_modulus):
    """The case's punch (its dictionaries, 100 mm, the cuboid keel's area correction as ./Allrun
    sets it) on another keel; returns its figures (summary + beamPhase)."""
    def prepare(folder):
        iceCases.copy_case(CASE, folder)
        props = os.path.join(folder, "constant", "ridgeProperties")
        cf = json.load(open(os.path.join(TOP, "cases", "rubbleBeam", "results", "summary_cuboid.json")))["area_correction"]
        iceCases.set_entry(props, "keel.settledRubble", '"%s"' % stage)
        iceCases.set_entry(props, "test.speed", speed)
        iceCases.set_entry(props, "assembly.youngsModulus", f"{keel_modulus:g}")
        iceCases.set_entry(os.path.join(folder, "constant", "freezeBondProperties"), "areaCorrection.value", cf)

    run = iceCases.prepared_run(run, prepare, upstream=[stage])
    if not iceCases.finished(run):
        iceCases.run_app("ridgeDEM", run, 1, ["-stage", "all"], "log.ridgeDEM")
    return figures(run)


def stiff_keel_points(work):
    """The case's cuboid keel compacted with the ice's stiffness to 0.45 (it needs 24 kPa), punched
    at 0.05 m/s and the laboratory's 0.005 m/s."""
    stage, info = full_keel(work, **STIFF_KEEL)
    if stage is None:
        raise RuntimeError(f"the case's keel does not compact at the ice's stiffness: {info}")
    published = json.load(open(os.path.join(CASE, "results", "summary_cuboid.json")))
    published_keel = json.load(open(os.path.join(TOP, "cases", "rubbleBeam", "results", "summary_cuboid.json")))
    compaction = published_keel["compaction"]
    extra = {"keel": "the case's cuboid keel (3.05 x 0.94 m, 0.325 m worth of ice), contacts and "
                     "blocks at 195 MPa from the compaction on: plates touch at %.3f, closed to %.3f under %.0f kPa "
                     "(mean overlap between blocks %.2f mm), %.3f after the hold at 500 Pa"
                     % (info["porosity_when_plates_touched"], info["porosity_when_closed"],
                        info["lid_pressure_when_closed_Pa"] / 1e3,
                        1e3 * info["overlaps_when_closed"]["mean_overlap_m"], info["porosity_after_hold"]),
             "the case's published punch (its keel compacted at %.3g MPa to %.2f, %g m/s)"
             % (compaction.get("youngs_modulus_Pa", SETTLING_MODULUS) / 1e6, compaction["target_porosity"],
                published["platen_speed_m_per_s"]):
                 "peak %.0f N at %.1f mm, %d freeze-bonds, %d broken"
                 % (published["peak_force_N"], 1e3 * published["travel_at_peak_m"],
                    published.get("freeze_bonds", -1), published["broken_bonds"])}
    points = [({"keel": "ice-stiff, 0.45", "speed (m/s)": speed},
               dict(run=os.path.join(work, "stiffKeel", f"speed{speed:g}"), stage=stage, speed=speed,
                    keel_modulus=STIFF_KEEL["modulus"], full=True))
              for speed in (0.05, 0.005)]
    return points, extra


def write_compaction_study(outputs, rows):
    import numpy as np
    keys = list(rows[0][0])
    lines = [",".join(keys)] + [",".join(fmt(r[k]) for k in keys) for r, _ in rows]
    iceCases.write_atomically(outputs[0], "\n".join(lines) + "\n")
    md = [f"Reduced heap of the case's width ({WIDE_BOX[0]} x {WIDE_BOX[1]} m, the ice of {WIDE_BOX[2]} m at porosity "
          f"{ICE_POROSITY}), closed towards {CURVE_TARGET} at 0.05 m/s, frictionless between blocks, until the lid "
          f"needs {CURVE_MAX_PRESSURE / 1e3:g} kPa (studies/punchStudies.py compaction; revision "
          f"{iceCases.git_revision()})", "",
          "| contacts E (MPa) | spheres (mm) | plates touch at | porosity at 1 / 10 / 50 kPa | closest (lid kPa) | "
          "mean / max overlap between blocks there (mm) | after the hold at 500 Pa | blocks tilted over 30 deg: "
          "settled, compacted |", "|---|---|---|---|---|---|---|---|"]
    for r, _ in rows:
        at = " / ".join(fmt(r[f"porosity_at_{p}kPa"]) or "-" for p in ("1", "10", "50"))
        closest = f"{r['reached']:.3f} ({r['lid_kPa']:.0f}{', jammed' if r['stopped'] else ''})"
        overlap = f"{fmt(r['mean_overlap_mm'])} / {fmt(r['max_overlap_mm']) or '-'}"
        tilted = f"{r['settled_tilted_over_30_share']:.0%}, " + (
            f"{r['compacted_tilted_over_30_share']:.0%}" if r["compacted_tilted_over_30_share"] is not None else "-")
        md.append(f"| {r['modulus_MPa']:g} | {r['particles_mm']:g} | {r['settled']:.3f} | {at} | {closest} | {overlap} | "
                  f"{fmt(r['after_hold']) or '-'} | {tilted} |")
    iceCases.write_atomically(outputs[1], "\n".join(md) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for r, keel in rows:
        porosity, lid = read_compaction_curve(keel)
        ax.plot(np.maximum(lid, 1.0) / 1e3, porosity,
                label=f"contacts E = {r['modulus_MPa']:g} MPa, {r['particles_mm']:g} mm spheres")
    ax.set(xscale="log", xlabel="lid pressure (kPa)", ylabel="porosity between the plates",
           title="compacting the reduced heap (studies/punchStudies.py compaction)")
    ax.axhspan(0.3, 0.45, color="0.9", label="laboratory rubble 0.30-0.45")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(outputs[2] + ".tmp.png", dpi=90)
    os.replace(outputs[2] + ".tmp.png", outputs[2])
    print("\n".join(md))


COLUMNS = ["peak_N", "travel_at_peak_mm", "freeze_bonds", "broken_bonds", "first_travel_mm", "first_force_N",
           "first_rise", "first_from_load_cm", "first_height", "first_mode", "bottom_centre_tension_share", "wall_s"]


def fmt(v):
    if v is None:
        return ""
    # the case's own paths as a reader of the published table finds them
    return f"{v:.4g}" if isinstance(v, float) else str(v).replace(CASE + os.sep, "")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("study", choices=("cause", "sweep", "compaction", "porosity", "stiffkeel"))
    ap.add_argument("--work", default=os.path.join(CASE, "runs", "punchStudies"))
    ap.add_argument("--jobs", type=iceCases.whole_number(1, 2), default=2)
    ap.add_argument("--publish", action="store_true", help="run nothing; copy the study's files into ../results/")
    a = ap.parse_args()
    outputs = [os.path.join(a.work, f"{a.study}.{ext}") for ext in ("csv", "md", "png")]
    if a.publish:
        iceCases.publish_files(outputs, os.path.join(CASE, "results"),
                               [f"punchStudy_{os.path.basename(p)}" for p in outputs])
        iceCases.write_readme_section(os.path.join(CASE, "README.md"), f"punchStudy {a.study} table",
                                      open(outputs[1]).read())
        return
    os.makedirs(a.work, exist_ok=True)
    if a.study == "compaction":
        write_compaction_study(outputs, compaction_study(a.work, a.jobs))
        return
    points, extra = {"cause": cause_points, "sweep": sweep_points, "porosity": porosity_points,
                     "stiffkeel": stiff_keel_points}[a.study](a.work)
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        def run_point(kw):
            kw = dict(kw)
            return full_punch(**{k: v for k, v in kw.items() if k != "full"}) if kw.get("full") else punch(**kw)
        futures = [(row, pool.submit(run_point, kw) if "run" in kw else None, kw) for row, kw in points]
        results = []
        for row, future, kw in futures:
            try:
                outcome = future.result() if future else {"refused": kw["refused"]}
            except RuntimeError as error:    # the application's message, in the table
                outcome = {"refused": "failed: " + iceCases.fatal_message(error)}
            results.append((row, outcome, kw.get("run") if "refused" not in outcome else None))
            print(row, results[-1][1], flush=True)
    keys = list(points[0][0])
    lines = [",".join(keys + COLUMNS)]
    lines += [",".join([fmt(row[k]) for k in keys] + [fmt(r.get(c)) for c in COLUMNS]) for row, r, _ in results]
    iceCases.write_atomically(outputs[0], "\n".join(lines) + "\n")
    scene = "The case's punch on another keel" if a.study == "stiffkeel" else "Reduced punch"
    md = [f"{scene}, {a.study} (studies/punchStudies.py {a.study}; revision {iceCases.git_revision()})", ""]
    md += [f"- {k}: {fmt(v)}" for k, v in extra.items()] + [""]
    md += ["| " + " | ".join(keys) + " | peak (N) at (mm) | freeze-bonds / broken | first freeze-bond failure: "
           "travel (mm), force (N), rise, from load line (cm), height in keel, mode | bottom-centre tension share "
           "of the first 10 |", "|" + "---|" * (len(keys) + 4)]
    for row, r, _ in results:
        if "refused" in r:
            md.append("| " + " | ".join(fmt(row[k]) for k in keys) + f" | refused: {fmt(r['refused'])} | | | |")
            continue
        first = ("%.2f, %.0f, x%.1f, %.0f, %.2f, %s" % (r["first_travel_mm"], r["first_force_N"], r["first_rise"] or 0,
                                                         r["first_from_load_cm"], r["first_height"], r["first_mode"])
                 if r["first_travel_mm"] is not None else "none broke")
        md.append("| " + " | ".join(fmt(row[k]) for k in keys) + f" | {r['peak_N']:.0f} at {r['travel_at_peak_mm']:.1f} | "
                  f"{r['freeze_bonds']} / {r['broken_bonds']} | {first} | {fmt(r['bottom_centre_tension_share'])} |")
    iceCases.write_atomically(outputs[1], "\n".join(md) + "\n")
    plot(outputs[2], results, keys, a.study)
    print("\n".join(md))


def plot(path, results, keys, study):
    """Force against travel, one row per value of the first key; left the whole travel, right its
    first 6 mm (where the first freeze-bond fails: the dots)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from breakageRecord import read_curve
    groups = list(dict.fromkeys(str(row[keys[0]]) for row, r, _ in results if "refused" not in r))
    fig, axes = plt.subplots(len(groups), 2, figsize=(12, 3.6 * len(groups)), squeeze=False,
                             gridspec_kw={"width_ratios": [2, 1]})
    for i, (row, r, run) in enumerate(results):
        if "refused" in r:
            continue
        _, travel, force = read_curve(os.path.join(run, "postProcessing", "platenForce.csv"))
        label = ", ".join(str(row[k]) for k in keys[1:])
        for ax in axes[groups.index(str(row[keys[0]]))]:
            line, = ax.plot(1e3 * travel, force, lw=0.8, label=label, color=plt.cm.tab10(i % 10))
            if r["first_travel_mm"] is not None:
                ax.plot(r["first_travel_mm"], r["first_force_N"], "o", ms=6, color=line.get_color())
    for group, (whole, start) in zip(groups, axes):
        whole.set(xlabel="platen travel (mm)", ylabel="platen force (N)", title=f"{keys[0]}: {group}")
        start.set(xlim=(0, 6), xlabel="platen travel (mm)", title="first 6 mm; dots: first freeze-bond failure")
        whole.legend(fontsize=7)
    scene = "the case's punch on another keel" if study == "stiffkeel" else "reduced punch"
    fig.suptitle(f"{scene}, {study} (studies/punchStudies.py)")
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=80)
    os.replace(path + ".tmp.png", path)


if __name__ == "__main__":
    main()
