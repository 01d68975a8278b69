#!/usr/bin/python3
"""Chart of time against error from `penumbra demo`'s CSV.

usage: speed_accuracy_chart.py results.csv chart.png

One panel per scene and truth (the `truth` column: the scene's light;
ssao-vo's obscurance, another quantity; the sun, the directional light the
cascades shade), each scene's shadow panel first: x = milliseconds per timed frame (the map's and the
receivers' work, median of the repetitions; the bar spans their min-max),
log; y = RMSE against the ray-traced ground truth; a marker per family
(moments, distance fields, percentage-closer, deep shadow maps), a colour
per method within its family, a point per setting labelled with it, and
each method's Pareto front (the settings no other setting of the same
method beats on both time and error) joined by a line. The dashed line is
the truth's own noise (its RMSE against a truth with 4x the rays; 0 for
the sun's exact truth; not drawn on the obscurance panels, whose truth's
noise the demo does not measure): differences below it are not resolved.
The legend takes an empty panel where there is one.
Needs matplotlib (Debian's python3-matplotlib, for /usr/bin/python3).
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402


def pareto_front(points):
    """Points (time, error) not dominated by another, sorted by time."""
    front, best = [], float("inf")
    for t, e in sorted(points):
        if e < best:
            front.append((t, e))
            best = e
    return front


# A method's family by its name: ten colours cannot tell seventeen methods
# apart, a colour within the family and a marker per family can.
FAMILIES = (("sdf", "s"), ("pcf", "^"), ("pcss", "^"), ("burley", "^"), ("dsm", "*"), ("ssao", "D"),
            ("cascades", "v"), ("single-", "v"), ("", "o"))


def family_marker(method):
    return next(marker for prefix, marker in FAMILIES if method.startswith(prefix))


def styles(methods):
    """(colour, marker) per method, the colour counted within its family."""
    counts, result = defaultdict(int), {}
    for m in methods:
        marker = family_marker(m)
        result[m] = (plt.cm.tab10(counts[marker] % 10), marker)
        counts[marker] += 1
    return result


def draw_panel(ax, rows, style):
    """One scene: the points with their spread and labels, the fronts."""
    points = defaultdict(list)
    for r in rows:
        points[r["method"]].append(r)
    for method, method_rows in points.items():
        colour, marker = style[method]
        xs = [float(r["frame_ms"]) for r in method_rows]
        ys = [float(r["rmse"]) for r in method_rows]
        spread = [[x - float(r["frame_ms_min"]) for x, r in zip(xs, method_rows)],
                  [float(r["frame_ms_max"]) - x for x, r in zip(xs, method_rows)]]
        ax.errorbar(xs, ys, xerr=spread, fmt="none", ecolor=colour, elinewidth=0.7, alpha=0.6)
        ax.scatter(xs, ys, color=colour, marker=marker, s=22, label=method, zorder=3)
        for x, y, r in zip(xs, ys, method_rows):
            ax.annotate(r["settings"], (x, y), xytext=(3, 2), textcoords="offset points", fontsize=5.5,
                        color=colour, alpha=0.9)
        front = pareto_front(list(zip(xs, ys)))
        ax.plot([p[0] for p in front], [p[1] for p in front], color=colour, lw=1.2)
    if rows and rows[0].get("truth", "shadow") != "obscurance":  # the obscurance truth's noise is not measured
        ax.axhline(float(rows[0]["truth_noise"]), color="grey", ls="--", lw=0.8)
    ax.set_xscale("log")
    # Ticks at 1, 2, 5 per decade, labelled: a panel spanning less than a
    # decade otherwise gets a single labelled tick.
    ax.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.grid(True, which="both", alpha=0.3)


# A panel's title by what its rows are scored against.
TRUTH_TITLES = {"shadow": "{}", "obscurance": "{}: ssao-vo, obscurance", "sun": "{}: the sun, cascades vs one map"}


def main(csv_path, png_path):
    rows = list(csv.DictReader(open(csv_path, newline="")))
    for r in rows:
        r.setdefault("truth", "shadow")  # a CSV from before the column
    panels = sorted({(r["scene"], r["truth"]) for r in rows}, key=[(r["scene"], r["truth"]) for r in rows].index)
    methods = sorted({r["method"] for r in rows}, key=[r["method"] for r in rows].index)
    style = styles(methods)
    columns = min(3, len(panels))
    lines = (len(panels) + columns - 1) // columns
    fig, axes = plt.subplots(lines, columns, figsize=(5.2 * columns, 4.2 * lines), squeeze=False)
    spare = list(axes.flat[len(panels):])
    for ax in spare:
        ax.set_visible(False)
    frame = rows[0]["frame"] if rows else ""
    for ax, (scene, truth) in zip(axes.flat, panels):
        draw_panel(ax, [r for r in rows if (r["scene"], r["truth"]) == (scene, truth)], style)
        ax.set_title(TRUTH_TITLES.get(truth, "{}: " + truth).format(scene))
        ax.set_xlabel(f"ms per {frame} frame (map + receivers)")
        ax.set_ylabel("RMSE vs ground truth" if truth == "shadow" else f"RMSE vs {truth} truth")
    handles = [plt.Line2D([], [], color=style[m][0], marker=style[m][1], lw=1.2, label=m) for m in methods]
    backend = rows[0]["backend"] if rows else ""
    fig.suptitle(f"penumbra: time against error ({backend})")
    if spare:
        fig.tight_layout(rect=(0, 0, 1, 0.97))
        box = spare[0].get_position()
        fig.legend(handles=handles, loc="center", bbox_to_anchor=(box.x0 + box.width / 2, box.y0 + box.height / 2),
                   ncol=2, frameon=False)
    else:
        fig.legend(handles=handles, loc="lower center", ncol=min(len(methods), 6), frameon=False)
        fig.tight_layout(rect=(0, 0.06, 1, 0.97))
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
