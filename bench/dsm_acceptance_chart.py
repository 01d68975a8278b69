#!/usr/bin/python3
"""Chart of bench/dsm_acceptance's CSV (docs/deep_shadow_maps.md, "Acceptance").

usage: dsm_acceptance_chart.py acceptance.csv chart.png

Three columns, one per scene (hair, fog, layers); rows:
 1. RMSE against N, log-log: the bilinear deep map against both truths (exact
    and pixel), with the N^-1/2 slope through the first pixel-truth point;
 2. RMSE against bytes per deep-map pixel: the deep map at each N (default
    tolerance, its best lookup filter) and, at equal memory, the best radius
    of PCF, VSM and MSM, against the pixel truth;
 3. bytes per pixel and RMSE against the tolerance at N = 16.
Needs matplotlib (Debian's python3-matplotlib, for /usr/bin/python3).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENES = ("hair", "fog", "layers")
SINGLE_DEPTH = (("pcf", "^", "tab:green"), ("vsm", "s", "tab:purple"), ("msm", "D", "tab:brown"))


def default_tolerance(row):
    return abs(float(row["tolerance"]) - 0.25 / int(row["samples"]) ** 0.5) < 1e-6


def deep_sweep(rows, method):
    """The deep map's N sweep at the default tolerance, sorted by N."""
    sweep = [r for r in rows if r["method"] == method and default_tolerance(r)]
    seen, result = set(), []
    for r in sorted(sweep, key=lambda r: int(r["samples"])):
        if r["samples"] not in seen:
            seen.add(r["samples"])
            result.append(r)
    return result


def error_against_samples(ax, rows):
    sweep = deep_sweep(rows, "dsm-bilinear")
    n = [int(r["samples"]) for r in sweep]
    for column, label, style in (("rmse_exact", "vs exact truth", "o-"), ("rmse_pixel", "vs pixel truth", "s-")):
        ax.plot(n, [float(r[column]) for r in sweep], style, label=label, ms=4)
    if sweep:
        first = float(sweep[0]["rmse_pixel"])
        ax.plot(n, [first * (k / n[0]) ** -0.5 for k in n], "k--", lw=0.8, label="N^-1/2")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("samples per pixel N")
    ax.set_ylabel("RMSE (bilinear lookup)")


def best_per_samples(rows, accept):
    """Per N, the row of least pixel-truth RMSE among the accepted ones."""
    best = {}
    for r in rows:
        if accept(r):
            key = int(r["samples"])
            if key not in best or float(r["rmse_pixel"]) < float(best[key]["rmse_pixel"]):
                best[key] = r
    return [best[k] for k in sorted(best)]


def error_against_memory(ax, rows):
    deep = best_per_samples(rows, lambda r: r["method"].startswith("dsm") and default_tolerance(r))
    ax.plot([float(r["bytes_per_pixel"]) for r in deep], [float(r["rmse_pixel"]) for r in deep], "o-",
            color="tab:blue", label="deep map (N sweep, best lookup)", ms=4)
    for r in deep:
        ax.annotate(f"N={r['samples']}", (float(r["bytes_per_pixel"]), float(r["rmse_pixel"])), xytext=(3, 2),
                    textcoords="offset points", fontsize=6)
    for method, marker, colour in SINGLE_DEPTH:
        best = best_per_samples(rows, lambda r, m=method: r["method"] == m)
        ax.plot([float(r["bytes_per_pixel"]) for r in best], [float(r["rmse_pixel"]) for r in best], marker,
                color=colour, label=f"{method} (best r)", ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("bytes per deep-map pixel (equal memory)")
    ax.set_ylabel("RMSE vs pixel truth")


def tolerance_sweep(ax, rows):
    sweep = sorted((r for r in rows if r["method"] == "dsm-bilinear" and r["samples"] == "16"),
                   key=lambda r: float(r["tolerance"]))
    eps = [max(float(r["tolerance"]), 1e-3) for r in sweep]
    ax.plot(eps, [float(r["bytes_per_pixel"]) for r in sweep], "o-", color="tab:blue", ms=4, label="bytes/px")
    ax.set_xscale("log")
    ax.set_xlabel("tolerance eps at N = 16 (0 drawn at 1e-3)")
    ax.set_yscale("log")
    ax.set_ylabel("bytes per pixel", color="tab:blue")
    twin = ax.twinx()
    twin.plot(eps, [float(r["rmse_pixel"]) for r in sweep], "s--", color="tab:red", ms=4, label="RMSE")
    twin.set_ylabel("RMSE vs pixel truth", color="tab:red")


def main(csv_path, png_path):
    rows = list(csv.DictReader(open(csv_path, newline="")))
    scenes = [s for s in SCENES if any(r["scene"] == s for r in rows)]
    fig, axes = plt.subplots(3, len(scenes), figsize=(4.6 * len(scenes), 11), squeeze=False)
    for column, scene in enumerate(scenes):
        scene_rows = [r for r in rows if r["scene"] == scene]
        for row, draw in enumerate((error_against_samples, error_against_memory, tolerance_sweep)):
            ax = axes[row][column]
            draw(ax, scene_rows)
            ax.grid(True, which="both", alpha=0.3)
            ax.set_title(scene, fontsize=10)
            if row < 2:
                ax.legend(fontsize=6.5)
    fig.suptitle("deep shadow maps: error, samples, memory (bench/dsm_acceptance)")
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    fig.savefig(png_path, dpi=100)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
