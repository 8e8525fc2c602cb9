#!/usr/bin/python3
"""The chain from effective to particle freeze-bond strengths, closed on a small
virtual test: the virtual shear and tension tests (cases/freezeBondShear,
cases/freezeBondTension) given the rubble's freeze-bond dictionary
(cases/common/freezeBondProperties: set 4h, c_f 0.197, particleStrengths
calibrated), at the calibration's confinement. The bonds get the particle
strengths the C++ derives; the plane must then show the set's effective shear
strength c_f x 88.8 kPa on the bond area, and the tension the relation
predicts, each within the calibration's stated relativeError (the fits'
largest residual or the study's verification runs' largest deviation). A bad particleStrengths
name is refused naming the file and the entry.

usage: freezeBondParticleStrengths.py SHEAR_CASE TENSION_CASE WORKDIR SHEAR_APP TENSION_APP"""
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
import iceCases  # noqa: E402

shear_case, tension_case, work, shear_app, tension_app = sys.argv[1:]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def rubble_bonds(case):
    """The case's freezeBondProperties replaced by the rubble's (cases/common, 4h)."""
    with open(os.path.join(case, "constant", "freezeBondProperties"), "w") as f:
        f.write('FoamFile { version 2.0; format ascii; class dictionary; object freezeBondProperties; }\n'
                '#include "../../common/freezeBondProperties"\n'
                'calibratedCoeffs { #include "../../common/freezeBondCalibration" }\n')


def scalar(text):
    return float(re.match(r"\s*([-+0-9.eE]+)", text).group(1))


common = os.path.join(iceCases.TOP, "cases", "common", "freezeBondProperties")
calibration = os.path.join(iceCases.TOP, "cases", "common", "freezeBondCalibration")
cf = scalar(iceCases.get_entry(common, "areaCorrection.value"))
tolerance = scalar(iceCases.get_entry(calibration, "relativeError"))
confinement = scalar(iceCases.get_entry(calibration, "confinement"))
# Per bond, the tests measure 0.46 of the applied end pressure (83 bonds of 2.3 times the cross-section).
pressure = confinement / 0.46
target_shear = cf * 88.8e3

# Shear: the load rises to the expected failure in about 0.04 s of DEM time.
shear = iceCases.copy_case(shear_case, os.path.join(work, "shear"))
rubble_bonds(shear)
props = os.path.join(shear, "constant", "shearTestProperties")
load = target_shear / 0.434 * 0.75 * 6.36e-3 * 1.6
iceCases.set_entry(props, "loading.loadRate", f"{load / 0.04:.6g}")
iceCases.set_entry(props, "loading.maxLoad", f"{3 * load:.6g}")
iceCases.run_app(shear_app, shear, 1, ["-label", "rubble4h", "-pressure", f"{pressure:.6g}"], "log.rubble4h")
s = json.load(open(os.path.join(shear, "postProcessing", "runs", "rubble4h", "summary.json")))
log = open(os.path.join(shear, "log.rubble4h")).read()
check("particle strengths calibrated" in log, "the shear test's bonds are calibrated (log names it)")
t_p, s_p = s["particle_tensile_strength_Pa"], s["particle_shear_strength_Pa"]
check(abs(t_p / s_p - 26.9 / 88.8) < 1e-6, f"particle tensile/shear {t_p / s_p:.4f} keeps the set's 26.9/88.8")
effective = s["effective_shear_strength_Pa"] * s["specimen_area_m2"] / s["freeze_bond_area_m2"]
check(s["failed"] and abs(effective / target_shear - 1) <= tolerance,
      f"particle {t_p:.0f} / {s_p:.0f} Pa give an effective shear strength of {effective:.0f} Pa on the bond area "
      f"against the set's c_f x 88.8 kPa = {target_shear:.0f} Pa (within {100 * tolerance:.1f} %: "
      f"{100 * (effective / target_shear - 1):+.2f} %)")
# The bonds' confinement (on the real area, c_f of the rubble's dictionary) is the calibration's.
measured = cf * s["mean_measured_confinement_Pa"]
check(abs(measured / confinement - 1) < 0.1,
      f"confinement per bond on the bond area {measured:.0f} Pa (c_f x {s['mean_measured_confinement_Pa']:.0f} Pa "
      f"on the real area) against the calibration's {confinement:.0f} Pa (within 10 %)")

# Tension: the same bonds pulled; what the relation predicts for them.
tension = iceCases.copy_case(tension_case, os.path.join(work, "tension"))
rubble_bonds(tension)
props = os.path.join(tension, "constant", "tensionTestProperties")
pull = 0.56e-9 * t_p
iceCases.set_entry(props, "loading.pullSpeed", f"{pull / 0.03:.6g}")
iceCases.set_entry(props, "loading.maxPull", f"{3 * pull:.6g}")
iceCases.set_entry(props, "loading.samples", 1000)
iceCases.run_app(tension_app, tension, 1, ["-label", "rubble4h", "-pressure", f"{pressure:.6g}"], "log.rubble4h")
t = json.load(open(os.path.join(tension, "postProcessing", "runs", "rubble4h", "summary.json")))
tensile = t["strength_Pa"] * t["specimen_area_m2"] / t["freeze_bond_area_m2"]
rhos = [scalar(x) for x in iceCases.get_entry(calibration, "ratios").strip("() ").split()]
slopes = [scalar(x) for x in iceCases.get_entry(calibration, "tensileSlopes").strip("() ").split()]
intercepts = [scalar(x) for x in iceCases.get_entry(calibration, "tensileIntercepts").strip("() ").split()]
rho = t_p / s_p
k = next(i for i in range(1, len(rhos)) if rhos[i] >= rho or i == len(rhos) - 1)
w = (rho - rhos[k - 1]) / (rhos[k] - rhos[k - 1])
predicted = (slopes[k - 1] + w * (slopes[k] - slopes[k - 1])) * t_p + intercepts[k - 1] + w * (intercepts[k] - intercepts[k - 1])
check(abs(tensile / predicted - 1) <= tolerance,
      f"effective tensile strength {tensile:.0f} Pa on the bond area against the relation's {predicted:.0f} Pa "
      f"({100 * (tensile / predicted - 1):+.2f} %; the set asks {cf * 26.9e3:.0f} Pa)")

# A bad name: refused, naming the file and the entry.
iceCases.set_entry(os.path.join(shear, "constant", "freezeBondProperties"), "particleStrengths", "derived")
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
r = subprocess.run([shear_app, "-case", shear, "-label", "bad"], capture_output=True, text=True, env=env)
message = r.stdout + r.stderr
check(r.returncode != 0 and "freezeBondProperties" in message and "entry 'particleStrengths'" in message
      and "allowed: direct calibrated" in message,
      "particleStrengths derived is refused naming file and entry: " + message.strip().splitlines()[-1][:200]
      if message.strip() else "no message")
sys.exit(1 if failures else 0)
