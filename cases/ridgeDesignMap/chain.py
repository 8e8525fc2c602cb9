#!/usr/bin/python3
"""From the laboratory data to the values the design map runs with (issue 21, part 1).

  chain.py status [-data NAME=FILE ...]   each step: up to date, or what changed since it was made
  chain.py run    [-data NAME=FILE ...] [-jobs N] [-only STEP,...]
                                          make every step whose inputs changed, in order; the steps
                                          after it see its new outputs, so exactly the steps
                                          downstream of a changed input run again
  chain.py adopt STEP -why TEXT           record STEP's committed output as made from its present
                                          inputs without making it (status says so, with TEXT)
  -root DIR                               the dictionaries (DIR/common/...), the state (DIR/state)
                                          and the runs (DIR/runs) under DIR instead of the case's

Each step writes its values into a dictionary that the next consumer #includes (no copying by
hand) and records in chain/<step>.json what it was made from: the fingerprint of its data files,
its case inputs, its code and the outputs of the steps it reads. The map's points include those
dictionaries through the ridge case's, so the study runner reruns a point when one of them changes.

Data (`-data NAME=FILE`, a CSV in the format of ../shared/data/<the default file>):
  freezeBondSets           freeze-bond strength sets (set, shear_kPa, tensile_kPa)
  freezeBondTensile        freeze-bond tension tests (submersion_min, p_actual_kPa, mean_kPa, ...)
  flexuralStrengthTargets  the layer's flexural strength by beam size (thickness_m, volume_m3, target_kPa)

Steps:
  freezeBondSets     the sets -> cases/common/chain/freezeBondSets (fixedSetCoeffs.sets of
                     cases/common/freezeBondProperties: every ridge, punch and keel-bond case)
  tensionLines       the tension tests -> cases/common/chain/freezeBondTensionLines: strength
                     against confinement, a line per submersion time (strengthModel
                     confinementLine; not upstream of the map, whose sets are fixed)
  particleStrengths  our virtual shear and tension tests at the ridge's moduli -> the relation from
                     effective to particle strengths, cases/common/freezeBondCalibrationRidge
                     (cases/freezeBondShear/studies/particleStrengths.py, about 20 min)
  layerStrength      three-point bending of the targets' beams (cases/threePointBending, its
                     resolution and speed, three packings) -> the layer's breakN whose mean
                     sigma_f meets every target within 5 %: cases/common/chain/layerStrength,
                     #included by cases/ridgeFlexure/constant/iceProperties (about 8 min)
The keels and the map itself follow in ./Allrun (their own fingerprints: designMap.py, runStudy.py).
"""
import argparse
import concurrent.futures
import csv
import hashlib
import inspect
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402

# Where the steps write (-root DIR moves all three, for tests): the outputs are named relative to ROOT.
ROOT = os.path.join(TOP, "cases")
STATE = os.path.join(HERE, "chain")
GENERATED = os.path.join(ROOT, "common", "chain")
WORK = os.path.join(HERE, "runs", "chain")


def use_root(root):
    global ROOT, STATE, GENERATED, WORK
    ROOT = os.path.abspath(root)
    STATE, GENERATED, WORK = (os.path.join(ROOT, sub) for sub in ("state", os.path.join("common", "chain"), "runs"))
DATA = {"freezeBondSets": "freezeBondSets.csv", "freezeBondTensile": "freezeBondTensile.csv",
        "flexuralStrengthTargets": "flexuralStrengthTargets.csv"}
ICE_RATIO = 195.0 / 88.8    # freshwater ice's tensile over shear (physics.md section 5): the *IceRatio sets


def rel(path):
    return os.path.relpath(path, TOP)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def header(step, made_from, lines):
    """An OpenFOAM dictionary's banner naming the step that wrote it and what from."""
    text = ["/*--------------------------------*- C++ -*----------------------------------*\\",
            f"  Written by cases/ridgeDesignMap/chain.py, step {step}: do not edit, rerun the chain",
            f"  (cases/ridgeDesignMap/README.md). Made from {made_from}."]
    text += ["  " + line for line in lines]
    text += ["\\*---------------------------------------------------------------------------*/", ""]
    return "\n".join(text)


# ---------------------------------------------------------------------------- the steps
def make_freeze_bond_sets(ctx):
    rows = read_csv(ctx.data["freezeBondSets"])
    try:
        sets = [(r["set"], float(r["tensile_kPa"]) * 1e3, float(r["shear_kPa"]) * 1e3) for r in rows]
    except (KeyError, ValueError) as e:
        raise SystemExit(f"chain: {ctx.data['freezeBondSets']}: needs columns set, shear_kPa, tensile_kPa with "
                         f"numbers ({type(e).__name__}: {e})")
    body = ["sets    // Pa, before the area correction c_f"]
    body.append("{")
    for name, tensile, shear in sets:
        body.append(f"    {name:<20s}{{ tensile {tensile:.6g}; shear {shear:.6g}; }}")
    body.append("    // the same shears, tensile 195 / 88.8 times them (freshwater ice's ratio)")
    for name, _, shear in sets:
        body.append(f"    {name + 'IceRatio':<20s}{{ tensile {shear * ICE_RATIO:.6g}; shear {shear:.6g}; }}")
    body.append("}")
    text = header("freezeBondSets", rel(ctx.data["freezeBondSets"]),
                  ["Included into fixedSetCoeffs by cases/common/freezeBondProperties."]) + "\n".join(body) + "\n"
    iceCases.write_atomically(os.path.join(GENERATED, "freezeBondSets"), text)
    return {"sets": {name: {"tensile_Pa": t, "shear_Pa": s} for name, t, s in sets}}


def make_tension_lines(ctx):
    rows = read_csv(ctx.data["freezeBondTensile"])
    by_time = {}
    for r in rows:
        by_time.setdefault(float(r["submersion_min"]), []).append((float(r["p_actual_kPa"]), float(r["mean_kPa"])))
    lines = {}
    for minutes, points in sorted(by_time.items()):
        if len({p for p, _ in points}) < 2:
            continue
        n = len(points)
        mx = sum(p for p, _ in points) / n
        my = sum(s for _, s in points) / n
        sxx = sum((p - mx) ** 2 for p, _ in points)
        slope = sum((p - mx) * (s - my) for p, s in points) / sxx
        intercept = my - slope * mx
        ss_tot = sum((s - my) ** 2 for _, s in points)
        ss_res = sum((s - intercept - slope * p) ** 2 for p, s in points)
        lines[minutes] = {"slope": slope, "intercept_Pa": intercept * 1e3, "tests": n,
                          "R2": 1 - ss_res / ss_tot if ss_tot > 0 else 1.0}
    if not lines:
        raise SystemExit(f"chain: {ctx.data['freezeBondTensile']}: no submersion time with two confinements")
    times = sorted(lines)
    body = [f"submersionTimes ({' '.join('%g' % t for t in times)});   // min",
            f"slopes          ({' '.join('%.4g' % lines[t]['slope'] for t in times)});",
            f"intercepts      ({' '.join('%.4g' % lines[t]['intercept_Pa'] for t in times)});   // Pa",
            f"// R2 {' '.join('%.3f' % lines[t]['R2'] for t in times)}; tests "
            f"{' '.join(str(lines[t]['tests']) for t in times)} (least squares of the means on the actual confinement)"]
    text = header("tensionLines", rel(ctx.data["freezeBondTensile"]),
                  ["Tensile strength = slope p + intercept, per submersion time: the measured lines",
                   "for strengthModel confinementLine (cases/freezeBondTension checks the DEM on them)."])
    iceCases.write_atomically(os.path.join(GENERATED, "freezeBondTensionLines"), text + "\n".join(body) + "\n")
    return {"lines": {"%g" % t: lines[t] for t in times}}


PARTICLE_STRENGTH_OPTIONS = ["--relation", "points", "--confinement", "397", "--ice-modulus", "5.4e8",
                             "--freeze-modulus", "2.80775e6", "--freeze-compression-modulus", "5.4e8", "--slow", "8",
                             "--sweep-strengths", "10e3,20e3,40e3,160e3", "--dictionary", "freezeBondCalibrationRidge"]


def make_particle_strengths(ctx):
    script = os.path.join(TOP, "cases", "freezeBondShear", "studies", "particleStrengths.py")
    out = os.path.join(WORK, "particleStrengths")
    base = [sys.executable, script] + PARTICLE_STRENGTH_OPTIONS + ["--sets", ctx.data["freezeBondSets"],
                                                                  "--out", out]
    for extra in ([], ["--publish"]):
        subprocess.run(base + ["--jobs", str(ctx.jobs)] + extra, check=True)
    return {"dictionary": "cases/common/freezeBondCalibrationRidge", "options": PARTICLE_STRENGTH_OPTIONS}


BENDING = os.path.join(TOP, "cases", "threePointBending")
SEEDS = (1, 2, 3)
LAYER_TOLERANCE = 0.05   # each thickness's mean over the packings within 5 % of its target (the case's criterion)


def layer_targets(path):
    """{thickness m: target Pa} of the flexural strength targets (thickness_m, target_kPa)."""
    try:
        return {float(r["thickness_m"]): float(r["target_kPa"]) * 1e3 for r in read_csv(path)}
    except (KeyError, ValueError) as e:
        raise SystemExit(f"chain: {path}: needs columns thickness_m, target_kPa with numbers ({type(e).__name__}: {e})")


def bending_run(thickness, seed, break_n):
    """sigma_f (Pa) of the three-point bending case's beam: its own resolution and speed."""
    name = f"D{thickness:g}_seed{seed}_breakN{break_n:.6g}"

    def prepare(folder):
        iceCases.copy_case(BENDING, folder)
        iceCases.set_entry(os.path.join(folder, "constant", "bendingProperties"), "packing.seed", seed)
        iceCases.set_entry(os.path.join(folder, "constant", "iceProperties"), "bondFamilies.ice.breakN", "%.6g" % break_n)
        iceCases.set_entry(os.path.join(folder, "system", "controlDict"), "writeInterval", 10)
    args = ["-thickness", "%g" % thickness]
    case = iceCases.prepared_run(os.path.join(WORK, "layerStrength", name), prepare, settings=args)
    if not iceCases.finished(case):
        iceCases.run_app("threePointBendingDEM", case, 1, args, "log.threePointBendingDEM")
    return iceCases.summary(case)["flexural_strength_Pa"]


def make_layer_strength(ctx):
    """breakN of the layer's ice bonds: three-point bending of the targets' thicknesses, three packings
    each, at the case's resolution and speed; accepted when every thickness's mean is within
    LAYER_TOLERANCE of its target, else moved by a secant step on the mean error (sigma_f grows about
    as a power of breakN)."""
    targets = layer_targets(ctx.data["flexuralStrengthTargets"])
    start = float(iceCases.get_entry(os.path.join(BENDING, "constant", "iceProperties"), "bondFamilies.ice.breakN"))

    def evaluate(break_n):
        jobs = [(d, s) for d in sorted(targets) for s in SEEDS]
        with concurrent.futures.ThreadPoolExecutor(ctx.jobs) as pool:
            strengths = list(pool.map(lambda j: bending_run(j[0], j[1], break_n), jobs))
        per = {}
        for (d, _), s in zip(jobs, strengths):
            per.setdefault(d, []).append(s)
        return {d: sum(v) / len(v) / targets[d] - 1 for d, v in per.items()}, per
    tries = []
    break_n, exponent = start, 0.8
    for _ in range(6):
        errors, per = evaluate(break_n)
        mean = sum(errors.values()) / len(errors)
        tries.append({"breakN": break_n, "mean_error": mean, "errors": {"%g" % d: e for d, e in errors.items()},
                      "sigma_f_Pa": {"%g" % d: v for d, v in per.items()}})
        print(f"chain layerStrength: breakN {break_n:.6g}: "
              f"{', '.join('%g m %+.1f%%' % (d, 100 * e) for d, e in errors.items())} (mean {mean:+.1%})", flush=True)
        if max(abs(e) for e in errors.values()) <= LAYER_TOLERANCE:
            break
        if len(tries) >= 2:
            a, b = tries[-2], tries[-1]
            slope = (math.log(1 + b["mean_error"]) - math.log(1 + a["mean_error"])) / \
                (math.log(b["breakN"]) - math.log(a["breakN"]))
            exponent = slope if slope > 0.1 else exponent
        break_n = break_n * (1 + mean) ** (-1.0 / exponent)
    best = min(tries, key=lambda t: max(abs(e) for e in t["errors"].values()))
    worst = max(abs(e) for e in best["errors"].values())
    if worst > LAYER_TOLERANCE:
        print(f"chain layerStrength: no breakN met every target within {LAYER_TOLERANCE:.0%} in {len(tries)} tries; "
              f"the closest ({best['breakN']:.6g}, largest error {worst:+.1%}) is written", flush=True)
    lines = ["The consolidated layer's ice bonds: breakN from three-point bending (cases/threePointBending, its",
             f"resolution and speed) of {', '.join('%g' % d for d in sorted(targets))} m beams, packings "
             f"{', '.join(map(str, SEEDS))}: the mean sigma_f of each",
             f"thickness within {', '.join('%+.1f %%' % (100 * e) for e in best['errors'].values())} of its target "
             f"({', '.join('%.0f' % (targets[d] / 1e3) for d in sorted(targets))} kPa).",
             "#included at the end of cases/ridgeFlexure/constant/iceProperties."]
    text = header("layerStrength", rel(ctx.data["flexuralStrengthTargets"]), lines)
    text += f"bondFamilies\n{{\n    ice\n    {{\n        breakN  {best['breakN']:.6g};\n    }}\n}}\n"
    iceCases.write_atomically(os.path.join(GENERATED, "layerStrength"), text)
    return {"breakN": best["breakN"], "errors": best["errors"], "tolerance": LAYER_TOLERANCE, "tries": tries,
            "targets_Pa": {"%g" % d: t for d, t in targets.items()}}


class Step:
    def __init__(self, name, make, data=(), inputs=(), upstream=(), outputs=()):
        self.name, self.make, self.data, self.inputs = name, make, list(data), list(inputs)
        self.upstream, self.outputs = list(upstream), list(outputs)


STEPS = [
    Step("freezeBondSets", make_freeze_bond_sets, data=["freezeBondSets"],
         outputs=["common/chain/freezeBondSets"]),
    Step("tensionLines", make_tension_lines, data=["freezeBondTensile"],
         outputs=["common/chain/freezeBondTensionLines"]),
    Step("particleStrengths", make_particle_strengths, data=["freezeBondSets"],
         inputs=["cases/freezeBondShear/constant", "cases/freezeBondShear/system", "cases/freezeBondShear/DEM",
                 "cases/freezeBondTension/constant", "cases/freezeBondTension/system", "cases/freezeBondTension/DEM",
                 "cases/freezeBondShear/studies/particleStrengths.py",
                 "cases/common/freezeBondProperties"],   # its areaCorrection.value (c_f)
         outputs=["common/freezeBondCalibrationRidge"]),
    Step("layerStrength", make_layer_strength, data=["flexuralStrengthTargets"],
         inputs=["cases/threePointBending/constant", "cases/threePointBending/system", "cases/threePointBending/DEM"],
         outputs=["common/chain/layerStrength"]),
]


# ---------------------------------------------------------------------------- fingerprints
_GENERATED_NAMES = (".h5", ".data", "variables.generated", "platen.stl")


def _files(path):
    path = os.path.join(TOP, path)
    if os.path.isfile(path):
        return [path]
    found = []
    for folder, dirs, names in os.walk(path):
        dirs[:] = sorted(d for d in dirs if d != "checkpoint")
        found += [os.path.join(folder, n) for n in sorted(names)
                  if not n.endswith(_GENERATED_NAMES) and ".restart." not in n]
    return found


def _digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def outputs(step):
    return step.outputs


def fingerprint(step, ctx):
    """What the step is made from: {kind: {name: sha256}}, and their digest."""
    parts = {"code": hashlib.sha256(inspect.getsource(step.make).encode()).hexdigest(),
             "data": {n: _digest(ctx.data[n]) for n in step.data},
             "inputs": {rel(f): _digest(f) for p in step.inputs for f in _files(p)},
             "upstream": {o: _digest(os.path.join(ROOT, o)) for name in step.upstream
                          for o in outputs(next(s for s in STEPS if s.name == name))}}
    return parts, hashlib.sha256(json.dumps(parts, sort_keys=True).encode()).hexdigest()[:16]


def recorded(step):
    try:
        return json.load(open(os.path.join(STATE, step.name + ".json")))
    except (OSError, ValueError):
        return {}


def verdict(step, ctx):
    """'up to date', or why the step must be made again."""
    parts, digest = fingerprint(step, ctx)
    old = recorded(step)
    missing = [o for o in outputs(step) if not os.path.isfile(os.path.join(ROOT, o))]
    if missing:
        return f"its output is missing: {', '.join(missing)}"
    if not old:
        return "never made (no chain/%s.json)" % step.name
    if old.get("madeFrom") == digest:
        changed = [o for o, h in old.get("outputs", {}).items()
                   if not os.path.isfile(os.path.join(ROOT, o)) or _digest(os.path.join(ROOT, o)) != h]
        if changed:
            return f"its output was edited since: {', '.join(changed)}"
        return "up to date" + (f" (adopted: {old['adopted']})" if old.get("adopted") else "")
    changed = []
    for kind in sorted(set(parts) | set(old.get("parts", {}))):
        items, before = parts.get(kind, {}), old.get("parts", {}).get(kind, {})
        if kind == "code":
            if items != before:
                changed.append("its code (chain.py)")
            continue
        for name in sorted(set(items) | set(before)):
            if items.get(name) != before.get(name):
                changed.append(f"{kind} {name}")
    if not changed:
        return "changed: how the step is fingerprinted (chain.py)"
    return "changed: " + ", ".join(changed[:6]) + (" ..." if len(changed) > 6 else "")


class Context:
    def __init__(self, args):
        self.jobs = args.jobs
        self.data = {n: os.path.join(iceCases.SHARED, "data", f) for n, f in DATA.items()}
        for spec in args.data or []:
            name, _, path = spec.partition("=")
            if name not in DATA or not path:
                raise SystemExit(f"chain: -data {spec}: needs NAME=FILE, NAME one of {', '.join(DATA)}")
            if not os.path.isfile(path):
                raise SystemExit(f"chain: -data {spec}: no file {path}")
            self.data[name] = os.path.abspath(path)


def status(ctx):
    for step in STEPS:
        print(f"{step.name:18s} {verdict(step, ctx)}")
    return 0


def record(step, ctx, made, adopted=None):
    parts, digest = fingerprint(step, ctx)
    state = {"step": step.name, "madeFrom": digest, "parts": parts,
             "outputs": {o: _digest(os.path.join(ROOT, o)) for o in outputs(step)},
             "data": {n: rel(ctx.data[n]) for n in step.data}, "git_revision": iceCases.git_revision(),
             "result": made}
    if adopted:
        state["adopted"] = adopted
    os.makedirs(STATE, exist_ok=True)
    iceCases.write_atomically(os.path.join(STATE, step.name + ".json"), json.dumps(state, indent=1) + "\n")


def run(ctx, only):
    for step in STEPS:
        if only and step.name not in only:
            continue
        why = verdict(step, ctx)
        if why.startswith("up to date"):
            print(f"chain: {step.name}: {why}")
            continue
        print(f"chain: {step.name}: making it ({why})", flush=True)
        os.makedirs(GENERATED, exist_ok=True)
        record(step, ctx, step.make(ctx))
    return 0


def adopt(ctx, name, why):
    step = next((s for s in STEPS if s.name == name), None)
    if step is None or not why:
        raise SystemExit(f"chain: adopt {name}: needs a step ({', '.join(s.name for s in STEPS)}) and -why TEXT")
    missing = [o for o in outputs(step) if not os.path.isfile(os.path.join(ROOT, o))]
    if missing:
        raise SystemExit(f"chain: adopt {name}: no output to adopt: {', '.join(missing)}")
    record(step, ctx, {}, adopted=why)
    return 0


def main(argv):
    parser = argparse.ArgumentParser(prog="chain.py", description=__doc__.split("\n\n")[0])
    parser.add_argument("command", choices=("status", "run", "adopt"))
    parser.add_argument("adopted", nargs="?", help="adopt: the step")
    parser.add_argument("-data", action="append", metavar="NAME=FILE")
    parser.add_argument("-jobs", type=iceCases.whole_number(1, 64), default=2)
    parser.add_argument("-only", type=iceCases.comma_list(str), default=[])
    parser.add_argument("-why", default="")
    parser.add_argument("-root", help="write the dictionaries, the state and the runs under this folder (tests)")
    args = parser.parse_args(argv)
    if args.root:
        use_root(args.root)
    names = [s.name for s in STEPS]
    for name in args.only:
        if name not in names:
            parser.error(f"-only {name}: no such step ({', '.join(names)})")
    ctx = Context(args)
    if args.command == "adopt":
        return adopt(ctx, args.adopted, args.why)
    return status(ctx) if args.command == "status" else run(ctx, args.only)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
