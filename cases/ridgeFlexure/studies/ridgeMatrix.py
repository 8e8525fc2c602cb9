#!/usr/bin/python3
"""The 16-run ridge matrix of ../shared/data/ridgeMatrix.csv (scenes.md section 7).

Each run is a copy of the ridge case (constant/, system/, DEM/) under
runs/<resolution>/ (runs/default-iceStiff/ on the ice-stiff keels, the default
resolution's default), with its keel, consolidated-layer thickness and
freeze-bond set set in its dictionaries. Runs go in parallel (one rank each,
--jobs at a time), a finished run (summary.json written) is skipped, and a
killed one continues from its checkpoint, both only when the folder was made
from the same inputs (madeFrom; a folder of other inputs is made again), so
the command can simply be run again. Each run is then classified by
postProcessing/failureAnalysis.py, and the table (ridgeMatrix_<resolution>.csv and .md; at the
default resolution ridgeMatrix_default_<keels>) and the plot (.png) of every finished run in the
runs folder are written there.

A run the application stopped (e.g. a particle past maxParticleSpeed: a blow-up)
after its load had fallen to 90 % of its peak or less has failed before it
stopped: its row keeps the peak and the breaks up to the stop, and its failure
mode says where and why it stopped. A run stopped earlier, or failed otherwise,
is listed at the end (exit status 1) and left out of the table.

Beside the matrix, the consolidated layer of each thickness in it is loaded
alone, in the same supports and at the same resolution (runs/<resolution>/
layerAlone_CL<cm>: keel.settledRubble none, ridgeDEM floats the layer alone),
so that each row carries its layer's own failure force and the keel's
contribution (failure force minus the layer's; the whole force without a CL).

--publish (./Allrun -publish) runs nothing: it writes the table and plot of
runs/<resolution>/ into the committed results/ folder, and refuses unless all 16
runs and the layers alone there are finished (or stopped after their failure, above): a partial set is never published (nor merged into the
published table, which would mix result sets).

Usage: studies/ridgeMatrix.py [--resolution default|quick|smoke] [--keels softened|iceStiff] [--jobs N]
                              [--runs 1,2,5] [--publish]
  smoke (./Allrun -smoke): the quick settings on small keels of runs/smoke/keels
  (1.6 x 0.4 m), 10 mm of platen travel, results in runs/smoke: checks that the case runs.
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(CASE)), "postProcessing"))
import h5py  # noqa: E402
import iceCases  # noqa: E402
import numpy as np  # noqa: E402


# The quick resolution: coarser keel blocks and layer, a faster platen and a
# shorter settling, so that the whole matrix runs in minutes. Its numbers
# show the trends, not calibrated strengths (see README).
QUICK = {
    "keelSuffix": "quick",
    "consolidatedLayer.particleDiameter": 0.075,
    "test.speed": 0.2,
    "test.settleTime": 0.05,
    "assembly.relaxTime": 0.1,
    "assembly.pressSpeed": 0.05,
}

# The platen speed of this invocation (--speed), over the case's and the quick settings' own; its runs
# go to runs/<resolution>-speed<V>/, apart from the matrix at the resolution's own speed.
SPEED = None

# The keels of this invocation (--keels): iceStiff, the case's at the default resolution since
# 2026-12-07 (keels/keel<depth>iceStiff, compacted at the ice's stiffness to 0.45; the layer rides the
# stiffening keel as a free rigid sheet; its runs go to runs/<resolution>-iceStiff/), or softened, the
# quick and smoke resolutions' and the water-level, support and rate studies' (keels/keel<depth>,
# compacted at the settling's softened contacts to 0.35, the layer held where it was pressed while the
# contacts stiffen; runs/<resolution>/): README "Keels at the ice's stiffness". The layers alone, which
# have no keel, are the resolution's own. The module's default stays softened for those studies.
KEEL_SETS = {
    "softened": {"suffix": "", "entries": {}},
    "iceStiff": {"suffix": "iceStiff", "entries": {"assembly.youngsModulus": 1.95e8, "assembly.layerHold": "balanced"}},
}
KEELS = "softened"

# The smoke resolution: the small keels' box and a short travel (system/controlDict).
SMOKE_BOX = (1.6, 0.4)
SMOKE_CONTROLS = {"maxTravel": 0.01, "minTravel": 0}


def matrix():
    path = os.path.join(iceCases.SHARED, "data", "ridgeMatrix.csv")
    with open(path) as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    return [{"run": int(r["run"]), "keel": r["keel_m"], "set": r["bond_set"], "cl_cm": float(r["CL_cm"])}
            for r in rows]


def keel_case(run, resolution):
    name = "keel" + run["keel"] + (QUICK["keelSuffix"] if resolution != "default" else "") + KEEL_SETS[KEELS]["suffix"]
    return os.path.join(CASE, "runs", "smoke", "keels", name) if resolution == "smoke" else os.path.join(CASE, "keels", name)


def layers_alone(runs):
    """The layer-alone runs the given matrix runs are compared with: one per CL thickness above 0.
    A layer alone has no keel and no freeze-bonds: its set changes nothing, but its folder is reused
    only when made from the same inputs, so it is always the matrix's first row's set, whichever runs
    are asked for (it was the first asked run's: `-runs 16` made the shared layer again)."""
    thicknesses = sorted({r["cl_cm"] for r in runs if r["cl_cm"] > 0})
    layer_set = matrix()[0]["set"]
    return [{"run": 0, "keel": "none", "set": layer_set, "cl_cm": cm, "alone": True} for cm in thicknesses]


def keels_suffix():
    """What the keels of this invocation add to a runs folder's name: nothing for the softened ones."""
    return "" if KEELS == "softened" else "-" + KEELS


def refuse_keels_at(resolution, parser):
    """Only the default resolution has keels other than the softened ones."""
    if KEELS != "softened" and resolution != "default":
        parser.error("argument --keels: %s keels are built at the default resolution only" % KEELS)


def runs_folder(resolution, alone=False):
    keels = "" if alone else keels_suffix()
    return os.path.join(CASE, "runs", resolution + ("-speed%g" % SPEED if SPEED else "") + keels)


def default_keels(resolution):
    """The keels a matrix of this resolution runs on when --keels is not given: the ice-stiff ones
    at the default resolution, the softened ones at the quick and smoke resolutions (their thin keels
    jam at the ice's stiffness)."""
    return "iceStiff" if resolution == "default" else "softened"


def label(resolution):
    """The matrix's name in its table's file names and README section: the resolution, and at the
    default resolution (the one with two kinds of keel) the keels."""
    return resolution + ("_" + KEELS if resolution == "default" else "")


def run_dir(run, resolution):
    if run.get("alone"):
        return os.path.join(runs_folder(resolution, alone=True), "layerAlone_CL%d" % run["cl_cm"])
    return os.path.join(runs_folder(resolution),
                        "run%02d_keel%s_%s_CL%d" % (run["run"], run["keel"], run["set"], run["cl_cm"]))


def upstream_files(run, resolution):
    """The saved stages a run reads by name: its keel (a layer alone has none)."""
    return [] if run.get("alone") else [iceCases.keel_file(keel_case(run, resolution))]


def prepare(run, resolution, target):
    """The run's case folder `target`: the ridge case with the run's keel, layer and bond set."""
    iceCases.copy_case(CASE, target)
    props = os.path.join(target, "constant", "ridgeProperties")
    if run.get("alone"):
        iceCases.set_entry(props, "keel.settledRubble", "none")
    else:
        keel = iceCases.keel_file(keel_case(run, resolution))
        iceCases.set_entry(props, "keel.settledRubble", '"%s"' % os.path.relpath(keel, target))
    iceCases.set_entry(props, "consolidatedLayer.thickness", run["cl_cm"] / 100.0)
    for entry, value in ({} if run.get("alone") else KEEL_SETS[KEELS]["entries"]).items():
        try:
            iceCases.set_entry(props, entry, value)
        except KeyError:
            iceCases.add_entry(props, entry, value)
    iceCases.set_entry(os.path.join(target, "constant", "freezeBondProperties"), "fixedSetCoeffs.set", run["set"])
    if resolution != "default":
        for entry, value in QUICK.items():
            if "." in entry:
                iceCases.set_entry(props, entry, value)
    if SPEED:
        iceCases.set_entry(props, "test.speed", SPEED)
    if resolution == "smoke":
        iceCases.set_entry(props, "box.length", SMOKE_BOX[0])
        iceCases.set_entry(props, "box.width", SMOKE_BOX[1])
        for entry, value in SMOKE_CONTROLS.items():
            iceCases.set_entry(os.path.join(target, "system", "controlDict"), entry, value)
    return target


def prepared(run, resolution):
    """The run's folder (run_dir), reused, finished or to resume, only when it was made from the same
    inputs: the case's dictionaries with what they include, the run's entries and its keel
    (iceCases.prepared_run, the madeFrom file); made again from anything else."""
    return iceCases.prepared_run(run_dir(run, resolution), lambda folder: prepare(run, resolution, folder),
                                 upstream=upstream_files(run, resolution))


def execute(run, resolution):
    """Runs (or resumes) one run and its failure analysis; returns its wall time or None if it was done."""
    target = prepared(run, resolution)
    if analysed(run, resolution):
        return None
    start = time.time()
    if not iceCases.finished(target) and not stopped_after_failure(target):
        resume = os.path.exists(os.path.join(target, "DEM", "checkpoint"))
        try:
            iceCases.run_app("ridgeDEM", target, 1, ["-stage", "all"] + (["-resume"] if resume else []),
                             log_name="log.ridgeDEM")
        except RuntimeError as error:
            if run.get("alone") or not stopped_after_failure(target):
                raise
            print("%s: %s; its curve up to the stop is kept (the load had fallen from its peak)"
                  % (os.path.basename(target), iceCases.fatal_message(error)), flush=True)
    if run.get("alone"):
        return time.time() - start
    analyse_failure(target)
    return time.time() - start


def analyse_failure(target):
    """postProcessing/failureAnalysis.py on a run, up to counted_until for one stopped after its failure."""
    until = counted_until(target)
    subprocess.run([sys.executable, os.path.join(iceCases.TOP, "postProcessing", "failureAnalysis.py"), target]
                   + ([] if until is None else ["--until", repr(until)]),
                   check=True, stdout=open(os.path.join(target, "log.failureAnalysis"), "w"),
                   stderr=subprocess.STDOUT)


def counted_until(target):
    """The time of the last force sample before the stop of a run stopped after its failure (None
    for any other run): the sample it stopped in holds the blow-up, whose breaks are not the ridge's
    (default run 7: 615 of its 1,012 breaks in its last 4 ms)."""
    if not stopped_after_failure(target):
        return None
    return iceCases.curve(target)["time"][-2]


def result_row(run, resolution):
    target = run_dir(run, resolution)
    stop = None if iceCases.finished(target) else stopped_after_failure(target)
    s = stopped_row(target) if stop else iceCases.summary(target)
    fa = json.load(open(os.path.join(target, "postProcessing", "failureAnalysis", "summary.json")))
    failure = dict(fa.get("ridge_failure", {"mode": "n/a", "text": []}))
    if stop:
        # The peak stands (the load had fallen from it); what came after the stop is missing.
        # (no commas: the CSV quotes only the evidence)
        failure["mode"] = ("%s; stopped at %.1f mm (after the peak at %.1f mm; breaks counted to %.1f mm, "
                           "the last sample's left out): %s" % (
            failure["mode"], s["stopped_at_mm"], s["travel_at_peak_mm"], s["breaks_counted_to_mm"],
            stop.split(": the run")[0])).replace(",", ";")
    force = s["peak_force_N"]
    depth = s["depth_m"]
    evidence = failure.get("text", [])
    return {
        "run": run["run"], "keel_m": run["keel"], "bond_set": run["set"], "CL_cm": int(run["cl_cm"]),
        "depth_m": round(depth, 4),
        "failure_force_kN": round(force * 1e-3, 3),
        "buoyancy_share_at_peak_kN": round(s["buoyancy_share_at_peak_N"] * 1e-3, 3),
        "flexural_strength_kPa": round(s["flexural_strength_Pa"] * 1e-3, 2),
        # sigma_f1 is the case's test.referenceFlexuralStrength; null for a force that never rose
        "equivalent_thickness_m": round(s["equivalent_thickness_m"] or 0.0, 4),
        "failure_mode": failure["mode"],
        # sigma_f and D_eq are simple-beam formulas: which supports made the force
        "end_support": s.get("end_support", {}).get("type", "clamped"),
        "freeze_broken_in_tension_share": round(s["freeze_bonds_broken_in_tension_share"], 3),
        "broken_ice": s["broken_by_family"]["ice"], "broken_freeze": s["broken_by_family"]["freeze"],
        "layer_keel_broken": s["layer_keel_bonds_broken"],
        "particles": s["particles"], "wall_s": round(s["wall_s"], 1),
        "evidence": " | ".join(evidence if isinstance(evidence, list) else [str(evidence)]),
    }


# How ridgeDEM's summary begins the reason of a run it stopped itself (PlatenLoading::run); a killed
# run's summary keeps the reason written when loading began ("in the making: ...").
STOPPED_BY_ERROR = "stopped by an error: "


def stopped_after_failure(target, drop=0.9):
    """The reason a ridge run stopped early (e.g. a particle faster than maxParticleSpeed) when it
    stopped after its failure: its force curve had fallen to `drop` of its peak or below, so the
    peak and the breaks before the stop stand. None for a finished run, one stopped earlier, and one
    killed (its summary still says it is in the making: it is resumed, not published)."""
    path = os.path.join(target, "postProcessing", "summary.json")
    curve = os.path.join(target, "postProcessing", "platenForce.csv")
    if not (os.path.exists(path) and os.path.exists(curve)):
        return None
    s = json.load(open(path))
    if s.get("complete", True) or not s.get("reason", "").startswith(STOPPED_BY_ERROR):
        return None
    c = iceCases.curve(target)
    if not c["force"] or c["force"][-1] > drop * max(c["force"]):
        return None
    return s["reason"]


def analysed(run, resolution):
    """Finished (or a ridge stopped after its failure, stopped_after_failure), and (a ridge)
    classified by its failure analysis (failure_analysed)."""
    target = run_dir(run, resolution)
    if run.get("alone"):
        return iceCases.finished(target)
    return failure_analysed(target)


def failure_analysed(target):
    """A ridge finished or stopped after its failure, with a failure analysis made after its breakage
    record (an analysis of a run killed and then resumed to its end is of the record up to the kill:
    made again)."""
    analysis = os.path.join(target, "postProcessing", "failureAnalysis", "summary.json")
    record = os.path.join(target, "postProcessing", "breakage.h5")
    return ((iceCases.finished(target) or stopped_after_failure(target)) and os.path.exists(analysis)
            and (not os.path.exists(record) or os.path.getmtime(analysis) >= os.path.getmtime(record)))


def stopped_row(target):
    """A stopped run's figures from its curve up to the stop and its geometry (the application
    wrote no summary figures): the summary's keys that result_row reads."""
    c = iceCases.curve(target)
    g = json.load(open(os.path.join(target, "postProcessing", "geometry.json")))
    peak = max(range(len(c["force"])), key=lambda k: c["force"][k])
    force, depth = c["force"][peak], g["depth"]
    sigma_f1 = float(iceCases.get_entry(os.path.join(target, "constant", "ridgeProperties"),
                                        "test.referenceFlexuralStrength"))
    # The breakage record on disk holds the breaks up to the stop (since 17d0133; before it, the
    # last ParaView frame's, which is why the first published run 7 recorded breaks to 15.1 mm of
    # its 20.0); they are counted as failureAnalysis counts them, up to counted_until.
    with h5py.File(os.path.join(target, "postProcessing", "breakage.h5"), "r") as f:
        family, mode, when = (np.array(f["breakage"][k]) for k in ("family", "mode", "time"))
    until = counted_until(target)
    family, mode, when = (a[when <= until] for a in (family, mode, when))
    freeze = family == 1
    loading = next(line for line in open(os.path.join(target, "log.ridgeDEM")) if line.startswith("Loading: "))
    return {"peak_force_N": force, "depth_m": depth, "buoyancy_share_at_peak_N": c["buoyancyShare"][peak],
            "flexural_strength_Pa": 3 * force * g["length"] / (2 * g["width"] * depth ** 2),
            "equivalent_thickness_m": math.sqrt(3 * force * g["length"] / (2 * sigma_f1 * g["width"])),
            "freeze_bonds_broken_in_tension_share": float(np.mean(mode[freeze] == 1)) if freeze.any() else 0.0,
            "broken_by_family": {"ice": int(np.sum(family == 0)), "freeze": int(np.sum(freeze))},
            "layer_keel_bonds_broken": "", "particles": int(loading.split()[1]), "wall_s": float("nan"),
            "stopped_at_mm": c["travel"][-1] * 1e3, "travel_at_peak_mm": c["travel"][peak] * 1e3,
            "breaks_counted_to_mm": float(np.interp(until, c["time"], c["travel"])) * 1e3}


def with_layer_alone(row, layer_forces):
    """The row with its layer's failure force alone and the keel's contribution beside it
    (blank where that layer alone has not run)."""
    cm = row["CL_cm"]
    alone = 0.0 if cm == 0 else layer_forces.get(cm)
    out = {}
    for key, value in row.items():
        out[key] = value
        if key == "failure_force_kN":
            out["layer_alone_kN"] = "" if alone is None else alone
            out["keel_contribution_kN"] = "" if alone is None else round(value - alone, 3)
    return out


def layer_forces(resolution):
    """Failure force (kN) of every finished layer-alone run of a resolution, by CL thickness (cm)."""
    forces = {}
    for layer in layers_alone(matrix()):
        target = run_dir(layer, resolution)
        if iceCases.finished(target):
            forces[int(layer["cl_cm"])] = round(iceCases.summary(target)["peak_force_N"] * 1e-3, 3)
    return forces


def table_rows(runs, resolution):
    forces = layer_forces(resolution)
    return [with_layer_alone(result_row(r, resolution), forces) for r in runs]


def write_table(rows, resolution, folder):
    os.makedirs(folder, exist_ok=True)
    base = os.path.join(folder, "ridgeMatrix_" + label(resolution))
    columns = list(rows[0].keys())
    lines = [",".join(columns)] + [",".join('"%s"' % r[c] if c == "evidence" else str(r[c]) for c in columns)
                                   for r in rows]
    iceCases.write_atomically(base + ".csv", "\n".join(lines) + "\n")
    short = [c for c in columns if c != "evidence"]
    supports = sorted({str(r.get("end_support", "clamped")) for r in rows})
    md = ["End supports: %s (ends.endSupport; README, \"End supports\"). flexural_strength_kPa = 3FL/(2BD^2) "
          "and equivalent_thickness_m = sqrt(3FL/(2 sigma_f1 B)) are the simply supported beam's formulas "
          "(scenes.md section 7), whatever held the ends." % ", ".join(supports), ""]
    md += ["| " + " | ".join(short) + " |", "|" + "---|" * len(short)]
    md += ["| " + " | ".join(str(r[c]) for c in short) + " |" for r in rows]
    md += ["", "Evidence of the failure mode (postProcessing/failureAnalysis.py, per run):", ""]
    md += ["- run %d: %s" % (r["run"], r["evidence"]) for r in rows]
    iceCases.write_atomically(base + ".md", "\n".join(md) + "\n")
    return base


def publication_record(runs, resolution):
    """Where a published matrix came from: the revision that publishes it, and per run the
    fingerprint of its inputs, its ranks, wall time and when it finished."""
    entries = []
    for run in runs:
        target = run_dir(run, resolution)
        stop = None if iceCases.finished(target) or run.get("alone") else stopped_after_failure(target)
        summary = os.path.join(target, "postProcessing", "summary.json")
        s = json.load(open(summary)) if stop else iceCases.summary(target)
        finished = os.path.getmtime(summary)
        entry = {"run": run["run"] if not run.get("alone") else os.path.basename(target),
                 "inputs_fingerprint": s.get("inputs_fingerprint"),   # none in a stopped run's summary
                 "made_from": open(os.path.join(target, "madeFrom")).read().strip(),
                 "ranks": s.get("ranks", 1), "wall_s": round(s.get("wall_s", 0.0), 1),
                 "finished": time.strftime("%Y-%m-%d %H:%M", time.gmtime(finished))}
        if stop:
            entry["stopped"] = stop
        entries.append(entry)
    return {"resolution": resolution, "keels": KEELS, "revision": iceCases.git_revision(),
            "published": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
            "machine": "%d cores" % (os.cpu_count() or 1), "runs": entries}


def readme_table(rows, record):
    """The README's table of a published matrix (generated by --publish, never typed)."""
    columns = [("run", "run"), ("keel_m", "keel [m]"), ("bond_set", "bond set"), ("CL_cm", "CL [cm]"),
               ("depth_m", "depth [m]"), ("failure_force_kN", "failure force [kN]"),
               ("layer_alone_kN", "layer alone [kN]"), ("keel_contribution_kN", "keel's contribution [kN]"),
               ("buoyancy_share_at_peak_kN", "buoyancy share [kN]"),
               ("flexural_strength_kPa", "sigma_f [kPa]"), ("equivalent_thickness_m", "D_eq [m]"),
               ("failure_mode", "failure mode"), ("broken_ice", "broken ice bonds"),
               ("broken_freeze", "broken freeze-bonds"), ("particles", "particles"), ("wall_s", "wall [s]")]
    finished = sorted(r["finished"] for r in record["runs"])
    lines = ["Published by `./Allrun%s -publish` at revision `%s` on %s from runs finished %s to %s "
             "(%s, wall times per run on 1 rank, runs side by side); sum of run wall times %.0f s. "
             "Generated from `results/ridgeMatrix_%s.csv`."
             % ((" -quick" if record["resolution"] == "quick" else "")
                + (" -keels " + record["keels"]
                   if record.get("keels", "softened") != default_keels(record["resolution"]) else ""),
                record["revision"], record["published"],
                finished[0], finished[-1], record["machine"], sum(r["wall_s"] for r in record["runs"]),
                label(record["resolution"])), "",
             "| " + " | ".join(label for _, label in columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(str(r[key]) for key, _ in columns) + " |" for r in rows]
    return "\n".join(lines)


def plot(rows, base):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    groups = {}
    for r in rows:
        groups.setdefault((r["keel_m"], r["bond_set"]), []).append(r)
    for (keel, bond_set), rs in sorted(groups.items()):
        rs = sorted(rs, key=lambda r: r["CL_cm"])
        style = "-o" if keel == "0.5" else "--s"
        label = "keel %s m, %s" % (keel, bond_set)
        ax1.plot([r["CL_cm"] for r in rs], [r["flexural_strength_kPa"] for r in rs], style, label=label)
        ax2.plot([r["CL_cm"] for r in rs], [r["failure_force_kN"] for r in rs], style, label=label)
    alone = sorted({(r["CL_cm"], r["layer_alone_kN"]) for r in rows if r.get("layer_alone_kN") != ""})
    if alone:
        ax2.plot([cm for cm, _ in alone], [f for _, f in alone], "k:^", label="layer alone, same supports")
    ax1.set_xlabel("consolidated layer thickness [cm]")
    ax1.set_ylabel("flexural strength 3FL/(2BD$^2$) [kPa]")
    ax2.set_xlabel("consolidated layer thickness [cm]")
    ax2.set_ylabel("failure force F [kN]")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    resolution, _, keels = os.path.basename(base)[len("ridgeMatrix_"):].partition("_")
    fig.suptitle("Ridge flexure matrix (%s resolution%s)" % (resolution, ", keels " + keels if keels else ""))
    iceCases.save_figure(fig, base + ".png", dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--resolution", choices=["default", "quick", "smoke"], default="default")
    parser.add_argument("--jobs", type=iceCases.whole_number(1), default=os.cpu_count() or 1)
    parser.add_argument("--runs", type=iceCases.comma_list(iceCases.whole_number(1)), default=[],
                        help="comma-separated run numbers (default: all 16)")
    parser.add_argument("--publish", action="store_true",
                        help="run nothing; write the table of all 16 finished runs into results/")
    parser.add_argument("--speed", type=iceCases.positive_number,
                        help="platen speed in m/s instead of the resolution's own (quick: 0.2; default: the "
                             "case's test.speed); the runs go to runs/<resolution>-speed<V>/")
    parser.add_argument("--keels", choices=sorted(KEEL_SETS),
                        help="iceStiff (keels/keel<depth>iceStiff, the default resolution's default; the runs go "
                             "to runs/<resolution>-iceStiff/) or softened (keels/keel<depth>, the quick and smoke "
                             "resolutions' default; runs/<resolution>/)")
    args = parser.parse_args()
    global SPEED, KEELS
    SPEED = args.speed
    KEELS = args.keels or default_keels(args.resolution)
    refuse_keels_at(args.resolution, parser)
    if args.publish and SPEED:
        parser.error("argument --publish: publishes the matrix at the resolution's own speed (not with --speed)")

    runs = matrix()
    if args.publish:
        if args.resolution == "smoke" or args.runs:
            parser.error("argument --publish: publishes the whole matrix of --resolution default or quick")
        missing = [os.path.basename(run_dir(r, args.resolution)) for r in runs + layers_alone(runs)
                   if not analysed(r, args.resolution)]
        if missing:
            sys.exit("ridgeMatrix: not published: %s not finished in %s (a partial matrix is never "
                     "published; run them first)" % (", ".join(missing), runs_folder(args.resolution)))
        rows = table_rows(runs, args.resolution)
        base = write_table(rows, args.resolution, os.path.join(CASE, "results"))
        plot(rows, base)
        record = publication_record(runs + layers_alone(runs), args.resolution)
        iceCases.write_atomically(base + ".json", json.dumps(record, indent=1) + "\n")
        iceCases.write_readme_section(os.path.join(CASE, "README.md"), "ridgeMatrix_%s table" % label(args.resolution),
                                      readme_table(rows, record))
        print("Published: %s.csv, %s.md, %s.png, %s.json" % (base, base, base, base))
        return
    if args.runs:
        unknown = sorted(set(args.runs) - {r["run"] for r in runs})
        if unknown:
            parser.error("argument --runs: no run %s in ridgeMatrix.csv (runs %d-%d)"
                         % (",".join(map(str, unknown)), min(r["run"] for r in runs), max(r["run"] for r in runs)))
        runs = [r for r in runs if r["run"] in set(args.runs)]
    runs = runs + layers_alone(runs)
    for run in (r for r in runs if not r.get("alone")):
        keel = iceCases.keel_file(keel_case(run, args.resolution))
        if not os.path.exists(keel):
            sys.exit("ridgeMatrix: %s is missing: build the keel first (./Allrun does)" % keel)

    lock = threading.Lock()
    started = time.time()
    done, times = [0], []

    failed = []

    def one(run):
        try:
            wall = execute(run, args.resolution)
        except (RuntimeError, subprocess.CalledProcessError) as error:
            with lock:
                failed.append("%s: %s" % (os.path.basename(run_dir(run, args.resolution)), iceCases.fatal_message(error)))
                print("%s failed: %s" % (os.path.basename(run_dir(run, args.resolution)), failed[-1]), flush=True)
            return
        with lock:
            done[0] += 1
            if wall is not None:
                times.append(wall)
            left = len(runs) - done[0]
            eta = (sum(times) / len(times) * left / args.jobs) if times else 0.0
            print("%s done (%s); %d of %d finished, %s elapsed, about %s left"
                  % (os.path.basename(run_dir(run, args.resolution)), "%.0f s" % wall if wall is not None else "already done", done[0], len(runs),
                     time.strftime("%H:%M:%S", time.gmtime(time.time() - started)),
                     time.strftime("%H:%M:%S", time.gmtime(eta))), flush=True)

    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for future in [pool.submit(one, r) for r in runs]:
            future.result()

    # The table of every finished run of the folder (runs of earlier invocations too).
    rows = table_rows([r for r in matrix() if analysed(r, args.resolution)], args.resolution)
    if rows:
        base = write_table(rows, args.resolution, runs_folder(args.resolution))
        plot(rows, base)
        print("Results: %s.csv, %s.md, %s.png (%s in all)"
              % (base, base, base, time.strftime("%H:%M:%S", time.gmtime(time.time() - started))))
    if failed:
        sys.exit("ridgeMatrix: %d run(s) failed (not in the table):\n  %s" % (len(failed), "\n  ".join(failed)))


if __name__ == "__main__":
    main()
