#!/usr/bin/python3
"""Where and when bonds broke, seen from above (x along the span, y the loading
direction), from a breakage record (HDF5 group /breakage).

    plotCrackPattern.py --h5 postProcessing/breakage.h5 --out postProcessing/crackPattern.png
        [--length 2.9 --width 0.5 --pad 0.2] [--summary postProcessing/summary.json]

Colour is the break time; marker is the mode (tension o, shear x, twist +, bending s).
When a summary is given, the time of its first peak is marked on the colour bar."""
import argparse
import json
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

MODES = {1: ("tension", "o"), 2: ("shear", "x"), 3: ("twist", "+"), 4: ("bending", "s")}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--h5", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--length", type=float, default=2.9)
    p.add_argument("--width", type=float, default=0.5)
    p.add_argument("--pad", type=float, default=0.2)
    p.add_argument("--summary")
    a = p.parse_args()

    with h5py.File(a.h5, "r") as f:
        g = f["breakage"]
        t, x, y, mode = (np.asarray(g[k]) for k in ("time", "x", "y", "mode"))

    fig, ax = plt.subplots(figsize=(11, 3.8))
    ax.add_patch(plt.Rectangle((0, 0), a.length, a.width, fill=False, lw=1, color="k"))
    for x0 in (0.0, a.length - a.pad):
        ax.add_patch(plt.Rectangle((x0, 0), a.pad, a.width, color="0.85", zorder=0))
    ax.add_patch(plt.Circle((a.length / 2, -0.077), 0.075, color="0.5", zorder=0))
    scatter = None
    for code, (name, marker) in MODES.items():
        sel = mode == code
        if sel.any():
            scatter = ax.scatter(x[sel], y[sel], c=t[sel], s=8, marker=marker, cmap="viridis",
                                 vmin=t.min(), vmax=t.max(), label=f"{name} ({sel.sum()})")
    if scatter is not None:
        bar = fig.colorbar(scatter, ax=ax, pad=0.01)
        bar.set_label("break time [s]")
        if a.summary and os.path.exists(a.summary):
            s = json.load(open(a.summary))
            speed = s.get("platen_speed_m_per_s")
            first = s.get("travel_at_first_peak_m")
            onset = s.get("contact_onset_travel_m", 0.0)
            if speed and first is not None:
                bar.ax.axhline((first + onset) / speed, color="red", lw=2)
                bar.ax.text(1.6, (first + onset) / speed, "first peak", color="red", fontsize=7,
                            transform=bar.ax.get_yaxis_transform(), va="center")
        ax.legend(loc="upper right", fontsize=7, markerscale=2)
    ax.set_aspect("equal")
    ax.set_xlim(-0.05, a.length + 0.05)
    ax.set_ylim(-0.2, a.width + 0.15)
    ax.set_xlabel("x along the span [m] (grey: fixed end pads; circle: platen at start)")
    ax.set_ylabel("y [m]")
    ax.set_title(f"Broken bonds seen from above: {len(t)} in all")
    fig.tight_layout()
    tmp = a.out + ".tmp.png"
    fig.savefig(tmp, dpi=130)
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
