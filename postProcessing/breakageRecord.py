"""Inputs of the failure analysis, read and checked: the breakage record (HDF5 group
/breakage written by demModels/core/bonds/BreakageRecord.C), a platen force curve (CSV) and
an optional geometry description (JSON, schema in failureAnalysis.py and its README).

Every reading error is an InputError naming the file, the entry and what is allowed."""
import csv
import json
import math

import numpy as np

FAMILIES = {0: "ice", 1: "freeze"}
MODES = {1: "tension", 2: "shear", 3: "twist", 4: "bending"}
DATASETS = ("time", "x", "y", "z", "tagA", "tagB", "family", "mode")


class InputError(Exception):
    def __init__(self, path, entry, what):
        super().__init__("file '%s', entry '%s': %s" % (path, entry, what))


def read_breakage(path):
    """{dataset: numpy array} of the record, sorted by time (stable)."""
    import h5py  # only needed here; keeps the rest importable without it

    try:
        handle = h5py.File(path, "r")
    except OSError as error:
        raise InputError(path, "/", "cannot open the HDF5 file (%s)" % error)
    with handle:
        if "breakage" not in handle:
            raise InputError(path, "/breakage", "no such group; a breakage record has group "
                             "/breakage with datasets " + ", ".join(DATASETS))
        group = handle["breakage"]
        record = {}
        for name in DATASETS:
            if name not in group:
                raise InputError(path, "/breakage/" + name, "dataset missing (needed: %s)"
                                 % ", ".join(DATASETS))
            record[name] = np.asarray(group[name][()]).reshape(-1)
    n = len(record["time"])
    for name, values in record.items():
        if len(values) != n:
            raise InputError(path, "/breakage/" + name, "has %d values, /breakage/time has %d"
                             % (len(values), n))
    for name, codes in (("family", FAMILIES), ("mode", MODES)):
        unknown = sorted(set(record[name].tolist()) - set(codes))
        if unknown:
            raise InputError(path, "/breakage/" + name, "unknown codes %s (allowed: %s)"
                             % (unknown, ", ".join("%d=%s" % c for c in codes.items())))
    for name in ("time", "x", "y", "z"):
        if not np.all(np.isfinite(record[name])):
            raise InputError(path, "/breakage/" + name, "non-finite values")
    order = np.argsort(record["time"], kind="stable")
    return {name: values[order] for name, values in record.items()}


def read_curve(path, columns=None):
    """(time [s], travel [m], force [N]) of a platen force CSV with columns time, force and
    travel (or displacement), or the three columns named in `columns`; '#' lines are
    comments; rows with non-finite numbers are dropped."""
    try:
        with open(path, newline="") as handle:
            rows = [r for r in csv.reader(line for line in handle
                                          if line.strip() and not line.lstrip().startswith("#"))]
    except OSError as error:
        raise InputError(path, "(file)", "cannot read the force curve (%s)" % error)
    if not rows:
        raise InputError(path, "header", "empty file; needs columns time, travel, force")
    header = [name.strip() for name in rows[0]]
    names = columns or ("time", "travel" if "travel" in header else "displacement", "force")
    for column in names:
        if column not in header:
            raise InputError(path, column, "column missing (columns: %s; needed: %s)"
                             % (", ".join(header), ", ".join(names) if columns else
                                "time, force and travel or displacement"))
    columns = [header.index(c) for c in names]
    data = []
    for number, row in enumerate(rows[1:], start=2):
        try:
            values = [float(row[c]) for c in columns]
        except (ValueError, IndexError):
            raise InputError(path, "line %d" % number, "%s must be numbers" % ", ".join(names))
        if all(math.isfinite(v) for v in values):
            data.append(values)
    if len(data) < 2:
        raise InputError(path, "rows", "needs at least two finite data rows, has %d" % len(data))
    time, travel, force = (np.array(c) for c in zip(*data))
    if np.any(np.diff(time) < 0):
        raise InputError(path, "time", "must not decrease")
    return time, travel, force


def _number(path, mapping, key, default=None, entry=None):
    value = mapping.get(key, default)
    entry = entry or key
    if value is None:
        raise InputError(path, entry, "missing (a number in m)")
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(path, entry, "must be a finite number, got %r" % (value,))
    return float(value)


def read_geometry(path):
    """The geometry JSON checked and with defaults filled in (see failureAnalysis.py)."""
    try:
        with open(path) as handle:
            geometry = json.load(handle)
    except (OSError, ValueError) as error:
        raise InputError(path, "(file)", "cannot read the geometry JSON (%s)" % error)
    if not isinstance(geometry, dict):
        raise InputError(path, "(file)", "must be a JSON object")
    checked = {key: _number(path, geometry, key, default)
               for key, default in (("length", None), ("width", None), ("x0", 0.0),
                                    ("y0", 0.0), ("loadHalfLength", 0.0),
                                    ("particleRadius", 0.0))}
    for key in ("length", "width"):
        if checked[key] <= 0:
            raise InputError(path, key, "must be positive")
    for key in ("loadHalfLength", "particleRadius"):
        if checked[key] < 0:
            raise InputError(path, key, "must not be negative")
    checked["loadX"] = _number(path, geometry, "loadX",
                               checked["x0"] + 0.5 * checked["length"])
    if "waterLevel" in geometry:
        checked["waterLevel"] = _number(path, geometry, "waterLevel")
    supports = geometry.get("supports", [])
    if not isinstance(supports, list):
        raise InputError(path, "supports", "must be a list of x positions [m]")
    checked["supports"] = [_number(path, {"x": s}, "x", entry="supports[%d]" % k)
                           for k, s in enumerate(supports)]
    layers = geometry.get("layers", [])
    if not isinstance(layers, list):
        raise InputError(path, "layers", "must be a list of {name, zBottom, zTop}")
    checked["layers"] = []
    for k, layer in enumerate(layers):
        entry = "layers[%d]" % k
        if not isinstance(layer, dict) or not isinstance(layer.get("name"), str):
            raise InputError(path, entry, "must be an object with a name, zBottom and zTop")
        bottom = _number(path, layer, "zBottom", entry=entry + ".zBottom")
        top = _number(path, layer, "zTop", entry=entry + ".zTop")
        if top <= bottom:
            raise InputError(path, entry, "zTop must be above zBottom")
        checked["layers"].append({"name": layer["name"], "zBottom": bottom, "zTop": top})
    return checked
