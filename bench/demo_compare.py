#!/usr/bin/python3
"""Do two `penumbra demo` runs agree on time? (issue 13's repeatability test)

usage: demo_compare.py first/results.csv second/results.csv

Per row (scene, method, setting): the ratio of the two frame-time medians;
prints the share of rows within 20% and the worst ratio. Per scene: the
Pareto front over all methods (the settings no other setting beats on both
time and RMSE), in order of time, and whether both runs give the same front
in the same order, and the same methods on it in the same order (settings
of one method that cost the same, such as a summed-area table's radii, may
trade places within it). Exit status 1 when any front differs or a row is off by
more than 20%, so a script can use it.
"""
import csv
import sys


def load(path):
    return {(r["scene"], r["method"], r["settings"]): r for r in csv.DictReader(open(path, newline=""))}


def front(rows):
    """Names of the scene's Pareto-optimal rows, fastest first."""
    best, names = float("inf"), []
    for r in sorted(rows, key=lambda r: (float(r["frame_ms"]), float(r["rmse"]))):
        if float(r["rmse"]) < best:
            best = float(r["rmse"])
            names.append(f"{r['method']} {r['settings']}")
    return names


def methods_of(names):
    """The front's methods in order, a method's neighbouring settings as one."""
    methods = []
    for name in names:
        method = name.split(" ")[0]
        if not methods or methods[-1] != method:
            methods.append(method)
    return methods


def main(first_path, second_path):
    first, second = load(first_path), load(second_path)
    keys = [k for k in first if k in second]
    ratios = {k: float(second[k]["frame_ms"]) / float(first[k]["frame_ms"]) for k in keys}
    within = sum(1 for r in ratios.values() if 1 / 1.2 <= r <= 1.2)
    worst = max(ratios, key=lambda k: max(ratios[k], 1 / ratios[k]))
    print(f"rows: {len(keys)}; median frame time within 20%: {within} ({100 * within / len(keys):.1f}%); "
          f"worst ratio {ratios[worst]:.3f} ({' '.join(worst)})")
    same = True
    for scene in sorted({k[0] for k in keys}, key=[k[0] for k in keys].index):
        a = front([first[k] for k in keys if k[0] == scene])
        b = front([second[k] for k in keys if k[0] == scene])
        same_methods = methods_of(a) == methods_of(b)
        same &= same_methods
        print(f"{scene}: front's methods {'same' if same_methods else 'DIFFER'} ({' < '.join(methods_of(a))}); "
              f"its points {'same' if a == b else 'differ'} ({len(a)}): {', '.join(a)}")
        if a != b:
            print(f"  second run: {', '.join(b)}")
    return 0 if same and within == len(keys) else 1


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
