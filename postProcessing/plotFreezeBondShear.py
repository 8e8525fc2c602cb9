"""Virtual freeze-bond shear tests (cases/freezeBondShear): our calibration
relation, effective shear strength against the particle-level strength S_p,
fitted and compared with the reference study's S_eff = 0.3555 S_p - 13761 Pa
(physics.md section 5), and the effective shear modulus against the bond
modulus. Run with Debian's /usr/bin/python3."""
import argparse
import glob
import json
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

REFERENCE_SLOPE, REFERENCE_INTERCEPT = 0.3555, -13761.0


def fit(x, y):
    slope, intercept = np.polyfit(x, y, 1)
    pred = slope * np.asarray(x) + intercept
    r2 = 1 - np.sum((np.asarray(y) - pred) ** 2) / np.sum((np.asarray(y) - np.mean(y)) ** 2)
    return float(slope), float(intercept), float(r2)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--runs", required=True)
    ap.add_argument("--summary", required=True)
    ap.add_argument("--table", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    runs = [json.load(open(p)) for p in sorted(glob.glob(os.path.join(a.runs, "*", "summary.json")))]
    if not runs:
        raise SystemExit("plotFreezeBondShear: no runs under " + a.runs)
    strength_runs = sorted([r for r in runs if r["label"].startswith("strength_")],
                           key=lambda r: r["particle_shear_strength_Pa"])
    modulus_runs = sorted([r for r in runs if r["label"].startswith("modulus_")],
                          key=lambda r: r["freeze_youngs_modulus_Pa"])
    sp = [r["particle_shear_strength_Pa"] for r in strength_runs]
    se = [r["effective_shear_strength_Pa"] for r in strength_runs]
    slope, intercept, r2 = fit(sp, se)
    summary = {
        "case": "freezeBondShear",
        "relation": {"slope": slope, "intercept_Pa": intercept, "R2": r2},
        "reference_relation": {"slope": REFERENCE_SLOPE, "intercept_Pa": REFERENCE_INTERCEPT},
        "all_failed": all(r["failed"] for r in runs),
        "strength_sweep": [{k: r[k] for k in ("particle_shear_strength_Pa", "effective_shear_strength_Pa",
                                              "effective_shear_modulus_Pa", "breaks_in_shear", "breaks")}
                           for r in strength_runs],
        "modulus_sweep": [{k: r[k] for k in ("freeze_youngs_modulus_Pa", "effective_shear_strength_Pa",
                                             "effective_shear_modulus_Pa")} for r in modulus_runs],
        "particles": runs[0]["particles"], "bonds": runs[0]["bonds"], "steps": runs[0]["steps"],
        "dt": runs[0]["dt"], "ranks": runs[0]["ranks"], "wall_s": sum(r["wall_s"] for r in runs),
    }
    tmp = a.summary + ".tmp"
    with open(tmp, "w") as f:
        json.dump(summary, f, indent=2)
    os.replace(tmp, a.summary)

    lines = ["| S_p (kPa) | bond E (Pa) | effective tau_max (kPa) | effective G (MPa) | breaks in shear / all |",
             "|---|---|---|---|---|"]
    for r in strength_runs + modulus_runs:
        lines.append(f"| {r['particle_shear_strength_Pa'] * 1e-3:.0f} | {r['freeze_youngs_modulus_Pa']:.3g} | "
                     f"{r['effective_shear_strength_Pa'] * 1e-3:.1f} | {r['effective_shear_modulus_Pa'] * 1e-6:.1f} | "
                     f"{r['breaks_in_shear']} / {r['breaks']} |")
    lines += ["", f"- ours: S_eff = {slope:.4f} S_p {intercept:+.0f} Pa (R2 {r2:.4f})",
              f"- reference study: S_eff = {REFERENCE_SLOPE} S_p {REFERENCE_INTERCEPT:+.0f} Pa"]
    open(a.table, "w").write("\n".join(lines) + "\n")

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.5))
    xs = np.linspace(0, max(sp) * 1.05, 2)
    ax.plot(np.array(sp) * 1e-3, np.array(se) * 1e-3, "s", label="DEM, this project")
    ax.plot(xs * 1e-3, (slope * xs + intercept) * 1e-3, "-", label=f"fit {slope:.3f} S_p {intercept * 1e-3:+.1f} kPa (R2 {r2:.3f})")
    ax.plot(xs * 1e-3, (REFERENCE_SLOPE * xs + REFERENCE_INTERCEPT) * 1e-3, "--",
            label=f"reference study {REFERENCE_SLOPE} S_p {REFERENCE_INTERCEPT * 1e-3:+.1f} kPa")
    ax.set_xlabel("particle-level freeze-bond strength S_p (kPa)")
    ax.set_ylabel("effective shear strength tau_max (kPa)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    if modulus_runs:
        e = [r["freeze_youngs_modulus_Pa"] for r in modulus_runs] + [strength_runs[0]["freeze_youngs_modulus_Pa"]]
        g = [r["effective_shear_modulus_Pa"] for r in modulus_runs] + [
            np.mean([r["effective_shear_modulus_Pa"] for r in strength_runs])]
        order = np.argsort(e)
        bx.plot(np.array(e)[order] * 1e-9, np.array(g)[order] * 1e-6, "o-")
    bx.set_xlabel("freeze-bond modulus E (GPa)")
    bx.set_ylabel("effective shear modulus of the joint (MPa)")
    bx.grid(alpha=0.3)
    fig.suptitle("Virtual freeze-bond shear test (asymmetric four-point bending)")
    fig.tight_layout()
    fig.savefig(a.out + ".tmp.png", dpi=120)
    os.replace(a.out + ".tmp.png", a.out)


if __name__ == "__main__":
    main()
