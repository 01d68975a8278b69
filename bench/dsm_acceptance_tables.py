#!/usr/bin/python3
"""Markdown tables of bench/dsm_acceptance's CSV (docs/deep_shadow_maps.md, "Acceptance").

usage: dsm_acceptance_tables.py acceptance.csv

1. the deep map against N at the default tolerance 0.25 N^-1/2 (bilinear
   lookup on the receiver plane): bytes, compression ratio, build time,
   error against both truths;
2. against the tolerance at N = 16;
3. at equal memory: per scene and deep-map N, the best setting of each
   method against the pixel truth, and the best single-depth RMSE over the
   deep map's.
"""
import csv
import sys

SCENES = ("hair", "fog", "layers")


def default_tolerance(row):
    return abs(float(row["tolerance"]) - 0.25 / int(row["samples"]) ** 0.5) < 1e-6


def number(row, key, digits=4):
    return f"{float(row[key]):.{digits}f}"


def samples_table(rows):
    print("| scene | N | eps | bytes/px | ratio | s per M samples | RMSE exact | p99 exact | RMSE pixel | p99 pixel |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for scene in SCENES:
        for r in rows:
            if r["scene"] == scene and r["method"] == "dsm-bilinear" and default_tolerance(r):
                print(f"| {scene} | {r['samples']} | {float(r['tolerance']):.4g} | {number(r, 'bytes_per_pixel', 1)} | "
                      f"{number(r, 'ratio', 2)} | {number(r, 's_per_msample', 2)} | {number(r, 'rmse_exact')} | "
                      f"{number(r, 'p99_exact')} | {number(r, 'rmse_pixel')} | {number(r, 'p99_pixel')} |")


def tolerance_table(rows):
    print("| scene | eps | bytes/px | ratio | RMSE pixel | p99 pixel |")
    print("|---|---|---|---|---|---|")
    for scene in SCENES:
        sweep = [r for r in rows if r["scene"] == scene and r["method"] == "dsm-bilinear" and r["samples"] == "16"]
        seen = set()
        for r in sorted(sweep, key=lambda r: float(r["tolerance"])):
            if r["tolerance"] in seen:
                continue
            seen.add(r["tolerance"])
            print(f"| {scene} | {float(r['tolerance']):.4g} | {number(r, 'bytes_per_pixel', 1)} | {number(r, 'ratio', 2)} | "
                  f"{number(r, 'rmse_pixel')} | {number(r, 'p99_pixel')} |")


def best(rows, accept):
    chosen = [r for r in rows if accept(r)]
    return min(chosen, key=lambda r: float(r["rmse_pixel"])) if chosen else None


def equal_memory_table(rows):
    print("| scene | N | bytes/px | deep map (best lookup) | pcf | vsm | msm | best single-depth RMSE / deep map's |")
    print("|---|---|---|---|---|---|---|---|")
    for scene in SCENES:
        scene_rows = [r for r in rows if r["scene"] == scene]
        for n in sorted({r["samples"] for r in scene_rows if r["method"] == "pcf"}, key=int):
            deep = best(scene_rows, lambda r: r["method"].startswith("dsm") and r["samples"] == n
                        and default_tolerance(r))
            singles = [best(scene_rows, lambda r, m=m: r["method"] == m and r["samples"] == n)
                       for m in ("pcf", "vsm", "msm")]
            cells = [f"{r['method']} {r['setting']}: {number(r, 'rmse_pixel')} / {number(r, 'p99_pixel', 3)}"
                     for r in [deep] + singles]
            best_single = min(float(r["rmse_pixel"]) for r in singles)
            print(f"| {scene} | {n} | {number(deep, 'bytes_per_pixel', 1)} | " + " | ".join(cells) +
                  f" | {best_single / float(deep['rmse_pixel']):.2f} |")


def main(csv_path):
    rows = list(csv.DictReader(open(csv_path, newline="")))
    for table in (samples_table, tolerance_table, equal_memory_table):
        table(rows)
        print()


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
