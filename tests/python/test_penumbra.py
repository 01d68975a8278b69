"""The Python bindings (python/penumbra_module.cpp) on every backend here: PCF
against a float64 numpy brute force of its window contract, every method on
a flat occluder against its closed form, the same data in every numpy layout
(planar, padded, an (H, W, C) transpose, float64, uint16) giving the same
bits, `out=` written in place, and errors as penumbra.Error naming the
parameter. Run by ctest (PythonBindings) with the module on PYTHONPATH."""
import numpy as np
import pytest

import penumbra

BACKENDS = ["scalar", "simd", "opencl"]


@pytest.fixture(scope="module", params=BACKENDS)
def context(request):
    try:
        return penumbra.Context(request.param)
    except penumbra.Error as e:
        if e.category == "unavailable":
            pytest.skip(f"{request.param} unavailable here: {e}")
        raise


def dyadic_map(height, width, seed):
    """Depths k / 16: the comparisons with receivers at odd multiples of 1/32 never tie."""
    return (np.random.default_rng(seed).integers(0, 17, (height, width)) / 16.0).astype(np.float32)


def texel_receivers(height, width, map_h, map_w, seed):
    """(3, H, W): u, v at texel centres of the map (cycling), z an odd multiple of 1/32."""
    y, x = np.mgrid[0:height, 0:width]
    u = ((x % map_w) + 0.5) / map_w
    v = ((y % map_h) + 0.5) / map_h
    z = (2 * np.random.default_rng(seed).integers(0, 16, (height, width)) + 1) / 32.0
    return np.stack([u, v, z]).astype(np.float32)


def pcf_box(depth, receivers, radius, bias):
    """The window contract (docs/pcf.md) in float64: the (2r+1)^2 block about the receiver's texel, clipped."""
    depth = depth.astype(np.float64)
    h, w = depth.shape
    out = np.empty(receivers.shape[1:])
    for y in range(out.shape[0]):
        for x in range(out.shape[1]):
            u, v, z = (float(c) for c in receivers[:, y, x])
            cx = min(max(int(np.floor(min(max(u, 0), 1) * w)), 0), w - 1)
            cy = min(max(int(np.floor(min(max(v, 0), 1) * h)), 0), h - 1)
            window = depth[max(cy - radius, 0):cy + radius + 1, max(cx - radius, 0):cx + radius + 1]
            out[y, x] = np.mean(window >= z - bias)
    return out


@pytest.mark.parametrize("width", [1, 7, 15, 16, 17])
def test_pcf_matches_a_float64_brute_force(context, width):
    depth = dyadic_map(5, 11, seed=width)
    receivers = texel_receivers(3, width, 5, 11, seed=width + 1)
    got = penumbra.shade(context, "pcf", depth, receivers, radius=2, depth_bias=0.001)
    assert got.shape == (3, width) and got.dtype == np.float32
    np.testing.assert_allclose(got, pcf_box(depth, receivers, 2, 0.001), atol=1e-6)


def test_every_method_on_a_flat_occluder(context):
    """A flat map at 0.25: receivers in front (z 0.1) are lit, behind (z 0.75) in shadow."""
    depth = np.full((16, 16), 0.25, np.float32)
    receivers = texel_receivers(4, 4, 4, 4, seed=0)
    receivers[2, :2] = 0.1
    receivers[2, 2:] = 0.75
    for method in penumbra.methods():
        if penumbra.method_input(method) != "shadow-map":
            continue  # dsm reads a deep shadow map, pismo a set of Pismo maps
        visibility = penumbra.shade(context, method, depth, receivers)
        np.testing.assert_allclose(visibility[:2], 1.0, atol=0.02, err_msg=method)
        np.testing.assert_allclose(visibility[2:], 0.0, atol=0.02, err_msg=method)


def test_every_layout_gives_the_same_bits(context):
    depth = dyadic_map(9, 13, seed=3)
    receivers = texel_receivers(5, 7, 9, 13, seed=4)
    expected = penumbra.shade(context, "vsm", depth, receivers, radius=2)
    padded = np.full((3, 5, 12), np.nan, np.float32)
    padded[:, :, :7] = receivers
    channels_last = np.ascontiguousarray(receivers.transpose(1, 2, 0))  # (H, W, 3) as images often are
    layouts = {
        "padded rows (in place)": padded[:, :, :7],
        "interleaved (H, W, C) transposed": channels_last.transpose(2, 0, 1),
        "float64": receivers.astype(np.float64),
        "every other column (a copy)": np.repeat(receivers, 2, axis=2)[:, :, ::2],
    }
    for name, layout in layouts.items():
        np.testing.assert_array_equal(penumbra.shade(context, "vsm", depth, layout, radius=2), expected, name)

    # A zero stride (a broadcast column) is copied, not read as distinct pixels.
    column = receivers[:, :, :1]
    np.testing.assert_array_equal(penumbra.shade(context, "vsm", depth, np.broadcast_to(column, receivers.shape)),
                                  penumbra.shade(context, "vsm", depth, np.repeat(column, 7, axis=2)))

    q = np.random.default_rng(5).integers(0, 65536, (9, 13)).astype(np.uint16)
    np.testing.assert_array_equal(penumbra.shade(context, "pcf", q, receivers),
                                  penumbra.shade(context, "pcf", q.astype(np.float32) / np.float32(65535), receivers))


def test_out_is_written_in_place(context):
    depth = dyadic_map(8, 8, seed=6)
    receivers = texel_receivers(4, 6, 8, 8, seed=7)
    out = np.full((4, 10), -1.0, np.float32)
    result = penumbra.shade(context, "pcf", depth, receivers, out=out[:, :6])
    assert np.shares_memory(result, out)
    np.testing.assert_array_equal(out[:, :6], penumbra.shade(context, "pcf", depth, receivers))
    assert np.all(out[:, 6:] == -1.0)

    mask = np.random.default_rng(8).random((2, 4, 6), dtype=np.float32)
    guide = np.ones((4, 6), np.float32)
    blurred = np.empty_like(mask)
    assert penumbra.blur(context, mask, guide, out=blurred, radius=1) is not None
    # A flat guide and a flat mask plane: the blur keeps it.
    flat = penumbra.blur(context, np.full((4, 6), 0.5, np.float32), guide, radius=1)
    np.testing.assert_allclose(flat, 0.5, atol=1e-6)
    np.testing.assert_array_equal(blurred, penumbra.blur(context, mask, guide, radius=1))


def test_errors_name_the_parameter(context):
    depth = np.full((4, 4), 0.5, np.float32)
    receivers = texel_receivers(2, 2, 4, 4, seed=9)
    with pytest.raises(penumbra.Error) as e:
        penumbra.shade(context, "vsm", depth, receivers, radius=-1)
    assert e.value.parameter == "radius" and e.value.category == "invalid argument"
    with pytest.raises(penumbra.Error, match="not a shading method"):
        penumbra.shade(context, "nope", depth, receivers)
    with pytest.raises(penumbra.Error) as e:
        penumbra.shade(context, "vsm", depth, receivers[0, 0])
    assert e.value.parameter == "receivers"
    bad = receivers.copy()
    bad[2, 1, 1] = np.nan
    with pytest.raises(penumbra.Error) as e:
        penumbra.shade(context, "pcf", depth, bad)
    assert e.value.category == "invalid data" and e.value.parameter == "receivers"
    with pytest.raises(penumbra.Error) as e:
        penumbra.shade(context, "pcf", depth, receivers, out=np.empty((2, 2), np.float64))
    assert e.value.parameter == "out"
    with pytest.raises(penumbra.Error) as e:
        penumbra.shade(context, "pcf", depth, receivers, out=np.empty((3, 3), np.float32))
    assert "receivers" in str(e.value)


def perspective(l, near, far):
    """D3D/Vulkan [0, 1] depth of normalised linear depth l, in float64 (penumbra/depth_convention.h)."""
    d = near + l.astype(np.float64) * (far - near)
    return (far * (d - near) / (d * (far - near))).astype(np.float32)


@pytest.mark.parametrize("method", ["pcf", "vsm"])
def test_depth_convention_keywords_reach_the_method_table(context, method):
    """A map and receivers in reversed Z (1 - perspective), near 0.5, far 50, shade as the normalised ones:
    the dyadic depths keep every comparison 1/32 from its decision, far above the storage's error (6e-6)."""
    depth = dyadic_map(9, 13, seed=5)
    receivers = texel_receivers(5, 17, 9, 13, seed=6)
    stored = receivers.copy()
    stored[2] = 1.0 - perspective(receivers[2], 0.5, 50.0)
    expected = penumbra.shade(context, method, depth, receivers)
    got = penumbra.shade(context, method, 1.0 - perspective(depth, 0.5, 50.0), stored,
                         depth_convention="reversed", near=0.5, far=50)
    np.testing.assert_allclose(got, expected, atol=1e-4)
    with pytest.raises(penumbra.Error) as error:
        penumbra.shade(context, method, depth, receivers, depth_convention="perspective", near=0, far=50)
    assert error.value.parameter == "near"
