#!/usr/bin/python3
"""Scaling laws of the bonded-ice model on the small beam, each of which fails
if a spring, a strength or the damping is wrong:

- quasi-static, rate-independent loading with strain-based strengths: doubling
  the modulus (bonds and contacts) doubles the elastic slope and the peak force
  (stress = E * strain);
- at fixed modulus the peak force is proportional to breakN
  (levelIceParametric.csv, figure 7);
- the loading is quasi-static (kinetic / elastic energy small at the peak).

usage: beamScaling.py CASE WORKDIR APP
"""
import json
import os
import re
import shutil
import subprocess
import sys

case, work, app = sys.argv[1:4]
common = ["-particles", "400", "-platenSpeed", "0.2"]


def run(name, edits):
    target = os.path.join(work, name)
    shutil.rmtree(target, ignore_errors=True)
    for sub in ("constant", "system", "DEM"):
        shutil.copytree(os.path.join(case, sub), os.path.join(target, sub))
    path = os.path.join(target, "constant", "iceProperties")
    text = open(path).read()
    for pattern, value in edits:
        text, n = re.subn(pattern, value, text)
        assert n > 0, f"no match for {pattern}"
    open(path, "w").write(text)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    log = open(os.path.join(target, "log.iceBeamDEM"), "w")
    subprocess.run(["mpirun", "-np", "1", app, "-case", target] + common,
                   check=True, stdout=log, stderr=subprocess.STDOUT, env=env)
    return json.load(open(os.path.join(target, "postProcessing", "summary.json")))


base = run("base", [])
stiff = run("doubleModulus", [(r"youngsModulus(\s+)5\.4e8", r"youngsModulus\g<1>1.08e9")])
strong = run("breakN1.5", [(r"breakN(\s+)0\.0037", r"breakN\g<1>0.00555")])

checks = [
    ("slope x2 with modulus x2", stiff["elastic_slope_N_per_m"] / base["elastic_slope_N_per_m"], 2.0, 0.05),
    ("peak x2 with modulus x2", stiff["peak_force_N"] / base["peak_force_N"], 2.0, 0.05),
    ("peak x1.5 with breakN x1.5", strong["peak_force_N"] / base["peak_force_N"], 1.5, 0.08),
    ("slope unchanged with breakN x1.5", strong["elastic_slope_N_per_m"] / base["elastic_slope_N_per_m"], 1.0, 0.05),
]
failed = 0
for name, ratio, expected, tolerance in checks:
    ok = abs(ratio / expected - 1.0) <= tolerance
    failed += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {name}: ratio {ratio:.4f}, expected {expected} +- {tolerance:.0%}")
ke = base["kinetic_to_elastic_energy_at_peak"]
ok = ke < 0.01 and base["half_load_reached"]
failed += not ok
print(f"{'ok  ' if ok else 'FAIL'} quasi-static at peak (kinetic/elastic {ke:.2e} < 0.01) and the beam unloads")
print(f"{5 - failed} passed, {failed} failed")
sys.exit(1 if failed else 0)
