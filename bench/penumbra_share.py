#!/usr/bin/python3
"""Per-image accuracy figures of issue 13's items 5 and 6, from EXR files:
RMSE against the truth, the share of penumbra pixels (visibility in
(0.05, 0.95)) against the truth's, the mean signed error, and how the fully
lit receivers (truth == 1) fare (the share above 0.98, the mean of the others), and the share of
receivers black (< 0.05) where the truth is at least 0.25.

usage: penumbra_share.py RECEIVERS.exr LX,LY,LZ TRUTH.exr ESTIMATE.exr...

RECEIVERS.exr is `penumbra render-scene`'s receivers file (P.*, N.*, mask) of
the same view; LX,LY,LZ the light's centre: receivers count when they are
valid and face the light, as the demo scores them (demo_command.cpp,
scored_mask). TRUTH.exr: render-scene's --truth, or the demo's cached truth
(out/cache/truth-<scene>-*.exr). Reads scanline EXRs with no or ZIP(S)
compression and float or half channels (what penumbra writes); numpy only.
"""
import struct
import sys
import zlib

import numpy as np

COMPRESSION_LINES = {0: 1, 2: 1, 3: 16}  # none, ZIPS, ZIP


def _attributes(data):
    """Header attributes {name: (type, bytes)} and the offset after them."""
    pos, attrs = 8, {}
    while data[pos] != 0:
        name_end = data.index(b"\0", pos)
        type_end = data.index(b"\0", name_end + 1)
        (size,) = struct.unpack_from("<i", data, type_end + 1)
        start = type_end + 5
        attrs[data[pos:name_end].decode()] = (data[name_end + 1:type_end].decode(), data[start:start + size])
        pos = start + size
    return attrs, pos + 1


def _channels(raw):
    """[(name, bytes per sample, numpy dtype)] in file order (alphabetical)."""
    out, pos = [], 0
    while raw[pos] != 0:
        end = raw.index(b"\0", pos)
        (pixel_type,) = struct.unpack_from("<i", raw, end + 1)
        dtype = {1: np.float16, 2: np.float32, 0: np.uint32}[pixel_type]
        out.append((raw[pos:end].decode(), np.dtype(dtype).itemsize, dtype))
        pos = end + 1 + 16
    return out


def _unzip(block, expected):
    """OpenEXR's ZIP: zlib, then undo the byte predictor and the interleave."""
    if len(block) == expected:
        return block
    t = np.frombuffer(zlib.decompress(block), dtype=np.uint8).copy()
    t = np.cumsum(t.astype(np.int64) - 128, dtype=np.int64) + 128  # t[i] = t[i-1] + d[i] - 128
    t = (t % 256).astype(np.uint8)
    half = (len(t) + 1) // 2
    out = np.empty_like(t)
    out[0::2], out[1::2] = t[:half], t[half:]
    return out.tobytes()


def read_exr(path):
    """{channel: float64 array (height, width)}."""
    data = open(path, "rb").read()
    if data[:4] != b"\x76\x2f\x31\x01":
        sys.exit(f"{path}: not an OpenEXR file")
    attrs, pos = _attributes(data)
    channels = _channels(attrs["channels"][1])
    compression = attrs["compression"][1][0]
    if compression not in COMPRESSION_LINES:
        sys.exit(f"{path}: compression {compression} not read here")
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"][1])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    lines = COMPRESSION_LINES[compression]
    chunks = (height + lines - 1) // lines
    offsets = struct.unpack_from(f"<{chunks}Q", data, pos)
    planes = {name: np.zeros((height, width)) for name, _, _ in channels}
    row_bytes = sum(size for _, size, _ in channels) * width
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        n = min(lines, y1 + 1 - y)
        block = _unzip(data[offset + 8:offset + 8 + size], n * row_bytes)
        at = 0
        for line in range(n):
            for name, sample, dtype in channels:
                planes[name][y - y0 + line] = np.frombuffer(block, dtype=dtype, count=width, offset=at)
                at += sample * width
    return planes


def scored_mask(receivers, light):
    p = [receivers[f"P.{c}"] for c in "xyz"]
    n = [receivers[f"N.{c}"] for c in "xyz"]
    facing = sum((light[i] - p[i]) * n[i] for i in range(3))
    return (receivers["mask"] > 0.5) & (facing > 0)


def figures(estimate, truth, mask):
    e, t = estimate[mask], truth[mask]
    lit = t == 1.0
    return {"rmse": np.sqrt(np.mean((e - t) ** 2)), "mean": np.mean(e - t),
            "black": np.mean(e[t >= 0.25] < 0.05), "pen": np.mean((e > 0.05) & (e < 0.95)), "pen_truth": np.mean((t > 0.05) & (t < 0.95)),
            "lit_ok": np.mean(e[lit] > 0.98) if lit.any() else 1.0,
            "dark_mean": np.mean(e[lit & (e <= 0.98)]) if (lit & (e <= 0.98)).any() else 1.0}


def main(argv):
    if len(argv) < 4:
        sys.exit(__doc__)
    mask = scored_mask(read_exr(argv[0]), [float(v) for v in argv[1].split(",")])
    truth = read_exr(argv[2])["Y"]
    print("| image | RMSE | mean error | penumbra share | truth's | ratio | lit > 0.98 | mean of the rest | black where truth >= 0.25 |")
    print("|---|---|---|---|---|---|---|---|---|")
    for path in argv[3:]:
        f = figures(read_exr(path)["Y"], truth, mask)
        ratio = f["pen"] / f["pen_truth"] if f["pen_truth"] > 0 else float("nan")
        print(f"| {path} | {f['rmse']:.4f} | {f['mean']:+.4f} | {100 * f['pen']:.2f}% | {100 * f['pen_truth']:.2f}% "
              f"| {ratio:.2f} | {100 * f['lit_ok']:.2f}% | {f['dark_mean']:.4f} | {100 * f['black']:.2f}% |")


if __name__ == "__main__":
    main(sys.argv[1:])
