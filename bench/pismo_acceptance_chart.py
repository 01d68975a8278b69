#!/usr/bin/python3
"""Chart of bench/pismo_acceptance's CSV (docs/pismo.md, "Convergence to the truth's noise").

usage: pismo_acceptance_chart.py acceptance.csv chart.png

One column per scene (contact, overlap, fence); the top row over every
receiver, the bottom row over the receivers on the scene's planes (outside
the casters' hull). RMSE against the number of maps (log-log), for each map setting (frustum or fitted cameras, map size):
Pismo on layered maps (solid), the average of hard shadows from the same maps
(dashed) and, as a flat line, the truth's own noise and the floor two
independent estimates of that noise make (sqrt(2) times it). The maximum-depth
variant is off the scale on contact and is left to the table.
Needs matplotlib (Debian's python3-matplotlib, for /usr/bin/python3).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENES = ("contact", "overlap", "fence")
COLOURS = ("tab:red", "tab:blue", "tab:green", "tab:purple", "tab:orange")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: pismo_acceptance_chart.py acceptance.csv chart.png")
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    settings = []
    for r in rows:
        key = (r["cameras"], int(r["map_size"]))
        if key not in settings:
            settings.append(key)
    # Row 0: every receiver; row 1: those on the scene's planes (outside the casters' hull).
    rows_of = (("pismo", "averaged", "truth_noise", "every receiver"),
               ("pismo_planes", "averaged_planes", "planes_noise", "receivers on the planes"))
    fig, axes = plt.subplots(2, len(SCENES), figsize=(5 * len(SCENES), 8.4), squeeze=False)
    for row, (pismo, averaged, noise_column, what) in enumerate(rows_of):
        for ax, scene in zip(axes[row], SCENES):
            mine = [r for r in rows if r["scene"] == scene]
            if not mine:
                ax.set_visible(False)
                continue
            for colour, (cameras, size) in zip(COLOURS, settings):
                series = sorted((r for r in mine if r["cameras"] == cameras and int(r["map_size"]) == size),
                                key=lambda r: int(r["maps"]))
                maps = [int(r["maps"]) for r in series]
                label = f"{cameras} {size}$^2$"
                ax.plot(maps, [float(r[pismo]) for r in series], "o-", color=colour, label=f"Pismo, {label}")
                ax.plot(maps, [float(r[averaged]) for r in series], "s--", color=colour, alpha=0.6,
                        label=f"averaged hard, {label}")
            noise = float(mine[0][noise_column])
            ax.axhline(noise, color="black", lw=1, label="truth's noise")
            ax.axhline(2 ** 0.5 * noise, color="gray", lw=1, ls=":", label="floor: $\\sqrt{2}$ x truth's noise")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("maps (light mesh vertices)")
            ax.set_ylabel("RMSE against the ray-traced truth")
            ax.set_title(f"{scene}: {what}")
            ax.grid(True, which="both", alpha=0.3)
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
