#!/usr/bin/python3
"""End supports (clamped, pinned, simple, floating) on small bonded beams
against beam theory, and the refusal of bad `endSupport` entries.

usage: endSupports.py bending  BENDING_CASE WORKDIR threePointBendingDEM
       endSupports.py floating BEAM_CASE    WORKDIR iceBeamDEM
       endSupports.py pinnedResume BEAM_CASE WORKDIR iceBeamDEM
       endSupports.py refusals TOP          WORKDIR BUILD_DEMMODELS_DIR

bending: a small three-point bending beam (1.2 m long, 1.0 m between the
  support axes, 0.3 x 0.1 m, 0.04 m particles, 638 particles) under simple,
  clamped and pinned ends (clamped and pinned hold the 0.1 m beyond each
  support axis), three packings each (seeds 1-3: one packing scatters by
  5-10 %, the mean is what beam theory describes). Beam theory for a central
  load F on a span L: the stress sigma is reached at F = c sigma B D^2 / L,
  c = 2/3 simply supported or pinned, 4/3 clamped; the elastic slope against
  mid-span deflection is 48 EI/L^3 simply supported or pinned, 192 EI/L^3
  clamped (Euler-Bernoulli). sigma is the calibrated ice's flexural strength:
  ../threePointBending's breakN puts it at the size-effect targets, 902-987
  kPa (README, "Scatter over packings"); the test uses their middle, 945 kPa.
  Checks, on the means over the packings: (a) simple and pinned highest loads
  within 10 % of beam theory; (b) clamped: the load of the first crack (first
  load drop) twice simple's within 10 %, and the highest load 1.0-1.3 times
  beam theory: measured +16 %, because after the first cracks the clamped
  pads hold the ends' axial movement and the cracked beam arches between
  them (the issue's "rigid end walls add arching"); (c) elastic slopes
  clamped / simple 4 and pinned / simple 1 within 10 %; (d) weightless, the
  supports' reaction equals the platen force over the rise (mean over 20-80 %
  of the highest load) within 10 % (measured 0.95-1.08 for seed 1: the rise
  lasts 0.05 s, and the beam still rings from the platen's ramp).
floating: the level-ice beam at 400 particles, 0.05 m/s, with its ends on
  springs of 2e8 N/m (floatingCoeffs), against simple and clamped: (a) its
  failure force and elastic slope lie between simple's and clamped's (10 %
  margin), as an end rotationally restrained by springs does in beam theory;
  (b) the springs carry the platen force (reaction within 5 % over the rise:
  nothing else holds the weightless beam); (c) much softer springs (2e6 N/m)
  give a softer beam.
pinnedResume: a pinned beam stopped part-way and resumed from its checkpoint
  gives the uninterrupted run's force curve to the last bit (the hinges'
  state is the pads' positions and spins, in LIGGGHTS' restart).
refusals: bad entries stop the applications with a message that names the
  file, the entry and the allowed values: an unknown name, floating without
  floatingCoeffs, floating in the (dry) three-point bending scene, simple in
  the keel-bond test, clamped/pinned ends with no room for pads.
"""
import csv
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "postProcessing"))
import iceCases  # noqa: E402

SIGMA = 945e3           # Pa: the middle of the calibration's targets (902-987 kPa)
SMALL_BENDING = {"beam.length": 1.2, "beam.width": 0.3, "supports.span": 1.0, "platen.speed": 0.1,
                 "platen.rampTime": 0.03, "packing.particleDiameter": 0.04}
THICKNESS = 0.1

failures = []


def check(name, value, expected, tolerance):
    err = value / expected - 1.0
    good = abs(err) <= tolerance
    if not good:
        failures.append(name)
    print(f"{'ok  ' if good else 'FAIL'} {name}: {value:.4g} against {expected:.4g} ({err:+.1%}, tolerance {tolerance:.0%})")


def between(name, value, low, high, margin):
    good = low * (1.0 - margin) <= value <= high * (1.0 + margin)
    if not good:
        failures.append(name)
    print(f"{'ok  ' if good else 'FAIL'} {name}: {value:.4g} in [{low:.4g}, {high:.4g}] (margin {margin:.0%})")


def finish():
    print(f"{'all passed' if not failures else 'failed: ' + ', '.join(failures)}")
    sys.exit(1 if failures else 0)


def rise_balance(case, force_column="force"):
    """Mean support reaction / mean platen force over the rise (20-80 % of the highest load, before it)."""
    rows = list(csv.DictReader(open(os.path.join(case, "postProcessing", "platenForce.csv"))))
    force = [float(r[force_column]) for r in rows]
    peak_at = max(range(len(force)), key=force.__getitem__)
    peak = force[peak_at]
    rise = [r for r, f in zip(rows[:peak_at], force[:peak_at]) if 0.2 * peak <= f <= 0.8 * peak]
    return (sum(float(r["supportReaction"]) for r in rise) / sum(float(r[force_column]) for r in rise), len(rise))


def bending(case, work, app):
    supports = ("simple", "clamped", "pinned")
    seeds = (1, 2, 3)
    runs = {}
    for seed in seeds:
        for support in supports:
            target = iceCases.copy_case(case, os.path.join(work, f"{support}_seed{seed}"))
            props = os.path.join(target, "constant", "bendingProperties")
            for entry, value in dict(SMALL_BENDING, **{"supports.endSupport": support, "packing.seed": seed}).items():
                iceCases.set_entry(props, entry, value)
            control = os.path.join(target, "system", "controlDict")
            iceCases.set_entry(control, "writeInterval", 0.05)
            iceCases.set_entry(control, "checkpointInterval", 1.0)
            wall = iceCases.run_app(app, target, 1, ["-thickness", THICKNESS], "log.threePointBendingDEM")
            s = runs[support, seed] = iceCases.summary(target)
            print(f"{support}, seed {seed}: {s['particles']} particles, highest load {s['failure_force_N']:.1f} N, "
                  f"first load drop {s['first_peak_force_N']:.1f} N, slope {s['elastic_slope_deflection_N_per_m']:.4g} N/m "
                  f"(R2 {s['elastic_slope_deflection_fit_R2']:.3f}), KE/elastic at peak "
                  f"{s['kinetic_to_elastic_energy_at_peak']:.2g}, {wall:.0f} s")

    def mean(support, key):
        return sum(runs[support, seed][key] for seed in seeds) / len(seeds)

    B, L = SMALL_BENDING["beam.width"], SMALL_BENDING["supports.span"]
    simple_theory = 2.0 * SIGMA * B * THICKNESS ** 2 / (3.0 * L)
    check("simple: highest load vs 2 sigma B D^2 / (3 L)", mean("simple", "failure_force_N"), simple_theory, 0.10)
    check("pinned: highest load vs 2 sigma B D^2 / (3 L)", mean("pinned", "failure_force_N"), simple_theory, 0.10)
    check("clamped / simple load of the first crack vs 2",
          mean("clamped", "first_peak_force_N") / mean("simple", "first_peak_force_N"), 2.0, 0.10)
    between("clamped: highest load / (4 sigma B D^2 / (3 L)) (arching after the first cracks)",
            mean("clamped", "failure_force_N") / (2.0 * simple_theory), 1.0, 1.3, 0.0)
    slope = {k: mean(k, "elastic_slope_deflection_N_per_m") for k in supports}
    check("clamped / simple elastic slope vs 192/48 = 4", slope["clamped"] / slope["simple"], 4.0, 0.10)
    check("pinned / simple elastic slope vs 1", slope["pinned"] / slope["simple"], 1.0, 0.10)
    for support in supports:
        ratio, n = rise_balance(os.path.join(work, f"{support}_seed1"))
        check(f"{support}: support reaction / platen force over the rise ({n} samples)", ratio, 1.0, 0.10)
    finish()


def floating(case, work, app):
    runs = {}
    for name, support, stiffness in (("simple", "simple", None), ("clamped", "clamped", None),
                                     ("floating", "floating", 2e8), ("floatingSoft", "floating", 2e6)):
        target = iceCases.copy_case(case, os.path.join(work, name))
        props = os.path.join(target, "constant", "beamProperties")
        iceCases.set_entry(props, "beam.endSupport", support)
        if stiffness:
            iceCases.set_entry(props, "beam.floatingCoeffs.stiffness", stiffness)
        control = os.path.join(target, "system", "controlDict")
        iceCases.set_entry(control, "writeInterval", 0.1)
        iceCases.set_entry(control, "checkpointInterval", 1.0)
        wall = iceCases.run_app(app, target, 1, ["-particles", 400, "-platenSpeed", 0.05], "log.iceBeamDEM")
        s = runs[name] = iceCases.summary(target)
        print(f"{name}: peak {s['peak_force_N'] / 1e3:.1f} kN, slope {s['elastic_slope_N_per_m']:.4g} N/m, "
              f"reaction at peak {s['support_reaction_at_peak_N'] / 1e3:.1f} kN, {wall:.0f} s")
    peak = {k: v["peak_force_N"] for k, v in runs.items()}
    slope = {k: v["elastic_slope_N_per_m"] for k, v in runs.items()}
    between("floating (2e8 N/m): highest load between simple and clamped", peak["floating"], peak["simple"], peak["clamped"], 0.10)
    between("floating (2e8 N/m): elastic slope between simple and clamped", slope["floating"], slope["simple"], slope["clamped"], 0.10)
    ratio, n = rise_balance(os.path.join(work, "floating"))
    check(f"floating: spring reaction / platen force over the rise ({n} samples)", ratio, 1.0, 0.05)
    good = slope["floatingSoft"] < 0.9 * slope["floating"]
    if not good:
        failures.append("soft springs")
    print(f"{'ok  ' if good else 'FAIL'} softer springs (2e6 N/m) give a softer beam: slope {slope['floatingSoft']:.4g} "
          f"against {slope['floating']:.4g} N/m")
    finish()


def pinned_resume(case, work, app):
    args = ["-particles", "400", "-platenSpeed", "0.2"]
    cases = {}
    for name in ("whole", "stoppedAndResumed"):
        target = cases[name] = iceCases.copy_case(case, os.path.join(work, name))
        iceCases.set_entry(os.path.join(target, "constant", "beamProperties"), "beam.endSupport", "pinned")
    iceCases.run_app(app, cases["whole"], 1, args, "log.iceBeamDEM")
    iceCases.run_app(app, cases["stoppedAndResumed"], 1, args + ["-steps", "9000"], "log.iceBeamDEM.1")
    iceCases.run_app(app, cases["stoppedAndResumed"], 1, args + ["-resume"], "log.iceBeamDEM.2")
    a = open(os.path.join(cases["whole"], "postProcessing", "platenForce.csv")).read()
    b = open(os.path.join(cases["stoppedAndResumed"], "postProcessing", "platenForce.csv")).read()
    sa, sb = iceCases.summary(cases["whole"]), iceCases.summary(cases["stoppedAndResumed"])
    good = a == b and sa["peak_force_N"] == sb["peak_force_N"]
    if not good:
        failures.append("pinned resume")
    print(f"{'ok  ' if good else 'FAIL'} pinned: the resumed run's platenForce.csv is byte-identical to the "
          f"uninterrupted run's ({a.count(chr(10))} lines; peak {sa['peak_force_N']:.6g} / {sb['peak_force_N']:.6g} N)")
    finish()


def refusals(top, work, bin_dir):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")

    def refused(name, app, source, entries, args, expected):
        target = iceCases.copy_case(os.path.join(top, "cases", source), os.path.join(work, name))
        for (file, entry), value in entries.items():
            path = os.path.join(target, file)
            if value is None:   # remove the sub-dictionary
                text = open(path).read()
                start = text.index(entry.split(".")[-1])
                open(path, "w").write(text[:start] + text[text.index("}", start) + 1:])
            else:
                iceCases.set_entry(path, entry, value)
        run = subprocess.run(["mpirun", "-np", "1", os.path.join(bin_dir, app), "-case", target] + args,
                             capture_output=True, text=True, env=env)
        text = run.stdout + run.stderr
        missing = [e for e in expected if e not in text]
        good = run.returncode != 0 and not missing and "Segmentation" not in text
        if not good:
            failures.append(name)
        line = next((l for l in text.splitlines() if "endSupport" in l or "floatingCoeffs" in l), text.strip()[-300:])
        print(f"{'ok  ' if good else 'FAIL'} {name}: exit {run.returncode}" + (f", missing {missing}" if missing else "")
              + f"\n     {line.strip()}")

    beam = ("constant/beamProperties", )
    refused("unknownName", "iceBeamDEM", "levelIceBeam", {(beam[0], "beam.endSupport"): "hinged"}, ["-particles", "100"],
            ["beamProperties", "beam.endSupport", "hinged", "clamped", "pinned", "simple", "floating"])
    refused("floatingWithoutCoeffs", "iceBeamDEM", "levelIceBeam",
            {(beam[0], "beam.endSupport"): "floating", (beam[0], "beam.floatingCoeffs"): None}, ["-particles", "100"],
            ["beamProperties", "floatingCoeffs"])
    refused("negativeStiffness", "iceBeamDEM", "levelIceBeam",
            {(beam[0], "beam.endSupport"): "floating", (beam[0], "beam.floatingCoeffs.stiffness"): -1},
            ["-particles", "100"], ["beamProperties", "beam.floatingCoeffs.stiffness"])
    bending = "constant/bendingProperties"
    refused("floatingInDryBending", "threePointBendingDEM", "threePointBending",
            {(bending, "supports.endSupport"): "floating"}, ["-quick"],
            ["bendingProperties", "supports.endSupport", "floating", "allowed here: simple clamped pinned"])
    refused("noRoomForPads", "threePointBendingDEM", "threePointBending",
            {(bending, "supports.endSupport"): "clamped"}, ["-quick"],
            ["bendingProperties", "supports.endSupport", "particle diameter"])
    ridge = "constant/ridgeProperties"
    refused("simpleInKeelBond", "ridgeDEM", "keelBond", {(ridge, "ends.endSupport"): "simple"}, ["-stage", "load"],
            ["ridgeProperties", "ends.endSupport", "simple", "allowed here: clamped"])
    refused("ridgeUnknownName", "ridgeDEM", "ridgeFlexure", {(ridge, "ends.endSupport"): "free"}, ["-stage", "load"],
            ["ridgeProperties", "ends.endSupport", "free", "clamped", "pinned", "simple", "floating"])
    finish()


if __name__ == "__main__":
    mode, *rest = sys.argv[1:]
    {"bending": bending, "floating": floating, "pinnedResume": pinned_resume, "refusals": refusals}[mode](*rest)
