#!/usr/bin/python3
"""Compares the settling sphere of an iceFoam run with the Schiller-Naumann ODE
    (rho_p + C_a rho_f) V dv/dt = (rho_p - rho_f) V g - 0.5 rho_f C_d(Re) (pi d^2/4) |v| v,
    C_d = max(0.44, 24/Re (1 + 0.15 Re^0.687)), Re = |v| d / nu
(C_a: the case's addedMassCoefficient, 0 when absent) and writes
postProcessing/summary.json. Exits non-zero when the terminal velocity differs
from the ODE's by more than --tolerance, or, with --max-deviation, the velocity
anywhere along the way by more than that (both relative to the terminal velocity).

Usage: compareWithOde.py CASE [--tolerance 0.02] [--max-deviation F] [--ranks N] [--wall SECONDS]"""
import argparse
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postProcessing"))
from iceCases import get_entry, write_atomically  # noqa: E402


def number(path, dotted):
    return float(get_entry(path, dotted).split()[-1])


def drag_coefficient_times_re(re):
    return max(0.44 * re, 24.0 * (1.0 + 0.15 * re ** 0.687))


def acceleration(v, d, rho_p, rho_f, nu, g, c_a=0.0):
    """dv/dt of the sphere, v positive downwards."""
    re = abs(v) * d / nu
    drag = 0.5 * rho_f * drag_coefficient_times_re(re) * nu / d * (math.pi * d * d / 4) * v
    volume = math.pi / 6 * d ** 3
    return ((rho_p - rho_f) * volume * g - drag) / ((rho_p + c_a * rho_f) * volume)


def terminal_velocity(d, rho_p, rho_f, nu, g):
    lo, hi = 0.0, 100.0
    for _ in range(200):
        v = 0.5 * (lo + hi)
        if acceleration(v, d, rho_p, rho_f, nu, g) > 0:
            lo = v
        else:
            hi = v
    return 0.5 * (lo + hi)


def ode_velocity(times, d, rho_p, rho_f, nu, g, c_a, steps_per_interval=50):
    """RK4 solution sampled at `times` (from rest at times[0])."""
    v, t, out = 0.0, times[0], [0.0]
    f = lambda u: acceleration(u, d, rho_p, rho_f, nu, g, c_a)  # noqa: E731
    for t_next in times[1:]:
        h = (t_next - t) / steps_per_interval
        for _ in range(steps_per_interval):
            k1 = f(v)
            k2 = f(v + 0.5 * h * k1)
            k3 = f(v + 0.5 * h * k2)
            k4 = f(v + h * k3)
            v += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        t = t_next
        out.append(v)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case")
    ap.add_argument("--tolerance", type=float, default=0.02)
    ap.add_argument("--max-deviation", type=float, default=None)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--wall", type=float, default=None)
    a = ap.parse_args()

    props = os.path.join(a.case, "constant", "couplingProperties")
    transport = os.path.join(a.case, "constant", "transportProperties")
    d = number(props, "demVariables.diameter")
    rho_p = number(props, "demVariables.density")
    dem_dt = number(props, "demVariables.demTimeStep")
    try:
        c_a = number(props, "addedMassCoefficient")
    except KeyError:
        c_a = 0.0
    rho_f = number(transport, "rho")
    nu = number(transport, "nu")
    g = abs(float(get_entry(os.path.join(a.case, "constant", "g"), "value").strip("() ").split()[2]))

    with open(os.path.join(a.case, "postProcessing", "particles.csv")) as f:
        rows = [r for r in csv.DictReader(f) if r["tag"] == "1"]
    times = [float(r["time"]) for r in rows]
    # Each coupling step is logged once; the first two rows share t = 0 (initial forces).
    keep = [i for i in range(len(times)) if i == 0 or times[i] > times[i - 1]]
    times = [times[i] for i in keep]
    v_sim = [-float(rows[i]["vz"]) for i in keep]

    v_ode = ode_velocity(times, d, rho_p, rho_f, nu, g, c_a)
    v_t = terminal_velocity(d, rho_p, rho_f, nu, g)
    # Terminal velocity of the run: mean over its last fifth (the ODE is at
    # terminal velocity there to better than 0.1 %, checked below).
    tail = [i for i, t in enumerate(times) if t >= 0.8 * times[-1]]
    v_t_sim = sum(v_sim[i] for i in tail) / len(tail)
    ode_settled = abs(v_ode[tail[0]] - v_t) / v_t
    error = (v_t_sim - v_t) / v_t
    deviation = max(abs(vs - vo) for vs, vo in zip(v_sim, v_ode)) / v_t

    result = {
        "terminal_velocity_m_s": v_t_sim,
        "terminal_velocity_ode_m_s": v_t,
        "terminal_velocity_relative_error": error,
        "max_velocity_deviation_from_ode_relative": deviation,
        "reynolds_number_terminal": v_t * d / nu,
        "added_mass_coefficient": c_a,
        "ode_settled_relative": ode_settled,
        "particles": 1,
        "bonds": 0,
        "steps": int(round(times[-1] / dem_dt)),
        "dt": dem_dt,
        "ranks": a.ranks,
        "wall_s": a.wall,
    }
    os.makedirs(os.path.join(a.case, "postProcessing"), exist_ok=True)
    write_atomically(os.path.join(a.case, "postProcessing", "summary.json"), json.dumps(result, indent=2) + "\n")
    print(f"terminal velocity {v_t_sim:.5f} m/s, Schiller-Naumann ODE {v_t:.5f} m/s "
          f"({100 * error:+.2f} %, Re {v_t * d / nu:.0f}); largest deviation along the way "
          f"{100 * deviation:.2f} % of v_t")
    if ode_settled > 1e-3:
        print(f"run too short: the ODE is still {100 * ode_settled:.2f} % from terminal velocity")
        return 1
    if abs(error) > a.tolerance:
        print(f"FAIL: terminal velocity off by more than {100 * a.tolerance:.1f} %")
        return 1
    if a.max_deviation is not None and deviation > a.max_deviation:
        print(f"FAIL: velocity off the ODE's by more than {100 * a.max_deviation:.1f} % of v_t")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
