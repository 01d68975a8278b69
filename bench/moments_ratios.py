#!/usr/bin/python3
"""Throughput and ratios of the moment family, from one run of penumbra_bench.

Usage:
    penumbra_bench --benchmark_filter='^(msm|evsm)' --benchmark_repetitions=3 \
        --benchmark_report_aggregates_only=true --benchmark_format=json > moments.json
    /usr/bin/python3 bench/moments_ratios.py moments.json [--markdown]

For every case of bench/moments_bench.cpp (names `op/backend:B/precision:P/
size:N[/threads:T]`) it prints the median pixels/s, then per operation and
precision: SIMD / scalar (both 1 thread), SIMD 2 threads / OpenCL (PoCL runs
on every core) and SIMD 2 threads / 1 thread. "SIMD" is the ISA the library
picks by default (the run's penumbra_default_isa context). Standard library
only.
"""
import os
import sys

# One reader of penumbra_bench's JSON and case names: bench/ratios.py's.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ratios import ISA_ORDER, find, load  # noqa: E402


def ratio(a, b):
    return "-" if a is None or b is None else f"{a['pixels'] / b['pixels']:.2f}"


def table(markdown, header, rows):
    if markdown:
        print("| " + " | ".join(header) + " |")
        print("|" + "|".join("---" for _ in header) + "|")
        for r in rows:
            print("| " + " | ".join(r) + " |")
        return
    widths = [max(len(x) for x in col) for col in zip(header, *rows)]
    for r in [header] + rows:
        print("  ".join(x.ljust(w) for x, w in zip(r, widths)))


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    markdown = "--markdown" in argv
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    context, cases = load(args[0], "median", ops=None)
    simd = context.get("penumbra_default_isa", "avx512")
    print(f"host {context.get('host_name', '?')}, {context.get('num_cpus', '?')} CPUs, "
          f"load average at start {context.get('load_avg', '?')}; SIMD = {simd}\n")
    ops = sorted({c["op"] for c in cases})
    rows = []
    for op in ops:
        for precision in ("exact", "float"):
            for backend in ISA_ORDER:
                for threads in (1, 2, 0):
                    c = find(cases, op=op, precision=precision, backend=backend, threads=threads)
                    if c:
                        rows.append([op, precision, backend, str(threads or "pocl"), f"{c['pixels'] / 1e6:.1f}"])
    table(markdown, ["case", "precision", "backend", "threads", "Mpx/s"], rows)
    print()
    rows = []
    for op in ops:
        for precision in ("exact", "float"):
            s1 = find(cases, op=op, precision=precision, backend=simd, threads=1)
            s2 = find(cases, op=op, precision=precision, backend=simd, threads=2)
            sc = find(cases, op=op, precision=precision, backend="scalar", threads=1)
            cl = find(cases, op=op, precision=precision, backend="opencl", threads=0)
            if s1 or s2:
                rows.append([op, precision, ratio(s1, sc), ratio(s2, cl), ratio(s2, s1)])
    table(markdown, ["case", "precision", f"{simd} 1T / scalar", f"{simd} 2T / opencl", f"{simd} 2T / 1T"], rows)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
