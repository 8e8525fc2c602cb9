"""The one PNG of a study (studies/runStudy.py): each figure against each knob (a line for each
combination of the other knobs, the measured reference dashed), and each figure's |error| against
wall time on log axes with the Pareto front (the cheapest point for its error) and the case's
default configuration marked."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def _num(text):
    try:
        return float(text)
    except ValueError:
        return None


def plot(runner, rows, path):
    study = runner.study
    knobs = study.knobs
    seeds = [r for r in rows if r["status"] == "done" and r.get("is_scatter")]
    done = [r for r in rows if r["status"] == "done" and not r.get("is_scatter")]
    # text figures (a failure mode) have no axis: the table holds them
    figs = [name for name, _ in study.figures if done and all(isinstance(r[name], float) for r in done)]
    if not figs:   # nothing finished yet
        return
    ncol = len(knobs) + 1
    fig, axes = plt.subplots(len(figs), ncol, figsize=(3.6 * ncol, 2.7 * len(figs)), squeeze=False)
    for i, name in enumerate(figs):
        for j, knob in enumerate(knobs):
            ax = axes[i][j]
            values = knob.quick if runner.args.quick and knob.quick else knob.values
            numeric = all(_num(v) is not None for v in values)
            pos = {v: (_num(v) if numeric else k) for k, v in enumerate(values)}
            others = [k for k in knobs if k is not knob]
            groups = {}
            for r in done:
                groups.setdefault(tuple(r[k.name] for k in others), []).append(r)
            def order(item):
                return [(0, _num(v), "") if _num(v) is not None else (1, 0, v) for v in item[0]]
            for key, group in sorted(groups.items(), key=order):
                group.sort(key=lambda r: pos[r[knob.name]])
                label = ", ".join(f"{k.name} {v}" for k, v in zip(others, key)) or None
                ax.plot([pos[r[knob.name]] for r in group], [r[name] for r in group], "o-", ms=3, lw=1,
                        label=label)
            for v in values:   # a value at which every point failed (refused): a red dotted line
                mine = [r for r in rows if r[knob.name] == v]
                if mine and all(r["status"] == "failed" for r in mine):
                    ax.axvline(pos[v], color="red", lw=0.8, ls=":", label=f"{v}: failed")
            if study.reference_type == "measured" and name in study.reference:
                ax.axhline(study.reference[name], color="k", ls="--", lw=0.8, label="measured")
            if numeric:
                vals = [pos[v] for v in values]
                if min(vals) > 0 and max(vals) / min(vals) >= 6:
                    ax.set_xscale("log")
                    ax.minorticks_off()
                ax.set_xticks(vals)
                ax.set_xticklabels(values, fontsize=7)
            else:
                ax.set_xticks(range(len(values)))
                ax.set_xticklabels(values, fontsize=7)
            ax.set_xlabel(knob.name, fontsize=8)
            ax.set_ylabel(name, fontsize=8)
            ax.tick_params(labelsize=7)
            if i == 0 and len(groups) <= 8 and ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize=6)
        ax = axes[i][-1]
        pts = [(r["wall_s"], max(abs(r[name + "_error"]) * 100, 1e-3), r) for r in done
               if r[name + "_error"] == r[name + "_error"] and r["wall_s"] == r["wall_s"]]
        if pts:
            first = knobs[0]
            colours = {v: f"C{k % 10}" for k, v in enumerate(first.values)}
            for v in first.values:
                mine = [p for p in pts if p[2][first.name] == v]
                if mine:
                    ax.scatter([p[0] for p in mine], [p[1] for p in mine], s=12, color=colours[v],
                               label=f"{first.name} {v}")
            front, best = [], math.inf
            for w, e, r in sorted(pts, key=lambda p: (p[0], p[1])):
                if e < best:
                    front.append((w, e))
                    best = e
            ax.step([f[0] for f in front], [f[1] for f in front], where="post", color="tab:orange", lw=1,
                    label="Pareto front")
            others = [(r["wall_s"], max(abs(r[name + "_error"]) * 100, 1e-3)) for r in seeds
                      if r[name + "_error"] == r[name + "_error"]]
            if others:
                ax.scatter([o[0] for o in others], [o[1] for o in others], marker="x", s=14, color="grey",
                           label=f"chosen point, other {study.scatter.name}s")
            sd = done[0].get(name + "_scatter")   # the same on every row (NaN until two seeds are done)
            if sd and sd == sd:
                ax.axhspan(1e-3, 200 * sd, color="grey", alpha=0.15, lw=0,
                           label=f"within 2 sd of the {study.scatter.name}s ({100 * sd:.2g} %)")
            for w, e, r in pts:
                if r["is_case_default"]:
                    ax.scatter([w], [e], marker="*", s=90, color="red", zorder=3, label="case default")
                if r["is_reference"]:
                    ax.scatter([w], [e], marker="s", s=25, facecolor="none", edgecolor="k", zorder=3,
                               label="reference (error 0)")
            if not any(r["is_case_default"] for r in rows):
                case = ", ".join(f"{k.name} {k.case_value}" for k in knobs)
                ax.text(0.02, 0.02, f"case default ({case}) not in this study", transform=ax.transAxes,
                        fontsize=6)
            ax.set_xscale("log")
            ax.set_yscale("log")
            handles, labels = ax.get_legend_handles_labels()
            unique = dict(zip(labels, handles))
            ax.legend(unique.values(), unique.keys(), fontsize=6)
        ax.set_xlabel("wall time [s]", fontsize=8)
        ax.set_ylabel(f"|{name} error| [%]", fontsize=8)
        ax.tick_params(labelsize=7)
    if study.reference_type in ("measured", "summary"):
        ref = "reference: " + study.reference_source
    elif study.reference_type == "none":
        ref = "no reference"
    else:
        ref = "reference: the finest point (" + ", ".join(
            f"{k.name} {k.finer[-1] if isinstance(k.finer, list) else k.finer}" for k in knobs if k.finer) + ")"
    fig.suptitle(f"{study.case_name}: {study.description or 'study'} ({ref})", fontsize=9)
    fig.tight_layout()
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=72)
    plt.close(fig)
    import os
    os.replace(tmp, path)
