#!/usr/bin/python3
"""What the Python binding adds to a call (issue 18, item 5): penumbra.shade on
numpy arrays against the same method through the C API (ctypes, on the same
arrays, in the same process), at 1080p receivers (the ratio) and at one
receiver on a one-texel map (the constant per call), alternated round by
round so that both see the same load. Prints medians, ratio and difference.

  PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py build/libpenumbra.so [rounds]
"""
import ctypes as C
import itertools
import statistics
import sys
import time

import numpy as np

import penumbra


class View(C.Structure):
    _fields_ = [("data", C.c_void_p), ("width", C.c_int), ("height", C.c_int), ("channels", C.c_int),
                ("row_pitch", C.c_size_t), ("plane_pitch", C.c_size_t), ("layout", C.c_int), ("type", C.c_int)]


class OutView(C.Structure):
    _fields_ = [("data", C.c_void_p), ("width", C.c_int), ("height", C.c_int), ("channels", C.c_int),
                ("row_pitch", C.c_size_t), ("plane_pitch", C.c_size_t), ("layout", C.c_int)]


def main():
    lib = C.CDLL(sys.argv[1])
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 15
    lib.penumbra_last_error.restype = C.c_char_p
    ctx_c = C.c_void_p()
    assert lib.penumbra_context_create(1, C.byref(ctx_c)) == 0, lib.penumbra_last_error()  # simd
    ctx_py = penumbra.Context("simd")
    for (method, options), (label, n, h, w) in itertools.product(
            [("pcf", {"radius": "2"}), ("vsm", {"radius": "2"})], [("1080p, map 1024^2", 1024, 1080, 1920),
                                                                    ("1 receiver, map 1^2", 1, 1, 1)]):
        rng = np.random.default_rng(1)
        depth = rng.random((n, n), dtype=np.float32)
        receivers = np.stack([rng.random((h, w), dtype=np.float32) for _ in range(3)])
        out_py = np.empty((h, w), np.float32)
        out_c = np.empty((h, w), np.float32)
        names = (C.c_char_p * len(options))(*[k.encode() for k in options])
        values = (C.c_char_p * len(options))(*[v.encode() for v in options.values()])
        m = C.c_void_p()
        assert lib.penumbra_method_create(method.encode(), names, values, len(options), C.byref(m)) == 0
        map_view = View(depth.ctypes.data, n, n, 1, n * 4, 0, 0, 0)
        rx_view = View(receivers.ctypes.data, w, h, 3, w * 4, w * h * 4, 0, 0)
        out_view = OutView(out_c.ctypes.data, w, h, 1, w * 4, 0, 0)

        def c_call():
            assert lib.penumbra_shade(ctx_c, m, C.byref(map_view), C.byref(rx_view), C.byref(out_view)) == 0

        def py_call():
            penumbra.shade(ctx_py, method, depth, receivers, out=out_py, **options)

        c_call(), py_call()  # warm: pages, TBB's threads
        times = {"c": [], "py": []}
        for _ in range(rounds):
            for name, call in (("c", c_call), ("py", py_call)):
                t = time.perf_counter()
                call()
                times[name].append(time.perf_counter() - t)
        assert np.array_equal(out_c, out_py)
        c_ms, py_ms = (statistics.median(times[k]) * 1e3 for k in ("c", "py"))
        print(f"{method} {label} (simd): C API {c_ms:.3f} ms, Python {py_ms:.3f} ms, "
              f"ratio {py_ms / c_ms:.3f}, difference {py_ms - c_ms:+.3f} ms (medians of {rounds})")
        lib.penumbra_method_destroy(m)
    lib.penumbra_context_destroy(ctx_c)


if __name__ == "__main__":
    main()
