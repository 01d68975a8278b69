#!/usr/bin/python3
"""Markdown table of `penumbra demo`'s CSV: per scene, each method's setting
with the lowest RMSE, with its leak, over-darkening, flicker and its time
per timed frame (median, and the map's and the receivers' shares).

usage: demo_table.py results.csv [method,method,...]

Without a method list every method is shown, in the CSV's order.
"""
import csv
import sys


def best_rows(rows, methods):
    """(scene, row) of the lowest-RMSE setting per scene and method."""
    scenes = sorted({r["scene"] for r in rows}, key=[r["scene"] for r in rows].index)
    for scene in scenes:
        for method in methods:
            own = [r for r in rows if r["scene"] == scene and r["method"] == method]
            if own:
                yield scene, min(own, key=lambda r: float(r["rmse"]))


def main(csv_path, wanted=None):
    rows = list(csv.DictReader(open(csv_path, newline="")))
    methods = wanted or sorted({r["method"] for r in rows}, key=[r["method"] for r in rows].index)
    frame = rows[0]["frame"] if rows else ""
    print(f"| scene | method | best setting | RMSE | p99 | leak | over-darkening | flicker | ms per {frame} frame "
          "(map + receivers) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene, r in best_rows(rows, methods):
        values = " | ".join(f"{float(r[k]):.4f}" for k in ("rmse", "p99", "leak", "overdark", "flicker"))
        times = f"{float(r['frame_ms']):.3g} ({float(r['map_ms']):.3g} + {float(r['receiver_ms']):.3g})"
        print(f"| {scene} | {r['method']} | {r['settings']} | {values} | {times} |")


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2].split(",") if len(sys.argv) == 3 else None)
