#!/usr/bin/python3
"""The speed-accuracy page (issue 20 item 3): every scene's study in one static HTML page, with one
summary chart of each scene's default configuration and its cheapest configuration within the
scene's tolerance, and the measured stability limits beside them.

usage: speedAccuracy.py run [-quick] [-jobs N] [-work DIR] [-out FOLDER]   every scene's study, then build
       speedAccuracy.py [build] [-quick] [-work DIR] [-out FOLDER] [-readme]   the page from the studies' tables
       speedAccuracy.py check PAGE [-screenshot PNG]      opens PAGE in headless Chromium and checks it

run runs each scene's study of SCENES in turn (studies/runStudy.py STUDY -jobs: N divided by the
cores a point takes), finished points skipped; -quick runs each study's quick ladder (tables in
studies/<study>/quick/, the page then in studies/speedAccuracy/quick/; 26 points, 8 min 47 s on
2 cores with the keels built, 2026-11-28); -work DIR runs them in
DIR/<study> instead, away from the committed studies' runs (a fresh ladder, timed whole).

build (the default) reads each runner study's results/table.csv (studies/<study>/, SCENES below),
the cases' own ladders and the measurement scripts' tables (EXTRAS), and writes into -out (default
studies/speedAccuracy): index.html (images linked by relative paths, no server), summary.png,
summary.csv and summary.md. -readme also rewrites the top README's block between
`<!-- speed accuracy table -->` and `<!-- end speed accuracy table -->` from summary.md.

check opens the page in Chromium (headless, as a user's browser would render it), counts the
images that loaded and the tables it drew, and takes a screenshot; exit 1 when an image is
missing, a scene has no section or the screenshot is blank.

The cheapest configuration within tolerance: the point with the least wall time whose every judged
figure is within the scene's tolerance of its reference (the measurement, the analytic answer, or
the study's finest point). The seed scatter, where the study measured it, is shown beside: a
tolerance below it cannot be told from the packing's own share of the error on one seed."""
import argparse
import csv
import datetime
import html
import io
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402

# scene, the runner study (studies/<folder>), tolerance, the figures judged against the reference,
# and where the case's default is not a point of the study, its committed run: (summary, {figure: key},
# configuration)
BEAM_DEFAULT = ("cases/levelIceBeam/results/summary_13000.json",
                {"slope": "elastic_slope_N_per_m", "firstPeak": "first_peak_force_N"},
                "particles 13000, platenSpeed 0.1 (the case's committed run)")
SCENES = (
    ("Level-ice beam (scenes.md 1)", "levelIceBeamQuick", 0.05, ("slope", "firstPeak"), BEAM_DEFAULT),
    ("Level-ice beam: time step x damping", "levelIceBeamTimeStep", 0.05, ("slope", "firstPeak")),
    ("Three-point bending (scenes.md 2)", "threePointBending", 0.05, ("strength",)),
    ("Freeze-bond tension (scenes.md 3)", "freezeBondTension", 0.05, ("slope30", "slope180")),
    ("Freeze-bond shear: the calibration sweep (scenes.md 4)", "freezeBondShear", 0.05, ("slope", "strength")),
    ("Rubble beam: settling (scenes.md 5)", "rubbleBeam", 0.05, ("aboveWater",)),
    ("Rubble punch: the cuboid keel's first 30 mm (scenes.md 6)", "rubblePunch", 0.05, ("peakForce",)),
    ("Rubble punch: inertia scaling at 5 mm/s, the first 30 mm (scenes.md 6)", "rubblePunchInertia", 0.05,
     ("peakForce",)),
    ("Ridge flexure: run 6, quick and default resolution (scenes.md 7)", "ridgeFlexure", 0.05, ("failureForce",)),
    ("Keel-to-layer bond (scenes.md 8)", "keelBond", 0.05, ("pullUp", "shear")),
    ("Floating block: the water level (scenes.md 9)", "floatingBlock", 0.01, ("submerged",)),
    ("Settling sphere (scenes.md 9)", "sphereSettling", 0.01, ("terminalVelocity", "worstDeviation=self")),
)

# the ladders and maps made by other scripts: title, markdown table(s), chart(s), what it is
EXTRAS = (
    ("Rubble punch: loading rate (the case's rate study)", (),
     (), "cases/rubblePunch/studies/rateStudy.csv",
     "`cases/rubblePunch/studies/rateStudy.py`: the reduced keel at 0.05-0.005 m/s; the case's own ladder, "
     "not yet a runner study."),
    ("Ridge flexure: loading rate (the case's rate study)", ("cases/ridgeFlexure/results/rateConvergence_quick_run06.md",),
     ("cases/ridgeFlexure/results/rateConvergence_quick_run06.png",), None,
     "`cases/ridgeFlexure/studies/rateConvergence.py`: matrix run 6 at the quick resolution, three packings at "
     "the slower speeds; the case's own ladder, not yet a runner study."),
    ("Inertia scaling: the beam, bending, punch and ridge at factors 1-100", ("results/inertiaScaling/inertiaScaling.md",),
     ("results/inertiaScaling/speedAccuracy.png", "results/inertiaScaling/inertiaScaling.png"), None,
     "`postProcessing/inertiaScalingStudy.py`."),
    ("Which water level", ("studies/waterLevels/results/waterLevels.md",), ("studies/waterLevels/results/waterLevels.png",),
     None, "`studies/waterLevels/waterLevelChart.py`: each scene at each water level, its error and cost "
     "(the floating block's Archimedes check is here)."),
    ("Stability map (a): time step against damping", ("studies/stabilityMap/results/stabilityMap.md",),
     ("studies/stabilityMap/results/stabilityMap.png",), None, "`studies/stabilityMap/stabilityMap.py`."),
    ("Stability map (b): coupling time against scheme and cell size", ("studies/stabilityMap/results/couplingMap.md",),
     ("studies/stabilityMap/results/couplingMap.png",), None, "`studies/stabilityMap/couplingMap.py`."),
    ("Stability map (c): loading rate against kinetic energy", ("studies/stabilityMap/results/rateMap.md",),
     ("studies/stabilityMap/results/rateMap.png",), None, "`studies/stabilityMap/rateMap.py`."),
    ("Cost on more ranks", ("studies/rankSpeedup/results/rankSpeedup.md", "studies/scaling/results/weakScaling.md"),
     (), None, "`studies/rankSpeedup`, `studies/scaling`."),
)

# scenes without a runner study yet, and why (shown on the page): none now
MISSING = ()

README_BEGIN, README_END = "<!-- speed accuracy table -->", "<!-- end speed accuracy table -->"


# ---------------------------------------------------------------------------- reading
def _float(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return float("nan")


def tables_folder(study, quick=False, work=None):
    """Where a study's table and chart are: studies/<study>/results (quick/ for -quick), or under -work."""
    return os.path.join(work or os.path.join(TOP, "studies"), study, "quick" if quick else "results")


def read_table(folder):
    path = os.path.join(folder, "table.csv")
    if not os.path.isfile(path):
        return None
    with open(path) as f:
        return list(csv.DictReader(f))


def knob_names(rows):
    """The knob columns: those before `status` but `point`, and the scatter's seed column."""
    columns = list(rows[0])
    return [c for c in columns[1:columns.index("status")] if c not in ("is_scatter",)]


def configuration(row, knobs):
    if "config" in row:
        return row["config"]
    return ", ".join(f"{k} {row[k]}" for k in knobs if row.get(k, "") != "")


def figure_error(row, figure):
    """A figure's relative error; `name=self` is a figure that is itself a relative error (the
    sphere's largest deviation from the ODE over the settling)."""
    name, _, how = figure.partition("=")
    return _float(row.get(name)) if how == "self" else _float(row.get(name + "_error"))


def judged_names(figures):
    return ", ".join(f.replace("=self", " (itself an error)") for f in figures)


def judged_error(row, figures):
    """The largest |error| over the judged figures (None when a figure has no error)."""
    errors = [figure_error(row, f) for f in figures]
    if any(e != e for e in errors):
        return None
    return max(abs(e) for e in errors)


def committed_default(rows, figures, external):
    """The case's committed run as a row of the study's table, its errors against the study's
    reference (each figure's reference recovered from a finished row: value / (1 + error))."""
    path, keys, config = external
    summary = json.load(open(os.path.join(TOP, path)))
    row = {"point": config, "is_case_default": "1", "is_scatter": "0", "status": "done", "config": config,
           "wall_s": str(summary["wall_s"]), "ranks": str(summary.get("ranks", 1)), "error": "",
           "particle_steps_per_s": str(summary.get("particle_steps_per_s", "nan")), "peak_rss_MiB": "nan"}
    for f in figures:
        ref = next((_float(r[f]) / (1 + _float(r[f + "_error"])) for r in rows
                    if r["status"] == "done" and _float(r[f + "_error"]) == _float(r[f + "_error"])), float("nan"))
        row[f] = str(summary[keys[f]])
        row[f + "_error"] = str(summary[keys[f]] / ref - 1)
    return row


def scene_summary(title, folder, tolerance, figures, external_default=None, tables=None):
    rows = read_table(tables)
    out = {"scene": title, "study": folder, "tolerance": tolerance, "figures": figures, "rows": rows,
           "tables": tables}
    if not rows:
        return out
    knobs = knob_names(rows)
    done = [r for r in rows if r["status"] == "done" and r.get("is_scatter", "0") != "1"
            and judged_error(r, figures) is not None]
    default = next((r for r in rows if r.get("is_case_default") == "1"), None)
    if default is None and external_default:
        default = committed_default(rows, figures, external_default)
    good = [r for r in done if judged_error(r, figures) <= tolerance]
    cheapest = min(good, key=lambda r: _float(r["wall_s"])) if good else None
    best = min(done, key=lambda r: judged_error(r, figures)) if done else None
    scatter = {f: _float(rows[0].get(f + "_scatter")) for f in figures if f + "_scatter" in rows[0]}
    out.update(knobs=knobs, default=default, cheapest=cheapest, best=best, scatter=scatter,
               reference=rows[0].get("reference", ""), points=len([r for r in rows if r["status"] == "done"]),
               revision=sorted({r["git_revision"] for r in rows if r["git_revision"]}),
               finished=max((r["finished_at"] for r in rows if r["finished_at"]), default=""))
    return out


# ---------------------------------------------------------------------------- writing
def fmt_pct(x):
    return "-" if x is None or x != x else f"{100 * x:.1f} %"


def fmt_wall(x):
    x = _float(x)
    if x != x:
        return "-"
    return f"{x:.0f} s" if x < 120 else f"{x / 60:.1f} min"


def summary_rows(scenes):
    out = []
    for s in scenes:
        if not s.get("rows"):
            out.append({"scene": s["scene"], "note": f"studies/{s['study']}: not run yet"})
            continue
        d, c, b = s["default"], s["cheapest"], s["best"]
        row = {"scene": s["scene"], "study": s["study"], "tolerance": s["tolerance"],
               "judged": judged_names(s["figures"])}
        scatter = [v for v in s["scatter"].values() if v == v]
        if scatter:
            row["scatter"] = max(scatter)
        if d:
            row.update(default=configuration(d, s["knobs"]), default_wall_s=_float(d["wall_s"]),
                       default_error=judged_error(d, s["figures"]))
        if c:
            row.update(cheapest=configuration(c, s["knobs"]) + (" (the reference)" if c.get("is_reference") == "1" else ""),
                       cheapest_wall_s=_float(c["wall_s"]),
                       cheapest_error=judged_error(c, s["figures"]), cheapest_cores=c["ranks"])
        elif b:
            row.update(best=configuration(b, s["knobs"]), best_wall_s=_float(b["wall_s"]),
                       best_error=judged_error(b, s["figures"]))
        if d and c:
            row["speedup"] = _float(d["wall_s"]) / _float(c["wall_s"])
        out.append(row)
    return out


def write_summary(rows, folder):
    columns = ["scene", "study", "tolerance", "judged", "scatter", "default", "default_wall_s", "default_error", "cheapest",
               "cheapest_wall_s", "cheapest_error", "cheapest_cores", "speedup", "best", "best_wall_s", "best_error",
               "note"]
    table = io.StringIO()
    writer = csv.DictWriter(table, columns, lineterminator="\n")
    writer.writeheader()
    for r in rows:
        writer.writerow({c: "%.4g" % r[c] if isinstance(r.get(c), float) else r.get(c, "") for c in columns})
    iceCases.write_atomically(os.path.join(folder, "summary.csv"), table.getvalue())
    md = ["| scene | tolerance (judged) | seed scatter (1 sd) | case default | its wall, worst error | "
          "cheapest within tolerance | its wall, worst error, cores | default / cheapest |",
          "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if "note" in r:
            md.append(f"| {r['scene']} | {r['note']} | | | | | | |")
            continue
        default = r.get("default", "not in the study")
        dw = f"{fmt_wall(r.get('default_wall_s'))}, {fmt_pct(r.get('default_error'))}" if "default" in r else "-"
        if "cheapest" in r:
            cheap = r["cheapest"]
            cw = f"{fmt_wall(r['cheapest_wall_s'])}, {fmt_pct(r['cheapest_error'])}, {r['cheapest_cores']}"
        else:
            cheap = f"none within {fmt_pct(r['tolerance'])}; least error: {r.get('best', '-')}"
            cw = f"{fmt_wall(r.get('best_wall_s'))}, {fmt_pct(r.get('best_error'))}"
        sp = f"{r['speedup']:.1f} x" if "speedup" in r else "-"
        md.append(f"| {r['scene']} | {fmt_pct(r['tolerance'])} ({r['judged']}) | {fmt_pct(r.get('scatter'))} | "
                  f"{default} | {dw} | {cheap} | {cw} | {sp} |")
    text = "\n".join(md) + "\n"
    iceCases.write_atomically(os.path.join(folder, "summary.md"), text)
    return text


def plot_summary(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    rows = [r for r in rows if "note" not in r]
    fig, ax = plt.subplots(figsize=(8.5, 0.55 * len(rows) + 1.4))
    for i, r in enumerate(rows):
        y = len(rows) - 1 - i
        if "default_wall_s" in r:
            ax.scatter([r["default_wall_s"]], [y], marker="*", s=140, color="red", zorder=3,
                       label="case default" if i == 0 else None)
            ax.annotate(fmt_pct(r.get("default_error")), (r["default_wall_s"], y), xytext=(6, 5),
                        textcoords="offset points", fontsize=7, color="red")
        key = "cheapest_wall_s" if "cheapest_wall_s" in r else "best_wall_s"
        if key in r:
            ok = key == "cheapest_wall_s"
            ax.scatter([r[key]], [y], marker="o", s=50, color="tab:green" if ok else "tab:grey", zorder=3,
                       label=("cheapest within tolerance" if ok else "least error (none within tolerance)"))
            err = r.get("cheapest_error" if ok else "best_error")
            ax.annotate(fmt_pct(err), (r[key], y), xytext=(6, -11), textcoords="offset points", fontsize=7,
                        color="tab:green" if ok else "tab:grey")
            if "default_wall_s" in r:
                ax.plot([r[key], r["default_wall_s"]], [y, y], color="0.7", lw=1, zorder=1)
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels([f"{r['scene']} (±{100 * r['tolerance']:g} %)" for r in reversed(rows)], fontsize=8)
    ax.set_xscale("log")
    walls = [r[k] for r in rows for k in ("default_wall_s", "cheapest_wall_s", "best_wall_s") if k in r]
    if walls:
        ax.set_xlim(min(walls) / 3, max(walls) * 3)
    ax.set_ylim(-0.7, len(rows) - 0.3)
    ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda x, _: f"{x:g}"))
    ax.set_xlabel("wall time of one point [s] (labels: the largest error of the judged figures)", fontsize=8)
    handles, labels = ax.get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    ax.legend(unique.values(), unique.keys(), fontsize=7, loc="lower right")
    ax.grid(axis="x", which="both", color="0.92")
    ax.set_title("Each scene: its default configuration and the cheapest within its tolerance", fontsize=9)
    fig.tight_layout()
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=80)
    plt.close(fig)
    os.replace(tmp, path)


_INLINE = ((re.compile(r"\*\*(.+?)\*\*"), r"<b>\1</b>"), (re.compile(r"`([^`]+)`"), r"<code>\1</code>"))


def inline(text):
    text = html.escape(text, quote=False)
    for pattern, repl in _INLINE:
        text = pattern.sub(repl, text)
    return text


def markdown_html(text):
    """The subset of Markdown the tables here are written in: pipe tables, paragraphs, bullets, headings."""
    out, table, para, items = [], [], [], []

    def flush():
        if table:
            head, body = table[0], [r for r in table[2:]]
            out.append("<table><tr>" + "".join(f"<th>{inline(c)}</th>" for c in head) + "</tr>"
                       + "".join("<tr>" + "".join(f"<td>{inline(c)}</td>" for c in r) + "</tr>" for r in body)
                       + "</table>")
            table.clear()
        if para:
            out.append("<p>" + inline(" ".join(para)) + "</p>")
            para.clear()
        if items:
            out.append("<ul>" + "".join(f"<li>{inline(i)}</li>" for i in items) + "</ul>")
            items.clear()
    for line in text.splitlines():
        s = line.strip()
        if s.startswith("|"):
            if para or items:
                flush()
            table.append([c.strip() for c in s.strip("|").split("|")])
        elif not s or s.startswith("<!--"):
            flush()
        elif s.startswith("#"):
            flush()
            out.append(f"<h4>{inline(s.lstrip('#').strip())}</h4>")
        elif s.startswith("- "):
            if table or para:
                flush()
            items.append(s[2:])
        elif items and line.startswith("  "):
            items[-1] += " " + s
        else:
            if table:
                flush()
            para.append(s)
    flush()
    return "\n".join(out)


def csv_html(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return markdown_html("\n".join("| " + " | ".join(r) + " |" + ("\n|" + "---|" * len(r) if i == 0 else "")
                                   for i, r in enumerate(rows)))


def table_of_points(s):
    rows, figures = s["rows"], [k for k in s["rows"][0] if k + "_error" in s["rows"][0]]
    head = ["point"] + [f"{f} (error)" for f in figures] + ["wall", "particle-steps/s", "peak RSS MiB", "status"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        cells = [("**" + configuration(r, s["knobs"]) + "** (default)") if r.get("is_case_default") == "1"
                 else configuration(r, s["knobs"]) + (" (seed)" if r.get("is_scatter") == "1" else "")]
        for f in figures:
            v, e = _float(r[f]), _float(r[f + "_error"])
            cells.append("-" if v != v else f"{v:.4g}" + ("" if e != e else f" ({100 * e:+.1f} %)"))
        pss = _float(r["particle_steps_per_s"])
        cells += [fmt_wall(r["wall_s"]), "-" if pss != pss else f"{pss:.3g}",
                  "-" if r["peak_rss_MiB"] in ("", "nan") else f"{_float(r['peak_rss_MiB']):.0f}",
                  r["status"] + (": " + r["error"][:80] if r["error"] else "")]
        lines.append("| " + " | ".join(c.replace("|", "/") for c in cells) + " |")
    return markdown_html("\n".join(lines))


PAGE_SCRIPT = """<script>
window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.images);
  document.body.setAttribute('data-images', imgs.length);
  document.body.setAttribute('data-images-loaded', imgs.filter(function (i) { return i.complete && i.naturalWidth > 0; }).length);
  document.body.setAttribute('data-tables', document.querySelectorAll('table').length);
  document.body.setAttribute('data-scenes', document.querySelectorAll('section.scene').length);
});
</script>"""

STYLE = """<style>
body { font-family: sans-serif; max-width: 1250px; margin: 1em auto; color: #222; }
table { border-collapse: collapse; font-size: 12px; margin: 0.5em 0 1em; }
th, td { border: 1px solid #ccc; padding: 2px 6px; text-align: left; }
th { background: #eef; } img { max-width: 100%; border: 1px solid #ddd; }
section { border-top: 2px solid #88a; margin-top: 1.5em; } code { background: #f4f4f4; }
.note { color: #555; font-size: 13px; }
</style>"""


def write_page(scenes, summary_md, out):
    def img(rel):
        path = os.path.relpath(os.path.join(TOP, rel), out)   # rel may be absolute: join keeps it
        return f'<p><img src="{html.escape(path)}" alt="{html.escape(rel)}"></p>'
    now = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>iceRidgeSim: speed against accuracy</title>",
             STYLE, "</head><body>", "<h1>Speed against accuracy, and where each method fails</h1>",
             f"<p class='note'>Written by <code>studies/speedAccuracy/speedAccuracy.py</code> on {now} at revision "
             f"{html.escape(iceCases.git_revision())} from the committed tables; every chart links to its study. "
             "Wall times are one point's on this shared 2-core machine (ratios hold, absolute times drift).</p>",
             "<h2>Summary</h2>", '<p><img src="summary.png" alt="summary"></p>', markdown_html(summary_md)]
    for s in scenes:
        parts.append(f"<section class='scene' id='{s['study']}'><h2>{html.escape(s['scene'])}</h2>")
        if not s.get("rows"):
            parts.append(f"<p>studies/{s['study']}: not run yet.</p></section>")
            continue
        scatter = ", ".join(f"{f} {100 * v:.2g} %" for f, v in s["scatter"].items() if v == v)
        parts.append(f"<p class='note'>Study <code>studies/{s['study']}</code> ({s['points']} points, "
                     f"finished {s['finished']}, revision {', '.join(s['revision'])}); reference: "
                     f"{html.escape(s['reference'])}; tolerance {100 * s['tolerance']:g} % on "
                     f"{judged_names(s['figures'])}" + (f"; seed scatter (relative sd) {scatter}" if scatter else "")
                     + ".</p>")
        parts.append(img(os.path.join(s["tables"], "study.png")))
        parts.append(table_of_points(s))
        parts.append("</section>")
    if MISSING:
        parts.append("<section class='extra'><h2>Scenes without a runner study</h2>" + markdown_html(
            "\n".join(f"- **{title}**: {why}." for title, why in MISSING)) + "</section>")
    for title, tables, charts, csv_file, what in EXTRAS:
        parts.append(f"<section class='extra'><h2>{html.escape(title)}</h2><p class='note'>{inline(what)}</p>")
        for t in tables:
            if os.path.isfile(os.path.join(TOP, t)):
                parts.append(markdown_html(open(os.path.join(TOP, t)).read()))
        if csv_file and os.path.isfile(os.path.join(TOP, csv_file)):
            parts.append(csv_html(os.path.join(TOP, csv_file)))
        for c in charts:
            if os.path.isfile(os.path.join(TOP, c)):
                parts.append(img(c))
        parts.append("</section>")
    parts += [PAGE_SCRIPT, "</body></html>"]
    iceCases.write_atomically(os.path.join(out, "index.html"), "\n".join(parts) + "\n")


def run(args):
    """Each scene's study in turn, then the page; the exit status of the worst study."""
    sys.path.insert(0, os.path.join(TOP, "studies"))
    import studyDict
    worst = 0
    for title, folder, *_ in SCENES:
        try:
            study = studyDict.read_study(os.path.join(TOP, "studies", folder))
        except studyDict.StudyDictError as e:
            print(f"speedAccuracy: {e}", file=sys.stderr)
            return 1
        jobs = max(1, args.jobs // study.cores)
        cmd = [sys.executable, os.path.join(TOP, "studies", "runStudy.py"), os.path.join(TOP, "studies", folder),
               "-jobs", str(jobs)] + (["-quick"] if args.quick else []) \
            + (["-out", os.path.join(os.path.abspath(args.work), folder)] if args.work else [])
        print(f"speedAccuracy: {title}: {' '.join(cmd[1:])}", flush=True)
        code = subprocess.run(cmd).returncode
        if code in (1, 2, 143):   # a bad dictionary, another runner, stopped: no page from a half run
            return code
        worst = max(worst, code)
    build(args)
    return worst


def build(args):
    default = os.path.join(args.work, "speedAccuracy") if args.work else os.path.join(HERE, "quick" if args.quick else "")
    out = os.path.abspath(args.out or default)
    os.makedirs(out, exist_ok=True)
    scenes = [scene_summary(*s[:4], external_default=s[4] if len(s) > 4 else None,
                            tables=tables_folder(s[1], args.quick, args.work and os.path.abspath(args.work)))
              for s in SCENES]
    rows = summary_rows(scenes)
    summary_md = write_summary(rows, out)
    plot_summary(rows, os.path.join(out, "summary.png"))
    write_page(scenes, summary_md, out)
    print(f"speedAccuracy: {os.path.join(out, 'index.html')}, summary.png, summary.csv, summary.md")
    if args.readme and not args.quick and not args.work:
        readme = os.path.join(TOP, "README.md")
        text = open(readme).read()
        if README_BEGIN not in text or README_END not in text:
            sys.exit(f"speedAccuracy: README.md has no {README_BEGIN} ... {README_END} block")
        block = (f"{README_BEGIN}\nGenerated by `studies/speedAccuracy/speedAccuracy.py -readme` from "
                 f"`studies/speedAccuracy/summary.md`.\n\n{summary_md}{README_END}")
        text = re.sub(re.escape(README_BEGIN) + ".*?" + re.escape(README_END), lambda m: block, text, flags=re.S)
        iceCases.write_atomically(readme, text)
        print("speedAccuracy: README.md's table rewritten")


# ---------------------------------------------------------------------------- the browser check
def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        for folder in os.environ.get("PATH", "").split(os.pathsep) + ["/usr/bin"]:
            path = os.path.join(folder, name)
            if os.access(path, os.X_OK):
                return path
    return None


def check(args):
    page = os.path.abspath(args.page)
    browser = chromium()
    if browser is None:
        print("speedAccuracy check: FAIL: no Chromium (bin/installDependencies installs the Debian package "
              "chromium)")
        return 1
    flags = [browser, "--headless", "--no-sandbox", "--disable-gpu", "--allow-file-access-from-files",
             "--hide-scrollbars", "--virtual-time-budget=15000"]
    with tempfile.TemporaryDirectory() as profile:
        flags.append(f"--user-data-dir={profile}")
        dom = subprocess.run(flags + ["--dump-dom", "file://" + page], capture_output=True, text=True, timeout=180)
        body = re.search(r"<body([^>]*)>", dom.stdout)
        attrs = dict(re.findall(r'data-([\w-]+)="(\d+)"', body.group(1))) if body else {}
        failures = []
        if not attrs:
            failures.append(f"Chromium rendered no page (exit {dom.returncode}): {dom.stderr.strip()[-300:]}")
        else:
            print(f"speedAccuracy check: {attrs.get('images-loaded')} of {attrs.get('images')} images loaded, "
                  f"{attrs.get('tables')} tables, {attrs.get('scenes')} scene sections")
            if attrs["images"] == "0" or attrs["images-loaded"] != attrs["images"]:
                failures.append(f"images loaded {attrs['images-loaded']} of {attrs['images']}")
            if int(attrs["scenes"]) != len(SCENES):
                failures.append(f"{attrs['scenes']} scene sections, {len(SCENES)} scenes")
        shot = os.path.abspath(args.screenshot or os.path.join(os.path.dirname(page), "screenshot.png"))
        subprocess.run(flags + ["--window-size=1300,2600", f"--screenshot={shot}", "file://" + page],
                       capture_output=True, text=True, timeout=180)
    if not os.path.isfile(shot):
        failures.append("no screenshot written")
    else:
        import matplotlib.image
        pixels = matplotlib.image.imread(shot)[:, :, :3]
        inked = float((pixels.min(axis=2) < 0.9).mean())
        colours = len({tuple(p) for p in (pixels[::7, ::7].reshape(-1, 3) * 255).astype(int).tolist()})
        print(f"speedAccuracy check: screenshot {shot}: {pixels.shape[1]} x {pixels.shape[0]}, "
              f"{100 * inked:.1f} % of the pixels inked, {colours} colours")
        if inked < 0.03 or colours < 20:
            failures.append("the screenshot is (nearly) blank")
    for f in failures:
        print(f"speedAccuracy check: FAIL: {f}")
    if not failures:
        print("speedAccuracy check: ok")
    return 1 if failures else 0


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("what", nargs="?", default="build", choices=("run", "build", "check"))
    p.add_argument("page", nargs="?", help="check: the page to open")
    p.add_argument("-out")
    p.add_argument("-quick", action="store_true")
    p.add_argument("-work", help="run: each study's runs and tables in WORK/<study> (-out of runStudy.py); "
                                 "build: the tables from there")
    p.add_argument("-jobs", type=iceCases.whole_number(1), default=2)
    p.add_argument("-readme", action="store_true")
    p.add_argument("-screenshot")
    a = p.parse_args()
    if a.what == "check":
        if not a.page:
            p.error("check needs the page (e.g. studies/speedAccuracy/index.html)")
        return check(a)
    if a.what == "run":
        return run(a)
    build(a)
    return 0


if __name__ == "__main__":
    sys.exit(main())
