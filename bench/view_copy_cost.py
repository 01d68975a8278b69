#!/usr/bin/python3
"""What the one copy of a view costs (docs/integration.md): the same 1080p
receivers handed to penumbra.shade planar (read in place) and interleaved (an
(H, W, 3) array's transpose: one planar copy inside the library), alternated
round by round in one process. Prints medians and their ratio.

  PYTHONPATH=build/python /usr/bin/python3 bench/view_copy_cost.py [rounds]
"""
import statistics
import sys
import time

import numpy as np

import penumbra


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 15
    rng = np.random.default_rng(1)
    depth = rng.random((1024, 1024), dtype=np.float32)
    planar = np.stack([rng.random((1080, 1920), dtype=np.float32) for _ in range(3)])
    interleaved = np.ascontiguousarray(planar.transpose(1, 2, 0)).transpose(2, 0, 1)
    out = np.empty((1080, 1920), np.float32)
    ctx = penumbra.Context("simd")
    for method in ("pcf", "vsm"):
        calls = {layout: (lambda r=r: penumbra.shade(ctx, method, depth, r, out=out, radius=2))
                 for layout, r in (("planar", planar), ("interleaved", interleaved))}
        for call in calls.values():
            call()
        times = {k: [] for k in calls}
        for _ in range(rounds):
            for k, call in calls.items():
                t = time.perf_counter()
                call()
                times[k].append(time.perf_counter() - t)
        p, i = (statistics.median(times[k]) * 1e3 for k in ("planar", "interleaved"))
        print(f"{method} 1080p (map 1024^2, simd): planar {p:.2f} ms, interleaved {i:.2f} ms, "
              f"ratio {i / p:.3f}, difference {i - p:+.2f} ms (medians of {rounds})")


if __name__ == "__main__":
    main()
