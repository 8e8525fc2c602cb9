#!/usr/bin/python3
"""Where, when and how bonds broke: failure analysis of a case's breakage record.

    failureAnalysis.py CASE_DIR [-at t1,t2] [--breakage H5] [--curve CSV] [--columns T,D,F]
                       [--geometry JSON]
                       [--out DIR] [--centre-half-width 0.25] [--interface-tolerance 0.05]

Inputs (defaults relative to CASE_DIR): postProcessing/breakage.h5 (group /breakage as
demModels/core/bonds/BreakageRecord.C writes it), postProcessing/platenForce.csv (columns time,
travel or displacement, force; others named by --columns) and, if present,
postProcessing/geometry.json:

    {"length": 3.05, "width": 0.94,          # body extent along x and y [m]
     "x0": 0.0, "y0": 0.0,                   # its lower corner (default 0)
     "layers": [{"name": "keel", "zBottom": 0.0, "zTop": 0.5},
                {"name": "consolidatedLayer", "zBottom": 0.5, "zTop": 0.6}],
     "loadX": 1.525,                         # mid-span load position (default the middle)
     "loadHalfLength": 0.125,                # half the platen length along x (default 0)
     "supports": [0.0, 3.05],                # x of the supports or fixed ends (optional)
     "waterLevel": 0.55,                     # optional, drawn in the side view
     "particleRadius": 0.0275}               # optional (default 0), see classifyRidgeFailure

Regions of a broken bond (its centre): the layer whose z range holds it ("outside" if none);
the span band, "centre" where |x - loadX| <= centre half-width, else "ends"; and "interface",
freeze-bonds within the interface tolerance of the bottom of the layer "consolidatedLayer".
Without a geometry every bond is in region "all".

Writes to DIR (default CASE_DIR/postProcessing/failureAnalysis), each file atomically:
counts.csv (cumulative counts at every curve sample, by mode, family, family and mode,
region), counts.png, at each moment (half load before the peak, peak, half load after the
peak, the -at times) moment_<name>.vtp (broken-bond centres with point data) and
moment_<name>.png (side and plan views), moments.pvd, summary.json (with the share of each
family broken where CASE_DIR/postProcessing/summary.json gives ice_bonds, freeze_bonds). With
a geometry that has
a layer "consolidatedLayer" and/or "keel" the ridge failure mode is classified
(classifyRidgeFailure, rules in its docstring) and printed.
Exit status 1 with a message naming the file and entry on bad input."""
import argparse
import dataclasses
import json
import math
import os
import sys
from xml.sax.saxutils import quoteattr

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from breakageRecord import (FAMILIES, MODES, InputError, read_breakage,  # noqa: E402
                            read_curve, read_geometry)
from iceCases import write_atomically  # noqa: E402
from plotForceDisplacement import save_atomically  # noqa: E402

CL = "consolidatedLayer"
KEEL = "keel"
MODE_COLOURS = {"tension": "tab:red", "shear": "tab:blue", "twist": "tab:green",
                "bending": "tab:orange"}
FAMILY_MARKERS = {"ice": "o", "freeze": "^"}


# --- regions -----------------------------------------------------------------------------

def layer_of(geometry, name):
    return next((layer for layer in geometry["layers"] if layer["name"] == name), None) \
        if geometry else None


def assign_regions(record, geometry, centre_half_width, interface_tolerance):
    """Per bond: layer index (-1 outside; 0 for all without layers), centre band (1/0, -1
    without geometry) and interface (1/0), plus the region names in code order."""
    n = len(record["time"])
    layer = np.zeros(n, dtype=int)
    centre = np.full(n, -1, dtype=int)
    interface = np.zeros(n, dtype=int)
    names = ["all"]
    if geometry:
        centre = (np.abs(record["x"] - geometry["loadX"]) <= centre_half_width).astype(int)
        if geometry["layers"]:
            names = [lay["name"] for lay in geometry["layers"]]
            layer[:] = -1
            for k, lay in reversed(list(enumerate(geometry["layers"]))):
                inside = (record["z"] >= lay["zBottom"]) & (record["z"] <= lay["zTop"])
                layer[inside] = k
        cl = layer_of(geometry, CL)
        if cl:
            interface = ((record["family"] == 1)
                         & (np.abs(record["z"] - cl["zBottom"]) <= interface_tolerance)).astype(int)
    return {"layer": layer, "centreBand": centre, "interface": interface, "layerNames": names,
            "hasInterface": layer_of(geometry, CL) is not None}


def region_masks(regions):
    """{region name: boolean mask over the record}, in a fixed order."""
    masks = {name: regions["layer"] == k for k, name in enumerate(regions["layerNames"])}
    if np.any(regions["layer"] < 0):
        masks["outside"] = regions["layer"] < 0
    if np.all(regions["centreBand"] >= 0) and len(regions["centreBand"]):
        masks["centre"] = regions["centreBand"] == 1
        masks["ends"] = regions["centreBand"] == 0
    if regions["hasInterface"]:
        masks["interface"] = regions["interface"] == 1
    return masks


def count_bonds(record, masks, selected):
    """Counts of the selected bonds by mode, family, family and mode, and region."""
    family = record["family"][selected]
    mode = record["mode"][selected]
    return {
        "total": int(selected.sum()),
        "mode": {name: int((mode == code).sum()) for code, name in MODES.items()},
        "family": {name: int((family == code).sum()) for code, name in FAMILIES.items()},
        "family_mode": {fname: {mname: int(((family == fc) & (mode == mc)).sum())
                                for mc, mname in MODES.items()}
                        for fc, fname in FAMILIES.items()},
        "region": {name: int((mask & selected).sum()) for name, mask in masks.items()},
    }


def freeze_tension_fraction(counts):
    freeze = counts["family"]["freeze"]
    return counts["family_mode"]["freeze"]["tension"] / freeze if freeze else None


# --- moments of the force curve ----------------------------------------------------------

def _crossing(time, travel, force, i, j, level):
    """The point between samples i and j where the force crosses level (linear)."""
    span = force[j] - force[i]
    s = 0.0 if span == 0 else (level - force[i]) / span
    return {"time": float(time[i] + s * (time[j] - time[i])),
            "travel": float(travel[i] + s * (travel[j] - travel[i])), "force": float(level)}


def find_moments(time, travel, force, extra_times=(), half_fraction=0.5):
    """(moments, not_found): the peak (first largest force); the last upward crossing of
    half the peak before it; the first downward crossing after it (both interpolated
    linearly between samples, as ForceCurveAnalysis does); then the extra times, with travel
    and force interpolated on the curve. not_found: {name: why} for moments without one."""
    peak = int(np.argmax(force))
    moments, not_found = [], {}
    half = half_fraction * force[peak]
    if force[peak] <= 0:
        not_found["peak"] = "the force never becomes positive"
    else:
        below = np.nonzero(force[:peak] <= half)[0]
        if len(below):
            moments.append(dict(name="halfLoadBeforePeak",
                                **_crossing(time, travel, force, below[-1], below[-1] + 1, half)))
        else:
            not_found["halfLoadBeforePeak"] = "the curve starts above half the peak"
        moments.append({"name": "peak", "time": float(time[peak]),
                        "travel": float(travel[peak]), "force": float(force[peak])})
        after = np.nonzero(force[peak + 1:] <= half)[0]
        if len(after):
            j = peak + 1 + after[0]
            moments.append(dict(name="halfLoadAfterPeak",
                                **_crossing(time, travel, force, j - 1, j, half)))
        else:
            not_found["halfLoadAfterPeak"] = "the force does not fall to half the peak"
    for t in extra_times:
        moment = {"name": "t%g" % t, "time": float(t),
                  "travel": float(np.interp(t, time, travel)),
                  "force": float(np.interp(t, time, force))}
        if not time[0] <= t <= time[-1]:
            moment["note"] = "outside the force curve: travel and force of its nearest end"
        moments.append(moment)
    return moments, not_found


# --- ridge failure mode ------------------------------------------------------------------

@dataclasses.dataclass
class RidgeFailureRules:
    """Thresholds of classifyRidgeFailure (lengths in m, the rest fractions)."""
    centreHalfWidth: float = 0.25        # "mid-span": |x - loadX| <= this
    interfaceTolerance: float = 0.05     # CL-keel freeze-bonds: |z - CL bottom| <= this
    earlyFraction: float = 0.1           # the first breaks: this share of the window's breaks
    earlyMajority: float = 0.5           # "first": this share of the first breaks
    dominantFraction: float = 0.6        # a region "dominates": this share of the breaks
    substantialFraction: float = 0.3     # a region "fails substantially": this share
    concentrationFraction: float = 0.6   # CL breaks "concentrated" at its hinges: this share
    supportHalfWidth: float = 0.25       # "at a support": |x - support| <= this (a clamped
                                         # layer hinges at its ends as well as at mid-span)
    throughThicknessFraction: float = 0.5  # breaks cover this share of the layer's depth
    keelBottomFraction: float = 1.0 / 3.0  # "near the keel bottom": the lowest third
    plugBandHalfWidth: float = 0.06      # plug-shear band: |x - edge| <= this
    plugSideFraction: float = 0.25       # "two bands": each side holds this share of them
    shearDominance: float = 0.5          # shear mode share of the band breaks


def _share(mask, within):
    n = int(within.sum())
    return float((mask & within).sum()) / n if n else 0.0


def _z_cover(z, bottom, top, inset=0.0):
    """Share of [bottom, top] spanned by z; bond centres lie about a particle radius (inset)
    inside a layer's faces, so the faces are moved in by it, up to a quarter of the depth."""
    inset = min(inset, 0.25 * (top - bottom))
    return float((z.max() - z.min()) / (top - bottom - 2 * inset)) if len(z) else 0.0


def _plug_shear(record, geometry, rules, window, depth):
    """Best pair of vertical bands (platen edges, supports): its evidence."""
    x = record["x"]
    pairs = []
    if geometry["loadHalfLength"] > 0:
        pairs.append(("platen edges", geometry["loadX"] - geometry["loadHalfLength"],
                      geometry["loadX"] + geometry["loadHalfLength"]))
    if len(geometry["supports"]) >= 2:
        pairs.append(("supports", min(geometry["supports"]), max(geometry["supports"])))
    best = None
    for name, left, right in pairs:
        in_left = window & (np.abs(x - left) <= rules.plugBandHalfWidth)
        in_right = window & (np.abs(x - right) <= rules.plugBandHalfWidth)
        band = in_left | in_right
        n_band = int(band.sum())
        found = {
            "bands": name, "x": [left, right], "share": _share(band, window),
            "side_shares": [float(in_left.sum()) / n_band if n_band else 0.0,
                            float(in_right.sum()) / n_band if n_band else 0.0],
            "shear_share": _share(record["mode"] == 2, band),
            "depth_cover": _z_cover(record["z"][band], *depth, geometry["particleRadius"]),
        }
        found["holds"] = (found["share"] >= rules.dominantFraction
                          and min(found["side_shares"]) >= rules.plugSideFraction
                          and found["shear_share"] >= rules.shearDominance
                          and found["depth_cover"] >= rules.throughThicknessFraction)
        if best is None or found["share"] > best["share"]:
            best = found
    return best


def classifyRidgeFailure(record, geometry, windowEnd=None, rules=RidgeFailureRules()):
    """Failure mode of a ridge (scenes.md 7) from its breakage record and geometry.

    record: {time, x, y, z, family, mode: arrays} (breakageRecord.read_breakage); geometry:
    breakageRecord.read_geometry's dict with a layer "consolidatedLayer" (CL) and/or "keel".
    The window is the breaks up to windowEnd (the tool passes the half load after the peak,
    else the last break); "the first breaks" are its earliest earlyFraction (at least one).
    CL and keel breaks are those in the layers' z ranges, CL-keel interface freeze-bonds
    (within interfaceTolerance of the CL bottom) counted apart. Rules, in this order:

    1. "plug shear": a pair of vertical bands |x - edge| <= plugBandHalfWidth at the platen
       edges (loadX -+ loadHalfLength) or at the supports holds >= dominantFraction of the
       breaks, each band >= plugSideFraction of them, shear is >= shearDominance of their
       modes, and they span >= throughThicknessFraction of the body's depth. (Depths and
       thicknesses here are taken less the geometry's particleRadius at each face, where
       bond centres cannot lie, at most a quarter of the depth each.)
    2. "mixed": CL and keel each hold >= substantialFraction of the breaks.
    3. "CL flexure": the CL holds >= dominantFraction and the keel < substantialFraction;
       >= concentrationFraction of the CL breaks lie at its hinges (mid-span, |x - loadX| <=
       centreHalfWidth, or at a support, |x - support| <= supportHalfWidth: fixed ends hinge
       too); those at mid-span cover >= throughThicknessFraction of the CL thickness; and
       >= earlyMajority of the first ice-bond breaks (the earliest earlyFraction of them) are
       in the CL. Ice bonds, not all bonds: weak freeze-bonds of the keel break first in every
       ridge, whatever fails in the end.
    4. "keel V-crack from the bottom": the keel holds >= dominantFraction and the CL
       < substantialFraction; >= earlyMajority of the first breaks are in the keel's bottom
       keelBottomFraction at mid-span; and the median height of the keel breaks in the
       window's second half (by count) is above that of the first breaks in the keel.
    Otherwise "undetermined" ("no failure" without breaks). Returns {"mode", "evidence"
    (numbers), "text" (lines: where and in what order the bonds broke)}."""
    t, x, z = record["time"], record["x"], record["z"]
    window = np.ones(len(t), bool) if windowEnd is None else t <= windowEnd
    n = int(window.sum())
    cl, keel = layer_of(geometry, CL), layer_of(geometry, KEEL)
    if n == 0:
        return {"mode": "no failure", "evidence": {"window_breaks": 0},
                "text": ["no bond broke up to t = %s s" % windowEnd]}

    interface = np.zeros(len(t), bool)
    if cl:
        interface = ((record["family"] == 1)
                     & (np.abs(z - cl["zBottom"]) <= rules.interfaceTolerance))

    def inside(layer):
        if layer is None:
            return np.zeros(len(t), bool)
        return (z >= layer["zBottom"]) & (z <= layer["zTop"]) & ~interface

    in_cl, in_keel = inside(cl), inside(keel)
    mid = np.abs(x - geometry["loadX"]) <= rules.centreHalfWidth
    ordered = np.nonzero(window)[0]
    ordered = ordered[np.argsort(t[ordered], kind="stable")]
    n_early = max(1, int(math.ceil(rules.earlyFraction * n)))
    early = np.zeros(len(t), bool)
    early[ordered[:n_early]] = True
    late = np.zeros(len(t), bool)
    late[ordered[n // 2:]] = True
    keel_bottom = np.zeros(len(t), bool)
    if keel:
        keel_bottom = in_keel & (z <= keel["zBottom"] + rules.keelBottomFraction
                                 * (keel["zTop"] - keel["zBottom"]))
    layers = [lay for lay in (cl, keel) if lay]
    depth = (min(lay["zBottom"] for lay in layers), max(lay["zTop"] for lay in layers))

    at_support = np.zeros(len(t), bool)
    for support in geometry.get("supports", []):
        at_support |= np.abs(x - support) <= rules.supportHalfWidth
    ice = window & (record["family"] == 0)
    ice_ordered = np.nonzero(ice)[0]
    ice_ordered = ice_ordered[np.argsort(t[ice_ordered], kind="stable")]
    early_ice = np.zeros(len(t), bool)
    early_ice[ice_ordered[:max(1, int(math.ceil(rules.earlyFraction * len(ice_ordered))))]] = True
    early_ice &= ice

    ev = {
        "window_end_s": None if windowEnd is None else float(windowEnd),
        "window_breaks": n, "first_breaks": n_early,
        "first_breaks_until_s": float(t[ordered[n_early - 1]]),
        "share_cl": _share(in_cl, window), "share_keel": _share(in_keel, window),
        "share_interface": _share(interface, window),
        "share_ice_family": _share(record["family"] == 0, window),
        "first_share_cl": _share(in_cl, early), "first_share_keel": _share(in_keel, early),
        "first_share_keel_bottom_mid_span": _share(keel_bottom & mid, early),
        "first_share_mid_span": _share(mid, early),
        "cl_share_mid_span": _share(mid, window & in_cl),
        "cl_share_hinges": _share(mid | at_support, window & in_cl),
        "first_ice_breaks": int(early_ice.sum()),
        "first_ice_share_cl": _share(in_cl, early_ice),
        "cl_thickness_cover_mid_span": _z_cover(z[window & in_cl & mid], cl["zBottom"],
                                                cl["zTop"], geometry["particleRadius"])
        if cl else 0.0,
        "first_break_s": {name: float(t[window & mask].min()) if (window & mask).any() else None
                          for name, mask in (("consolidatedLayer", in_cl), ("keel", in_keel),
                                             ("interface", interface))},
    }
    if keel:
        height = z - keel["zBottom"]
        early_keel, late_keel = early & in_keel, late & in_keel
        ev["keel_first_median_height_m"] = float(np.median(height[early_keel])) \
            if early_keel.any() else None
        ev["keel_late_median_height_m"] = float(np.median(height[late_keel])) \
            if late_keel.any() else None
        third = (keel["zTop"] - keel["zBottom"]) / 3.0
        for label, lo, hi in (("bottom", 0.0, third), ("top", 2 * third, 3 * third)):
            sel = window & in_keel & (height >= lo) & (height <= hi)
            ev["keel_%s_third_mean_abs_dx_m" % label] = \
                float(np.mean(np.abs(x[sel] - geometry["loadX"]))) if sel.any() else None
    plug = _plug_shear(record, geometry, rules, window, depth)
    ev["plug_bands"] = plug

    upward = (ev.get("keel_first_median_height_m") is not None
              and ev.get("keel_late_median_height_m") is not None
              and ev["keel_late_median_height_m"] > ev["keel_first_median_height_m"])
    if plug and plug["holds"]:
        mode = "plug shear"
    elif (ev["share_cl"] >= rules.substantialFraction
          and ev["share_keel"] >= rules.substantialFraction):
        mode = "mixed"
    elif (ev["share_cl"] >= rules.dominantFraction
          and ev["share_keel"] < rules.substantialFraction
          and ev["cl_share_hinges"] >= rules.concentrationFraction
          and ev["cl_thickness_cover_mid_span"] >= rules.throughThicknessFraction
          and ev["first_ice_share_cl"] >= rules.earlyMajority):
        mode = "CL flexure"
    elif (ev["share_keel"] >= rules.dominantFraction
          and ev["share_cl"] < rules.substantialFraction
          and ev["first_share_keel_bottom_mid_span"] >= rules.earlyMajority and upward):
        mode = "keel V-crack from the bottom"
    else:
        mode = "undetermined"
    return {"mode": mode, "evidence": ev, "text": _evidence_text(ev, rules)}


def _pct(value):
    return "%.0f%%" % (100 * value)


def _evidence_text(ev, rules):
    lines = ["%d breaks up to %s" % (ev["window_breaks"], "the end" if ev["window_end_s"] is None
                                     else "t = %.4g s" % ev["window_end_s"]),
             "shares: CL %s, keel %s, CL-keel interface %s; ice bonds %s"
             % (_pct(ev["share_cl"]), _pct(ev["share_keel"]), _pct(ev["share_interface"]),
                _pct(ev["share_ice_family"])),
             "first %s of breaks (%d, until t = %.4g s): CL %s, keel %s, keel bottom third "
             "within %.2g m of mid-span %s, within %.2g m of mid-span %s"
             % (_pct(rules.earlyFraction), ev["first_breaks"], ev["first_breaks_until_s"],
                _pct(ev["first_share_cl"]), _pct(ev["first_share_keel"]), rules.centreHalfWidth,
                _pct(ev["first_share_keel_bottom_mid_span"]), rules.centreHalfWidth,
                _pct(ev["first_share_mid_span"])),
             "CL breaks within %.2g m of mid-span: %s, covering %s of the CL thickness; at its "
             "hinges (mid-span or within %.2g m of a support): %s; first %s of ice-bond breaks (%d) "
             "in the CL: %s"
             % (rules.centreHalfWidth, _pct(ev["cl_share_mid_span"]),
                _pct(ev["cl_thickness_cover_mid_span"]), rules.supportHalfWidth,
                _pct(ev["cl_share_hinges"]), _pct(rules.earlyFraction), ev["first_ice_breaks"],
                _pct(ev["first_ice_share_cl"]))]
    if ev.get("keel_first_median_height_m") is not None:
        late = ev["keel_late_median_height_m"]
        lines.append("keel: median height above its bottom of the first breaks %.3g m, of the "
                     "later half %s; mean |x - loadX| bottom third %s, top third %s"
                     % (ev["keel_first_median_height_m"],
                        "-" if late is None else "%.3g m" % late,
                        *("-" if ev[k] is None else "%.3g m" % ev[k]
                          for k in ("keel_bottom_third_mean_abs_dx_m",
                                    "keel_top_third_mean_abs_dx_m"))))
    plug = ev.get("plug_bands")
    if plug:
        lines.append("bands at the %s (x = %.3g, %.3g m, +-%.2g m): %s of breaks, sides %s/%s, "
                     "shear %s, over %s of the depth"
                     % (plug["bands"], plug["x"][0], plug["x"][1], rules.plugBandHalfWidth,
                        _pct(plug["share"]), _pct(plug["side_shares"][0]),
                        _pct(plug["side_shares"][1]), _pct(plug["shear_share"]),
                        _pct(plug["depth_cover"])))
    firsts = sorted((v, k) for k, v in ev["first_break_s"].items() if v is not None)
    lines.append("first break: " + ", ".join("%s t = %.4g s" % (k, v) for v, k in firsts))
    return lines


# --- writers -----------------------------------------------------------------------------

def _data_array(vtk_type, name, values, fmt):
    body = " ".join(fmt % v for v in values)
    return ('        <DataArray type="%s" Name="%s" format="ascii">%s</DataArray>\n'
            % (vtk_type, name, body))


def vtp_text(record, regions, selected):
    """ASCII VTK PolyData: one vertex per broken bond (its centre), with point data."""
    idx = np.nonzero(selected)[0]
    n = len(idx)
    points = " ".join("%.9g %.9g %.9g" % (record["x"][i], record["y"][i], record["z"][i])
                      for i in idx)
    point_data = "".join([
        _data_array("Int32", "mode", record["mode"][idx], "%d"),
        _data_array("Int32", "family", record["family"][idx], "%d"),
        _data_array("Float64", "time", record["time"][idx], "%.9g"),
        _data_array("Int32", "layer", regions["layer"][idx], "%d"),
        _data_array("Int32", "centreBand", regions["centreBand"][idx], "%d"),
        _data_array("Int32", "interface", regions["interface"][idx], "%d"),
        _data_array("Int64", "tagA", record["tagA"][idx], "%d"),
        _data_array("Int64", "tagB", record["tagB"][idx], "%d"),
    ])
    return ('<?xml version="1.0"?>\n'
            '<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">\n'
            '  <PolyData>\n'
            '    <Piece NumberOfPoints="%d" NumberOfVerts="%d" NumberOfLines="0" '
            'NumberOfStrips="0" NumberOfPolys="0">\n'
            '      <PointData Scalars="mode">\n%s      </PointData>\n'
            '      <Points>\n'
            '        <DataArray type="Float64" NumberOfComponents="3" format="ascii">%s'
            '</DataArray>\n'
            '      </Points>\n'
            '      <Verts>\n%s%s      </Verts>\n'
            '    </Piece>\n'
            '  </PolyData>\n'
            '</VTKFile>\n'
            % (n, n, point_data, points,
               _data_array("Int64", "connectivity", range(n), "%d"),
               _data_array("Int64", "offsets", range(1, n + 1), "%d")))


def pvd_text(entries):
    rows = "".join('    <DataSet timestep="%.9g" group="" part="0" file=%s/>\n'
                   % (time, quoteattr(name)) for time, name in entries)
    return ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" '
            'byte_order="LittleEndian">\n  <Collection>\n%s  </Collection>\n</VTKFile>\n' % rows)


def counts_csv_text(record, masks, time, travel, force):
    """Cumulative counts at every curve sample."""
    columns = (["broken"] + list(MODES.values()) + list(FAMILIES.values())
               + ["%s_%s" % (f, m) for f in FAMILIES.values() for m in MODES.values()]
               + ["region_" + name for name in masks])
    series = [np.ones(len(record["time"]), bool)]
    series += [record["mode"] == c for c in MODES]
    series += [record["family"] == c for c in FAMILIES]
    series += [(record["family"] == fc) & (record["mode"] == mc) for fc in FAMILIES for mc in MODES]
    series += list(masks.values())
    table = [np.searchsorted(record["time"][s], time, side="right") for s in series]
    lines = [",".join(["time", "travel", "force"] + columns)]
    for k in range(len(time)):
        lines.append(",".join(["%.9g" % time[k], "%.9g" % travel[k], "%.9g" % force[k]]
                              + ["%d" % column[k] for column in table]))
    return "\n".join(lines) + "\n"


def _mark_moments(ax, moments, key):
    for m in moments:
        ax.axvline(m[key] * (1e3 if key == "travel" else 1.0), color="0.5", lw=0.8, ls=":")


def plot_counts(path, record, curve, moments):
    time, travel, force = curve
    fig, axes = plt.subplots(2, 2, figsize=(12, 8), sharey=True)
    for row, (key, values, label) in enumerate((("time", time, "time [s]"),
                                                ("travel", travel * 1e3, "platen travel [mm]"))):
        for col, (title, groups) in enumerate((
                ("by mode", [(name, record["mode"] == c, MODE_COLOURS[name])
                             for c, name in MODES.items()]),
                ("by family", [(name, record["family"] == c, colour) for (c, name), colour
                               in zip(FAMILIES.items(), ("tab:cyan", "tab:purple"))]))):
            ax = axes[row, col]
            ax.step(values, np.searchsorted(record["time"], time, side="right"), where="post",
                    color="k", lw=1.5, label="all (%d)" % len(record["time"]))
            for name, sel, colour in groups:
                if sel.any():
                    ax.step(values, np.searchsorted(record["time"][sel], time, side="right"),
                            where="post", color=colour, label="%s (%d)" % (name, sel.sum()))
            _mark_moments(ax, moments, key)
            twin = ax.twinx()
            twin.plot(values, force * 1e-3, color="0.6", lw=0.8)
            twin.set_ylabel("platen force [kN] (grey)")
            ax.set_xlabel(label)
            ax.set_ylabel("broken bonds, cumulative")
            ax.set_title("Broken bonds %s (dotted: moments)" % title)
            ax.legend(loc="upper left", fontsize=8)
            ax.grid(alpha=0.3)
    fig.tight_layout()
    save_atomically(fig, path)
    plt.close(fig)


def _outline(ax, geometry, view):
    """Body outline: layers in the side view (x-z), the plan rectangle in the plan view."""
    x0, length = geometry["x0"], geometry["length"]
    ax.axvspan(geometry["loadX"] - geometry["loadHalfLength"],
               geometry["loadX"] + geometry["loadHalfLength"], color="0.9", zorder=0)
    ax.axvline(geometry["loadX"], color="0.4", lw=0.8, ls="--")
    if view == "side":
        for lay in geometry["layers"]:
            ax.add_patch(plt.Rectangle((x0, lay["zBottom"]), length, lay["zTop"] - lay["zBottom"],
                                       fill=False, lw=1, color="k"))
            ax.text(x0 + 0.01 * length, lay["zTop"], lay["name"], fontsize=7, va="top")
        if "waterLevel" in geometry:
            ax.axhline(geometry["waterLevel"], color="tab:blue", lw=0.8, ls="-.")
        if geometry["layers"]:
            bottom = min(lay["zBottom"] for lay in geometry["layers"])
            for s in geometry["supports"]:
                ax.plot([s], [bottom], "k^", markersize=9, clip_on=False)
    else:
        ax.add_patch(plt.Rectangle((x0, geometry["y0"]), length, geometry["width"], fill=False,
                                   lw=1, color="k"))


def _set_limits(ax, record, geometry, coord):
    """The same limits at every moment: all broken bonds and the body outline."""
    xs, vs = list(record["x"]), list(record[coord])
    if geometry:
        xs += [geometry["x0"], geometry["x0"] + geometry["length"]]
        if coord == "y":
            vs += [geometry["y0"], geometry["y0"] + geometry["width"]]
        else:
            vs += [v for lay in geometry["layers"] for v in (lay["zBottom"], lay["zTop"])]
    for values, setter in ((xs, ax.set_xlim), (vs, ax.set_ylim)):
        if values:
            lo, hi = min(values), max(values)
            margin = 0.05 * (hi - lo) or 0.05
            setter(lo - margin, hi + margin)


def plot_moment(path, record, selected, geometry, title):
    fig, axes = plt.subplots(2, 1, figsize=(11, 8))
    for ax, (view, coord, label) in zip(axes, (("side", "z", "z [m]"), ("plan", "y", "y [m]"))):
        if geometry:
            _outline(ax, geometry, view)
        for mcode, mname in MODES.items():
            for fcode, fname in FAMILIES.items():
                sel = selected & (record["mode"] == mcode) & (record["family"] == fcode)
                if sel.any():
                    ax.scatter(record["x"][sel], record[coord][sel], s=10,
                               marker=FAMILY_MARKERS[fname], color=MODE_COLOURS[mname],
                               label="%s, %s bonds (%d)" % (mname, fname, sel.sum()))
        ax.set_aspect("equal")
        _set_limits(ax, record, geometry, coord)
        ax.set_xlabel("x [m]")
        ax.set_ylabel(label)
        ax.set_title("%s view (%s)%s" % (view, "x-z" if view == "side" else "x-y",
                                         "; grey: platen, dashed: load line, triangles: "
                                         "supports" if geometry else ""))
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, markerscale=1.5)
    fig.suptitle(title)
    fig.tight_layout()
    save_atomically(fig, path)
    plt.close(fig)


# --- the tool ----------------------------------------------------------------------------

def order_of_events(record, masks, moments, curve):
    """First break of each family, mode and region, and the moments, in time order."""
    time, travel, _ = curve
    events = []
    groups = ([("family " + n, record["family"] == c) for c, n in FAMILIES.items()]
              + [("mode " + n, record["mode"] == c) for c, n in MODES.items()]
              + [("region " + n, m) for n, m in masks.items()])
    for name, sel in groups:
        if sel.any():
            t = float(record["time"][sel][0])
            events.append({"event": "first break, " + name, "time_s": t,
                           "travel_m": float(np.interp(t, time, travel))})
    events += [{"event": "moment " + m["name"], "time_s": m["time"], "travel_m": m["travel"]}
               for m in moments]
    return sorted(events, key=lambda e: e["time_s"])


def bond_population(case):
    """{family: bonds in the case} from CASE/postProcessing/summary.json's ice_bonds and
    freeze_bonds, where the scene wrote them."""
    path = os.path.join(case, "postProcessing", "summary.json")
    try:
        with open(path) as f:
            summary = json.load(f)
    except (OSError, ValueError):
        return {}
    found = {family: summary.get(family + "_bonds") for family in FAMILIES.values()}
    return {family: n for family, n in found.items()
            if isinstance(n, int) and not isinstance(n, bool) and n > 0}


def broken_shares(counts, population):
    """Share of each family's bonds broken, and of the freeze-bonds broken in tension."""
    shares = {"broken_share_of_%s_bonds" % family: counts["family"][family] / n
              for family, n in population.items()}
    if "freeze" in population:
        shares["freeze_bonds_broken_in_tension_share_of_all_freeze_bonds"] = \
            counts["family_mode"]["freeze"]["tension"] / population["freeze"]
    return shares


def analyse(case, out, breakage, curve_path, geometry_path, extra_times, centre_half_width,
            interface_tolerance, rules=None, curve_columns=None, until=None):
    record = read_breakage(breakage)
    curve = read_curve(curve_path, curve_columns)
    if until is not None:
        record = {name: values[record["time"] <= until] for name, values in record.items()}
        curve = tuple(column[curve[0] <= until] for column in curve)
        if len(curve[0]) < 2:
            raise InputError(curve_path, "--until", "%g s leaves %d curve rows; needs at least two"
                             % (until, len(curve[0])))
    geometry = read_geometry(geometry_path) if geometry_path else None
    regions = assign_regions(record, geometry, centre_half_width, interface_tolerance)
    masks = region_masks(regions)
    moments, not_found = find_moments(*curve, extra_times)
    os.makedirs(out, exist_ok=True)

    write_atomically(os.path.join(out, "counts.csv"), counts_csv_text(record, masks, *curve))
    plot_counts(os.path.join(out, "counts.png"), record, curve, moments)
    population = bond_population(case)
    pvd = []
    for m in moments:
        selected = record["time"] <= m["time"]
        m["counts"] = count_bonds(record, masks, selected)
        m["freeze_bonds_broken_in_tension_fraction"] = freeze_tension_fraction(m["counts"])
        m.update(broken_shares(m["counts"], population))
        m["vtp"] = "moment_%s.vtp" % m["name"]
        m["png"] = "moment_%s.png" % m["name"]
        write_atomically(os.path.join(out, m["vtp"]), vtp_text(record, regions, selected))
        plot_moment(os.path.join(out, m["png"]), record, selected, geometry,
                    "Bonds broken up to %s: t = %.4g s, travel %.1f mm, force %.1f kN, %d bonds"
                    % (m["name"], m["time"], m["travel"] * 1e3, m["force"] * 1e-3,
                       m["counts"]["total"]))
        pvd.append((m["time"], m["vtp"]))
    write_atomically(os.path.join(out, "moments.pvd"), pvd_text(pvd))

    everything = np.ones(len(record["time"]), bool)
    totals = count_bonds(record, masks, everything)
    summary = {
        "case": os.path.abspath(case), "breakage_file": os.path.abspath(breakage),
        "curve_file": os.path.abspath(curve_path),
        "geometry_file": os.path.abspath(geometry_path) if geometry_path else None,
        "centre_half_width_m": centre_half_width, "interface_tolerance_m": interface_tolerance,
        "until_s": until,
        "point_data_codes": {"mode": {str(c): n for c, n in MODES.items()},
                             "family": {str(c): n for c, n in FAMILIES.items()},
                             "layer": dict({"-1": "outside"}, **{str(k): n for k, n in
                                                                 enumerate(regions["layerNames"])}),
                             "centreBand": {"-1": "no geometry", "0": "ends", "1": "centre"},
                             "interface": {"0": "no", "1": "CL-keel interface freeze-bond"}},
        "broken_bonds": totals["total"], "counts": totals,
        "freeze_bonds_broken_in_tension_fraction": freeze_tension_fraction(totals),
        "bonds_in_case": population,
        **broken_shares(totals, population),
        "moments": moments, "moments_not_found": not_found,
        "order_of_events": order_of_events(record, masks, moments, curve),
    }
    if geometry and (layer_of(geometry, CL) or layer_of(geometry, KEEL)):
        after = [m["time"] for m in moments if m["name"] == "halfLoadAfterPeak"]
        rules = rules or RidgeFailureRules(centreHalfWidth=centre_half_width,
                                           interfaceTolerance=interface_tolerance)
        result = classifyRidgeFailure(record, geometry, after[0] if after else None, rules)
        result["rules"] = dataclasses.asdict(rules)
        summary["ridge_failure"] = result
    write_atomically(os.path.join(out, "summary.json"), json.dumps(summary, indent=1) + "\n")
    return summary


def parse_times(text):
    try:
        times = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise InputError("command line", "-at", "needs times in s separated by commas, got '%s'"
                         % text)
    if not times or not all(math.isfinite(t) and t >= 0 for t in times):
        raise InputError("command line", "-at", "needs finite times >= 0, got '%s'" % text)
    return times


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     epilog=__doc__.split("\n\n", 1)[1],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", help="case directory")
    parser.add_argument("-at", "--at", default="", help="further moments: times t1,t2 [s]")
    parser.add_argument("--breakage", help="default CASE/postProcessing/breakage.h5")
    parser.add_argument("--curve", help="default CASE/postProcessing/platenForce.csv")
    parser.add_argument("--columns", metavar="TIME,TRAVEL,FORCE",
                        help="the curve's column names if not time, travel, force")
    parser.add_argument("--geometry", help="default CASE/postProcessing/geometry.json if present")
    parser.add_argument("--out", help="default CASE/postProcessing/failureAnalysis")
    parser.add_argument("--until", type=float, metavar="T",
                        help="leave out the breaks and curve rows after time T [s] (a run stopped by "
                             "a blow-up: the breaks of the sample it stopped in are the blow-up's)")
    parser.add_argument("--centre-half-width", type=float, default=0.25,
                        help="centre band |x - loadX| <= this [m] (default 0.25)")
    parser.add_argument("--interface-tolerance", type=float, default=0.05,
                        help="CL-keel interface: |z - CL bottom| <= this [m] (default 0.05)")
    args = parser.parse_args(argv)

    def in_case(path, default):
        return path if path else os.path.join(args.case, "postProcessing", default)

    try:
        if not os.path.isdir(args.case):
            raise InputError(args.case, "CASE_DIR", "not a directory")
        for name, value in (("--centre-half-width", args.centre_half_width),
                            ("--interface-tolerance", args.interface_tolerance)):
            if not (math.isfinite(value) and value > 0):
                raise InputError("command line", name, "must be a positive length [m]")
        if args.until is not None and not (math.isfinite(args.until) and args.until > 0):
            raise InputError("command line", "--until", "must be a positive time [s]")
        columns = args.columns.split(",") if args.columns else None
        if columns is not None and (len(columns) != 3 or not all(columns)):
            raise InputError("command line", "--columns", "needs three column names "
                             "TIME,TRAVEL,FORCE, got '%s'" % args.columns)
        geometry = args.geometry
        if geometry is None and os.path.exists(in_case(None, "geometry.json")):
            geometry = in_case(None, "geometry.json")
        summary = analyse(args.case, args.out or in_case(None, "failureAnalysis"),
                          in_case(args.breakage, "breakage.h5"),
                          in_case(args.curve, "platenForce.csv"), geometry,
                          parse_times(args.at) if args.at else [], args.centre_half_width,
                          args.interface_tolerance, curve_columns=columns, until=args.until)
    except InputError as error:
        sys.exit("failureAnalysis.py: %s" % error)
    counts = summary["counts"]
    print("failureAnalysis.py: %d broken bonds (%s; %s)"
          % (counts["total"], ", ".join("%s %d" % kv for kv in counts["mode"].items()),
             ", ".join("%s %d" % kv for kv in counts["family"].items())))
    for m in summary["moments"]:
        print("  %-18s t = %.4g s, travel %.1f mm, force %.1f kN: %d broken%s"
              % (m["name"], m["time"], m["travel"] * 1e3, m["force"] * 1e-3,
                 m["counts"]["total"], " (%s)" % m["note"] if "note" in m else ""))
    for name, why in summary["moments_not_found"].items():
        print("  %-18s not found: %s" % (name, why))
    if "ridge_failure" in summary:
        print("  ridge failure mode: %s" % summary["ridge_failure"]["mode"])
        for line in summary["ridge_failure"]["text"]:
            print("    " + line)
    print("  written to %s" % (args.out or in_case(None, "failureAnalysis")))


if __name__ == "__main__":
    main()
