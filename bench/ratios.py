#!/usr/bin/python3
"""Ratios the project quotes, from one run of penumbra_bench.

Usage (docs/benchmarks.md has the full command, with its filter):
    penumbra_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
        --benchmark_enable_random_interleaving=true --benchmark_format=json > bench.json
    /usr/bin/python3 bench/ratios.py bench.json [--stat median|min] [--markdown]

Reads the JSON of one penumbra_bench run (standard library only), takes the
median of every case (the "median" aggregate, or the median of the repetitions
when aggregates were not reported; --stat min takes the fastest repetition
instead, the "min" aggregate penumbra_bench adds, with every rate scaled by
median time / min time since each case does fixed work per iteration) and
prints:
  - the medians (time, bytes/s, pixels/s, coefficient of variation);
  - table build bytes/s / memcpy bytes/s at the same size and thread count,
    for `table` (returns a new table) and `table_into` (fills an existing one),
    and for `table_traffic` (the exact build's bytes without its arithmetic)
    (target >= 0.85 at 4096^2, 2 moments, float, SIMD, 2 threads; OpenCV's
    integral image is about 0.65 single-threaded, for scale);
  - VSM r=8 pixels/s at 4096^2, `vsm_r8` and `vsm_r8_into` (target >= 250 M/s,
    SIMD, 2 threads);
  - SIMD / OpenCL, SIMD / scalar and 2 threads / 1 thread.
"SIMD" is the ISA the library picks by default (the run's
penumbra_default_isa context), every ISA is listed in the medians.

Case names are made in bench/penumbra_bench.cpp as
`op/key:value/.../threads:n`; the two files must agree on that format.
"""
import json
import statistics
import sys

TABLE_TARGET = 0.85
OPENCV_SCALE = 0.65
VSM_TARGET = 250e6
ISA_ORDER = ["scalar", "sse4.2", "avx2", "avx512", "opencl"]
# The cases of bench/penumbra_bench.cpp; other families' cases in the same
# binary (bench/*_bench.cpp) have their own ratio scripts and are left out.
OPS = ("memcpy", "table_traffic", "table", "table_into", "opencv_integral", "vsm_r8", "vsm_r8_into", "vsm_r8_shuffled", "vsm_r8_magnified", "vssm",
       "vssm_into", "vssm_shuffled", "vssm_magnified", "diag_table_alloc")


def parse_name(run_name):
    parts = run_name.split("/")
    case = {"op": parts[0]}
    for part in parts[1:]:
        if ":" in part:
            key, value = part.split(":", 1)
            if key != "min_time":
                case[key] = value
    case["size"] = int(case.get("size", 0))
    case["threads"] = int(case["threads"]) if "threads" in case else 0
    return case


def load(path, stat, ops=OPS):
    """(context, cases) of one run: `ops` names the cases kept (None: every case;
    bench/moments_ratios.py reads the moment family's with it)."""
    with open(path) as f:
        doc = json.load(f)
    groups = {}
    for b in doc["benchmarks"]:
        if b.get("error_occurred"):
            continue
        name = b.get("run_name", b["name"])
        g = groups.setdefault(name, {"runs": [], "median": None, "min": None, "cv": None})
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") in g:
                g[b["aggregate_name"]] = b
        else:
            g["runs"].append(b)
    cases = []
    for name, g in groups.items():
        case = parse_name(name)
        if ops is not None and case["op"] not in ops:
            continue
        if g["median"] is not None:
            m = g["median"]
            case["ms"] = to_ms(m["real_time"], m["time_unit"])
            case["bytes"] = m.get("bytes/s")
            case["pixels"] = m.get("pixels/s")
        elif g["runs"]:
            runs = g["runs"]
            case["ms"] = statistics.median(to_ms(r["real_time"], r["time_unit"]) for r in runs)
            case["bytes"] = median_of(runs, "bytes/s")
            case["pixels"] = median_of(runs, "pixels/s")
            if stat == "min":
                g["min"] = {"real_time": min(r["real_time"] for r in runs), "time_unit": runs[0]["time_unit"]}
        else:
            continue
        if stat == "min":
            if g["min"] is None:
                sys.exit(f"{name}: no 'min' aggregate in this JSON; use --stat median")
            fastest = to_ms(g["min"]["real_time"], g["min"]["time_unit"])
            scale = case["ms"] / fastest if fastest > 0 else 1.0
            case["ms"] = fastest
            for key in ("bytes", "pixels"):
                if case[key] is not None:
                    case[key] *= scale
        case["cv"] = g["cv"]["real_time"] if g["cv"] is not None else None
        case["name"] = name
        cases.append(case)
    return doc.get("context", {}), cases


def to_ms(value, unit):
    return value * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[unit]


def median_of(runs, key):
    values = [r[key] for r in runs if key in r]
    return statistics.median(values) if values else None


def find(cases, **want):
    for c in cases:
        if all(c.get(k) == v for k, v in want.items()):
            return c
    return None


def fmt_rate(value, scale, digits=2):
    return "-" if value is None else f"{value / scale:.{digits}f}"


def fmt_ratio(value):
    return "-" if value is None else f"{value:.2f}"


def ratio(a, b, key):
    if a is None or b is None or a.get(key) is None or not b.get(key):
        return None
    return a[key] / b[key]


class Table:
    def __init__(self, markdown, header):
        self.markdown, self.rows, self.header = markdown, [], header

    def add(self, *row):
        self.rows.append([str(x) for x in row])

    def show(self, title):
        print(f"\n{'### ' if self.markdown else ''}{title}\n")
        if not self.rows:
            print("(no cases)")
            return
        if self.markdown:
            print("| " + " | ".join(self.header) + " |")
            print("|" + "|".join("---" for _ in self.header) + "|")
            for r in self.rows:
                print("| " + " | ".join(r) + " |")
            return
        widths = [max(len(x) for x in col) for col in zip(self.header, *self.rows)]
        for r in [self.header] + self.rows:
            print("  ".join(x.ljust(w) for x, w in zip(r, widths)))


def sort_key(c):
    backend = c.get("backend", "")
    rank = ISA_ORDER.index(backend) if backend in ISA_ORDER else -1
    return (c["op"], rank, c.get("precision", ""), c["size"], c["threads"])


def main(argv):
    args, stat, markdown = [], "median", False
    rest = iter(argv[1:])
    for a in rest:
        if a == "--markdown":
            markdown = True
        elif a == "--stat":
            stat = next(rest, "")
        elif a.startswith("--stat="):
            stat = a.split("=", 1)[1]
        else:
            args.append(a)
    if len(args) != 1 or stat not in ("median", "min"):
        print(__doc__, file=sys.stderr)
        return 2
    context, cases = load(args[0], stat)
    print(f"statistic: {stat} over the repetitions; "
          f"host {context.get('host_name', '?')}, {context.get('num_cpus', '?')} CPUs, "
          f"load average at start {context.get('load_avg', '?')}")
    simd = context.get("penumbra_default_isa", "avx512")
    ops = sorted({c["op"] for c in cases})
    sizes = sorted({c["size"] for c in cases if c["size"]})

    med = Table(markdown, ["case", "backend", "precision", "size", "threads", "ms", "GB/s", "Mpx/s", "cv %"])
    for c in sorted(cases, key=sort_key):
        backend = c.get("backend") or ("opencv 32f/32f" if c["op"] == "opencv_integral" else "-")
        med.add(c["op"], backend, c.get("precision", "-"), c["size"], c["threads"] or "pocl",
                f"{c['ms']:.3f}", fmt_rate(c["bytes"], 1e9), fmt_rate(c["pixels"], 1e6, 1),
                "-" if c["cv"] is None else f"{100 * c['cv']:.1f}")
    med.show("Medians" if stat == "median" else "Fastest repetition (rates scaled from the medians)")

    # Table build (and the OpenCV peer) against memcpy of the same bytes.
    bw = Table(markdown, ["case", "backend", "precision", "size", "threads", "GB/s", "memcpy GB/s", "ratio", "note"])
    for c in sorted(cases, key=sort_key):
        if c["op"] not in ("table", "table_into", "table_traffic", "opencv_integral"):
            continue
        threads = c["threads"] or 2  # OpenCL: PoCL runs on both cores
        mem = find(cases, op="memcpy", size=c["size"], threads=threads)
        r = ratio(c, mem, "bytes")
        note = ""
        backend = c.get("backend", "opencv 32f/32f" if c["op"] == "opencv_integral" else "-")
        if (c["op"] in ("table", "table_into") and backend == simd and c.get("precision") == "float" and c["size"] == 4096
                and c["threads"] == 2 and r is not None):
            note = f"target >= {TABLE_TARGET:.2f}: " + ("met" if r >= TABLE_TARGET else
                                                       f"MISSED by {TABLE_TARGET - r:.2f} ({r / TABLE_TARGET:.0%} of target)")
        if c["op"] == "opencv_integral" and c["threads"] == 1 and r is not None:
            note = f"scale: about {OPENCV_SCALE:.2f}"
        if c["op"] == "table_traffic":
            note = "the exact build's bytes alone (its bound)"
        bw.add(c["op"], backend, c.get("precision", "exact" if c["op"] == "table_traffic" else "float"), c["size"], c["threads"] or "pocl",
               fmt_rate(c["bytes"], 1e9), fmt_rate(mem and mem["bytes"], 1e9), fmt_ratio(r), note)
    bw.show("Bytes/s / memcpy bytes/s (same size, same threads; OpenCL against 2 threads)")

    vt = Table(markdown, ["case (4096^2)", "backend", "precision", "threads", "Mpx/s", "target", "verdict"])
    for c in sorted(cases, key=sort_key):
        if c["op"] in ("vsm_r8", "vsm_r8_into") and c["size"] == 4096:
            target = c.get("backend") == simd and c["threads"] == 2
            verdict = "-"
            if target and c["pixels"] is not None:
                verdict = "met" if c["pixels"] >= VSM_TARGET else (
                    f"MISSED: {c['pixels'] / VSM_TARGET:.0%} of target, x{VSM_TARGET / c['pixels']:.1f} short")
            vt.add(c["op"], c.get("backend"), c.get("precision"), c["threads"] or "pocl",
                   fmt_rate(c["pixels"], 1e6, 1), ">= 250" if target else "", verdict)
    vt.show(f"VSM r=8 at 4096^2 (target >= {VSM_TARGET / 1e6:.0f} Mpx/s, {simd}, 2 threads)")

    # Speed-ups, on pixels/s (defined for every case).
    su = Table(markdown, ["case", "precision", "size", f"{simd} 2T / opencl", f"{simd} 1T / scalar 1T",
                          f"{simd} 2T / 1T", "memcpy 2T / 1T", "opencv 2T / 1T"])
    for op in [o for o in ("table", "table_into", "vsm_r8", "vsm_r8_into", "vssm") if o in ops]:
        for precision in ("float", "exact"):
            for size in sizes:
                s1 = find(cases, op=op, backend=simd, precision=precision, size=size, threads=1)
                s2 = find(cases, op=op, backend=simd, precision=precision, size=size, threads=2)
                if s1 is None and s2 is None:
                    continue
                cl = find(cases, op=op, backend="opencl", precision=precision, size=size)
                sc = find(cases, op=op, backend="scalar", precision=precision, size=size, threads=1)
                m1 = find(cases, op="memcpy", size=size, threads=1)
                m2 = find(cases, op="memcpy", size=size, threads=2)
                o1 = find(cases, op="opencv_integral", size=size, threads=1)
                o2 = find(cases, op="opencv_integral", size=size, threads=2)
                peer = op in ("table", "table_into") and precision == "float"
                su.add(op, precision, size, fmt_ratio(ratio(s2, cl, "pixels")), fmt_ratio(ratio(s1, sc, "pixels")),
                       fmt_ratio(ratio(s2, s1, "pixels")), fmt_ratio(ratio(m2, m1, "pixels")) if peer else "",
                       fmt_ratio(ratio(o2, o1, "pixels")) if peer else "")
    su.show("Speed-ups (pixels/s ratios)")

    it = Table(markdown, ["case", "precision", "size", "threads"] + [b for b in ISA_ORDER[1:4]] + ["best"])
    for op in [o for o in ("table", "table_into", "vsm_r8", "vsm_r8_into", "vssm") if o in ops]:
        for precision in ("float", "exact"):
            for size in sizes:
                for threads in (1, 2):
                    row = [find(cases, op=op, backend=b, precision=precision, size=size, threads=threads)
                           for b in ISA_ORDER[1:4]]
                    if all(r is None for r in row):
                        continue
                    best = max((r for r in row if r and r["pixels"]), key=lambda r: r["pixels"], default=None)
                    it.add(op, precision, size, threads, *[fmt_rate(r and r["pixels"], 1e6, 1) for r in row],
                           best["backend"] if best else "-")
    it.show("Mpx/s per ISA")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
