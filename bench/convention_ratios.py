#!/usr/bin/python3
"""Each depth convention's time against the normalised one, from one run of
penumbra_bench's `depth_convention` cases (docs/integration.md, "Depth
conventions").

Usage:
    PENUMBRA_CACHE_DIR=$PWD/build/cache taskset -c 1 build/bench/penumbra_bench \
        --benchmark_filter='^depth_convention/table/' --benchmark_repetitions=30 \
        --benchmark_enable_random_interleaving=true --benchmark_min_time=0.02 \
        --benchmark_format=json > run.json
    /usr/bin/python3 bench/convention_ratios.py run.json

For every operation (`table`, `vsm_direct`, ...) and backend it prints the
fastest and the median repetition of each convention (wall time, ms) and their
ratios to normalised. On a shared VM another tenant can only add time, so the
fastest of many interleaved repetitions is the steadier comparison; the median
is printed beside it. Needs the repetitions themselves (no
--benchmark_report_aggregates_only). Standard library only.
"""
import collections
import json
import os
import statistics
import sys

# penumbra_bench's time units as bench/ratios.py reads them. Its load() keys a
# case by its first name component and drops the unkeyed second one (here the
# operation: depth_convention/table/convention:...), so the names are split here.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ratios import to_ms  # noqa: E402

CONVENTIONS = ("normalized", "linear", "perspective", "reversed")


def repetitions(path):
    """{(family, op): {convention: [ms, ...]}} from the run's iterations."""
    with open(path, encoding="utf-8") as f:
        benchmarks = json.load(f)["benchmarks"]
    times = collections.defaultdict(lambda: collections.defaultdict(list))
    for b in benchmarks:
        if b.get("run_type") != "iteration" or not b["run_name"].startswith("depth_convention"):
            continue
        parts = b["run_name"].split("/")
        fields = dict(p.split(":", 1) for p in parts[2:] if ":" in p)
        if "convention" not in fields:
            continue
        times[(parts[0], parts[1])][fields["convention"]].append(to_ms(b["real_time"], b.get("time_unit", "ns")))
    return times


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[0], file=sys.stderr)
        print("usage: convention_ratios.py RUN.json", file=sys.stderr)
        return 2
    try:
        times = repetitions(argv[1])
    except (OSError, ValueError, KeyError, TypeError) as e:
        print(f"convention_ratios.py: cannot read {argv[1]} as a Google Benchmark JSON run: {e}", file=sys.stderr)
        return 2
    if not times:
        print(f"convention_ratios.py: {argv[1]} has no depth_convention repetitions "
              "(run without --benchmark_report_aggregates_only)", file=sys.stderr)
        return 2
    for (family, op), by_convention in sorted(times.items()):
        base = by_convention.get("normalized")
        if not base:
            continue
        row = [f"{family}/{op} ({len(base)} repetitions):"]
        for convention in CONVENTIONS:
            t = by_convention.get(convention)
            if not t:
                continue
            fastest, median = min(t), statistics.median(t)
            row.append(f"{convention} {fastest:.3f} / {median:.3f} ms "
                       f"({fastest / min(base):.3f} / {median / statistics.median(base):.3f})")
        print("  ".join(row))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
