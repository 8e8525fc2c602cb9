#!/usr/bin/python3
"""Two questions put to the default matrix's finished force curves (postProcessing/platenForce.csv,
one sample every 0.2 mm of platen travel), without running anything:

1. What an earlier stop after the failure would save (issue 17, goal 3: "stopping a run once it
   has failed"). ridgeDEM stops a run once its force has stayed below half its peak for
   travelAfterHalfLoad (system/controlDict: 0.5 and 5 mm; PlatenLoading::run). This replays that
   rule with other fractions of the peak (a sample below `fraction x peak so far` starts the count,
   one at or above it resets it; never before minTravel) and reports per fraction the loading time
   kept (simulated seconds of loading up to the stop over the finished runs': the loop's cost is
   close to proportional), the runs whose stop would come before their highest force, and the
   broken bonds counted up to the stop. Fraction 0.5 must give back every run's own stop (the
   script exits 1 where it does not).

2. Whether a run's failure force is a sustained load or one sample's spike. The failure force is
   the largest sampled force; a block caught under the platen can snap and throw one sample far
   above its neighbours, with the kinetic energy jumping with it (a dynamic event, not the ridge's
   capacity). Per run: the largest force, its neighbouring samples, the kinetic energy there against
   the run's median, and the largest running mean over 3, 5 and 11 samples (0.6, 1.0 and 2.2 mm).
   A peak both of whose neighbours are below SPIKE of it is marked a spike.

The runs: the default matrix's on the keels of --keels (runs/default-iceStiff/, the case's;
softened: runs/default/) and the layers alone (runs/default/layerAlone_CL*), finished ones only;
with --speed V those of ./Allrun -speed V. Writes runs/forceCurves[-speedV]/; --publish into results/ (earlyStop.*, forceSpikes.*) and the README
sections "ridge early stop" and "ridge force spikes".

usage: studies/forceCurves.py [--case DIR] [--keels iceStiff|softened] [--speed V] [--fractions 0.5,0.6,0.7,0.8,0.9] [--publish]
  (DIR: the ridgeFlexure case, this script's by default)"""
import argparse
import csv
import glob
import io
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(CASE)), "postProcessing"))
import iceCases  # noqa: E402
sys.path.insert(0, HERE)
import ridgeMatrix  # noqa: E402
import supportStudy  # noqa: E402

# The stop rule's entries of a run's system/controlDict and PlatenLoadingControl::readControl's
# defaults where the file does not write them (maxTravel it must write).
CONTROL_DEFAULTS = {"minTravel": 0.0, "travelAfterHalfLoad": 0.005, "sampleInterval": 2e-4}
SPIKE = 0.8                # a peak whose both neighbouring samples are below this share of it
WINDOWS = (3, 5, 11)       # samples of the running means


def run_control(run_folder):
    """The run's own maxTravel, minTravel, travelAfterHalfLoad and sampleInterval (m)."""
    path = os.path.join(run_folder, "system", "controlDict")
    control = {}
    for key in ("maxTravel", *CONTROL_DEFAULTS):
        try:
            control[key] = float(iceCases.get_entry(path, key).split()[0])
        except KeyError:
            if key not in CONTROL_DEFAULTS:
                raise
            control[key] = CONTROL_DEFAULTS[key]
    return control


def stop_index(c, control, fraction):
    """The sample a run would stop at (PlatenLoading::run's rule with `fraction` for 0.5, the run's
    own controlDict entries) and True, or its last sample and False where the rule never fires."""
    peak, below_since = 0.0, None
    for i, (travel, force) in enumerate(zip(c["travel"], c["force"])):
        peak = max(peak, force)
        if force >= fraction * peak:
            below_since = None
        elif below_since is None:
            below_since = travel
        if (below_since is not None and travel > below_since + control["travelAfterHalfLoad"]
                and travel >= control["minTravel"]):
            return i, True
    return len(c["force"]) - 1, False


def short_name(name):
    return name.split("_keel")[0]


def early_stop_table(curves, controls, fractions):
    # A run stopped by the rule ends on the sample it fired at; one that ran to maxTravel never fired.
    mismatched = [name for name, c in curves.items() if stop_index(c, controls[name], 0.5)
                  != (len(c["force"]) - 1, c["travel"][-1] < controls[name]["maxTravel"] - 1e-4)]
    if mismatched:
        sys.exit("forceCurves.py: the replayed rule at 0.5 does not give back the runs' own stop: " + ", ".join(mismatched))
    rows = []
    for fraction in fractions:
        kept = total = 0.0
        early, breaks_kept, breaks_all = [], 0, 0
        for name, c in curves.items():
            i, _ = stop_index(c, controls[name], fraction)
            kept += c["time"][i] - c["time"][0]
            total += c["time"][-1] - c["time"][0]
            peak, peak_kept = max(c["force"]), max(c["force"][: i + 1])
            if peak_kept < peak:
                early.append(f"{short_name(name)} {peak_kept / peak - 1:+.1%}")
            breaks_kept += c["brokenBonds"][i]
            breaks_all += c["brokenBonds"][-1]
        rows.append({"fraction_of_peak": fraction, "runs": len(curves), "loading_time_kept": round(kept / total, 3),
                     "runs_stopped_before_their_peak": "; ".join(early) or "none",
                     "broken_bonds_counted": round(breaks_kept / breaks_all, 3)})
    md = ["| stop once the force stays below (of its peak) | runs | loading time kept | runs stopped before their peak "
          "(failure force against the finished run's) | broken bonds counted (of the finished runs') |",
          "|---|---|---|---|---|"]
    md += [f"| {r['fraction_of_peak']:g} | {r['runs']} | {r['loading_time_kept']:.2f} | {r['runs_stopped_before_their_peak']} "
           f"| {r['broken_bonds_counted']:.2f} |" for r in rows]
    return rows, "\n".join(md) + "\n"


def running_mean_peak(curve, window, sample_travel):
    """The largest mean over `window` samples (odd): supportStudy's mean over +- half a window of
    travel, the half-width half a sample past the outermost sample."""
    return supportStudy.smoothed_peak(curve, half=(window // 2 + 0.5) * sample_travel)


def spike_table(curves, controls):
    rows = []
    for name, c in curves.items():
        f = c["force"]
        i = max(range(len(f)), key=f.__getitem__)
        neighbours = [f[j] / f[i] for j in (i - 1, i + 1) if 0 <= j < len(f)]
        kinetic = sorted(c["kineticEnergy"])
        row = {"run": short_name(name), "peak_kN": round(f[i] * 1e-3, 3), "travel_at_peak_mm": round(c["travel"][i] * 1e3, 1),
               "neighbours_of_peak": " / ".join(f"{n:.2f}" for n in neighbours),
               "kinetic_at_peak_over_median": round(c["kineticEnergy"][i] / kinetic[len(kinetic) // 2], 1)}
        for w in WINDOWS:
            row[f"running_mean_{w}_kN"] = round(running_mean_peak(c, w, controls[name]["sampleInterval"]) * 1e-3, 3)
        row["spike"] = "yes" if all(n < SPIKE for n in neighbours) else "no"
        rows.append(row)
    sample_mm = sorted({control["sampleInterval"] * 1e3 for control in controls.values()})
    md = ["| run | largest force [kN] at [mm] | its neighbours (of it) | kinetic energy there / run's median | "
          + " | ".join(f"largest mean of {w} samples ({' or '.join(f'{w * mm:.1f}' for mm in sample_mm)} mm) [kN]"
                       for w in WINDOWS) + " | spike |",
          "|---|---|---|---|" + "---|" * len(WINDOWS) + "---|"]
    md += [f"| {r['run']} | {r['peak_kN']} at {r['travel_at_peak_mm']} | {r['neighbours_of_peak']} | "
           f"{r['kinetic_at_peak_over_median']} | " + " | ".join(str(r[f'running_mean_{w}_kN']) for w in WINDOWS)
           + f" | {'**yes**' if r['spike'] == 'yes' else 'no'} |" for r in rows]
    return rows, "\n".join(md) + "\n"


def csv_text(rows):
    text = io.StringIO()
    writer = csv.DictWriter(text, list(rows[0]), quoting=csv.QUOTE_NONNUMERIC, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    return text.getvalue()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", default=CASE, help="the ridgeFlexure case (default: this script's)")
    parser.add_argument("--keels", choices=sorted(ridgeMatrix.KEEL_SETS), default="iceStiff",
                        help="the default matrix's runs on these keels (runs/default-iceStiff or runs/default)")
    parser.add_argument("--speed", type=iceCases.positive_number, default=None,
                        help="the runs of ./Allrun -speed V (runs/default-speedV-...; not published)")
    parser.add_argument("--fractions", type=iceCases.comma_list(float), default=[0.5, 0.6, 0.7, 0.8, 0.9])
    parser.add_argument("--publish", action="store_true", help="write results/ and the README sections")
    args = parser.parse_args()
    if args.speed and args.publish:
        parser.error("--speed: without --publish (the published tables are of the case's own speed)")
    ridgeMatrix.KEELS = args.keels
    ridgeMatrix.SPEED = args.speed
    ridgeMatrix.CASE = case = os.path.abspath(args.case)
    runs = ridgeMatrix.runs_folder("default")
    alone = ridgeMatrix.runs_folder("default", alone=True)
    folders = sorted(f for f in glob.glob(os.path.join(runs, "run*")) + glob.glob(os.path.join(alone, "layerAlone_CL*"))
                     if iceCases.finished(f))
    if not folders:
        sys.exit(f"forceCurves.py: no finished run in {runs} or {alone}")
    curves = {os.path.basename(f): iceCases.curve(f) for f in folders}
    controls = {os.path.basename(f): run_control(f) for f in folders}
    outputs = {"earlyStop": early_stop_table(curves, controls, args.fractions),
               "forceSpikes": spike_table(curves, controls)}
    folder = os.path.join(case, "results") if args.publish else os.path.join(
        case, "runs", "forceCurves" + ("-speed%g" % args.speed if args.speed else ""))
    os.makedirs(folder, exist_ok=True)
    for stem, (rows, md) in outputs.items():
        iceCases.write_atomically(os.path.join(folder, stem + ".csv"), csv_text(rows))
        iceCases.write_atomically(os.path.join(folder, stem + ".md"), md)
        if args.publish:
            section = {"earlyStop": "ridge early stop", "forceSpikes": "ridge force spikes"}[stem]
            iceCases.write_readme_table(os.path.join(case, "README.md"), section, "studies/forceCurves.py --publish",
                                        f"results/{stem}.csv", md)
        print(md)


if __name__ == "__main__":
    main()
