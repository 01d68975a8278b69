#!/usr/bin/python3
"""The deep shadow map lookup's figures, from one run of penumbra_bench.

Usage (docs/deep_shadow_maps.md, "Lookup", has the command):
    penumbra_bench --benchmark_filter='dsm_lookup/' --benchmark_repetitions=5 \
        --benchmark_enable_random_interleaving=true --benchmark_format=json > dsm.json
    /usr/bin/python3 bench/dsm_ratios.py dsm.json

Medians of the repetitions (real time) of bench/dsm_bench.cpp's cases
(dsm_lookup/backend:B/filter:F/search:S/radius:R/size:N[/threads:T]), printed
as a markdown table: per filter, radius and backend, the lookups/s of both
searches and linear / binary; then SIMD / OpenCL (each search, 1 and 2
threads) and 2 threads / 1 thread. Standard library only.
"""
import json
import statistics
import sys
from collections import defaultdict


def cases(path):
    with open(path) as f:
        run = json.load(f)
    times = defaultdict(list)
    for b in run["benchmarks"]:
        if b.get("run_type") == "aggregate" or not b["name"].startswith("dsm_lookup/"):
            continue
        times[b.get("run_name", b["name"])].append(b["real_time"])
    out = {}
    for name, t in times.items():
        key = dict(part.split(":", 1) for part in name.split("/")[1:] if ":" in part)
        config = key["backend"] + ("/" + key["threads"] + "T" if "threads" in key else "")
        out[(key["filter"], int(key["radius"]), config, key["search"])] = statistics.median(t)
    return out


def main():
    medians = cases(sys.argv[1])
    pixels = 1920 * 1080
    rate = {k: pixels / (ms / 1e3) for k, ms in medians.items()}  # real_time in ms
    configs = sorted({k[2] for k in medians})
    print("| filter | radius | backend | binary M/s | linear M/s | linear / binary |")
    print("|---|---|---|---|---|---|")
    for (f, r) in sorted({(k[0], k[1]) for k in medians}):
        for c in configs:
            b, l = rate.get((f, r, c, "binary")), rate.get((f, r, c, "linear"))
            if b and l:
                print(f"| {f} | {r} | {c} | {b / 1e6:.1f} | {l / 1e6:.1f} | {l / b:.2f} |")
    print()
    print("| filter | radius | search | avx512/1T / opencl | avx512/2T / opencl | 2T / 1T |")
    print("|---|---|---|---|---|---|")
    for (f, r, s) in sorted({(k[0], k[1], k[3]) for k in medians}):
        one, two, cl = (rate.get((f, r, c, s)) for c in ("avx512/1T", "avx512/2T", "opencl"))
        if one and two and cl:
            print(f"| {f} | {r} | {s} | {one / cl:.2f} | {two / cl:.2f} | {two / one:.2f} |")


if __name__ == "__main__":
    main()
