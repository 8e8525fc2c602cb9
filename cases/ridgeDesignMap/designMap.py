#!/usr/bin/python3
"""The ridge design map (issue 21): the keels it needs, and the map drawn from the two studies.

  designMap.py keels [-quick] [-jobs N]   build the keels of studyDict: one rubble case per keel
                                          depth and packing (keels/keel<depth>_packing<packing>),
                                          settled and compacted (rubbleDEM on 2 ranks); a keel made
                                          from the same inputs is kept, one of other inputs made again
  designMap.py analyse [-quick]           the map from the tables of studyDict and layerAlone/studyDict
                                          (results/ or quick/): designMap.csv / .md / .json and the
                                          charts keelShare.png, failureModes.png
  designMap.py analyse -map DIR -layers DIR -out DIR
                                          the same from the tables (table.csv) in other folders (tests)
  designMap.py smoke                      checks that the case runs (./Allrun -smoke): a small keel
                                          (1.6 x 0.4 m, 0.25 m of rubble), the 10 cm layer alone and on
                                          it, 10 mm of travel, the map drawn; all in runs/smoke
  designMap.py resolution                 how far the map's (quick) resolution is from the default:
                                          ../ridgeFlexure's published quick and default matrices, the
                                          same 16 runs, failure force and keel share side by side
                                          (results/resolution.md, the README's block)

The keels are ../ridgeFlexure's quick keels (keels/keel1.0quick: 0.1 m spheres, one layer a block)
with the depth as the compacted rubble's thickness, the packing as the blocks' seed, and a box and
water deep enough for the depth. The keel's share of the strength is F_ridge / F_layer - 1 of the
same packing (a ridge of packing p against the layer alone of packing p), its uncertainty the spread
over the packings; each threshold ratio (keel depth over layer thickness where the share passes 25 %
and 50 %) is read off a least-squares line of the share in log(ratio) for each packing apart, and
reported as their mean and standard deviation.
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
sys.path.insert(0, os.path.join(TOP, "studies"))
import iceCases  # noqa: E402
import studyDict  # noqa: E402

KEEL_TEMPLATE = os.path.join(TOP, "cases", "ridgeFlexure", "keels", "keel1.0quick")
KEELS = os.path.join(HERE, "keels")
THRESHOLDS = (0.25, 0.5)
SETS_ORDER = ("2min", "4h", "ultimate")


def knob_values(study, name, quick):
    knob = next(k for k in study.knobs if k.name == name)
    return knob.quick if quick and knob.quick else knob.values


# ---------------------------------------------------------------------------- keels
def keel_box(depth):
    """Box height and water surface (m above the floor) for a keel of this depth: ../ridgeFlexure's
    0.94 / 0.9 m up to 0.5 m of rubble, and depth + 0.5 / depth + 0.35 m beyond (its 1.0 m keel's
    1.5 / 1.35 m), so that the floating keel keeps clear of the floor."""
    return (0.94, 0.9) if depth <= 0.5 else (depth + 0.5, depth + 0.35)


def prepare_keel(depth, packing):
    def make(folder):
        os.makedirs(folder)
        for sub in ("constant", "DEM"):
            shutil.copytree(os.path.join(KEEL_TEMPLATE, sub), os.path.join(folder, sub),
                                     ignore=shutil.ignore_patterns(
                                         "*.h5", "*.data", "*.restart.*", "variables.generated"))
        height, surface = keel_box(depth)
        rubble = os.path.join(folder, "constant", "rubbleProperties")
        iceCases.set_entry(rubble, "blocks.rubbleThickness", depth)
        iceCases.set_entry(rubble, "blocks.seed", packing)
        iceCases.set_entry(rubble, "box.height", height)
        iceCases.set_entry(os.path.join(folder, "constant", "couplingProperties"), "hydrostatic.surfaceLevel", surface)
    return make


def build_keel(depth, packing, ranks):
    """Settles and compacts one keel (as ../ridgeFlexure's Allrun, bin/caseCommon.sh build_keel)."""
    folder = iceCases.prepared_run(os.path.join(KEELS, f"keel{depth}_packing{packing}"),
                                   prepare_keel(float(depth), int(packing)))
    made = []
    if not os.path.exists(os.path.join(folder, "DEM", "settled.h5")):
        made.append("settled in %.0f s" % iceCases.run_app("rubbleDEM", folder, ranks, ["-stage", "settle"],
                                                           log_name="log.rubbleDEM"))
    if not os.path.exists(iceCases.keel_file(folder)):
        made.append("compacted in %.0f s" % iceCases.run_app("rubbleDEM", folder, ranks, ["-stage", "compact"],
                                                             log_name="log.compact"))
    print(f"keel {os.path.basename(folder)}: {', '.join(made) if made else 'kept (made from the same inputs)'}",
          flush=True)
    return folder


def keels(args):
    study = studyDict.read_study(HERE)
    wanted = [(d, p) for d in knob_values(study, "keelDepth", args.quick)
              for p in knob_values(study, "packing", args.quick)]
    # Settling is chaotic: the rank count is part of a keel's identity (2, as ../ridgeFlexure's keels).
    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs // 2)) as pool:
        for future in [pool.submit(build_keel, d, p, 2) for d, p in wanted]:
            future.result()
    return 0


# ---------------------------------------------------------------------------- the map
def read_table(path):
    if not os.path.exists(path):
        raise SystemExit(f"designMap: no table {path}: run ./Allrun{' -quick' if 'quick' in path else ''} first")
    with open(path) as f:
        return list(csv.DictReader(f))


def number(text):
    try:
        value = float(text)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def mean_sd(values):
    if not values:
        return None, None
    m = sum(values) / len(values)
    sd = math.sqrt(sum((v - m) ** 2 for v in values) / (len(values) - 1)) if len(values) > 1 else 0.0
    return m, sd


def crossing(points, level):
    """The ratio where a least-squares line of share against log(ratio) reaches `level`, or None
    (a line that does not rise); whether that ratio lies inside the points' range; and the
    standard deviation of the points about the line (how much the ratio alone leaves unexplained)."""
    xs = [math.log(r) for r, _ in points]
    ys = [s for _, s in points]
    if len(set(xs)) < 2:
        return None, False, None
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    residual = math.sqrt(sum((y - my - slope * (x - mx)) ** 2 for x, y in zip(xs, ys)) / max(1, len(xs) - 2))
    if slope <= 0:
        return None, False, residual
    ratio = math.exp(mx + (level - my) / slope)
    return ratio, min(xs) <= math.log(ratio) <= max(xs), residual


def analyse(args):
    sub = "quick" if args.quick else "results"
    ridge = read_table(os.path.join(args.map or os.path.join(HERE, sub), "table.csv"))
    alone = read_table(os.path.join(args.layers or os.path.join(HERE, "layerAlone", sub), "table.csv"))
    for r in ridge + alone:   # a study without packings is one packing
        r.setdefault("packing", "1")
    layer_force = {(float(r["layer"]), r["packing"]): number(r["failureForce"])
                   for r in alone if r["status"] == "done"}
    not_done = [r["point"] + ": " + (r["error"] or r["status"]) for r in ridge + alone if r["status"] != "done"]

    groups = {}
    for r in ridge:
        key = (float(r["keelDepth"]), float(r["layer"]), r["bondSet"])
        groups.setdefault(key, []).append(r)
    rows = []
    share_points = {}   # (set, packing) -> [(ratio, share)]
    for (depth, layer, bond_set), runs in sorted(groups.items(), key=lambda i: (SETS_ORDER.index(i[0][2]),
                                                                               i[0][0], i[0][1])):
        done = [r for r in runs if r["status"] == "done"]
        forces = [number(r["failureForce"]) * 1e-3 for r in done]
        d_eq = [number(r["equivalentThickness"]) for r in done if number(r["equivalentThickness"]) is not None]
        shares = []
        for r in done:
            f_layer = layer_force.get((layer, r["packing"])) if layer > 0 else None
            if f_layer:
                share = number(r["failureForce"]) / f_layer - 1.0
                shares.append(share)
                share_points.setdefault((bond_set, r["packing"]), []).append((depth / layer, share, layer))
        modes = {}
        for r in done:
            modes[r["mode"]] = modes.get(r["mode"], 0) + 1
        f_mean, f_sd = mean_sd(forces)
        s_mean, s_sd = mean_sd(shares)
        alone_kN = [layer_force[(layer, r["packing"])] * 1e-3 for r in done if (layer, r["packing"]) in layer_force]
        rows.append({
            "keel_depth_m": depth, "layer_m": layer, "bond_set": bond_set,
            "ratio": round(depth / layer, 3) if layer > 0 else "",
            "packings": len(done), "of": len(runs),
            "failure_force_kN": _r(f_mean, 3), "failure_force_sd_kN": _r(f_sd, 3),
            "layer_alone_kN": _r(mean_sd(alone_kN)[0], 3),
            "keel_share": _r(s_mean, 3), "keel_share_sd": _r(s_sd, 3),
            "equivalent_thickness_m": _r(mean_sd(d_eq)[0], 4), "equivalent_thickness_sd_m": _r(mean_sd(d_eq)[1], 4),
            "failure_mode": max(modes, key=modes.get) if modes else "",
            "modes": "; ".join(f"{m} {n}" for m, n in sorted(modes.items(), key=lambda i: -i[1])),
        })

    sets = [s for s in SETS_ORDER if any(k[0] == s for k in share_points)]
    thresholds = []
    # all layers, and without the thinnest (the 5 cm layer has smaller spheres: another resolution)
    thinnest = min((p[2] for pts in share_points.values() for p in pts), default=0.0)
    subsets = [("all", lambda layer: True)]
    if any(p[2] > thinnest for pts in share_points.values() for p in pts):
        subsets.append((f"without {thinnest * 100:g} cm", lambda layer: layer > thinnest))
    for bond_set, (subset, keep), level in ((b, which, lv) for b in sets for which in subsets for lv in THRESHOLDS):
        per_packing = []
        outside = []
        residuals = []
        for (s, packing), points in sorted(share_points.items()):
            if s != bond_set:
                continue
            ratio, inside, residual = crossing([(r, v) for r, v, layer in points if keep(layer)], level)
            if residual is not None:
                residuals.append(residual)
            if ratio is not None:
                per_packing.append(ratio)
                if not inside:
                    outside.append(packing)
        m, sd = mean_sd(per_packing)
        thresholds.append({"bond_set": bond_set, "layers": subset, "keel_share": level,
                           "ratio": _r(m, 2), "ratio_sd": _r(sd, 2),
                           "packings": len(per_packing),
                           "per_packing": ", ".join("%.2f" % v for v in per_packing),
                           "extrapolated_packings": ", ".join(outside),
                           "share_scatter_about_line": _r(mean_sd(residuals)[0], 3)})

    out = args.out or os.path.join(HERE, sub)
    write_outputs(out, rows, thresholds, not_done, share_points, sets, args.quick)
    print(f"designMap: {os.path.join(out, 'designMap.md')} (+ .csv, .json, keelShare.png, failureModes.png)")
    if not args.quick and not args.out:
        write_readme(rows, thresholds, not_done, ridge + alone, sets)
    return 0


def write_readme(rows, thresholds, not_done, points, sets):
    """The README's results block from the full map: thresholds, the keel's share on a grid, cost."""
    depths = sorted({r["keel_depth_m"] for r in rows})
    layers = sorted({r["layer_m"] for r in rows if r["layer_m"] > 0})
    text = ["| bond set | layers | share 25 % at depth / layer | share 50 % at depth / layer | per packing (25 %; 50 %) | "
            "share's scatter about the line |", "|---|---|---|---|---|---|"]
    for bond_set, subset in dict.fromkeys((x["bond_set"], x["layers"]) for x in thresholds):
        t = {x["keel_share"]: x for x in thresholds if x["bond_set"] == bond_set and x["layers"] == subset}

        def cell(level):
            x = t.get(level)
            if not x or x["ratio"] == "":
                return "not reached"
            flag = f" (extrapolated: packing {x['extrapolated_packings']})" if x["extrapolated_packings"] else ""
            return f"**{x['ratio']} +- {x['ratio_sd']}**{flag}"
        per = "; ".join(t[level]["per_packing"] if level in t else "" for level in THRESHOLDS)
        scatter = t[0.25]["share_scatter_about_line"] if 0.25 in t else ""
        text.append(f"| {bond_set} | {subset} | {cell(0.25)} | {cell(0.5)} | {per} | {scatter} |")
    for bond_set in sets:
        text += ["", f"Keel's share (mean +- sd over packings), set {bond_set}; rows: keel depth [m], columns: "
                     "layer [cm]; in brackets the failure force [kN] with no layer:", "",
                 "| depth | " + " | ".join(f"{l * 100:g} cm" for l in layers) + " | no layer |",
                 "|---|" + "---|" * (len(layers) + 1)]
        for d in depths:
            cells = []
            for l in layers:
                r = next((x for x in rows if x["bond_set"] == bond_set and x["keel_depth_m"] == d
                          and x["layer_m"] == l), None)
                cells.append(f"{r['keel_share']:+.2f} +- {r['keel_share_sd']:.2f}" if r and r["keel_share"] != "" else "-")
            bare = next((x for x in rows if x["bond_set"] == bond_set and x["keel_depth_m"] == d and x["layer_m"] == 0),
                        None)
            cells.append(f"({bare['failure_force_kN']} kN)" if bare and bare["failure_force_kN"] != "" else "-")
            text.append(f"| {d:g} | " + " | ".join(cells) + " |")
    walls = [number(p["wall_s"]) for p in points if p["status"] == "done" and number(p["wall_s"])]
    finished = sorted(p["finished_at"] for p in points if p.get("finished_at"))
    text += ["", f"{len(walls)} points (the layer alone and the ridge), sum of their wall times "
                 f"{sum(walls) / 3600:.1f} h on one core each, two at a time on 2 cores; finished "
                 f"{finished[0] if finished else '-'} to {finished[-1] if finished else '-'}."]
    if not_done:
        text += ["", f"{len(not_done)} points are not in the map (results/designMap.md lists them and why)."]
    text += ["", "![keel share](results/keelShare.png)", "", "![failure modes](results/failureModes.png)"]
    iceCases.write_readme_table(os.path.join(HERE, "README.md"), "design map results", "./Allrun",
                                "results/designMap.md", "\n".join(text), dated=True)


def _r(value, digits):
    return "" if value is None else round(value, digits)


def write_outputs(out, rows, thresholds, not_done, share_points, sets, quick):
    os.makedirs(out, exist_ok=True)
    columns = list(rows[0])
    lines = [",".join(columns)] + [",".join(('"%s"' % r[c]) if c in ("modes", "failure_mode") else str(r[c])
                                            for c in columns) for r in rows]
    iceCases.write_atomically(os.path.join(out, "designMap.csv"), "\n".join(lines) + "\n")
    md = [f"Ridge design map ({'quick' if quick else 'full'} study): ../ridgeFlexure at its quick resolution, "
          "clamped ends; failure force and equivalent thickness as mean over the packings (sd beside); "
          "keel_share = F_ridge / F_layer alone - 1, per packing, then mean (sd).", ""]
    md += ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    md += ["| " + " | ".join(str(r[c]) for c in columns) + " |" for r in rows]
    md += ["", "Keel depth over layer thickness where the keel's share passes 25 % and 50 % (a line of the share "
               "in log(ratio) for each packing; mean and sd over the packings; 'extrapolated' where a packing's "
               "crossing lies outside the ratios run):", ""]
    tcols = list(thresholds[0]) if thresholds else []
    if tcols:
        md += ["| " + " | ".join(tcols) + " |", "|" + "---|" * len(tcols)]
        md += ["| " + " | ".join(str(t[c]) for c in tcols) + " |" for t in thresholds]
    if not_done:
        md += ["", "Points not in the map (not finished, or failed):", ""] + [f"- {t}" for t in not_done]
    iceCases.write_atomically(os.path.join(out, "designMap.md"), "\n".join(md) + "\n")
    record = {"rows": rows, "thresholds": thresholds, "not_done": not_done,
              "git_revision": iceCases.git_revision(),
              "share_points": {f"{s}|{p}": pts for (s, p), pts in share_points.items()}}
    iceCases.write_atomically(os.path.join(out, "designMap.json"), json.dumps(record, indent=1) + "\n")
    plot_share(out, rows, thresholds, sets)
    plot_modes(out, rows, sets)


def plot_share(out, rows, thresholds, sets):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    colours = {"2min": "tab:blue", "4h": "tab:orange", "ultimate": "tab:green"}
    thinnest = min((r["layer_m"] for r in rows if r["layer_m"] > 0), default=0.0)
    for bond_set in sets:
        pts = [r for r in rows if r["bond_set"] == bond_set and r["keel_share"] != ""]
        pts.sort(key=lambda r: r["ratio"])
        for thin in (False, True):
            mine = [r for r in pts if (r["layer_m"] == thinnest) == thin]
            if mine:
                ax.errorbar([r["ratio"] for r in mine], [r["keel_share"] for r in mine],
                            yerr=[r["keel_share_sd"] or 0 for r in mine], fmt="o", ms=4, capsize=2,
                            mfc="none" if thin else None, color=colours.get(bond_set),
                            label=f"set {bond_set}" + (f", {thinnest * 100:g} cm layer (smaller spheres)" if thin else ""))
        drawn = [t for t in thresholds if t.get("layers", "all") != "all"] or thresholds   # the headline subset
        for t in drawn:
            if t["bond_set"] == bond_set and t["ratio"] != "":
                ax.errorbar([t["ratio"]], [t["keel_share"]], xerr=[t["ratio_sd"] or 0], fmt="D", ms=7,
                            mfc="none", color=colours.get(bond_set), capsize=3)
    for level in THRESHOLDS:
        ax.axhline(level, color="grey", lw=0.7, ls="--")
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xscale("log")
    ax.set_yscale("symlog", linthresh=1.0)   # linear to 1, where the thresholds are; the 5 cm row above
    ax.set_ylim(bottom=-0.2)
    ax.set_xlabel("keel depth / layer thickness")
    ax.set_ylabel("keel's share: F_ridge / F_layer alone - 1")
    ax.set_title("Where the keel starts to matter (diamonds: the 25 % and 50 % ratios without the thinnest layer, "
                 "sd over packings)", fontsize=8)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    iceCases.save_figure(fig, os.path.join(out, "keelShare.png"))


def plot_modes(out, rows, sets):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    depths = sorted({r["keel_depth_m"] for r in rows})
    layers = sorted({r["layer_m"] for r in rows})
    modes = sorted({r["failure_mode"] for r in rows if r["failure_mode"]})
    cmap = plt.get_cmap("tab10")
    colour = {m: cmap(i % 10) for i, m in enumerate(modes)}
    fig, axes = plt.subplots(1, len(sets), figsize=(4.6 * len(sets), 4.0), squeeze=False)
    for ax, bond_set in zip(axes[0], sets):
        for r in rows:
            if r["bond_set"] != bond_set or not r["failure_mode"]:
                continue
            x, y = depths.index(r["keel_depth_m"]), layers.index(r["layer_m"])
            ax.add_patch(plt.Rectangle((x - 0.5, y - 0.5), 1, 1, color=colour[r["failure_mode"]], alpha=0.55))
            force = r["failure_force_kN"]
            ax.text(x, y, f"{force:.1f} kN" if force != "" else "", ha="center", va="center", fontsize=7)
        ax.set_xlim(-0.5, len(depths) - 0.5)
        ax.set_ylim(-0.5, len(layers) - 0.5)
        ax.set_xticks(range(len(depths)))
        ax.set_xticklabels([f"{d:g}" for d in depths])
        ax.set_yticks(range(len(layers)))
        ax.set_yticklabels([f"{l * 100:g}" for l in layers])
        ax.set_xlabel("keel depth [m]")
        ax.set_ylabel("layer [cm]")
        ax.set_title(f"set {bond_set}: failure mode (most packings), force", fontsize=9)
    handles = [plt.Rectangle((0, 0), 1, 1, color=colour[m], alpha=0.55) for m in modes]
    axes[0][-1].legend(handles, modes, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, title="mode",
                       title_fontsize=8)
    iceCases.save_figure(fig, os.path.join(out, "failureModes.png"))


SMOKE_STUDY = """study {{ case ridgeFlexure; application ridgeDEM; ranks 1; arguments (-stage all); {post} }}
knobs
{{
{knobs}
}}
set
{{
    "constant/ridgeProperties:box.length" 1.6;
    "constant/ridgeProperties:box.width" 0.4;
    "constant/ridgeProperties:consolidatedLayer.particleDiameter" 0.075;
    "constant/ridgeProperties:test.speed" 0.2;
    "constant/ridgeProperties:test.settleTime" 0.05;
    "constant/ridgeProperties:assembly.relaxTime" 0.1;
    "constant/ridgeProperties:assembly.pressSpeed" 0.05;
    "system/controlDict:writeInterval" 1;
    "system/controlDict:maxTravel" 0.01;
    "system/controlDict:minTravel" 0;
    {extra}
}}
figures {{ failureForce peak_force_N; equivalentThickness equivalent_thickness_m; {figures} }}
reference {{ type none; }}
"""


def smoke(args):
    """The case's pieces on a small keel: the chain's status, a keel, both studies, the map."""
    folder = os.path.join(HERE, "runs", "smoke")
    shutil.rmtree(folder, ignore_errors=True)
    subprocess.run([sys.executable, os.path.join(HERE, "chain.py"), "status"], check=True)
    keel = os.path.join(folder, "map", "keels", "keel0.25")

    prepare_keel(0.25, 1)(keel)
    iceCases.smoke_keel(os.path.join(keel, "constant", "rubbleProperties"))
    iceCases.run_app("rubbleDEM", keel, 1, ["-stage", "settle"], log_name="log.rubbleDEM")
    iceCases.run_app("rubbleDEM", keel, 1, ["-stage", "compact"], log_name="log.compact")
    layer = "layer { entry constant/ridgeProperties:consolidatedLayer.thickness; values (0.10); }"
    studies = {
        "layerAlone": SMOKE_STUDY.format(post="", knobs=layer, figures="",
                                         extra='"constant/ridgeProperties:keel.settledRubble" none;'),
        "map": SMOKE_STUDY.format(
            post='postProcess ("postProcessing/failureAnalysis.py");',
            knobs='keelDepth { entry constant/ridgeProperties:keel.settledRubble; '
                  'template "${STUDY}/keels/keel${keelDepth}/DEM/compacted.h5"; values (0.25); }\n' + layer
                  + '\nbondSet { entry constant/freezeBondProperties:fixedSetCoeffs.set; values (4h); }',
            figures='mode "failureAnalysis/summary.json:ridge_failure.mode";', extra=""),
    }
    for name, text in studies.items():
        os.makedirs(os.path.join(folder, name), exist_ok=True)
        iceCases.write_atomically(os.path.join(folder, name, "studyDict"), text)
        subprocess.run([sys.executable, os.path.join(TOP, "studies", "runStudy.py"), os.path.join(folder, name)],
                       check=True)
    return analyse(argparse.Namespace(quick=True, map=os.path.join(folder, "map", "results"),
                                      layers=os.path.join(folder, "layerAlone", "results"), out=folder))


def resolution(args):
    folder = os.path.join(TOP, "cases", "ridgeFlexure", "results")
    quick = {r["run"]: r for r in read_table(os.path.join(folder, "ridgeMatrix_quick.csv"))}
    # the default resolution on the quick matrix's kind of keel (softened), so that only the resolution differs
    default = {r["run"]: r for r in read_table(os.path.join(folder, "ridgeMatrix_default_softened.csv"))}

    def share(r):
        alone = number(r["layer_alone_kN"])
        return number(r["failure_force_kN"]) / alone - 1 if alone else None
    lines = ["| run | keel [m] | set | layer [cm] | force quick / default [kN] | ratio | keel share quick / default |",
             "|---|---|---|---|---|---|---|"]
    ratios, shifts = [], []
    for run in sorted(quick, key=int):
        q, d = quick[run], default[run]
        fq, fd = number(q["failure_force_kN"]), number(d["failure_force_kN"])
        ratios.append(fq / fd)
        sq, sd = share(q), share(d)
        if sq is not None and sd is not None:
            shifts.append(sq - sd)
        shares = f"{sq:+.2f} / {sd:+.2f}" if sq is not None and sd is not None else "-"
        lines.append(f"| {run} | {q['keel_m']} | {q['bond_set']} | {q['CL_cm']} | {fq:.2f} / {fd:.2f} | "
                     f"{fq / fd:.2f} | {shares} |")
    shifts.sort()
    median = shifts[len(shifts) // 2] if len(shifts) % 2 else 0.5 * (shifts[len(shifts) // 2 - 1] + shifts[len(shifts) // 2])
    summary = (f"The quick resolution's failure forces are {min(ratios):.2f} to {max(ratios):.2f} times the default's "
               f"(median {sorted(ratios)[len(ratios) // 2]:.2f}); its keel share differs from the default's by "
               f"{shifts[0]:+.2f} to {shifts[-1]:+.2f} (median {median:+.2f}) over the {len(shifts)} runs with a layer. "
               "The quick resolution is not within 10 % of the default: the map shows the trends of the model at "
               "the quick resolution, and its threshold ratios are biased low by the keel's larger share there.")
    text = "\n".join(lines) + "\n\n" + summary + "\n"
    out = os.path.join(HERE, "results")
    os.makedirs(out, exist_ok=True)
    iceCases.write_atomically(os.path.join(out, "resolution.md"), text)
    iceCases.write_readme_table(os.path.join(HERE, "README.md"), "resolution check", "designMap.py resolution",
                                "../ridgeFlexure/results/ridgeMatrix_quick.csv, ridgeMatrix_default_softened.csv", text)
    print(summary)
    return 0


def main(argv):
    parser = argparse.ArgumentParser(prog="designMap.py", description=__doc__.split("\n\n")[0])
    parser.add_argument("step", choices=("keels", "analyse", "resolution", "smoke"))
    parser.add_argument("-quick", action="store_true")
    parser.add_argument("-jobs", type=iceCases.whole_number(1, 64), default=2)
    parser.add_argument("-map", help="analyse: the folder of the map's table.csv")
    parser.add_argument("-layers", help="analyse: the folder of the layers' table.csv")
    parser.add_argument("-out", help="analyse: where the map goes")
    args = parser.parse_args(argv)
    return {"keels": keels, "analyse": analyse, "resolution": resolution, "smoke": smoke}[args.step](args)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
