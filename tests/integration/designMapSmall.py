#!/usr/bin/python3
"""A 2 x 2 ridge design map on the small keel (cases/ridgeDesignMap in small): the study runner's
templated keel path, per-value entries (`with`), post-processing and text figures, and the map's
analysis.

usage: designMapSmall.py KEEL WORK BIN_DIR
  KEEL: the small keel's rubble case (ridgeSmall.py keel: 1.6 x 0.4 m, 0.25 m of rubble, settled)

Checks: every point finishes with its failure mode (failureAnalysis.py as the study's postProcess,
a text column); the thicker layer fails at a higher force for both freeze-bond sets, alone and on
the keel; the per-value entry reached its point only; a dictionary #included by a `with` block
overrides the case's own entry (a doubled breakN makes the layer stronger); the keel's share (F_ridge / F_layer - 1) in
designMap.csv is the tables' own; a second run keeps every point; without the keel file every
point's fingerprint changes (the upstream file is part of it)."""
import csv
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402

keel_source, work, bin_dir = (os.path.abspath(a) for a in sys.argv[1:4])
RUNNER = os.path.join(TOP, "studies", "runStudy.py")
DESIGN_MAP = os.path.join(TOP, "cases", "ridgeDesignMap", "designMap.py")
sys.path.insert(0, os.path.dirname(HERE))
from checkList import CheckList  # noqa: E402
check = CheckList()


SMALL = """
    "constant/ridgeProperties:box.length"                           1.6;
    "constant/ridgeProperties:box.width"                            0.4;
    "constant/ridgeProperties:test.speed"                           0.2;
    "constant/ridgeProperties:test.settleTime"                      0.05;
    "constant/ridgeProperties:assembly.relaxTime"                   0.1;
    "constant/ridgeProperties:assembly.pressSpeed"                  0.05;
    "system/controlDict:writeInterval"                              1;
"""
LAYERS = "values (0.07 0.12);"


def study(folder, knobs, extra_set="", post="", figures=""):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "studyDict"), "w") as f:
        f.write(f"""study {{ case ridgeFlexure; application ridgeDEM; ranks 1; arguments (-stage all); {post} }}
knobs
{{
{knobs}
}}
set {{ {SMALL} {extra_set} }}
figures {{ failureForce peak_force_N; equivalentThickness equivalent_thickness_m; {figures} }}
reference {{ type none; }}
""")
    return folder


def run(folder):
    r = subprocess.run(["/usr/bin/python3", RUNNER, folder, "-bin", bin_dir, "-jobs", "1"],
                       capture_output=True, text=True)
    print(r.stdout[-3000:] + r.stderr[-2000:])
    return r


def table(folder):
    with open(os.path.join(folder, "results", "table.csv")) as f:
        return {r["point"]: r for r in csv.DictReader(f)}


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
# the map's keels live in its study folder (${STUDY}/keels/...), as cases/ridgeDesignMap's
ridge_study = os.path.join(work, "map")
shutil.copytree(os.path.join(keel_source, "DEM"), os.path.join(ridge_study, "keels", "keel0.25", "DEM"),
                ignore=shutil.ignore_patterns("*.restart.*", "checkpoint*"))
keel_h5 = os.path.join(ridge_study, "keels", "keel0.25", "DEM", "settled.h5")
check(os.path.isfile(keel_h5), f"the small keel: {keel_h5}")

study(ridge_study, f"""
    keelDepth {{ entry constant/ridgeProperties:keel.settledRubble;
                 template "${{STUDY}}/keels/keel${{keelDepth}}/DEM/settled.h5"; values (0.25); }}
    layer {{ entry constant/ridgeProperties:consolidatedLayer.thickness; {LAYERS}
             with {{ 0.12 {{ "constant/ridgeProperties:consolidatedLayer.radiusSpread" 0.05; }} }} }}
    bondSet {{ entry constant/freezeBondProperties:fixedSetCoeffs.set; values (4h ultimate); }}
""", post='postProcess ("postProcessing/failureAnalysis.py");',
      figures='mode "failureAnalysis/summary.json:ridge_failure.mode";')
alone_study = study(os.path.join(work, "layerAlone"), f"""
    layer {{ entry constant/ridgeProperties:consolidatedLayer.thickness; {LAYERS}
             with {{ 0.12 {{ "constant/ridgeProperties:consolidatedLayer.radiusSpread" 0.05; }} }} }}
""", extra_set='"constant/ridgeProperties:keel.settledRubble" none;')

r_alone, r_map = run(alone_study), run(ridge_study)
check(r_alone.returncode == 0 and r_map.returncode == 0,
      f"both studies finish (exit {r_alone.returncode}, {r_map.returncode})")
alone, ridge = table(alone_study), table(ridge_study)
check(len(ridge) == 4 and all(r["status"] == "done" for r in ridge.values()), f"4 map points done: "
      f"{[(p, r['status'], r['error']) for p, r in ridge.items()]}")
modes = [r["mode"] for r in ridge.values()]
check(all(m and m != "nan" and not m.replace(".", "").isdigit() for m in modes),
      f"each point's failure mode is a text column: {modes}")


def force(t, point):
    return float(t[point]["failureForce"])


thin, thick = force(alone, "layer-0.07"), force(alone, "layer-0.12")
check(thick > 1.5 * thin, f"the layer alone: 12 cm fails at {thick:.0f} N, above 1.5 x 7 cm's {thin:.0f} N")
for bond_set in ("4h", "ultimate"):
    a = force(ridge, f"keelDepth-0.25_layer-0.07_bondSet-{bond_set}")
    b = force(ridge, f"keelDepth-0.25_layer-0.12_bondSet-{bond_set}")
    check(b > a, f"set {bond_set}: the ridge with 12 cm of layer fails at {b:.0f} N, above 7 cm's {a:.0f} N")

# the per-value entry: in the 0.12 points only
for point in ridge:
    props = os.path.join(ridge_study, "runs", point, "ridgeFlexure", "constant", "ridgeProperties")
    spread = float(iceCases.get_entry(props, "consolidatedLayer.radiusSpread"))
    want = 0.05 if "layer-0.12" in point else 0.1
    check(spread == want, f"{point}: radiusSpread {spread} (the with-block's 0.05 beside 0.12 only)")

out = os.path.join(work, "analysis")
r = subprocess.run(["/usr/bin/python3", DESIGN_MAP, "analyse", "-map", os.path.join(ridge_study, "results"),
                    "-layers", os.path.join(alone_study, "results"), "-out", out], capture_output=True, text=True)
check(r.returncode == 0, f"designMap.py analyse: exit {r.returncode} {r.stderr[-500:]}")
with open(os.path.join(out, "designMap.csv")) as f:
    rows = list(csv.DictReader(f))
check(len(rows) == 4, f"designMap.csv: {len(rows)} rows (4)")
for row in rows:
    layer = float(row["layer_m"])
    point = f"keelDepth-0.25_layer-{'0.07' if layer < 0.1 else '0.12'}_bondSet-{row['bond_set']}"
    want = force(ridge, point) / force(alone, f"layer-{'0.07' if layer < 0.1 else '0.12'}") - 1
    check(abs(float(row["keel_share"]) - want) < 1e-3,
          f"{point}: keel share {row['keel_share']} = F_ridge / F_layer - 1 = {want:.4f}")
check(all(os.path.getsize(os.path.join(out, n)) > 1000 for n in ("keelShare.png", "failureModes.png")),
      "keelShare.png and failureModes.png written")

# a generated dictionary #included after a case file's own entries overrides them (the chain's
# layerStrength_d<diameter>, here breakN doubled): the layer alone is stronger with it
strong = os.path.join(work, "strongLayer")
with open(strong, "w") as f:
    f.write("bondFamilies\n{\n    ice\n    {\n        breakN  0.0026;\n    }\n}\n")
include_study = study(os.path.join(work, "include"), f"""
    strength {{ entry system/controlDict:writeInterval; values (1 2);   // no frames either way
                with {{ 2 {{ "constant/iceProperties:#include" "{strong}"; }} }} }}
""", extra_set='"constant/ridgeProperties:keel.settledRubble" none; '
               '"constant/ridgeProperties:consolidatedLayer.thickness" 0.07;')
r = run(include_study)
inc = table(include_study)
check(r.returncode == 0 and float(inc["strength-2"]["failureForce"]) > 1.3 * float(inc["strength-1"]["failureForce"]),
      f"breakN 0.0026 included: the layer alone fails at {inc['strength-2']['failureForce']} N, above 1.3 x "
      f"{inc['strength-1']['failureForce']} N (0.0013)")
ice = open(os.path.join(include_study, "runs", "strength-2", "ridgeFlexure", "constant", "iceProperties")).read()
check(ice.rstrip().endswith(f'#include "{strong}"'), "the #include is the point's iceProperties' last line")

r = run(ridge_study)
check("(4 finished before, 0 to run)" in r.stdout, "a second run keeps every point")
os.rename(keel_h5, keel_h5 + ".away")
listing = subprocess.run(["/usr/bin/python3", RUNNER, ridge_study, "-bin", bin_dir, "-list"],
                         capture_output=True, text=True).stdout
os.rename(keel_h5 + ".away", keel_h5)
check(listing.count(" run") == 4, f"without the keel file every point would run again:\n{listing}")

check.finish()
