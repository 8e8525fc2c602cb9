"""Virtual freeze-bond tension tests against the measurements
(cases/freezeBondTension, scenes.md section 3): a table, summary.json and a
plot of strength against confinement pressure, per submersion time.

Run with Debian's /usr/bin/python3 (numpy, matplotlib)."""
import argparse
import csv
import json
import math
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def read_measurements(path):
    rows = [line for line in open(path) if not line.startswith("#")]
    out = []
    for r in csv.DictReader(rows):
        repeats = [float(r[k]) for k in ("repeat1_kPa", "repeat2_kPa", "repeat3_kPa") if r[k].strip()]
        out.append({
            "label": "tests_" + r["tests"],
            "minutes": float(r["submersion_min"]),
            "pressure_kPa": float(r["p_actual_kPa"]),
            "mean_kPa": float(r["mean_kPa"]),
            "sd_kPa": float(r["sd_kPa"]) if r["sd_kPa"].strip() else None,
            "repeats_kPa": repeats,
        })
    return out


def fit(x, y):
    if len(x) < 2:
        return None
    slope, intercept = np.polyfit(x, y, 1)
    pred = slope * np.asarray(x) + intercept
    ss_res = float(np.sum((np.asarray(y) - pred) ** 2))
    ss_tot = float(np.sum((np.asarray(y) - np.mean(y)) ** 2))
    return {"slope": float(slope), "intercept_kPa": float(intercept),
            "R2": 1.0 - ss_res / ss_tot if ss_tot > 0 else 1.0}


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--data", required=True)
    ap.add_argument("--runs", required=True)
    ap.add_argument("--summary", required=True)
    ap.add_argument("--table", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()

    measured = read_measurements(a.data)
    # A single test has no standard deviation: judge it by the mean
    # coefficient of variation of the repeated ones.
    cov = float(np.mean([m["sd_kPa"] / m["mean_kPa"] for m in measured if m["sd_kPa"]]))
    results = []
    for m in measured:
        path = os.path.join(a.runs, m["label"], "summary.json")
        if not os.path.exists(path):
            raise SystemExit(f"plotFreezeBondTension: {path} is missing (did the run fail? see log.{m['label']})")
        s = json.load(open(path))
        sd = m["sd_kPa"] if m["sd_kPa"] else cov * m["mean_kPa"]
        sim = s["strength_Pa"] * 1e-3
        model = (s["model_slope"] * s["confinement_pressure_Pa"] + s["model_intercept_Pa"]) * 1e-3
        results.append({**m, "simulated_kPa": sim, "model_line_kPa": model,
                        "sd_used_kPa": sd, "sd_is_estimate": m["sd_kPa"] is None,
                        "deviation_in_sd": (sim - m["mean_kPa"]) / sd,
                        "within_one_sd": bool(abs(sim - m["mean_kPa"]) <= sd),
                        "freeze_bonds": s["freeze_bonds"], "area_correction": s["area_correction"],
                        "mean_measured_confinement_kPa": s["mean_measured_confinement_Pa"] * 1e-3,
                        "model_slope": s["model_slope"], "model_intercept_kPa": s["model_intercept_Pa"] * 1e-3,
                        "wall_s": s["wall_s"], "particles": s["particles"], "steps": s["steps"],
                        "dt": s["dt"], "ranks": s["ranks"], "bonds": s["bonds"]})

    times = sorted({r["minutes"] for r in results})
    fits = {}
    for t in times:
        rs = [r for r in results if r["minutes"] == t]
        sim_fit = fit([r["pressure_kPa"] for r in rs], [r["simulated_kPa"] for r in rs])
        meas_fit = fit([r["pressure_kPa"] for r in rs], [r["mean_kPa"] for r in rs])
        fits[f"{t:g}"] = {"simulated": sim_fit, "measured": meas_fit,
                          "model_slope": rs[0]["model_slope"], "model_intercept_kPa": rs[0]["model_intercept_kPa"]}

    summary = {
        "case": "freezeBondTension",
        "runs": results,
        "all_within_one_sd": all(r["within_one_sd"] for r in results),
        "max_abs_deviation_in_sd": max(abs(r["deviation_in_sd"]) for r in results),
        "fits_by_submersion_min": fits,
        "particles": results[0]["particles"],
        "bonds": results[0]["bonds"],
        "steps": results[0]["steps"],
        "dt": results[0]["dt"],
        "ranks": results[0]["ranks"],
        "wall_s": sum(r["wall_s"] for r in results),
    }
    tmp = a.summary + ".tmp"
    with open(tmp, "w") as f:
        json.dump(summary, f, indent=2)
    os.replace(tmp, a.summary)

    lines = ["| tests | time (min) | p_c (kPa) | measured (kPa) | sd (kPa) | simulated (kPa) | deviation (sd) | within 1 sd | model line (kPa) |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        sd = f"{r['sd_used_kPa']:.0f}" + (" (est.)" if r["sd_is_estimate"] else "")
        lines.append(f"| {r['label'][6:]} | {r['minutes']:g} | {r['pressure_kPa']:.1f} | {r['mean_kPa']:.0f} | {sd} | "
                     f"{r['simulated_kPa']:.1f} | {r['deviation_in_sd']:+.2f} | {'yes' if r['within_one_sd'] else 'NO'} | "
                     f"{r['model_line_kPa']:.1f} |")
    lines.append("")
    for t, f in fits.items():
        if f["simulated"]:
            lines.append(f"- {t} min: simulated sigma = {f['simulated']['slope']:.2f} p_c + {f['simulated']['intercept_kPa']:.1f} kPa "
                         f"(R2 {f['simulated']['R2']:.3f}); measured means {f['measured']['slope']:.2f} p_c + "
                         f"{f['measured']['intercept_kPa']:.1f} kPa; model line {f['model_slope']:.2f} p_c + {f['model_intercept_kPa']:.1f} kPa")
    open(a.table, "w").write("\n".join(lines) + "\n")

    fig, ax = plt.subplots(figsize=(10, 5))
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(times)))
    for t, c in zip(times, colours):
        rs = [r for r in results if r["minutes"] == t]
        p = [r["pressure_kPa"] for r in rs]
        ax.errorbar(p, [r["mean_kPa"] for r in rs], yerr=[r["sd_used_kPa"] for r in rs], fmt="o", color=c,
                    capsize=4, mfc="none", label=f"measured, {t:g} min (mean +- sd)")
        ax.plot(p, [r["simulated_kPa"] for r in rs], "s", color=c, label=f"DEM, {t:g} min")
        f = fits[f"{t:g}"]["simulated"]
        if f:
            xs = np.linspace(0, 110, 2)
            ax.plot(xs, f["slope"] * xs + f["intercept_kPa"], "-", color=c, lw=1,
                    label=f"DEM fit {f['slope']:.2f} p + {f['intercept_kPa']:.0f} (R2 {f['R2']:.2f})")
    ax.set_xlabel("confinement pressure p_c (kPa)")
    ax.set_ylabel("tensile strength (kPa)")
    ax.set_title("Freeze-bond tension: virtual tests against measurements")
    ax.set_xlim(0, 110)
    ax.set_ylim(0, None)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    fig.savefig(a.out + ".tmp.png", dpi=130)
    os.replace(a.out + ".tmp.png", a.out)


if __name__ == "__main__":
    main()
