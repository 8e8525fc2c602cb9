#!/usr/bin/python3
"""The design map's calibration chain (cases/ridgeDesignMap/chain.py): its plumbing, without
running a simulation.

usage: chainTests.py WORKDIR

Checks: the committed chain is up to date with the committed data and inputs; a changed data file
makes exactly the steps that read it stale (the sets: freezeBondSets and particleStrengths; the
tension tests: tensionLines), the others stay up to date; a step made from a user's CSV writes its
values into the dictionary the cases include (no copy by hand) and is then up to date for that
data only; bad data is refused with the file named."""
import csv
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
CHAIN = os.path.join(TOP, "cases", "ridgeDesignMap", "chain.py")
DATA = os.path.join(os.path.dirname(TOP), "shared", "data")
work = os.path.abspath(sys.argv[1])
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
sys.path.insert(0, os.path.dirname(HERE))
from checkList import CheckList  # noqa: E402
check = CheckList()


def chain(*args):
    return subprocess.run(["/usr/bin/python3", CHAIN] + list(args), capture_output=True, text=True)


def status(*args):
    r = chain("status", *args)
    return {line.split()[0]: line.split(None, 1)[1] for line in r.stdout.splitlines() if line.strip()}


s = status()
check(s and all(v.startswith("up to date") for v in s.values()),
      "the committed chain is up to date with its data and inputs:\n" + "\n".join(f"  {k}: {v}" for k, v in s.items()))

# what a case reads through the include inside fixedSetCoeffs: the generated sets
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402
punch_bonds = os.path.join(TOP, "cases", "rubblePunch", "constant", "freezeBondProperties")
tensile = iceCases.get_entry(punch_bonds, "fixedSetCoeffs.sets.4h.tensile")
check(float(tensile) == 26.9e3, f"fixedSetCoeffs.sets.4h.tensile through the include inside fixedSetCoeffs: {tensile} Pa")
ridge_ice = os.path.join(TOP, "cases", "ridgeFlexure", "constant", "iceProperties")
break_n = iceCases.get_entry(ridge_ice, "bondFamilies.ice.breakN")
check(float(break_n) == 0.0013, f"ridgeFlexure's breakN from the chain's layerStrength (its last include): {break_n}")

# the user's sets: 4 h tensile doubled
sets = os.path.join(work, "mySets.csv")
with open(os.path.join(DATA, "freezeBondSets.csv")) as f:
    rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
for r in rows:
    if r["set"] == "4h":
        r["tensile_kPa"] = str(2 * float(r["tensile_kPa"]))
with open(sets, "w") as f:
    w = csv.DictWriter(f, list(rows[0]))
    w.writeheader()
    w.writerows(rows)
s = status("-data", f"freezeBondSets={sets}")
check(s["freezeBondSets"] == "changed: data freezeBondSets" and s["particleStrengths"] == "changed: data freezeBondSets",
      f"other sets: the steps that read them are stale ({s['freezeBondSets']}; {s['particleStrengths']})")
check(s["tensionLines"].startswith("up to date") and s["layerStrength"].startswith("up to date"),
      f"other sets: the tension lines and the layer strength stay ({s['tensionLines']}; {s['layerStrength']})")

tension = os.path.join(work, "myTension.csv")
text = open(os.path.join(DATA, "freezeBondTensile.csv")).read()
open(tension, "w").write(text.replace(",117,", ",127,", 1))
s = status("-data", f"freezeBondTensile={tension}")
stale = sorted(k for k, v in s.items() if not v.startswith("up to date"))
check(stale == ["tensionLines"], f"other tension tests: only tensionLines is stale ({stale})")

# the step made from the user's sets, in a scratch root: the dictionary the cases include holds them
root = os.path.join(work, "root")
r = chain("run", "-only", "freezeBondSets", "-root", root, "-data", f"freezeBondSets={sets}")
check(r.returncode == 0, f"run -only freezeBondSets -root: exit {r.returncode} {r.stderr[-300:]}")
generated = open(os.path.join(root, "common", "chain", "freezeBondSets")).read()
check("4h                  { tensile 53800; shear 88800; }" in generated,
      "the generated dictionary holds the user's 4 h tensile (53.8 kPa)")
check("mySets.csv" in generated, "and names the data it was made from")
s = status("-root", root, "-data", f"freezeBondSets={sets}")
check(s["freezeBondSets"] == "up to date", f"then it is up to date for that data ({s['freezeBondSets']})")
s = status("-root", root)
check(s["freezeBondSets"] == "changed: data freezeBondSets", f"and stale for the laboratory's ({s['freezeBondSets']})")

bad = os.path.join(work, "bad.csv")
open(bad, "w").write("set,shear,tensile\n4h,1,2\n")
r = chain("run", "-only", "freezeBondSets", "-root", root, "-data", f"freezeBondSets={bad}")
check(r.returncode != 0 and "bad.csv" in r.stderr and "shear_kPa" in r.stderr,
      f"a CSV without the columns is refused naming the file and the columns: {r.stderr.strip()[-200:]}")
r = chain("status", "-data", "freezeBondSets=/no/such.csv")
check(r.returncode != 0 and "/no/such.csv" in r.stderr, f"a missing data file is named: {r.stderr.strip()}")
r = chain("status", "-data", "mySets=x.csv")
check(r.returncode != 0 and "freezeBondSets" in r.stderr, f"an unknown data name lists the names: {r.stderr.strip()}")

check.finish()
