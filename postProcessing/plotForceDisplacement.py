#!/usr/bin/python3
"""Plot platen force against platen travel and compare with the field test's key figures.

Run with Debian's python (numpy, matplotlib; no display needed):

    /usr/bin/python3 plotForceDisplacement.py \
        --csv <case>/postProcessing/platenForce.csv \
        --field ../shared/data/levelIceBeamField.csv \
        --summary <case>/postProcessing/summary.json \
        --out <case>/postProcessing/forceDisplacement.png

Curve CSVs have a header line with at least the columns `displacement` [m, from contact]
and `force` [N, along the loading direction]; lines starting with '#' are ignored.
`--series label=file.csv` (repeatable) overlays further curves, e.g. a speed-convergence
study. The PNG is written atomically (temporary file, then rename).

Field key figures (data/levelIceBeamField.csv), with the settling-in travel removed:
  - the linear part, field travel 60-90 mm, is drawn from 10 mm to 40 mm with the field slope
    (6.25 MN/m). The field data give no force at its start, so the segment starts on the
    (first) simulated curve at 10 mm, or at zero without a curve, and is cut at the field peak;
  - the field peak, 120 kN, as a horizontal line (its travel is not in the field data);
  - the half load, 70 mm of further travel after the peak, drawn from the simulated peak.
"""

import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

MM = 1e3   # m -> mm
KN = 1e-3  # N -> kN


def fail(message):
    sys.exit("plotForceDisplacement.py: " + message)


def data_lines(handle):
    for line in handle:
        stripped = line.strip()
        if stripped and not stripped.startswith("#"):
            yield line


def read_curve(path):
    """Return (displacement [m], force [N]) of the finite rows of a curve CSV."""
    try:
        with open(path, newline="") as handle:
            rows = list(csv.reader(data_lines(handle)))
    except OSError as error:
        fail("cannot read curve '%s': %s" % (path, error))
    if not rows:
        fail("curve '%s' is empty (no header line)" % path)
    header = [name.strip() for name in rows[0]]
    for column in ("displacement", "force"):
        if column not in header:
            fail("curve '%s' has no column '%s' (columns: %s)"
                 % (path, column, ", ".join(header)))
    i_d = header.index("displacement")
    i_f = header.index("force")
    displacement, force = [], []
    for number, row in enumerate(rows[1:], start=2):
        try:
            d, f = float(row[i_d]), float(row[i_f])
        except (ValueError, IndexError):
            fail("curve '%s', data line %d: cannot read displacement and force" % (path, number))
        if math.isfinite(d) and math.isfinite(f):
            displacement.append(d)
            force.append(f)
    return np.array(displacement), np.array(force)


def read_field(path):
    """Return the field key figures as {quantity: value} (SI units)."""
    try:
        with open(path, newline="") as handle:
            rows = list(csv.DictReader(data_lines(handle)))
    except OSError as error:
        fail("cannot read field data '%s': %s" % (path, error))
    values = {}
    for row in rows:
        try:
            values[row["quantity"].strip()] = float(row["value"])
        except (KeyError, TypeError, ValueError):
            fail("field data '%s': cannot read row %s" % (path, row))
    needed = ("settling_in_travel", "linear_range_start", "linear_range_end",
              "elastic_slope", "peak_load", "post_peak_half_load_travel")
    missing = [name for name in needed if name not in values]
    if missing:
        fail("field data '%s' lacks %s" % (path, ", ".join(missing)))
    return values


def read_summary(path):
    try:
        with open(path) as handle:
            summary = json.load(handle)
    except (OSError, ValueError) as error:
        fail("cannot read summary '%s': %s" % (path, error))
    if not isinstance(summary, dict):
        fail("summary '%s' is not a JSON object" % path)
    return summary


def summary_number(summary, key):
    """The summary's value for key as a finite float, or None when absent or not a number."""
    value = summary.get(key)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return float(value) if math.isfinite(value) else None


def parse_series(specs):
    series = []
    for spec in specs:
        label, sep, path = spec.partition("=")
        if not sep or not label or not path:
            fail("--series needs label=file.csv, got '%s'" % spec)
        series.append((label, path))
    return series


def simulated_peak(summary, curves):
    """(travel [m], force [N]) of the simulated peak: from the summary, else the first curve."""
    travel = summary_number(summary, "travel_at_peak_m")
    force = summary_number(summary, "peak_force_N")
    if travel is not None and force is not None:
        return travel, force
    for _, (d, f) in curves:
        if len(f):
            i = int(np.argmax(f))
            return d[i], f[i]
    return None


def plot_field(ax, field, curves, peak):
    settle = field["settling_in_travel"]
    start = field["linear_range_start"] - settle
    end = field["linear_range_end"] - settle
    slope = field["elastic_slope"]
    field_peak = field["peak_load"]
    half_travel = field["post_peak_half_load_travel"]

    anchor = 0.0
    anchored = False
    for _, (d, f) in curves:
        if len(d) > 1 and d[0] <= start <= d[-1]:
            anchor = float(np.interp(start, d, f))
            anchored = True
            break
    if anchor < field_peak:
        end = min(end, start + (field_peak - anchor) / slope)
    xs = np.array([start, end])
    ys = anchor + slope * (xs - start)
    ax.plot(xs * MM, ys * KN, color="black", linewidth=3, alpha=0.6,
            label="field linear part, slope %.3g MN/m: field travel %.0f-%.0f mm drawn at "
                  "%.0f-%.0f mm (%.0f mm settling-in removed)%s, cut at the field peak"
                  % (slope * 1e-6, field["linear_range_start"] * MM,
                     field["linear_range_end"] * MM, start * MM,
                     (field["linear_range_end"] - settle) * MM, settle * MM,
                     ", starting on the simulated curve" if anchored else ""))

    ax.axhline(field_peak * KN, color="black", linestyle="--", linewidth=1,
               label="field peak %.0f kN (travel at peak not in the field data)"
                     % (field_peak * KN))

    if peak is not None:
        x0, _ = peak
        ax.plot([x0 * MM, (x0 + half_travel) * MM], [field_peak / 2 * KN] * 2,
                color="black", linestyle=":", marker="|", markersize=12,
                label="field: half load %.0f mm after the peak (from the simulated peak)"
                      % (half_travel * MM))
        ax.plot([(x0 + half_travel) * MM], [field_peak / 2 * KN], "s", color="black",
                markersize=6)


def annotate_simulation(ax, summary):
    peak_force = summary_number(summary, "peak_force_N")
    peak_travel = summary_number(summary, "travel_at_peak_m")
    slope = summary_number(summary, "elastic_slope_N_per_m")
    half = summary_number(summary, "half_load_travel_after_peak_m")

    if peak_force is not None and peak_travel is not None:
        ax.plot([peak_travel * MM], [peak_force * KN], "o", color="tab:red", markersize=8,
                label="simulated peak %.1f kN at %.1f mm" % (peak_force * KN, peak_travel * MM))
        if half is not None:
            ax.plot([(peak_travel + half) * MM], [peak_force / 2 * KN], "D", color="tab:red",
                    markersize=7,
                    label="simulated half load %.1f mm after the peak" % (half * MM))
            ax.annotate("", xy=((peak_travel + half) * MM, peak_force / 2 * KN),
                        xytext=(peak_travel * MM, peak_force / 2 * KN),
                        arrowprops=dict(arrowstyle="<->", color="tab:red", lw=1))
    first_force = summary_number(summary, "first_peak_force_N")
    first_travel = summary_number(summary, "travel_at_first_peak_m")
    if first_force is not None and first_travel is not None:
        ax.plot([first_travel * MM], [first_force * KN], "^", color="tab:green", markersize=9,
                label="simulated first peak (centre crack) %.1f kN at %.1f mm"
                % (first_force * KN, first_travel * MM))
    if slope is not None:
        # A legend entry only: the slope is a property of the curve drawn above.
        ax.plot([], [], " ", label="simulated elastic slope %.3g MN/m" % (slope * 1e-6))


def save_atomically(fig, out):
    folder = os.path.dirname(os.path.abspath(out))
    os.makedirs(folder, exist_ok=True)
    temp = os.path.join(folder, ".%s.tmp.%d.png" % (os.path.basename(out), os.getpid()))
    try:
        fig.savefig(temp, format="png", dpi=150, bbox_inches="tight")
        os.replace(temp, out)
    except BaseException:
        if os.path.exists(temp):
            os.remove(temp)
        raise


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--csv", help="simulated curve (columns displacement [m], force [N])")
    parser.add_argument("--series", action="append", default=[], metavar="LABEL=CSV",
                        help="a further curve to overlay (repeatable)")
    parser.add_argument("--field", help="field key figures (data/levelIceBeamField.csv)")
    parser.add_argument("--summary", help="the case's postProcessing/summary.json")
    parser.add_argument("--out", required=True, help="PNG to write")
    parser.add_argument("--title", default="Level-ice beam, side-loaded: platen force")
    args = parser.parse_args(argv)

    named = ([("simulation", args.csv)] if args.csv else []) + parse_series(args.series)
    if not named:
        fail("give --csv and/or --series")
    curves = [(label, read_curve(path)) for label, path in named]
    summary = read_summary(args.summary) if args.summary else {}

    fig, ax = plt.subplots(figsize=(10, 6.5))
    for label, (d, f) in curves:
        if len(d) == 0:
            print("plotForceDisplacement.py: curve '%s' has no data rows" % label,
                  file=sys.stderr)
        ax.plot(d * MM, f * KN, linewidth=1.2, label=label)
    if args.field:
        plot_field(ax, read_field(args.field), curves, simulated_peak(summary, curves))
    annotate_simulation(ax, summary)

    ax.set_title(args.title)
    ax.set_xlabel("platen travel from contact [mm]")
    ax.set_ylabel("platen force [kN]")
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=min(0.0, ax.get_ylim()[0]))
    ax.grid(True, alpha=0.4)
    # Below the axes: the labels are long and the curves fill the upper left.
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), fontsize="small", ncol=1)
    save_atomically(fig, args.out)
    plt.close(fig)


if __name__ == "__main__":
    main()
