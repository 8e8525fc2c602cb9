#!/usr/bin/python3
"""Results of the three-point bending beams: a table (CSV and Markdown) and a
chart with the force against mid-span deflection of each beam and the flexural
strength against thickness with the size-effect targets.

    /usr/bin/python3 plotThreePointBending.py --runs RUN [RUN ...] \
        --targets ../shared/data/flexuralStrengthTargets.csv --out PREFIX

Each RUN is a case directory with postProcessing/summary.json and platenForce.csv
(threePointBendingDEM). Writes PREFIX.csv, PREFIX.md and PREFIX.png atomically."""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import iceCases  # noqa: E402


def table(summaries):
    head = ["thickness_m", "particles", "bonds", "first_drop_N", "failure_force_N", "sigma_f_kPa", "target_kPa", "error",
            "deflection_at_failure_mm", "E_eff_GPa", "KE_over_elastic_at_peak", "broken_bonds", "steps",
            "wall_s", "particle_steps_per_s"]
    rows = [[f"{s['thickness_m']:.2f}", str(s["particles"]), str(s["bonds"]), f"{s['first_peak_force_N']:.0f}",
             f"{s['failure_force_N']:.0f}",
             f"{s['flexural_strength_Pa'] / 1e3:.1f}", f"{s['target_strength_Pa'] / 1e3:.0f}",
             f"{s['strength_error']:+.4f}", f"{s['deflection_at_failure_m'] * 1e3:.1f}",
             f"{s['effective_modulus_Pa'] / 1e9:.3f}", f"{s['kinetic_to_elastic_energy_at_peak']:.2g}",
             str(s["broken_bonds"]), str(s["steps"]), f"{s['wall_s']:.0f}", f"{s['particle_steps_per_s']:.3g}"]
            for s in summaries]
    csv_text = "\n".join(",".join(r) for r in [head] + rows) + "\n"
    md = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    md += ["| " + " | ".join(r[:7] + [f"{float(r[7]):+.1%}"] + r[8:]) + " |" for r in rows]
    return csv_text, "\n".join(md) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--runs", nargs="+", required=True)
    p.add_argument("--targets", required=True)
    p.add_argument("--out", required=True)
    a = p.parse_args()
    summaries = sorted((iceCases.summary(r) for r in a.runs), key=lambda s: s["thickness_m"])
    curves = {r: iceCases.curve(r) for r in a.runs}
    csv_text, md = table(summaries)
    iceCases.write_atomically(a.out + ".csv", csv_text)
    iceCases.write_atomically(a.out + ".md", md)
    print(md, end="")

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for run in a.runs:
        s, c = iceCases.summary(run), curves[run]
        left.plot([d * 1e3 for d in c["midspanDeflection"]], [f * 1e-3 for f in c["force"]],
                  label=f"D = {s['thickness_m']:.2f} m")
    left.set_xlabel("mid-span deflection [mm]")
    left.set_ylabel("platen force [kN]")
    left.set_title(f"{summaries[0]['resolution']} resolution ({summaries[0]['particle_diameter_m']} m particles)")
    left.legend()
    left.grid(alpha=0.3)
    with open(a.targets) as f:
        targets = list(csv.DictReader(line for line in f if not line.startswith("#")))
    right.plot([float(t["thickness_m"]) for t in targets], [float(t["target_kPa"]) for t in targets], "ks--",
               label="target (size-effect regression)")
    for t in targets:
        band = float(t["target_kPa"])
        right.fill_between([float(t["thickness_m"]) - 0.005, float(t["thickness_m"]) + 0.005],
                           0.95 * band, 1.05 * band, color="0.85")
    right.plot([s["thickness_m"] for s in summaries], [s["flexural_strength_Pa"] / 1e3 for s in summaries], "o-",
               label="model, 3 F L / (2 B D²)")
    right.set_xlabel("beam thickness D [m]")
    right.set_ylabel("flexural strength [kPa]")
    right.set_title("strength against thickness (grey: target ± 5 %)")
    right.legend()
    right.grid(alpha=0.3)
    iceCases.save_figure(fig, a.out + ".png", dpi=120)


if __name__ == "__main__":
    main()
