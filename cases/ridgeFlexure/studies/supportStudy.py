#!/usr/bin/python3
"""Support study (issue 18, end conditions): the failure force of the same
specimens under each end support (clamped, pinned, simple, floating), with
beam theory beside the consolidated layer alone.

Subjects (one rank each, --jobs at a time, each run in
runs/supportStudy/<subject>_<support>/; a finished run made from the same inputs is skipped):

  beam    ../levelIceBeam at 1,200 particles (its parametric studies'
          resolution, the cheapest the case documents; it still breaks as a
          beam: centre crack first), platen 0.1 m/s; floating with the case's
          beam.floatingCoeffs.stiffness.
  layer   the 20 cm consolidated layer alone: this ridge case with
          keel.settledRubble none (ridgeDEM places the layer alone in the
          water), at the quick resolution of studies/ridgeMatrix.py.
  layerDefault  the same layer at the default resolution (50 mm spheres, the
          calibrated ones, 0.05 m/s; 10-20 min a run): clamped, pinned and
          simple only (floating cannot break it, see below).
  run08   ridge run 8 of ../shared/data/ridgeMatrix.csv (0.5 m keel, 4h
          bonds, 20 cm CL), quick resolution.
  run15   ridge run 15 (1.0 m keel, ultimate bonds, no CL), quick resolution.

Beam theory for the layer (scenes.md section 2's size-effect strength of a
0.20 m beam, sigma = test.referenceFlexuralStrength 902 kPa): a simply
supported (or pinned) span L carries F = 2 sigma B D^2 / (3 L), a clamped one
twice that; L is the span between the supports (the pads' inner faces, 3.05 -
2 x ends.fixedLength = 2.85 m), and the line for L = 3.05 m (scenes.md's) is
given too. A floating layer is held by nothing but its buoyancy: once its
freeboard is under, the platen meets no more resistance than its own
submerged weight, so floating has no flexural failure to compare.

The default resolution of the ridge case takes 3-26 min a run with a keel
(README): the ridge runs use the quick one (tens of seconds); only the layer
alone is run at the default resolution too (9-11 min a run), for beam theory.

Writes runs/supportStudy/supportStudy.{csv,md,png}; --publish (the README's table too) copies them into
results/ (refuses unless every run of the study is finished).

Usage: studies/supportStudy.py [--jobs N] [--subjects beam,layer,run08,run15]
                               [--supports clamped,pinned,simple,floating] [--publish]
"""
import argparse
import concurrent.futures
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.dirname(HERE)
TOP = os.path.dirname(os.path.dirname(CASE))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
sys.path.insert(0, HERE)
import iceCases  # noqa: E402
import ridgeMatrix  # noqa: E402

SUPPORTS = ["clamped", "pinned", "simple", "floating"]
SUBJECTS = ["beam", "layer", "layerDefault", "run08", "run15"]
# Floating cannot break the layer (its buoyancy reserve is its freeboard); at
# the default resolution it would run 40 min to maxTravel to show that again.
SKIPPED = {("layerDefault", "floating")}
BEAM_CASE = os.path.join(TOP, "cases", "levelIceBeam")
BEAM_PARTICLES = 1200
LAYER_THICKNESS = 0.20
OUT = os.path.join(CASE, "runs", "supportStudy")


def run_folder(subject, support):
    return os.path.join(OUT, f"{subject}_{support}")


def matrix_run(number):
    return next(r for r in ridgeMatrix.matrix() if r["run"] == number)


def prepare(subject, support, target):
    if subject == "beam":
        iceCases.copy_case(BEAM_CASE, target)
        props = os.path.join(target, "constant", "beamProperties")
        iceCases.set_entry(props, "beam.endSupport", support)
        return target
    if subject in ("layer", "layerDefault"):
        # Run 12's layer (20 cm) without its keel.
        run = dict(matrix_run(12))
        ridgeMatrix.prepare(run, "quick" if subject == "layer" else "default", target)
        props = os.path.join(target, "constant", "ridgeProperties")
        iceCases.set_entry(props, "keel.settledRubble", "none")
        iceCases.set_entry(props, "consolidatedLayer.thickness", LAYER_THICKNESS)
    else:
        ridgeMatrix.prepare(matrix_run(int(subject[3:])), "quick", target)
    iceCases.set_entry(os.path.join(target, "constant", "ridgeProperties"), "ends.endSupport", support)
    if support == "floating" or (support == "simple" and subject.startswith("run")):
        # Nothing to break it (floating: the platen pushes the ridge under), or
        # a ridge on rollers that first moves down as one body before it sits
        # on them (run 8: support reaction 0 for 8 mm): the run goes on to
        # maxTravel instead of stopping after the first contact's spike.
        iceCases.set_entry(os.path.join(target, "system", "controlDict"), "stopAfterHalfLoad", "false")
    return target


def upstream_files(subject):
    """The keel a ridge subject reads (the layers and the beam read none)."""
    if subject.startswith("run"):
        return ridgeMatrix.upstream_files(matrix_run(int(subject[3:])), "quick")
    return []


def execute(subject, support):
    target = iceCases.prepared_run(run_folder(subject, support), lambda folder: prepare(subject, support, folder),
                                   settings=[BEAM_PARTICLES] if subject == "beam" else [],
                                   upstream=upstream_files(subject))
    if iceCases.finished(target):
        return target, None
    if subject == "beam":
        wall = iceCases.run_app(os.path.join(TOP, "build", "demModels", "iceBeamDEM"), target, 1,
                                ["-particles", str(BEAM_PARTICLES)], "log.iceBeamDEM")
    else:
        wall = iceCases.run_app(os.path.join(TOP, "build", "demModels", "ridgeDEM"), target, 1,
                                ["-stage", "all"], "log.ridgeDEM")
    return target, wall


def beam_theory(subject, support, s):
    """F of a layer of strength sigma as a beam on these supports (N), and the
    same for the span scenes.md uses (3.05 m)."""
    if not subject.startswith("layer") or support == "floating":
        return None, None
    props = os.path.join(run_folder(subject, support), "constant", "ridgeProperties")
    sigma = float(iceCases.get_entry(props, "test.referenceFlexuralStrength").split()[0])
    length = float(iceCases.get_entry(props, "box.length").split()[0])
    width = float(iceCases.get_entry(props, "box.width").split()[0])
    pad = float(iceCases.get_entry(props, "ends.fixedLength").split()[0])
    factor = 2.0 if support == "clamped" else 1.0
    simple = lambda span: 2.0 * sigma * width * LAYER_THICKNESS ** 2 / (3.0 * span)
    return factor * simple(length - 2.0 * pad), factor * simple(length)


def smoothed_peak(curve, half=0.001):
    """The highest force averaged over +-half of travel (the ridge samples the
    platen force at single steps, and at the quick settings it chatters)."""
    t, f = curve["travel"], curve["force"]
    best, lo, hi, total = 0.0, 0, 0, 0.0
    for k in range(len(t)):
        while hi < len(t) and t[hi] <= t[k] + half:
            total += f[hi]
            hi += 1
        while t[lo] < t[k] - half:
            total -= f[lo]
            lo += 1
        best = max(best, total / (hi - lo))
    return best


def end_force(curve, window=0.002):
    """Mean force over the last `window` m of travel."""
    last = curve["travel"][-1]
    values = [f for t, f in zip(curve["travel"], curve["force"]) if t >= last - window]
    return sum(values) / len(values)


def row(subject, support):
    target = run_folder(subject, support)
    s = iceCases.summary(target)
    theory, theory305 = beam_theory(subject, support, s)
    curve = iceCases.curve(target)
    travel = curve["travel"]
    peak = s["peak_force_N"]
    broke = s.get("broken_bonds", s.get("crack_pattern", {}).get("broken_bonds", 0))
    r = {
        "subject": subject,
        "support": support,
        "failure_force_kN": round(peak * 1e-3, 3),
        "smoothed_peak_kN": round(smoothed_peak(curve) * 1e-3, 3),
        "beam_theory_kN": round(theory * 1e-3, 3) if theory else "",
        "beam_theory_L3.05_kN": round(theory305 * 1e-3, 3) if theory305 else "",
        "ratio_to_theory": round(peak / theory, 3) if theory else "",
        "smoothed_ratio_to_theory": round(smoothed_peak(curve) / theory, 3) if theory else "",
        "travel_at_peak_mm": round(1e3 * s["travel_at_peak_m"], 1),
        "max_travel_mm": round(1e3 * max(travel), 1),
        "force_at_end_kN": round(end_force(curve) * 1e-3, 3),
        "support_reaction_at_peak_kN": round(s["support_reaction_at_peak_N"] * 1e-3, 3),
        "buoyancy_share_at_peak_kN": round(s["buoyancy_share_at_peak_N"] * 1e-3, 3) if "buoyancy_share_at_peak_N" in s else "",
        "broken_bonds": broke,
        "particles": s["particles"],
        "wall_s": round(s["wall_s"], 1),
    }
    if subject == "beam":
        r["first_peak_kN"] = round(s["first_peak_force_N"] * 1e-3, 3)
    else:
        r["first_peak_kN"] = ""
    return r


COLUMNS = ["subject", "support", "failure_force_kN", "smoothed_peak_kN", "first_peak_kN", "beam_theory_kN", "beam_theory_L3.05_kN",
           "ratio_to_theory", "smoothed_ratio_to_theory", "travel_at_peak_mm", "max_travel_mm", "force_at_end_kN", "support_reaction_at_peak_kN",
           "buoyancy_share_at_peak_kN", "broken_bonds", "particles", "wall_s"]

TITLES = {
    "beam": "level-ice beam, 1,200 particles (side-loaded, no water)",
    "layer": "20 cm consolidated layer alone, quick (in water)",
    "layerDefault": "the same layer, default resolution",
    "run08": "ridge run 8: 0.5 m keel, 4h, 20 cm CL, quick",
    "run15": "ridge run 15: 1.0 m keel, ultimate, no CL, quick",
}


def write(rows, folder):
    os.makedirs(folder, exist_ok=True)
    base = os.path.join(folder, "supportStudy")
    lines = [",".join(COLUMNS)] + [",".join(str(r[c]) for c in COLUMNS) for r in rows]
    iceCases.write_atomically(base + ".csv", "\n".join(lines) + "\n")
    md = ["# Support study: failure force per end support", "",
          "`cases/ridgeFlexure/studies/supportStudy.py` (see its docstring and ../README.md, \"End supports\").",
          "Beam theory for the layer alone: F = 2 sigma B D^2 / (3 L) simple and pinned, twice that clamped,",
          "sigma 902 kPa, B 0.94 m, D 0.20 m, L 2.85 m between the supports (3.05 m: scenes.md's L).", "",
          "| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    md += ["| " + " | ".join(str(r[c]) for c in COLUMNS) + " |" for r in rows]
    iceCases.write_atomically(base + ".md", "\n".join(md) + "\n")
    plot(rows, base + ".png")


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    subjects = [s for s in SUBJECTS if any(r["subject"] == s for r in rows)]
    fig, axes = plt.subplots(1, len(subjects), figsize=(4.2 * len(subjects), 4.6), squeeze=False)
    for ax, subject in zip(axes[0], subjects):
        mine = [r for r in rows if r["subject"] == subject]
        names = [r["support"] for r in mine]
        # A floating layer goes under before it breaks (README); a bare keel's punch is local.
        spike = subject in ("layer", "run08")
        colours = ["lightgrey" if n == "floating" and spike else "tab:blue" for n in names]
        ax.bar(names, [r["failure_force_kN"] for r in mine], color=colours, label="DEM highest load")
        ax.plot(names, [r["smoothed_peak_kN"] for r in mine], "wo", mec="k", label="highest +-1 mm mean")
        if spike and "floating" in names:
            ax.annotate("floating: no failure\n(contact spike)", (names.index("floating"), 0.0),
                        xytext=(0, 25), textcoords="offset points", ha="center", fontsize=7)
        if subject == "beam":
            ax.plot(names, [r["first_peak_kN"] for r in mine], "kv", label="first peak (centre crack)")
        theory = [(n, r["beam_theory_kN"]) for n, r in zip(names, mine) if r["beam_theory_kN"] != ""]
        if theory:
            ax.plot([t[0] for t in theory], [t[1] for t in theory], "r_", markersize=30, mew=3,
                    label="beam theory (L 2.85 m)")
        ax.set_title(TITLES[subject], fontsize=9)
        ax.set_ylabel("failure force [kN]")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--jobs", type=iceCases.whole_number(1, 16), default=1)
    p.add_argument("--subjects", type=iceCases.comma_list(str), default=SUBJECTS)
    p.add_argument("--supports", type=iceCases.comma_list(str), default=SUPPORTS)
    p.add_argument("--publish", action="store_true")
    a = p.parse_args()
    for s in a.subjects:
        if s not in SUBJECTS:
            p.error(f"unknown subject {s}; allowed: {', '.join(SUBJECTS)}")
    for s in a.supports:
        if s not in SUPPORTS:
            p.error(f"unknown support {s}; allowed: {', '.join(SUPPORTS)}")
    pairs = [(s, c) for s in a.subjects for c in a.supports if (s, c) not in SKIPPED]
    if a.publish:
        everything = [(s, c) for s in SUBJECTS for c in SUPPORTS if (s, c) not in SKIPPED]
        missing = [f"{s}_{c}" for s, c in everything if not iceCases.finished(run_folder(s, c))]
        if missing:
            sys.exit("supportStudy.py --publish: unfinished runs: " + ", ".join(missing))
        write([row(s, c) for s, c in everything], os.path.join(CASE, "results"))
        table = open(os.path.join(CASE, "results", "supportStudy.md")).read()
        table = table[table.index("| subject"):]
        iceCases.write_readme_table(os.path.join(CASE, "README.md"), "supportStudy table",
                                    "studies/supportStudy.py --publish", "results/supportStudy.md", table, dated=True)
        print("published results/supportStudy.{csv,md,png} and the README's table")
        return
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        for target, wall in pool.map(lambda sc: execute(*sc), pairs):
            print(f"{os.path.relpath(target, CASE)}: " + ("done before" if wall is None else f"{wall:.0f} s"), flush=True)
    done = [(s, c) for s in SUBJECTS for c in SUPPORTS if iceCases.finished(run_folder(s, c))]
    write([row(s, c) for s, c in done], OUT)
    for s, c in done:
        r = row(s, c)
        print(f"{s:6s} {c:9s} {r['failure_force_kN']:8.3f} kN  theory {r['beam_theory_kN']}")


if __name__ == "__main__":
    main()
