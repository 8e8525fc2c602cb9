#!/usr/bin/python3
"""Pressure drop of the packedBed runs against the Ergun equation
    dp/L = 150 mu (1 - e)^2 / (e^3 d^2) U + 1.75 rho (1 - e) / (e^3 d) U^2
(U superficial velocity, e porosity) and the minimum fluidisation velocity,
where dp/L reaches the buoyant weight of the bed per volume (1 - e)(rho_p - rho) g.

  ergun.py fixed CASE [--tolerance 0.1]
      fixed bed: at every written time (the end of one inlet velocity's window)
      dp/L is the slope of the layer-mean p_rgh over the cell layers inside the
      bed (one cell layer clear of the floor and of the bed's top), the
      porosity that of the same slab from the sphere positions (exact
      sphere-slab volumes; periodic sides). Writes postProcessing/summary.json
      and ergun.png; exits non-zero when a point is off Ergun by more than
      the tolerance.
  ergun.py fluidisation CASE [--fixed FIXED_CASE]
      free bed under a slowly rising inlet velocity: dp over the bed (inlet
      p_rgh, outlet 0) in 0.15 s means; U_mf where a fit a U + b U^2 of the
      packed branch reaches the bed's buoyant weight per area, against the
      Ergun equality at the settled porosity and Wen-Yu; the plateau and the
      bed expansion. Writes postProcessing/summary.json and fluidisation.png
      (with the fixed bed's points when given).
"""
import argparse
import csv
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
from iceCases import get_entry, write_atomically  # noqa: E402


def number(path, dotted):
    return float(get_entry(path, dotted).split()[-1])


class Case:
    """The geometry and material of a packedBed case directory."""

    def __init__(self, path):
        self.path = path
        props = os.path.join(path, "constant", "couplingProperties")
        transport = os.path.join(path, "constant", "transportProperties")
        self.d = number(props, "demVariables.diameter")
        self.rho_p = number(props, "demVariables.density")
        self.floor = number(props, "demVariables.floor")
        self.rho = number(transport, "rho")
        self.nu = number(transport, "nu")
        self.g = abs(float(get_entry(os.path.join(path, "constant", "g"), "value").strip("() ").split()[2]))
        # The block of blockMesh: the distinct x and z of its points (ascii).
        text = open(os.path.join(path, "constant", "polyMesh", "points")).read()
        body = text[re.search(r"^\d+\s*\n\(", text, re.M).end():]
        points = [tuple(float(c) for c in p.split()) for p in re.findall(r"\(([^()]*)\)", body)]
        xs = sorted({round(p[0], 9) for p in points})
        zs = sorted({round(p[2], 9) for p in points})
        self.width = xs[-1] - xs[0]
        self.height = zs[-1] - zs[0]
        self.n_width = len(xs) - 1
        self.n_height = len(zs) - 1
        self.cell_height = self.height / self.n_height

    def particles_at_start(self):
        """(z, radius) of every particle at the first coupling step."""
        with open(os.path.join(self.path, "postProcessing", "particles.csv")) as f:
            rows = csv.DictReader(f)
            first = None
            out = []
            for r in rows:
                if first is None:
                    first = r["time"]
                if r["time"] != first:
                    break
                out.append((float(r["z"]), 0.5 * float(r["diameter"])))
        return out

    def times(self):
        return sorted((d for d in os.listdir(self.path) if re.fullmatch(r"[0-9.e+-]+", d) and float(d) > 0),
                      key=float)

    def layer_means(self, time, field="p_rgh"):
        """Mean of a scalar field over each horizontal cell layer (blockMesh order: x, then y, then z)."""
        text = open(os.path.join(self.path, time, field)).read()
        m = re.search(r"internalField\s+nonuniform\s+List<scalar>\s*(\d+)\s*\(([^)]*)\)", text)
        values = [float(v) for v in m.group(2).split()]
        per_layer = self.n_width ** 2
        return [sum(values[k * per_layer:(k + 1) * per_layer]) / per_layer for k in range(self.n_height)]

    def inlet_velocity(self, time):
        text = open(os.path.join(self.path, time, "U")).read()
        block = text[text.index("inlet"):]
        return float(re.search(r"value\s+uniform\s+\(([^)]*)\)", block).group(1).split()[2])


def solid_volume_in_slab(particles, lo, hi):
    """Total volume of the spheres (z, r) between the planes z = lo and z = hi."""
    total = 0.0
    for zc, r in particles:
        a, b = max(lo, zc - r) - zc, min(hi, zc + r) - zc
        if b > a:
            total += math.pi * (r * r * (b - a) - (b ** 3 - a ** 3) / 3.0)
    return total


def ergun_pressure_gradient(u, e, d, rho, mu):
    return 150.0 * mu * (1 - e) ** 2 / (e ** 3 * d * d) * u + 1.75 * rho * (1 - e) / (e ** 3 * d) * u * u


def ergun_minimum_fluidisation(e, case):
    """U at which the Ergun pressure gradient equals the buoyant weight per volume."""
    weight = (1 - e) * (case.rho_p - case.rho) * case.g
    lo, hi = 0.0, 10.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if ergun_pressure_gradient(mid, e, case.d, case.rho, case.rho * case.nu) < weight:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def wen_yu_minimum_fluidisation(case):
    """Wen and Yu (1966): Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7."""
    ar = case.d ** 3 * case.rho * (case.rho_p - case.rho) * case.g / (case.rho * case.nu) ** 2
    return (math.sqrt(33.7 ** 2 + 0.0408 * ar) - 33.7) * case.nu / case.d


def bed_slab(case, particles):
    """Cell layers wholly inside the bed, one cell layer clear of the floor and of the bed's top."""
    top = max(z + r for z, r in particles)
    layers = [k for k in range(case.n_height)
              if k * case.cell_height >= case.floor + case.cell_height - 1e-12
              and (k + 1) * case.cell_height <= top - case.cell_height + 1e-12]
    if len(layers) < 2:
        raise SystemExit(f"bed too shallow: {len(layers)} cell layer(s) inside it (need 2)")
    lo, hi = layers[0] * case.cell_height, (layers[-1] + 1) * case.cell_height
    solid = solid_volume_in_slab(particles, lo, hi)
    porosity = 1.0 - solid / (case.width ** 2 * (hi - lo))
    return layers, lo, hi, top, porosity


def slope(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def plot(path, title, series, curve, extra=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.plot(*curve[:2], "k-", label=curve[2])
    for xs, ys, style, label in series:
        ax.plot(xs, ys, style, label=label)
    if extra:
        extra(ax)
    ax.set_xlabel("superficial velocity U (m/s)")
    ax.set_ylabel("pressure gradient dp/L (Pa/m)")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=110)
    os.replace(path + ".tmp.png", path)


def fixed_bed(case, tolerance):
    particles = case.particles_at_start()
    layers, lo, hi, top, e = bed_slab(case, particles)
    mu = case.rho * case.nu
    centres = [(k + 0.5) * case.cell_height for k in layers]
    points = []
    for t in case.times():
        means = case.layer_means(t)
        u = case.inlet_velocity(t)
        measured = -case.rho * slope(centres, [means[k] for k in layers])
        ergun = ergun_pressure_gradient(u, e, case.d, case.rho, mu)
        points.append({"time_s": float(t), "superficial_velocity_m_s": u, "reynolds_number": u * case.d / case.nu,
                       "dp_per_length_Pa_m": measured, "ergun_Pa_m": ergun, "ratio_to_ergun": measured / ergun})
    if not points:
        raise SystemExit("no written time directories: nothing to compare")
    worst = max(abs(p["ratio_to_ergun"] - 1) for p in points)
    result = {
        "particles": len(particles), "diameter_m": case.d, "bed_top_m": top, "floor_m": case.floor,
        "slab_m": [lo, hi], "porosity": e, "tolerance": tolerance, "max_relative_deviation": worst,
        "points": sorted(points, key=lambda p: p["superficial_velocity_m_s"]),
    }
    out = os.path.join(case.path, "postProcessing")
    write_atomically(os.path.join(out, "summary.json"), json.dumps(result, indent=2) + "\n")
    for p in result["points"]:
        print(f"U = {p['superficial_velocity_m_s']:.2e} m/s (Re {p['reynolds_number']:5.1f}): dp/L "
              f"{p['dp_per_length_Pa_m']:9.2f} Pa/m, Ergun {p['ergun_Pa_m']:9.2f} ({100 * (p['ratio_to_ergun'] - 1):+.1f} %)")
    print(f"{len(particles)} spheres, porosity {e:.4f} in z = {lo * 1e3:.0f}..{hi * 1e3:.0f} mm (bed top {top * 1e3:.1f} mm)")
    us = [p["superficial_velocity_m_s"] for p in result["points"]]
    grid = [max(us) * 1.05 * k / 100 for k in range(101)]
    plot(os.path.join(out, "ergun.png"), f"packed bed, d = {case.d * 1e3:g} mm, porosity {e:.3f}",
         [(us, [p["dp_per_length_Pa_m"] for p in result["points"]], "o", "iceFoam (Di Felice drag)")],
         (grid, [ergun_pressure_gradient(u, e, case.d, case.rho, mu) for u in grid], "Ergun"))
    if worst > tolerance:
        print(f"FAIL: off Ergun by {100 * worst:.1f} % (allowed {100 * tolerance:.0f} %)")
        return 1
    return 0


def inlet_pressure_history(case):
    """(time, inlet p_rgh kinematic) from the inletPressure function object (controlDict)."""
    path = os.path.join(case.path, "postProcessing", "inletPressure", "0", "surfaceFieldValue.dat")
    rows = [line.split() for line in open(path) if line.strip() and not line.startswith("#")]
    return [float(r[0]) for r in rows], [float(r[1]) for r in rows]


def inlet_velocity_schedule(case):
    """The inlet's velocity table of 0/U as [(time, w)]."""
    text = open(os.path.join(case.path, "0", "U")).read()
    table = text[text.index("inlet"):]
    table = table[table.index("table"):]
    return [(float(t), float(w)) for t, w in re.findall(r"\(\s*([0-9.eE+-]+)\s*\(\s*\S+\s+\S+\s+([0-9.eE+-]+)\s*\)\s*\)", table)]


def interpolate(schedule, t):
    for (t0, u0), (t1, u1) in zip(schedule, schedule[1:]):
        if t0 <= t <= t1:
            return u0 + (u1 - u0) * (t - t0) / (t1 - t0)
    return schedule[-1][1]


def mean_heights(case):
    """(time, mean particle centre height) over the run, from particles.csv."""
    sums = {}
    with open(os.path.join(case.path, "postProcessing", "particles.csv")) as f:
        for r in csv.DictReader(f):
            s = sums.setdefault(float(r["time"]), [0.0, 0])
            s[0] += float(r["z"])
            s[1] += 1
    times = sorted(sums)
    return times, [sums[t][0] / sums[t][1] for t in times]


def fluidisation(case, fixed_case):
    particles = case.particles_at_start()
    _, _, _, top, e = bed_slab(case, particles)
    bed_height = top - case.floor
    volume = sum(4.0 / 3.0 * math.pi * r ** 3 for _, r in particles)
    weight_per_area = volume * (case.rho_p - case.rho) * case.g / case.width ** 2
    times, p_inlet = inlet_pressure_history(case)
    schedule = inlet_velocity_schedule(case)
    h_times, h_mean = mean_heights(case)
    h0 = h_mean[0]
    expanded = next((interpolate(schedule, t) for t, h in zip(h_times, h_mean)
                     if h > h0 + 0.01 * (h0 - case.floor)), None)
    # The inlet pressure jumps from step to step (fluid-fraction pulses of the
    # jiggling bed, coupling/README.md): means over windows of `window` s.
    window = 0.15
    u, dp = [], []
    t0 = times[0]
    while t0 + window <= times[-1] + 1e-12:
        rows = [k for k, t in enumerate(times) if t0 <= t < t0 + window]
        u.append(sum(interpolate(schedule, times[k]) for k in rows) / len(rows))
        dp.append(case.rho * sum(p_inlet[k] for k in rows) / len(rows))
        t0 += window
    # The packed branch (below 3/4 of the weight), fitted by a U + b U^2 as
    # Ergun's form; U_mf where it reaches the buoyant weight per area.
    branch = [(v, d) for v, d in zip(u, dp) if d < 0.75 * weight_per_area and (expanded is None or v < expanded)]
    if len(branch) < 3 or expanded is None:
        raise SystemExit("ramp too short: fewer than 3 packed windows, or the bed never expanded by 1 %")
    s11 = sum(v ** 2 for v, _ in branch)
    s12 = sum(v ** 3 for v, _ in branch)
    s22 = sum(v ** 4 for v, _ in branch)
    r1 = sum(v * d for v, d in branch)
    r2 = sum(v * v * d for v, d in branch)
    det = s11 * s22 - s12 * s12
    a_fit, b_fit = (r1 * s22 - r2 * s12) / det, (s11 * r2 - s12 * r1) / det
    u_mf = (-a_fit + math.sqrt(a_fit ** 2 + 4 * b_fit * weight_per_area)) / (2 * b_fit) if b_fit > 0 \
        else weight_per_area / a_fit
    plateau = [d for d, v in zip(dp, u) if v >= expanded]
    for v, d in zip(u, dp):
        print(f"  U {v * 1e3:5.1f} mm/s: dp {d:6.1f} Pa ({d / weight_per_area:.2f} of the weight)")
    u_ergun = ergun_minimum_fluidisation(e, case)
    u_wen_yu = wen_yu_minimum_fluidisation(case)
    result = {
        "particles": len(particles), "diameter_m": case.d, "particle_density_kg_m3": case.rho_p,
        "porosity_settled": e, "bed_height_m": bed_height, "weight_per_area_Pa": weight_per_area,
        "u_mf_measured_m_s": u_mf, "u_mf_ergun_m_s": u_ergun, "u_mf_wen_yu_m_s": u_wen_yu,
        "u_mf_relative_to_ergun": u_mf / u_ergun - 1.0,
        "packed_branch_fit_Pa": {"a_Pa_s_per_m": a_fit, "b_Pa_s2_per_m2": b_fit, "windows": len(branch)},
        "window_s": window,
        "plateau_dp_over_weight": sum(plateau) / len(plateau) / weight_per_area if plateau else None,
        "velocity_at_1pct_expansion_m_s": expanded,
        "final_mean_height_rise_relative": (h_mean[-1] - h0) / (h0 - case.floor),
    }
    out = os.path.join(case.path, "postProcessing")
    write_atomically(os.path.join(out, "summary.json"), json.dumps(result, indent=2) + "\n")
    print(f"bed: {len(particles)} spheres, porosity {e:.4f}, height {bed_height * 1e3:.1f} mm, "
          f"buoyant weight {weight_per_area:.1f} Pa")
    print(f"U_mf: {u_mf * 1e3:.2f} mm/s where the packed branch reaches the weight; Ergun equality {u_ergun * 1e3:.2f} mm/s "
          f"({100 * (u_mf / u_ergun - 1):+.1f} %), Wen-Yu {u_wen_yu * 1e3:.2f} mm/s")
    if plateau:
        print(f"plateau dp / weight once expanded: {result['plateau_dp_over_weight']:.3f}")
    print(f"bed expands (mean height +1 %) at U = {expanded * 1e3:.1f} mm/s; final mean height rise "
          f"{100 * result['final_mean_height_rise_relative']:.1f} %")

    grid = [max(u) * k / 100 for k in range(101)]
    mu = case.rho * case.nu
    series = [(u, [d / bed_height for d in dp], "s-", f"iceFoam, free bed, inlet ramp ({window:g} s means)")]
    if fixed_case:
        fixed = json.load(open(os.path.join(fixed_case, "postProcessing", "summary.json")))
        pts = [p for p in fixed["points"] if p["superficial_velocity_m_s"] <= max(u)]
        series.append(([p["superficial_velocity_m_s"] for p in pts], [p["dp_per_length_Pa_m"] for p in pts],
                       "o", f"iceFoam, fixed bed (porosity {fixed['porosity']:.3f})"))

    def marks(ax):
        ax.axhline(weight_per_area / bed_height, color="grey", ls="--", label="buoyant weight / bed volume")
        ax.axvline(u_mf, color="C3", ls=":", label=f"U_mf iceFoam {u_mf * 1e3:.1f} mm/s")
        ax.axvline(u_ergun, color="k", ls=":", label=f"U_mf Ergun {u_ergun * 1e3:.1f} mm/s")
        ax.set_ylim(0, 1.6 * weight_per_area / bed_height)

    plot(os.path.join(out, "fluidisation.png"), f"minimum fluidisation, d = {case.d * 1e3:g} mm glass",
         series, (grid, [ergun_pressure_gradient(v, e, case.d, case.rho, mu) for v in grid], "Ergun (settled porosity)"),
         marks)
    return 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mode", choices=["fixed", "fluidisation"])
    ap.add_argument("case")
    ap.add_argument("--tolerance", type=float, default=0.1)
    ap.add_argument("--fixed", default=None)
    a = ap.parse_args()
    case = Case(a.case)
    if a.mode == "fixed":
        return fixed_bed(case, a.tolerance)
    return fluidisation(case, a.fixed)


if __name__ == "__main__":
    sys.exit(main())
