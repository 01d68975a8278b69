#!/usr/bin/python3
"""docs/ssao.md, "Accuracy": the chart of bench/ssao_accuracy's table.

    ./build/bench/ssao_accuracy > table.md
    /usr/bin/python3 bench/ssao_accuracy_chart.py table.md docs/ssao_accuracy.png

Per scene, per unusable-sample rule, without and with the blur: the
obscurance's RMSE against the volumetric-obscurance truth (left) and its
signed mean error in the band around depth edges, the halo (right).
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

RULES = ["paired", "zero", "half", "renormalise"]


def rows(path):
    """The table's rows as dicts keyed by its header."""
    lines = [l for l in open(path) if l.startswith("|")]
    header = [c.strip() for c in lines[0].strip("|\n").split("|")]
    for line in lines[2:]:
        cells = [c.strip() for c in line.strip("|\n").split("|")]
        yield dict(zip(header, cells))


def main(table, out):
    data = list(rows(table))
    scenes = list(dict.fromkeys(r["scene"] for r in data))
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    width = 0.8 / (2 * len(RULES))
    for axis, column, title in ((axes[0], "VO RMSE", "obscurance RMSE against the VO truth"),
                                (axes[1], "halo VO mean", "signed mean error near depth edges (halo)")):
        for k, rule in enumerate(RULES):
            for b, blur in enumerate(("none", "5x5")):
                values = [float(next(r[column] for r in data if r["scene"] == s and r["rule"] == rule
                                     and r["blur"] == blur)) for s in scenes]
                offset = (2 * k + b - len(RULES)) * width + width / 2
                axis.bar([i + offset for i in range(len(scenes))], values, width,
                         label=f"{rule}{' + blur' if b else ''}", color=f"C{k}", alpha=1.0 if b == 0 else 0.55)
        axis.set_xticks(range(len(scenes)), scenes)
        axis.set_title(title)
        axis.axhline(0, color="black", linewidth=0.6)
    axes[0].legend(fontsize=7, ncol=2)
    fig.suptitle("ssao-vo per unusable-sample rule (bench/ssao_accuracy)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
