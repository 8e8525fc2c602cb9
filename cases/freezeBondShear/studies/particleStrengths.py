#!/usr/bin/python3
"""From effective to particle freeze-bond strengths (issue 18, physics.md section 5).

The rubble's freeze-bonds should show, on their DEM bond area, the effective
strengths c_f x (laboratory strength) of freezeBondSets.csv. What a bond
breaks at (its particle-level strengths T_p, S_p) is not what an interface of
such bonds shows: this study runs our two virtual tests (cases/freezeBondShear,
cases/freezeBondTension, their applications with the strengths and the
confinement on the command line) at the confinement the rubble's freeze-bonds
form under, fits the effective strengths against the particle ones, and
inverts the relation for each freeze-bond set.

Effective strengths are per DEM bond area, as c_f x laboratory is: the test's
strength (per specimen cross-section, as the laboratory's) times
A_specimen / sum(A_bond) (0.434 in both tests: their 83 bonds have 2.3 times
the cross-section in area). A test interface that is frozen over its whole
cross-section (c_f = A_specimen / sum(A_bond), the tension test's `interface`
correction) then shows the laboratory strength, as it must.

Steps (every run a copy of its case under --out, two at a time):
  1. confinement: the rubble's per bond, c_f x p_c = F_n / A_bond, from the
     rubble summaries (mean) and, when given, a rubbleBeam freezeBonds.csv
     (distribution); one probe run per test finds the applied end pressure
     that gives it (the tests measure per bond as the rubble does);
  2. sweep: particle ratios rho = T_p / S_p (the sets' own, the ice ratio
     195 : 88.8 and a few around them) x four S_p, both tests; linear fit of
     S_eff(S_p) and T_eff(T_p) at each rho;
  3. confinement sensitivity (half, twice the rubble's, and the old 25 kPa),
     loading rate (half the rate), absolute modulus (1.95e8 instead of 5.4e8
     for every modulus: the punch and keel-bond cases' ice);
  4. inversion for each set and both tension choices (the sets' ratio; the
     ice ratio), and verification runs at the derived particle strengths.

Writes into --out: particleStrengths.csv (every run), particleStrengths.md
(tables), particleStrengths.png, particleStrengths.json (relation, derived
strengths), freezeBondCalibration (the calibratedCoeffs dictionary of
cases/common). --publish copies the first four into this folder and the
dictionary into cases/common.

Moduli: by default every bond family keeps the test cases' modulus (freeze and
ice bonds equal, `freezeToIceModulusRatio 1`). A case whose freeze-bonds are
more compliant than its ice (the punch: the reference's k_n 51.05 MPa/m, E
2.81 MPa against the ice's 195 MPa) needs the relation measured at its own
moduli: --ice-modulus and --freeze-modulus set them in every run, the
dictionary records their ratio (the program refuses a case of another
ratio), --dictionary names the file written into cases/common, and --slow
stretches every test's loading time (compliant bonds respond slower: the
interface's first period grows as 1/sqrt(E)). --freeze-compression-modulus
gives the freeze-bonds' normal spring another modulus in compression (a
bonded pair has no contact: a compliant bond in compression let its particles
interpenetrate, and the contact that took over when it broke kicked them
apart); the dictionary records that ratio too.

usage: particleStrengths.py [--jobs 2] [--out DIR] [--rubble SUMMARY.json ...]
                            [--bonds freezeBonds.csv] [--ice-modulus PA --freeze-modulus PA
                            [--freeze-compression-modulus PA]]
                            [--slow FACTOR] [--dictionary NAME] [--publish]"""
import argparse
import re
import concurrent.futures
import csv
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402

SHEAR_CASE = os.path.join(TOP, "cases", "freezeBondShear")
TENSION_CASE = os.path.join(TOP, "cases", "freezeBondTension")
COMMON = os.path.join(TOP, "cases", "common")
SETS_CSV = os.path.join(os.path.dirname(TOP), "shared", "data", "freezeBondSets.csv")
ICE_TENSILE = 195e3             # Pa, freshwater ice (physics.md section 5, the reference's punch)
ICE_RATIO_SHEAR = 88.8e3        # Pa, the shear the reference set it against (195 : 88.8)
ICE_RATIO = ICE_TENSILE / ICE_RATIO_SHEAR
CONTEXT_RATIOS = [0.25, 0.5, 1.0, 3.0]
SWEEP_STRENGTHS = [10e3, 40e3, 160e3, 400e3]     # S_p, Pa
SHEAR_TIME_TO_FAILURE = 0.04    # s of DEM time: load rate = expected failure load / this
TENSION_TIME_TO_PEAK = 0.03     # s of DEM time: pull speed = expected pull at the peak / this
OLD_CONFINEMENT = 25e3          # Pa, applied: the committed freezeBondShear relation's


def read_sets(path=SETS_CSV):
    """{name: (tensile Pa, shear Pa)} of freezeBondSets.csv (real strengths)."""
    rows = [r for r in csv.reader(line for line in open(path) if not line.startswith("#"))]
    header = rows[0]
    out = {}
    for r in rows[1:]:
        d = dict(zip(header, r))
        out[d["set"]] = (float(d["tensile_kPa"]) * 1e3, float(d["shear_kPa"]) * 1e3)
    return out


def rubble_confinement(summaries, bonds_csv):
    """Per-bond confinement of the rubble on the bond area (c_f p_c = F_n / A_bond), Pa:
    the means of the summaries and, from a freezeBonds.csv, its distribution."""
    rows = []
    for path in summaries:
        s = json.load(open(path))
        rows.append({"source": os.path.relpath(path, TOP), "shape": s.get("block_shape", "?"),
                     "bonds": s["freeze_bonds"], "c_f": s["area_correction"],
                     "real_mean_Pa": s["confinement_mean_Pa"], "real_max_Pa": s["confinement_max_Pa"],
                     "bond_mean_Pa": s["area_correction"] * s["confinement_mean_Pa"]})
    dist = None
    if bonds_csv:
        with open(bonds_csv) as f:
            table = list(csv.DictReader(f))
        key = next(k for k in table[0] if k.startswith("confinement"))
        c_f = rows[0]["c_f"] if rows else 1.0
        p = np.array([float(r[key]) for r in table])
        dist = {"source": os.path.relpath(bonds_csv, TOP), "bonds": len(p), "column": key, "c_f": c_f,
                "zero_share": float(np.mean(p <= 0.0)),
                "real": {q: float(np.percentile(p, q)) for q in (10, 25, 50, 75, 90)},
                "real_mean": float(p.mean())}
    return rows, dist


def cached(work, done, tensile, shear, pressure, made_from):
    """Whether a finished run's summary is there and was made with these strengths and pressure,
    and with these moduli and loading (made_from, recorded in work/madeFrom)."""
    stamp = os.path.join(work, "madeFrom")
    if not os.path.exists(done) or not os.path.exists(stamp) or open(stamp).read() != made_from:
        return False
    s = json.load(open(done))
    made = (s.get("particle_tensile_strength_Pa", s.get("bond_tensile_strength_mean_Pa")),
            s.get("particle_shear_strength_Pa", s.get("bond_shear_strength_mean_Pa")), s["confinement_pressure_Pa"])
    return all(abs(m / w - 1) < 1e-5 for m, w in zip(made, (tensile, shear, pressure)))


class Runner:
    """Runs the virtual tests, each in its own copy of its case under `out`; resumable
    (a run whose summary exists, made with the same strengths, pressure, moduli and loading, is not
    repeated)."""

    def __init__(self, out, ice_modulus=None, freeze_modulus=None, slow=1.0, compression_modulus=None):
        """ice_modulus: material and ice bonds; freeze_modulus: freeze-bonds (each None: the case's);
        compression_modulus: the freeze-bonds' in compression (None: their freeze_modulus);
        slow: every test's loading time multiplied by it."""
        self.out = out
        self.ice_modulus = ice_modulus
        self.freeze_modulus = freeze_modulus
        self.compression_modulus = compression_modulus
        self.slow = slow

    def _made_from(self, **loading):
        """What a run is made from besides its strengths and pressure: moduli and loading."""
        return json.dumps({"ice": self.ice_modulus, "freeze": self.freeze_modulus,
                           "compression": self.compression_modulus, "loading": {k: float(f"{v:.6g}") for k, v in loading.items()}},
                          sort_keys=True) + "\n"

    def _copy(self, case, work):
        iceCases.copy_case(case, work)
        props = os.path.join(work, "constant", "freezeBondProperties")
        # the particle-level strengths themselves: one fixed set, c_f = 1, direct
        with open(props, "w") as f:
            f.write(open(os.path.join(SHEAR_CASE, "constant", "freezeBondProperties")).read())
        ice = os.path.join(work, "constant", "iceProperties")
        moduli = {"material.youngsModulus": self.ice_modulus, "bondFamilies.ice.youngsModulus": self.ice_modulus,
                  "bondFamilies.freeze.youngsModulus": self.freeze_modulus}
        for entry, value in moduli.items():
            if value:
                iceCases.set_entry(ice, entry, f"{value:g}")
        if self.compression_modulus:
            iceCases.add_entry(ice, "bondFamilies.freeze.compressionModulus", f"{self.compression_modulus:g}")

    def shear(self, label, tensile, shear, pressure, expected, time_to_failure=SHEAR_TIME_TO_FAILURE):
        """expected: the effective shear strength on the bond area guessed beforehand (sets the
        load rate so that the plane fails after about time_to_failure of DEM time)."""
        work = os.path.join(self.out, "shear", label)
        done = os.path.join(work, "postProcessing", "runs", label, "summary.json")

        def load_at(strength):      # N, P at failure for this effective strength on the bond area, roughly
            return strength / 0.434 * 0.75 * 6.36e-3 * 1.6 + 1.0
        # The cap allows for the friction of the plane's contacts under the confinement (per bond
        # about 0.46 x the applied pressure), which the guess (from 0.4 kPa) leaves out.
        rate = load_at(expected) / (time_to_failure * self.slow)
        cap = 3 * load_at(expected + 0.3 * 0.46 * pressure)
        made_from = self._made_from(loadRate=rate, maxLoad=cap)
        if not cached(work, done, tensile, shear, pressure, made_from):
            self._copy(SHEAR_CASE, work)
            props = os.path.join(work, "constant", "shearTestProperties")
            iceCases.set_entry(props, "loading.loadRate", f"{rate:.6g}")
            iceCases.set_entry(props, "loading.maxLoad", f"{cap:.6g}")
            iceCases.set_entry(props, "loading.samples", 1000)
            iceCases.write_atomically(os.path.join(work, "madeFrom"), made_from)
            iceCases.run_app("freezeBondShearDEM", work, 1,
                             ["-label", label, "-tensileStrength", f"{tensile:.6g}", "-shearStrength",
                              f"{shear:.6g}", "-pressure", f"{pressure:.6g}"], "log.freezeBondShearDEM")
        s = json.load(open(done))
        to_bond = s["specimen_area_m2"] / s["freeze_bond_area_m2"]
        if not s["failed"]:
            raise RuntimeError(f"{work}: the plane did not fail")
        return {"test": "shear", "label": label, "T_p": s["particle_tensile_strength_Pa"],
                "S_p": s["particle_shear_strength_Pa"], "applied_Pa": pressure,
                "confinement_Pa": s["mean_measured_confinement_Pa"], "bonds": s["freeze_bonds"],
                "specimen_Pa": s["effective_shear_strength_Pa"], "effective_Pa": s["effective_shear_strength_Pa"] * to_bond,
                "breaks_in_shear": s["breaks_in_shear"], "breaks": s["breaks"], "steps": s["steps"],
                "modulus_Pa": s["freeze_youngs_modulus_Pa"], "wall_s": s["wall_s"]}

    def tension(self, label, tensile, shear, pressure, expected, time_to_peak=TENSION_TIME_TO_PEAK):
        """expected: the effective tensile strength on the bond area guessed beforehand (sets the
        pull speed so that the peak comes after about time_to_peak of DEM time)."""
        work = os.path.join(self.out, "tension", label)
        done = os.path.join(work, "postProcessing", "runs", label, "summary.json")
        # pull at the peak about 0.56 um per kPa on the bond area (5.4e8 Pa; scales as 1/E)
        modulus = self.freeze_modulus or 5.4e8
        pull = 0.56e-9 * expected * 5.4e8 / modulus
        speed = pull / (time_to_peak * self.slow)
        made_from = self._made_from(pullSpeed=speed, maxPull=3 * pull)
        if not cached(work, done, tensile, shear, pressure, made_from):
            self._copy(TENSION_CASE, work)
            props = os.path.join(work, "constant", "tensionTestProperties")
            iceCases.set_entry(props, "loading.pullSpeed", f"{speed:.6g}")
            iceCases.set_entry(props, "loading.maxPull", f"{3 * pull:.6g}")
            iceCases.set_entry(props, "loading.samples", 1000)
            iceCases.write_atomically(os.path.join(work, "madeFrom"), made_from)
            iceCases.run_app("freezeBondTensionDEM", work, 1,
                             ["-label", label, "-tensileStrength", f"{tensile:.6g}", "-shearStrength",
                              f"{shear:.6g}", "-pressure", f"{pressure:.6g}"], "log.freezeBondTensionDEM")
        s = json.load(open(done))
        to_bond = s["specimen_area_m2"] / s["freeze_bond_area_m2"]
        return {"test": "tension", "label": label, "T_p": s["bond_tensile_strength_mean_Pa"],
                "S_p": s["bond_shear_strength_mean_Pa"], "applied_Pa": pressure,
                "confinement_Pa": s["mean_measured_confinement_Pa"], "bonds": s["freeze_bonds"],
                "specimen_Pa": s["strength_Pa"], "effective_Pa": s["strength_Pa"] * to_bond,
                "breaks_in_shear": "", "breaks": "", "steps": s["steps"],
                "modulus_Pa": modulus_of(work), "wall_s": s["wall_s"]}


def modulus_of(work):
    return float(iceCases.get_entry(os.path.join(work, "constant", "iceProperties"),
                                    "bondFamilies.freeze.youngsModulus").split()[0])


def attempt(test, *args):
    """A virtual test's figures, or {"failed": the application's message} (compliant freeze-bonds
    strong in tension slip out of the shear test's box before their plane fails)."""
    label, t_p, s_p, applied = args[:4]
    try:
        return test(*args)
    except RuntimeError as error:
        reason = iceCases.fatal_message(error)
        print(f"{test.__name__} {label}: failed ({reason})", flush=True)
        return {"test": test.__name__, "label": label, "T_p": t_p, "S_p": s_p, "applied_Pa": applied,
                "failed": reason}


def succeeded(run):
    return "failed" not in run


def strengths(text):
    """An argparse type: at least two positive strengths in Pa, comma-separated, ascending."""
    try:
        values = [iceCases.positive_number(v) for v in text.split(",")]
    except argparse.ArgumentTypeError as error:
        raise argparse.ArgumentTypeError(f"'{text}': {error}")
    if len(values) < 2 or values != sorted(set(values)):
        raise argparse.ArgumentTypeError(f"needs two or more ascending strengths, got '{text}'")
    return values


def guess_shear(rho, s_p):
    """S_eff / S_p against rho, roughly (exploratory runs at 0.4 kPa): sets the load rate only."""
    return s_p * float(np.interp(rho, [0.1, 0.25, 0.5, 1.0, 2.0, 3.0, 4.0], [0.19, 0.40, 0.57, 0.84, 1.25, 1.5, 1.8]))


def fit(x, y):
    """Least squares of the relative residuals, y = a x + b; (a, b, largest relative residual)."""
    a, b = np.polyfit(np.asarray(x, float), np.asarray(y, float), 1, w=1.0 / np.asarray(y, float))
    resid = np.abs(a * np.asarray(x) + b - np.asarray(y)) / np.asarray(y)
    return float(a), float(b), float(resid.max())


def kpa(x, digits=1):
    return f"{x * 1e-3:.{digits}f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--jobs", type=iceCases.whole_number(1), default=2)
    ap.add_argument("--sets", default=SETS_CSV, help="the freeze-bond sets (CSV as ../shared/data/freezeBondSets.csv)")
    ap.add_argument("--out", default=os.path.join(SHEAR_CASE, "runs", "particleStrengths"))
    ap.add_argument("--rubble", nargs="+", default=[
        os.path.join(TOP, "cases", "rubbleBeam", "results", "summary_cuboid.json"),
        os.path.join(TOP, "cases", "rubbleBeam", "results", "summary_empirical.json")],
        help="rubble summaries whose mean confinement the tests take (the first one's)")
    ap.add_argument("--confinement", type=iceCases.positive_number, default=None,
                    help="the confinement per bond on the bond area the tests take, Pa, instead of the first "
                         "rubble summary's mean at bonding (e.g. the floating rubble's while it is loaded)")
    ap.add_argument("--bonds", help="a rubbleBeam run's postProcessing/freezeBonds.csv (distribution, reported)")
    ap.add_argument("--area-correction", type=iceCases.positive_number, default=None,
                    help="c_f of the derived table (default: cases/common/freezeBondProperties')")
    ap.add_argument("--ice-modulus", type=iceCases.positive_number, default=None,
                    help="Young's modulus of the material and the ice bonds in every run, Pa (default: the cases')")
    ap.add_argument("--freeze-modulus", type=iceCases.positive_number, default=None,
                    help="Young's modulus of the freeze-bonds in every run, Pa (default: the ice's)")
    ap.add_argument("--freeze-compression-modulus", type=iceCases.positive_number, default=None,
                    help="the freeze-bonds' modulus in compression, Pa (default: their --freeze-modulus); "
                         "the blocks bear on each other: the ice's")
    ap.add_argument("--slow", type=iceCases.positive_number, default=1.0,
                    help="every test's loading time multiplied by this (compliant freeze-bonds)")
    ap.add_argument("--sweep-strengths", type=strengths, default=SWEEP_STRENGTHS, metavar="S1,S2,...",
                    help="particle shear strengths S_p of the sweep, Pa (default %(default)s; compliant "
                         "freeze-bonds slip millimetres before the strongest break)")
    ap.add_argument("--relation", choices=["lines", "points"], default="lines",
                    help="what the dictionary holds: a straight line per ratio (lines), or the measured points "
                         "(points; where the relation bends: compliant bonds at the compacted rubble's confinement)")
    ap.add_argument("--dictionary", default="freezeBondCalibration",
                    help="name of the calibratedCoeffs dictionary written (and published into cases/common)")
    ap.add_argument("--publish", action="store_true",
                    help="run nothing; copy the finished study's csv, md, png here and its dictionary into cases/common")
    a = ap.parse_args()
    if not {40e3, 160e3} <= set(a.sweep_strengths):
        ap.error("--sweep-strengths: must hold 40000 and 160000 (the sensitivity runs' S_p)")
    if a.freeze_compression_modulus is not None and a.freeze_modulus is None:
        ap.error("--freeze-compression-modulus goes with --ice-modulus and --freeze-modulus")
    if (a.ice_modulus is None) != (a.freeze_modulus is None):
        ap.error("--ice-modulus and --freeze-modulus go together (their ratio is what the calibration holds for)")
    if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", a.dictionary):
        ap.error(f"--dictionary: a plain file name (letters, digits, _), got '{a.dictionary}'")
    # freezeBondCalibration<Suffix> -> particleStrengths<Suffix>.*
    prefix = "freezeBondCalibration"
    stem = "particleStrengths" + (a.dictionary[len(prefix):] if a.dictionary.startswith(prefix)
                                  else "_" + a.dictionary)
    outputs = [os.path.join(a.out, f) for f in ("particleStrengths.csv", "particleStrengths.md", "particleStrengths.png",
                                                "particleStrengths.json")]
    if a.publish:
        iceCases.publish_files(outputs, HERE, [os.path.basename(p).replace("particleStrengths", stem) for p in outputs])
        iceCases.publish_files([os.path.join(a.out, a.dictionary)], COMMON)
        return
    os.makedirs(a.out, exist_ok=True)
    cf = a.area_correction or float(iceCases.get_entry(os.path.join(COMMON, "freezeBondProperties"),
                                                       "areaCorrection.value"))
    sets = read_sets(a.sets)
    conf_rows, dist = rubble_confinement(a.rubble, a.bonds)
    target = a.confinement or conf_rows[0]["bond_mean_Pa"]
    print(f"confinement on the bond area: {target:.0f} Pa "
          f"({'--confinement' if a.confinement else conf_rows[0]['source']})", flush=True)

    runner = Runner(a.out, a.ice_modulus, a.freeze_modulus, a.slow, a.freeze_compression_modulus)
    modulus_ratio = a.freeze_modulus / a.ice_modulus if a.ice_modulus else 1.0
    compression = a.freeze_compression_modulus or a.freeze_modulus
    compression_ratio = compression / a.ice_modulus if a.ice_modulus else 1.0
    pool = concurrent.futures.ThreadPoolExecutor(a.jobs)

    # 1. the applied pressure that gives the rubble's per-bond confinement in each test
    probe_s = runner.shear("probe", 12e3, 40e3, target / 0.434, 17e3)
    probe_t = runner.tension("probe", 12e3, 40e3, target / 0.434, 11.5e3)
    pressure = {"shear": target / 0.434 * target / probe_s["confinement_Pa"],
                "tension": target / 0.434 * target / probe_t["confinement_Pa"]}
    print(f"applied pressures: shear {pressure['shear']:.0f} Pa, tension {pressure['tension']:.0f} Pa", flush=True)

    def submit(test, label, rho, s_p, factor=1.0, applied=None, r=runner, slow=1.0):
        t_p = rho * s_p
        p = applied if applied is not None else factor * pressure[test]
        if test == "shear":
            return pool.submit(attempt, r.shear, label, t_p, s_p, p, guess_shear(rho, s_p), SHEAR_TIME_TO_FAILURE * slow)
        return pool.submit(attempt, r.tension, label, t_p, s_p, p, 0.96 * t_p, TENSION_TIME_TO_PEAK * slow)

    # 2. the sweep
    set_ratios = sorted({round(t / s, 4) for t, s in sets.values()})
    ratios = sorted(set(set_ratios + [round(ICE_RATIO, 4)] + CONTEXT_RATIOS))
    sweep = {}
    for rho in ratios:
        for s_p in a.sweep_strengths:
            for test in ("shear", "tension"):
                sweep[(test, rho, s_p)] = submit(test, f"rho{rho:g}_S{s_p:g}", rho, s_p)
    # 3. sensitivity at the 4 h set's ratio
    rho0 = round(sets["4h"][0] / sets["4h"][1], 4)
    sens = {}
    for name, factor, applied in (("half", 0.5, None), ("twice", 2.0, None), ("old25kPa", None, OLD_CONFINEMENT)):
        for s_p in (40e3, 160e3):
            for test in ("shear", "tension"):
                sens[(name, test, s_p)] = submit(test, f"{name}_rho{rho0:g}_S{s_p:g}", rho0, s_p,
                                                 factor or 1.0, applied)
    for test in ("shear", "tension"):
        sens[("old25kPa_rho1", test, 160e3)] = submit(test, "old25kPa_rho1_S160000", 1.0, 160e3, applied=OLD_CONFINEMENT)
        sens[("slower", test, 160e3)] = submit(test, f"slower_rho{rho0:g}_S160000", rho0, 160e3, slow=2.0)
    soft = Runner(os.path.join(a.out, "modulus1.95e8"), 1.95e8, 1.95e8 * modulus_ratio, a.slow,
                  1.95e8 * compression_ratio if a.freeze_compression_modulus else None)
    for test in ("shear", "tension"):
        sens[("modulus1.95e8", test, 160e3)] = submit(test, f"E1.95e8_rho{rho0:g}_S160000", rho0, 160e3, r=soft)

    runs = [probe_s, probe_t]
    sweep = {k: f.result() for k, f in sweep.items()}
    sens = {k: f.result() for k, f in sens.items()}
    runs += list(sweep.values()) + list(sens.values())

    broke_early = sorted(r["label"] for (test, _, _), r in sweep.items()
                         if test == "tension" and succeeded(r) and r["effective_Pa"] <= 0)
    if broke_early:
        sys.exit(f"particleStrengths: tension specimens {', '.join(broke_early)} broke before the pull "
                 f"(strength 0): their freeze-bonds do not survive the release of {pressure['tension']:.0f} Pa "
                 f"of applied confinement ({target:.0f} Pa on the bond area); use --confinement for a lower "
                 f"bond-area confinement, or --sweep-strengths without the weakest strengths")

    relation = {}
    for rho in ratios:
        shear = [s for s in a.sweep_strengths if succeeded(sweep[("shear", rho, s)])]
        tension = [s for s in a.sweep_strengths if succeeded(sweep[("tension", rho, s)])]
        if len(shear) < 2 or len(tension) < 2:
            print(f"rho {rho:g}: left out of the relation, fewer than two runs of a test finished", flush=True)
            continue
        ss, bs, es = fit(shear, [sweep[("shear", rho, s)]["effective_Pa"] for s in shear])
        st, bt, et = fit([rho * s for s in tension], [sweep[("tension", rho, s)]["effective_Pa"] for s in tension])
        relation[rho] = {"shearSlope": ss, "shearIntercept": bs, "shearError": es,
                         "tensileSlope": st, "tensileIntercept": bt, "tensileError": et}
    ratios = sorted(relation)
    error = max(max(r["shearError"], r["tensileError"]) for r in relation.values())
    points = measured_points(sweep, relation, a.sweep_strengths) if a.relation == "points" else None

    def coefficients(rho):
        keys = sorted(relation)
        return {k: float(np.interp(rho, keys, [relation[x][k] for x in keys])) for k in relation[keys[0]]}

    def rows_at(rho):
        """The measured points at rho, interpolated between ratios at each S_p (the program's pointsAt)."""
        keys = sorted(points)
        return ([float(np.interp(rho, keys, [points[x]["shear"][j] for x in keys])) for j in range(len(a.sweep_strengths))],
                [float(np.interp(rho, keys, [points[x]["tension"][j] for x in keys])) for j in range(len(a.sweep_strengths))])

    def invert(t_eff, s_eff):
        rho = t_eff / s_eff
        if points:
            s_p = along_polyline(rows_at(rho)[0], a.sweep_strengths, s_eff)
            return rho * s_p, s_p
        c = coefficients(rho)
        s_p = (s_eff - c["shearIntercept"]) / c["shearSlope"]
        return rho * s_p, s_p

    def forward(t_p, s_p):
        rho = t_p / s_p
        if points:
            shear, tension = rows_at(rho)
            return (along_polyline([rho * s for s in a.sweep_strengths], tension, t_p),
                    along_polyline(a.sweep_strengths, shear, s_p))
        c = coefficients(rho)
        return c["tensileSlope"] * t_p + c["tensileIntercept"], c["shearSlope"] * s_p + c["shearIntercept"]

    # 4. inversion and verification
    derived = []
    for name, (t_real, s_real) in sets.items():
        for choice, t_used in (("sets", t_real), ("iceRatio", ICE_RATIO * s_real)):
            t_eff, s_eff = cf * t_used, cf * s_real
            t_p, s_p = invert(t_eff, s_eff)
            derived.append({"set": name, "choice": choice, "T_real": t_used, "S_real": s_real,
                            "T_eff": t_eff, "S_eff": s_eff, "T_p": t_p, "S_p": s_p,
                            "pred": forward(t_p, s_p)})
        # today's: the effective strengths straight on the bonds
        derived.append({"set": name, "choice": "direct (before)", "T_real": t_real, "S_real": s_real,
                        "T_eff": cf * t_real, "S_eff": cf * s_real, "T_p": cf * t_real, "S_p": cf * s_real,
                        "pred": forward(cf * t_real, cf * s_real)})
    checks = {}
    for d in derived:
        tag = f"check_{d['set']}_{d['choice'].split()[0]}"
        # guesses kept positive: they set the load rate and its cap only
        checks[(tag, "shear")] = pool.submit(attempt, runner.shear, tag, d["T_p"], d["S_p"], pressure["shear"],
                                             max(d["pred"][1], 0.5 * d["S_p"]))
        checks[(tag, "tension")] = pool.submit(attempt, runner.tension, tag, d["T_p"], d["S_p"], pressure["tension"],
                                               max(d["pred"][0], 0.5 * d["T_p"]))
    checks = {k: f.result() for k, f in checks.items()}
    runs += list(checks.values())
    for d in derived:
        tag = f"check_{d['set']}_{d['choice'].split()[0]}"
        d["check"] = tuple(checks[(tag, test)].get("effective_Pa", float("nan")) for test in ("tension", "shear"))
    # The stated error: the fits' largest residual or the verification runs' largest
    # deviation from the relation, whichever is larger.
    # (The measured points hold the sweep exactly: their error is the verification runs'.)
    fit_error = error
    error = max([0.0 if points else fit_error] + [abs(d["check"][k] / d["pred"][k] - 1) for d in derived for k in (0, 1)
                                                  if math.isfinite(d["check"][k])])

    write_csv(os.path.join(a.out, "particleStrengths.csv"), runs)
    summary = {"case": "freezeBondShear", "study": "particleStrengths", "area_correction": cf,
               "fit_error": fit_error,
               "rubble_confinement": conf_rows, "rubble_confinement_distribution": dist,
               "calibration_confinement_Pa": target, "applied_pressure_Pa": pressure,
               "relation": {f"{rho:g}": r for rho, r in sorted(relation.items())}, "relative_error": error,
               "relation_form": a.relation,
               "points": ({f"{rho:g}": p for rho, p in sorted(points.items())} if points else None),
               "derived": [{k: (list(v) if isinstance(v, tuple) else v) for k, v in d.items()} for d in derived]}
    iceCases.write_atomically(os.path.join(a.out, "particleStrengths.json"), json.dumps(summary, indent=2) + "\n")
    write_dictionary(os.path.join(a.out, a.dictionary), relation, target, error, cf, derived,
                     (a.ice_modulus, a.freeze_modulus, a.slow, compression), points, a.sweep_strengths,
                     f"--confinement {a.confinement:g}" if a.confinement else
                     "c_f p_c of cases/rubbleBeam's cuboid rubble at bonding")
    write_markdown(os.path.join(a.out, "particleStrengths.md"), conf_rows, dist, pressure, probe_s, probe_t,
                   relation, fit_error, error, sens, rho0, derived, cf, a.sweep_strengths, forward, points)
    plot(os.path.join(a.out, "particleStrengths.png"), sweep, relation, ratios, derived, sens, rho0, sets, cf,
         a.sweep_strengths, points)
    print(open(os.path.join(a.out, "particleStrengths.md")).read())


def along_polyline(xs, ys, x):
    """y(x) on the polyline through (xs, ys), extended along its end segments (the program's)."""
    k = 1
    while k + 1 < len(xs) and xs[k] < x:
        k += 1
    return ys[k - 1] + (ys[k] - ys[k - 1]) * (x - xs[k - 1]) / (xs[k] - xs[k - 1])


def measured_points(sweep, relation, strengths):
    """{rho: {"shear": S_eff at each S_p, "tension": T_eff at each rho S_p, "filled": [...]}} of every
    ratio of the relation; a sweep run that failed is filled from its ratio's straight line (named in
    "filled"). Each row must rise with the particle strength (the program refuses one that does not)."""
    points = {}
    for rho, line in sorted(relation.items()):
        row = {"shear": [], "tension": [], "filled": []}
        for s_p in strengths:
            for test, key, x in (("shear", "shear", s_p), ("tension", "tensile", rho * s_p)):
                run = sweep[(test, rho, s_p)]
                if succeeded(run):
                    row[test].append(run["effective_Pa"])
                else:
                    row[test].append(line[key + "Slope"] * x + line[key + "Intercept"])
                    row["filled"].append(f"{test} S_p {s_p:g}")
        for test in ("shear", "tension"):
            values = row[test]
            if any(b <= a for a, b in zip(values, values[1:])):
                sys.exit(f"particleStrengths: at rho {rho:g} the {test} test's effective strengths do not rise with "
                         f"S_p {list(strengths)}: {[round(v) for v in values]} Pa (scatter larger than the steps: "
                         f"choose --sweep-strengths further apart, or --relation lines)")
        points[rho] = row
    return points


def write_csv(path, runs):
    keys = ["test", "label", "T_p", "S_p", "applied_Pa", "confinement_Pa", "bonds", "specimen_Pa", "effective_Pa",
            "breaks_in_shear", "breaks", "steps", "modulus_Pa", "wall_s"]
    lines = [",".join(keys)]
    for r in runs:
        lines.append(",".join(f"{r[k]:.6g}" if isinstance(r.get(k), float) else str(r.get(k, "failed")) for k in keys))
    iceCases.write_atomically(path, "\n".join(lines) + "\n")


def write_dictionary(path, relation, confinement, error, cf, derived, moduli, points=None, strengths=None,
                     source="c_f p_c of cases/rubbleBeam's cuboid rubble at bonding"):
    rhos = sorted(relation)
    ice_modulus, freeze_modulus, slow, compression = moduli
    if ice_modulus:
        stiffer = compression != freeze_modulus
        how = (f"freeze-bonds of {freeze_modulus:g} Pa"
               + (f" ({compression:g} Pa in compression)" if stiffer else "")
               + f" on ice of\n  {ice_modulus:g} Pa"
               + (f", every test's loading {slow:g} times slower" if slow != 1.0 else "")
               + f" (--ice-modulus {ice_modulus:g} --freeze-modulus {freeze_modulus:g}"
               + (f" --freeze-compression-modulus {compression:g}" if stiffer else "") + ").")
        ratio, compression_ratio = freeze_modulus / ice_modulus, compression / ice_modulus
    else:
        how, ratio, compression_ratio = "freeze and ice bonds of equal modulus.", 1.0, 1.0

    def column(key, scale=1.0, fmt="{:.4f}"):
        return "(" + " ".join(fmt.format(relation[r][key] * scale) for r in rhos) + ")"

    table = "\n".join(
        f"      {d['set']:<9} {d['choice']:<16} effective {kpa(d['T_eff']):>6} / {kpa(d['S_eff']):>6} kPa"
        f" -> particle {kpa(d['T_p']):>6} / {kpa(d['S_p']):>6} kPa (virtual tests: {kpa(d['pred'][0])} / "
        f"{kpa(d['pred'][1])} kPa)" for d in derived if not d["choice"].startswith("direct"))
    if points:
        form = ("  At each particle ratio rho = T_p / S_p, on the bond area, the measured S_eff at\n"
                "  the sweep's S_p and T_eff at T_p = rho S_p (the relation bends: friction\n"
                "  under the confinement first), interpolated between them (--relation points)."
                + ("\n  Filled from the ratio's straight line where a run failed: "
                   + "; ".join(f"rho {r:g}: " + ", ".join(points[r]["filled"]) for r in rhos if points[r]["filled"])
                   if any(points[r]["filled"] for r in rhos) else ""))

        def table_rows(key):
            return "\n".join("    " + " ".join(f"{v:.0f}" for v in points[r][key]) for r in rhos)
        body = (f"particleShears          ({' '.join(f'{s:g}' for s in strengths)});    // S_p of the sweep, Pa\n"
                f"effectiveShears         // Pa, one row per ratio\n(\n{table_rows('shear')}\n);\n"
                f"effectiveTensiles       // Pa at T_p = rho S_p, one row per ratio\n(\n{table_rows('tension')}\n);")
    else:
        form = ("  At each particle ratio rho = T_p / S_p, on the bond area:\n"
                "      S_eff = shearSlope S_p + shearIntercept\n"
                "      T_eff = tensileSlope T_p + tensileIntercept")
        body = (f"shearSlopes             {column('shearSlope')};\n"
                f"shearIntercepts         {column('shearIntercept', fmt='{:.0f}')};    // Pa\n"
                f"tensileSlopes           {column('tensileSlope')};\n"
                f"tensileIntercepts       {column('tensileIntercept', fmt='{:.0f}')};    // Pa")
    text = f"""/*--------------------------------*- C++ -*----------------------------------*\\
  Our calibration of particle-level freeze-bond strengths (physics.md
  section 5, "From effective to particle strengths"), written by
  cases/freezeBondShear/studies/particleStrengths.py (see its README
  section there): the virtual shear and tension tests run at the rubble's
  confinement, {confinement:.0f} Pa per bond on the bond area ({source}),
  {how}
{form}
  Included into calibratedCoeffs by cases/common/freezeBondProperties and
  the rubble beam's; selected by `particleStrengths calibrated;`.
  With c_f = {cf:g} (tensile / shear):
{table}
\\*---------------------------------------------------------------------------*/

ratios                  ({' '.join(f'{r:g}' for r in rhos)});    // rho = T_p / S_p
{body}
confinement             {confinement:.0f};        // Pa, per bond on the bond area, in the tests
freezeToIceModulusRatio {ratio:.6g};
freezeCompressionToIceModulusRatio {compression_ratio:.6g};
relativeError           {error:.3f};      // {"the verification runs' largest deviation" if points else "the fits' largest residual or the verification runs' deviation"}

// ************************************************************************* //
"""
    iceCases.write_atomically(path, text)


def write_markdown(path, conf_rows, dist, pressure, probe_s, probe_t, relation, fit_error, error, sens, rho0, derived,
                   cf, sweep_strengths, forward, points):
    """forward(t_p, s_p): the (T_eff, S_eff) the dictionary's relation gives (lines or points)."""
    md = ["## Confinement", "",
          "| rubble | freeze-bonds | c_f | p_c on the real area: mean / max (kPa) | per bond on the bond area, c_f p_c: mean (kPa) |",
          "|---|---|---|---|---|"]
    for r in conf_rows:
        md.append(f"| {r['source']} ({r['shape']}) | {r['bonds']} | {r['c_f']:.3f} | {kpa(r['real_mean_Pa'], 2)} / "
                  f"{kpa(r['real_max_Pa'], 1)} | **{kpa(r['bond_mean_Pa'], 3)}** |")
    if dist:
        q = dist["real"]
        md += ["", f"Distribution ({dist['source']}, {dist['bonds']} bonds, column `{dist['column']}`, on the real area): "
               f"{100 * dist['zero_share']:.0f} % at zero, percentiles 10/25/50/75/90: "
               + " / ".join(kpa(q[k], 2) for k in (10, 25, 50, 75, 90)) + f" kPa, mean {kpa(dist['real_mean'], 2)} kPa."]
    md += ["", f"Applied end pressure for the rubble's mean per-bond confinement: shear test {pressure['shear']:.0f} Pa "
           f"(probe: {probe_s['confinement_Pa']:.0f} Pa per bond at {probe_s['applied_Pa']:.0f} Pa applied), tension "
           f"test {pressure['tension']:.0f} Pa (probe: {probe_t['confinement_Pa']:.0f} Pa at {probe_t['applied_Pa']:.0f} Pa).",
           "", "## Relation at the rubble's confinement (per bond area)", "",
           *(["The dictionary holds the measured points (`--relation points`, the plot's polylines); the straight-line "
              "fits below show how far the relation bends.", ""] if points else []),
           "| rho = T_p/S_p | S_eff = a S_p + b: a | b (kPa) | largest residual | T_eff = a T_p + b: a | b (kPa) | largest residual | S_eff/T_eff at S_p 160 kPa |",
           "|---|---|---|---|---|---|---|---|"]
    for rho, r in sorted(relation.items()):
        ratio = (r["shearSlope"] * 160e3 + r["shearIntercept"]) / (r["tensileSlope"] * rho * 160e3 + r["tensileIntercept"])
        md.append(f"| {rho:g} | {r['shearSlope']:.4f} | {kpa(r['shearIntercept'], 2)} | {100 * r['shearError']:.1f} % | "
                  f"{r['tensileSlope']:.4f} | {kpa(r['tensileIntercept'], 2)} | {100 * r['tensileError']:.1f} % | {ratio:.2f} |")
    md += ["", f"Largest residual of the fits: {100 * fit_error:.1f} % (S_p {kpa(sweep_strengths[0], 0)}-{kpa(sweep_strengths[-1], 0)} kPa); largest deviation of a "
           f"verification run (the table at the end, before and after) from the relation: "
           f"{100 * max(abs(d['check'][k] / d['pred'][k] - 1) for d in derived for k in (0, 1)):.1f} %. The "
           f"stated error of the relation, `relativeError`: **{100 * error:.1f} %**.", "",
           f"## Sensitivity (rho = {rho0:g} unless named; effective on the bond area, kPa)", "",
           "| variant | test | S_p (kPa) | confinement per bond (kPa) | effective (kPa) | against the relation |",
           "|---|---|---|---|---|---|"]
    for (name, test, s_p), r in sens.items():
        if not succeeded(r):
            md.append(f"| {name} | {test} | {kpa(s_p, 0)} | | failed: {r['failed']} | |")
            continue
        rho = r["T_p"] / r["S_p"]
        pred = None
        if min(relation) <= rho <= max(relation):
            pred = forward(rho * s_p, s_p)[1 if test == "shear" else 0]
        md.append(f"| {name} | {test} | {kpa(s_p, 0)} | {kpa(r['confinement_Pa'], 3)} | {kpa(r['effective_Pa'], 2)} | "
                  + (f"{100 * (r['effective_Pa'] / pred - 1):+.1f} %" if pred else "") + " |")
    md += ["", f"## Derived particle strengths (c_f = {cf:g}; Pa on the bond area, shown in kPa)", "",
           "| set | tension | real T / S | effective target T / S | particle T_p / S_p | relation gives T / S | verification run T / S | run against relation T / S | shear off target |",
           "|---|---|---|---|---|---|---|---|---|"]
    for d in derived:
        md.append(f"| {d['set']} | {d['choice']} | {kpa(d['T_real'])} / {kpa(d['S_real'])} | {kpa(d['T_eff'], 2)} / "
                  f"{kpa(d['S_eff'], 2)} | **{kpa(d['T_p'], 2)} / {kpa(d['S_p'], 2)}** | {kpa(d['pred'][0], 2)} / "
                  f"{kpa(d['pred'][1], 2)} | {kpa(d['check'][0], 2)} / {kpa(d['check'][1], 2)} | "
                  f"{100 * (d['check'][0] / d['pred'][0] - 1):+.1f} % / {100 * (d['check'][1] / d['pred'][1] - 1):+.1f} % | "
                  f"{100 * (d['check'][1] / d['S_eff'] - 1):+.1f} % |")
    iceCases.write_atomically(path, "\n".join(md) + "\n")


def plot(path, sweep, relation, ratios, derived, sens, rho0, sets, cf, sweep_strengths, points=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import ScalarFormatter
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    ax = axes.ravel()
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(ratios)))
    x = np.array(sweep_strengths)
    for rho, col in zip(ratios, colours):
        r = relation[rho]
        done = [s for s in x if succeeded(sweep[("shear", rho, s)])]
        ax[0].plot(np.array(done) * 1e-3, [sweep[("shear", rho, s)]["effective_Pa"] * 1e-3 for s in done], "o", color=col)
        shear_line = np.array(points[rho]["shear"]) if points else r["shearSlope"] * x + r["shearIntercept"]
        ax[0].plot(x * 1e-3, shear_line * 1e-3, "-", color=col, label=f"rho {rho:g}")
        done = [s for s in x if succeeded(sweep[("tension", rho, s)])]
        ax[1].plot(rho * np.array(done) * 1e-3, [sweep[("tension", rho, s)]["effective_Pa"] * 1e-3 for s in done], "o",
                   color=col)
        tension_line = np.array(points[rho]["tension"]) if points else r["tensileSlope"] * rho * x + r["tensileIntercept"]
        ax[1].plot(rho * x * 1e-3, tension_line * 1e-3, "-", color=col)
    for d in derived:
        marker = {"sets": "*", "iceRatio": "s"}.get(d["choice"], "x")
        ax[0].plot(d["S_p"] * 1e-3, d["check"][1] * 1e-3, marker, color="C3", ms=10 if marker == "*" else 6,
                   label=None)
    ax[0].plot([], [], "*", color="C3", ms=10, label="derived, sets (verification)")
    ax[0].plot([], [], "s", color="C3", label="derived, ice ratio")
    ax[0].plot([], [], "x", color="C3", label="direct (before)")
    ax[0].set(xscale="log", yscale="log", xlabel="particle shear strength S_p (kPa)",
              ylabel="effective shear strength on the bond area (kPa)",
              title="virtual shear test at the rubble's confinement")
    ax[0].legend(fontsize=8)
    ax[1].plot([1, 1e3], [1, 1e3], "k:", lw=0.8, label="effective = particle")
    ax[1].set(xscale="log", yscale="log", xlabel="particle tensile strength T_p (kPa)",
              ylabel="effective tensile strength on the bond area (kPa)",
              title="virtual tension test at the rubble's confinement")
    ax[1].legend(fontsize=8)
    rr = sorted(relation)
    reach = [(relation[r]["shearSlope"] * 160e3 + relation[r]["shearIntercept"])
             / (relation[r]["tensileSlope"] * r * 160e3 + relation[r]["tensileIntercept"]) for r in rr]
    ax[2].plot(rr, reach, "o-", label="what the interface shows, S_eff / T_eff (S_p 160 kPa)")
    set_ratios = {}
    for name, (t, s) in sets.items():
        set_ratios.setdefault(round(s / t, 2), []).append(name)
    for value, names in set_ratios.items():
        ax[2].axhline(value, color="C1", ls="--", lw=0.8)
        ax[2].text(rr[0], value, f"sets {', '.join(names)}: S/T {value:.2f}", va="bottom", fontsize=8, color="C1")
    ax[2].axhline(1 / ICE_RATIO, color="C2", ls="--", lw=0.8)
    ax[2].text(rr[0], 1 / ICE_RATIO, f"ice ratio: S/T {1 / ICE_RATIO:.2f}", va="bottom", fontsize=8, color="C2")
    ax[2].set(xscale="log", yscale="log", xlabel="particle ratio rho = T_p / S_p",
              ylabel="effective shear / tensile strength", title="which ratio an interface of our bonds can show")
    for axis in (ax[2].xaxis, ax[2].yaxis):
        axis.set_major_formatter(ScalarFormatter())
        axis.set_minor_formatter(ScalarFormatter())
    ax[2].tick_params(which="minor", labelsize=7)
    ax[2].legend(fontsize=8, loc="center right")
    base = {s_p: sweep[("shear", rho0, s_p)] for s_p in (40e3, 160e3)}
    for s_p, col in ((40e3, "C0"), (160e3, "C1")):
        points = [(base[s_p]["confinement_Pa"], base[s_p]["effective_Pa"])]
        for name in ("half", "twice", "old25kPa"):
            r = sens[(name, "shear", s_p)]
            if not succeeded(r):
                continue
            points.append((r["confinement_Pa"], r["effective_Pa"]))
        points.sort()
        c = relation[rho0]
        pred = c["shearSlope"] * s_p + c["shearIntercept"]
        ax[3].plot([p[0] * 1e-3 for p in points], [p[1] / pred for p in points], "o-", color=col,
                   label=f"shear, S_p {s_p * 1e-3:g} kPa")
        tens = [(base[s_p]["confinement_Pa"], sweep[("tension", rho0, s_p)]["effective_Pa"])]
        for name in ("half", "twice", "old25kPa"):
            r = sens[(name, "tension", s_p)]
            if not succeeded(r):
                continue
            tens.append((r["confinement_Pa"], r["effective_Pa"]))
        tens.sort()
        tpred = c["tensileSlope"] * rho0 * s_p + c["tensileIntercept"]
        ax[3].plot([p[0] * 1e-3 for p in tens], [p[1] / tpred for p in tens], "s--", color=col,
                   label=f"tension, S_p {s_p * 1e-3:g} kPa")
    ax[3].axvline(base[40e3]["confinement_Pa"] * 1e-3, color="k", lw=0.8, ls=":")
    ax[3].text(base[40e3]["confinement_Pa"] * 1e-3, 1.6, " rubble (mean)", fontsize=8)
    ax[3].set(xscale="log", xlabel="confinement per bond on the bond area (kPa)",
              ylabel="effective strength / relation at the rubble's confinement",
              title=f"confinement (rho {rho0:g}): the old test's 25 kPa is 11.5 kPa per bond")
    ax[3].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=100)
    os.replace(path + ".tmp.png", path)


if __name__ == "__main__":
    main()
