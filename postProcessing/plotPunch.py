#!/usr/bin/python3
"""Rubble punch (cases/rubblePunch, scenes.md section 6): the punches of the keels together.

Writes to CASE/postProcessing/, each file atomically:
  punch.png        total platen force, its buoyancy share (rho_w g times the rise of the ice's
                   submerged volume) and force minus buoyancy share, against platen travel
                   (hydrostatic runs);
  punchWater_<keel>.png  the same keel at the hydrostatic level and the cfd and vof levels where
                   run (runs <keel>, <keel>-cfd, <keel>-vof; ./Allrun -water cfd|vof): force
                   and buoyancy share; at vof also the share as the experiment read it, rho_w g
                   times the box's area times the level's rise plus the platen's own displaced
                   water (everything pushed under), and the ice's share under the moving surface;
  punchVof_<keel>.png  a keel at the vof level (run <keel>-vof): force, the buoyancy share as the
                   experiment read it (level's rise, platen included), the ice's share under the
                   moving surface and the share below the still level, and the level's rise;
  breakage.png     broken bonds against time by mode, one panel per keel;
  maps.png         the failure analysis's maps (runs/<keel>/postProcessing/failureAnalysis/
                   moment_*.png) at half load before the peak, the peak and half load after it;
  punchSummary.csv one row per run: water level, peak force, buoyancy share at the peak, mean
                   force and buoyancy share over 20-100 mm, force and share (means over +-5 mm)
                   at 50, 80 and 100 mm, at the cfd level the drag and the pressure force less
                   buoyancy over 20-100 mm (mean; standard deviation), at the vof level the
                   level-rise and moving-surface shares (means over 20-100 mm, at 100 mm) and
                   the level's rise at the end, broken bonds by mode and family, wall time,
                   particle-steps/s.

usage: plotPunch.py CASE [--runs cuboid empirical cuboid-cfd cuboid-vof]
       plotPunch.py CASE --merge-into results/punchSummary.csv
         (writes postProcessing/punchSummary.merged.csv: that table with this run's rows replaced
         or added, so that publishing one water level keeps the others' rows)"""
import argparse
import csv
import io
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from breakageRecord import MODES, read_breakage  # noqa: E402
from iceCases import finished, fluid_force_figures, summary, write_atomically  # noqa: E402
from plotForceDisplacement import save_atomically  # noqa: E402

MOMENTS = ("halfLoadBeforePeak", "peak", "halfLoadAfterPeak")
MODE_STYLES = {"tension": "-", "shear": "--", "twist": ":", "bending": "-."}


def columns(path):
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


RHO_W, G = 1000.0, 9.81


def water_level(run):
    return summary(run).get("water", "hydrostatic")


def vof_shares(run, c):
    """At the vof level (a waterLevel column), the buoyancy share as the experiment read it:
    rho_w g times the box's area times the level's rise since the first sample, plus the
    platen's own displaced water (the DEM platen displaces none in the fluid); and the ice's
    share under the moving surface, rho_w g times the rise of the caps under it. None elsewhere."""
    if "waterLevel" not in c:
        return None
    geometry = json.load(open(os.path.join(run, "postProcessing", "geometry.json")))
    area = geometry["length"] * geometry["width"]
    level_rise = RHO_W * G * area * (c["waterLevel"] - c["waterLevel"][0]) + c["platenBuoyancy"]
    ice = RHO_W * G * (c["iceSubmergedVolume"] - c["iceSubmergedVolume"][0])
    return {"levelRiseShare": level_rise, "iceShareMovingSurface": ice}


def plot_water_levels(keel, runs, out):
    """One keel at its water levels: force and buoyancy share against travel."""
    fig, ax = plt.subplots(figsize=(8, 5))
    for colour, (level, run) in zip(("tab:blue", "tab:red", "tab:green"), runs.items()):
        c = columns(os.path.join(run, "postProcessing", "platenForce.csv"))
        mm = c["travel"] * 1e3
        ax.plot(mm, c["force"], color=colour, lw=1.0, label=f"{level}: total platen force")
        ax.plot(mm, c["buoyancyShare"], color=colour, ls="--", lw=1.5,
                label=f"{level}: buoyancy share (ice below the still level)")
        shares = vof_shares(run, c)
        if shares:
            ax.plot(mm, shares["levelRiseShare"], color="black", ls="-.", lw=1.5,
                    label=f"{level}: share from the level's rise, platen included (as measured)")
            ax.plot(mm, shares["iceShareMovingSurface"], color=colour, ls=":", lw=1.5,
                    label=f"{level}: ice's share under the moving surface")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_xlabel("platen travel (mm)")
    ax.set_ylabel("force (N)")
    ax.set_title(f"Rubble punch, {keel} keel: " + ", ".join(runs) + " water")
    ax.legend(fontsize=8)
    save_atomically(fig, out)
    plt.close(fig)


def plot_vof(keel, run, out):
    """A keel at the vof level: the platen force and the buoyancy share three ways, and the
    level's rise (right axis)."""
    c = columns(os.path.join(run, "postProcessing", "platenForce.csv"))
    shares = vof_shares(run, c)
    mm = c["travel"] * 1e3
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.plot(mm, c["force"], color="tab:green", lw=1.0, label="total platen force")
    ax.plot(mm, shares["levelRiseShare"], color="black", ls="-.", lw=1.5,
            label="buoyancy share from the level's rise, platen included (as the experiment)")
    ax.plot(mm, shares["iceShareMovingSurface"], color="tab:green", ls=":", lw=1.5,
            label="ice's share under the moving surface")
    ax.plot(mm, c["buoyancyShare"], color="tab:green", ls="--", lw=1.2, label="ice's share below the still level")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_xlabel("platen travel (mm)")
    ax.set_ylabel("force (N)")
    rise = ax.twinx()
    rise.plot(mm, (c["waterLevel"] - c["waterLevel"][0]) * 1e3, color="tab:blue", lw=0.8, alpha=0.6)
    rise.set_ylabel("water level's rise (mm)", color="tab:blue")
    ax.set_title(f"Rubble punch, {keel} keel, vof level: water and air, a moving surface")
    ax.legend(fontsize=8, loc="upper left")
    save_atomically(fig, out)
    plt.close(fig)


def merge_summary(table, rows_text, out):
    """The published table with these rows replaced (same run) or added, columns united."""
    rows = list(csv.DictReader(io.StringIO(rows_text)))
    old = list(csv.DictReader(open(table, newline=""))) if os.path.exists(table) else []
    mine = {r["run"] for r in rows}
    merged = [r for r in old if r["run"] not in mine] + rows
    order = {name: i for i, name in enumerate(r["run"] for r in old)}
    merged.sort(key=lambda r: order.get(r["run"], len(order)))
    fields = list(dict.fromkeys([f for r in old[:1] for f in r] + [f for r in rows[:1] for f in r]))
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=fields, lineterminator="\n", restval="")
    writer.writeheader()
    writer.writerows(merged)
    write_atomically(out, text.getvalue())


def plot_forces(runs, out):
    fig, ax = plt.subplots(figsize=(8, 5))
    for k, (name, run) in enumerate(runs.items()):
        colour = f"C{k}"   # tab:blue, orange, green, red, ...: every run drawn, not the first four
        c = columns(os.path.join(run, "postProcessing", "platenForce.csv"))
        mm = c["travel"] * 1e3
        ax.plot(mm, c["force"] * 1e-3, color=colour, lw=1.5, label=f"{name}: total platen force")
        ax.plot(mm, c["buoyancyShare"] * 1e-3, color=colour, ls="--", lw=1.2,
                label=f"{name}: buoyancy share")
        ax.plot(mm, (c["force"] - c["buoyancyShare"]) * 1e-3, color=colour, ls=":", lw=1.2,
                label=f"{name}: force - buoyancy share")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_xlabel("platen travel (mm)")
    ax.set_ylabel("force (kN)")
    ax.set_title("Rubble punch: platen force and its buoyancy share")
    if len(runs) > 2:   # a study's points: a legend that long would hide the curves' peaks
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    else:
        ax.legend(fontsize=8)
    save_atomically(fig, out)
    plt.close(fig)


def plot_breakage(runs, out):
    fig, axes = plt.subplots(1, len(runs), figsize=(6 * len(runs), 4.5), squeeze=False, sharey=True)
    for ax, (name, run) in zip(axes[0], runs.items()):
        record = read_breakage(os.path.join(run, "postProcessing", "breakage.h5"))
        for code, mode in MODES.items():
            for family, colour in ((0, "tab:grey"), (1, "tab:red")):
                t = np.sort(record["time"][(record["mode"] == code) & (record["family"] == family)])
                if len(t):
                    ax.step(t, np.arange(1, len(t) + 1), where="post", color=colour,
                            ls=MODE_STYLES[mode],
                            label=f"{mode}, {'ice' if family == 0 else 'freeze'}-bonds")
        ax.set_title(f"{name}: broken bonds by mode")
        ax.set_xlabel("time (s)")
        ax.legend(fontsize=8)
    axes[0][0].set_ylabel("broken bonds (cumulative)")
    save_atomically(fig, out)
    plt.close(fig)


def plot_maps(runs, out):
    fig, axes = plt.subplots(len(runs), len(MOMENTS), figsize=(7 * len(MOMENTS), 4.2 * len(runs)),
                             squeeze=False)
    for row, (name, run) in zip(axes, runs.items()):
        for ax, moment in zip(row, MOMENTS):
            ax.axis("off")
            png = os.path.join(run, "postProcessing", "failureAnalysis", f"moment_{moment}.png")
            if os.path.exists(png):
                ax.imshow(mpimg.imread(png))
                ax.set_title(f"{name}: {moment}", fontsize=10)
            else:
                ax.set_title(f"{name}: {moment} not reached", fontsize=10)
    save_atomically(fig, out)
    plt.close(fig)


def table_text(rows):
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=list(rows[0]), lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    return text.getvalue()


def curve_figures(run):
    """Means over 20-100 mm of travel, and means over +-5 mm at 50, 80, 100 mm (the last: 95-100)."""
    c = columns(os.path.join(run, "postProcessing", "platenForce.csv"))
    mm = c["travel"] * 1e3
    figures = {}

    def mean(name, lo, hi):
        inside = (mm >= lo) & (mm <= hi)
        return round(float(c[name][inside].mean()), 1) if inside.any() else float("nan")
    figures["mean_force_20_100mm_N"] = mean("force", 20, 100)
    figures["mean_share_20_100mm_N"] = mean("buoyancyShare", 20, 100)
    for at in (50, 80, 100):
        figures[f"force_{at}mm_N"] = mean("force", at - 5, at + 5)
        figures[f"share_{at}mm_N"] = mean("buoyancyShare", at - 5, at + 5)
    # At the cfd level, what the resolved water adds beyond still-water buoyancy over 20-100 mm.
    fluid = fluid_force_figures(c, (20, 100))
    for name in ("drag_mean", "dynamic_pressure_mean", "dynamic_pressure_std"):
        figures[f"{name}_20_100mm_N"] = round(fluid[f"{name}_N"], 2) if fluid else ""
    # At the vof level, the share as the experiment read it and the ice's under the moving surface.
    shares = vof_shares(run, c)
    for name in ("levelRiseShare", "iceShareMovingSurface"):
        if shares:
            c[name] = shares[name]
        figures[f"mean_{name}_20_100mm_N"] = mean(name, 20, 100) if shares else ""
        figures[f"{name}_100mm_N"] = mean(name, 95, 105) if shares else ""
    figures["level_rise_mm"] = round(float(c["waterLevel"][-1] - c["waterLevel"][0]) * 1e3, 2) if shares else ""
    return figures


def summary_row(name, run):
    s = summary(run)
    return {"run": name, "water": water_level(run), "platen_speed_m_per_s": s["platen_speed_m_per_s"],
            "peak_force_N": round(s["peak_force_N"], 1),
            "travel_at_peak_mm": round(s["travel_at_peak_m"] * 1e3, 2),
            "buoyancy_share_at_peak_N": round(s["buoyancy_share_at_peak_N"], 1),
            "buoyancy_share_fraction": round(s["buoyancy_share_at_peak_N"] / s["peak_force_N"], 3),
            "peak_without_buoyancy_N": round(s["peak_force_without_buoyancy_N"], 1),
            **curve_figures(run),
            "broken_bonds": s["broken_bonds"],
            **{f"broken_{m}": s["broken_by_mode"][m] for m in MODES.values()},
            **{f"broken_{f}": n for f, n in s["broken_by_family"].items()},
            "particles": s["particles"], "ranks": s["ranks"], "wall_s": round(s["wall_s"], 1),
            "particle_steps_per_s": round(s["particle_steps_per_s"], -3)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case")
    ap.add_argument("--runs", nargs="+", default=["cuboid", "empirical"])
    ap.add_argument("--merge-into", metavar="TABLE")
    a = ap.parse_args(argv)
    out = os.path.join(a.case, "postProcessing")
    if a.merge_into:
        merge_summary(a.merge_into, open(os.path.join(out, "punchSummary.csv")).read(),
                      os.path.join(out, "punchSummary.merged.csv"))
        return
    os.makedirs(out, exist_ok=True)
    runs = {name: os.path.join(a.case, "runs", name) for name in a.runs
            if finished(os.path.join(a.case, "runs", name))}
    if not runs:
        sys.exit(f"plotPunch.py: no finished run among {a.runs} in {a.case}/runs")
    hydrostatic = {name: run for name, run in runs.items() if water_level(run) == "hydrostatic"}
    if hydrostatic:
        plot_forces(hydrostatic, os.path.join(out, "punch.png"))
    for keel, run in hydrostatic.items():
        levels = {"hydrostatic": run}
        for level in ("cfd", "vof"):
            other = runs.get(f"{keel}-{level}")
            if other and water_level(other) == level:
                levels[level] = other
        if len(levels) > 1:
            plot_water_levels(keel, levels, os.path.join(out, f"punchWater_{keel}.png"))
    for name, run in runs.items():
        if name.endswith("-vof") and water_level(run) == "vof":
            plot_vof(name[:-4], run, os.path.join(out, f"punchVof_{name[:-4]}.png"))
    plot_breakage(runs, os.path.join(out, "breakage.png"))
    plot_maps(runs, os.path.join(out, "maps.png"))
    rows = [summary_row(name, run) for name, run in runs.items()]
    write_atomically(os.path.join(out, "punchSummary.csv"), table_text(rows))
    print(table_text(rows), end="")


if __name__ == "__main__":
    main()
