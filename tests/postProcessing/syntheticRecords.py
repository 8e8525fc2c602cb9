"""Synthetic inputs for the failure-analysis tests: breakage records in the format of
demModels/core/bonds/BreakageRecord.C (written with h5py), force curves, a ridge geometry, and
break patterns of the four ridge failure modes of scenes.md 7."""
import json
import os

import h5py
import numpy as np

TENSION, SHEAR, TWIST, BENDING = 1, 2, 3, 4
ICE, FREEZE = 0, 1

# Keel 0-0.5 m, CL 0.5-0.65 m, platen 0.25 m long at mid-span, supports at the ends.
RIDGE = {"length": 3.05, "width": 0.94,
         "layers": [{"name": "keel", "zBottom": 0.0, "zTop": 0.5},
                    {"name": "consolidatedLayer", "zBottom": 0.5, "zTop": 0.65}],
         "loadX": 1.525, "loadHalfLength": 0.125, "supports": [0.0, 3.05], "waterLevel": 0.6}
MID = RIDGE["loadX"]


def write_record(path, events, drop=()):
    """events: {time, x, y, z, family, mode: sequences}; tags are numbered. drop: datasets
    left out (to make bad files)."""
    n = len(events["time"])
    columns = {"time": np.asarray(events["time"], float), "x": np.asarray(events["x"], float),
               "y": np.asarray(events["y"], float), "z": np.asarray(events["z"], float),
               "tagA": np.arange(n, dtype=np.int64), "tagB": np.arange(n, dtype=np.int64) + n,
               "family": np.asarray(events["family"], np.int32),
               "mode": np.asarray(events["mode"], np.int32)}
    with h5py.File(path, "w") as f:
        g = f.create_group("breakage")
        for name, values in columns.items():
            if name not in drop:
                g.create_dataset(name, data=values)
        g.attrs["familyCodes"] = np.bytes_("0=ice,1=freeze")
        g.attrs["modeCodes"] = np.bytes_("1=tension,2=shear,3=twist,4=bending")
        g.attrs["count"] = np.int64(n)


def write_curve(path, time, force, speed=0.005):
    with open(path, "w") as f:
        f.write("time,travel,displacement,force\n")
        for t, F in zip(time, force):
            f.write("%.12g,%.12g,%.12g,%.12g\n" % (t, speed * t, speed * t, F))


def triangle_curve(peak_time=1.0, peak_force=1e5, fall=80e3, end=2.0, dt=0.01):
    """Force rising linearly to the peak and falling linearly after it: half the peak at
    peak_time / 2 before it and peak_force / (2 fall) after it."""
    time = np.arange(0.0, end + dt / 2, dt)
    force = np.where(time <= peak_time, peak_force * time / peak_time,
                     peak_force - fall * (time - peak_time))
    return time, force


def make_case(folder, events, geometry=None, curve=None):
    os.makedirs(os.path.join(folder, "postProcessing"), exist_ok=True)
    write_record(os.path.join(folder, "postProcessing", "breakage.h5"), events)
    write_curve(os.path.join(folder, "postProcessing", "platenForce.csv"),
                *(curve or triangle_curve()))
    if geometry:
        with open(os.path.join(folder, "postProcessing", "geometry.json"), "w") as f:
            json.dump(geometry, f)
    return folder


def _events(time, x, z, family, mode, rng):
    order = np.argsort(time, kind="stable")
    return {"time": np.asarray(time)[order], "x": np.asarray(x)[order],
            "y": rng.uniform(0.0, RIDGE["width"], len(time)), "z": np.asarray(z)[order],
            "family": np.asarray(family)[order], "mode": np.asarray(mode)[order]}


def _join(*parts):
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


def cl_crack(rng, n=150, start=1.0, spread=0.08):
    """Ice bonds through the CL thickness at mid-span, tension and bending."""
    return dict(time=start + np.sort(rng.uniform(0.0, 1.0, n)),
                x=MID + rng.uniform(-spread, spread, n), z=rng.uniform(0.51, 0.64, n),
                family=np.full(n, ICE), mode=rng.choice([TENSION, BENDING], n, p=[0.7, 0.3]))


def keel_v_crack(rng, n=150, start=1.0):
    """Freeze-bonds from the keel bottom at mid-span upward, opening outward (a V)."""
    progress = np.arange(n) / n
    height = 0.48 * progress * rng.uniform(0.8, 1.0, n)
    side = rng.choice([-1.0, 1.0], n)
    return dict(time=start + progress, x=MID + side * (0.05 + 0.6 * height), z=height,
                family=np.full(n, FREEZE), mode=rng.choice([TENSION, SHEAR], n, p=[0.8, 0.2]))


def scattered_keel(rng, n, start):
    return dict(time=start + rng.uniform(0.0, 1.0, n), x=rng.uniform(0.0, 3.05, n),
                z=rng.uniform(0.0, 0.45, n), family=np.full(n, FREEZE),
                mode=np.full(n, TENSION))


def scenario(name, seed=1):
    """A break pattern of one ridge failure mode, or one that resembles a mode but breaks one
    of its rules."""
    rng = np.random.default_rng(seed)
    if name == "CL flexure":
        parts = [cl_crack(rng), scattered_keel(rng, 20, 1.5)]
    elif name == "keel V-crack from the bottom":
        late_cl = cl_crack(rng, n=15, start=1.9)
        late_cl["time"] = 1.9 + 0.1 * (late_cl["time"] - 1.9)
        parts = [keel_v_crack(rng), late_cl]
    elif name == "mixed":
        parts = [cl_crack(rng, n=100), keel_v_crack(rng, n=100)]
    elif name == "plug shear":
        n = 200
        z = rng.uniform(0.02, 0.63, n)
        edge = MID + rng.choice([-1.0, 1.0], n) * RIDGE["loadHalfLength"]
        parts = [dict(time=1.0 + rng.uniform(0.0, 1.0, n), x=edge + rng.normal(0.0, 0.015, n),
                      z=z, family=np.where(z < 0.5, FREEZE, ICE),
                      mode=rng.choice([SHEAR, TENSION], n, p=[0.7, 0.3]))]
    elif name == "keel bottom band growing downward":
        n = 150
        progress = np.arange(n) / n
        parts = [dict(time=1.0 + progress, x=MID + rng.uniform(-0.2, 0.2, n),
                      z=0.16 * (1.0 - progress), family=np.full(n, FREEZE),
                      mode=np.full(n, TENSION))]
    elif name == "one shear band":
        n = 200
        z = rng.uniform(0.02, 0.63, n)
        parts = [dict(time=1.0 + rng.uniform(0.0, 1.0, n),
                      x=MID - RIDGE["loadHalfLength"] + rng.normal(0.0, 0.015, n), z=z,
                      family=np.where(z < 0.5, FREEZE, ICE), mode=np.full(n, SHEAR))]
    elif name == "clamped CL flexure":
        # The keel's weak freeze-bonds go first; the layer then cracks through at mid-span and
        # at both fixed ends (x = 0 and 3.05 in RIDGE), as a clamped beam must to fail.
        ends = [cl_crack(rng, n=45, start=1.1) for _ in range(2)]
        for crack, support in zip(ends, RIDGE["supports"]):
            crack["x"] = crack["x"] - MID + support + (0.1 if support < MID else -0.1)
        keel = scattered_keel(rng, 20, 0.9)
        keel["time"] = 0.9 + 0.1 * (keel["time"] - 0.9)
        parts = [keel, cl_crack(rng, n=60)] + ends
    elif name == "scattered CL":
        crack = cl_crack(rng)
        crack["x"] = rng.uniform(0.0, 3.05, len(crack["x"]))
        parts = [crack]
    else:
        raise ValueError(name)
    joined = _join(*[{k: np.asarray(v) for k, v in p.items()} for p in parts])
    return _events(joined["time"], joined["x"], joined["z"], joined["family"], joined["mode"], rng)
