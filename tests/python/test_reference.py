"""penumbra.reference from Python (python/reference_module.cpp): the metrics
against their float64 numpy definitions (penumbra/reference/metrics.h), and a
built-in scene's shadow map, receivers and ground truth, shaded by VSM and
measured, as tests/consumer_reference does in C++."""
import math

import numpy as np
import pytest

import penumbra

ref = penumbra.reference


def test_metrics_match_their_definitions():
    rng = np.random.default_rng(1)
    truth = rng.random((13, 17), dtype=np.float32)
    truth[:3] = 0.01  # some umbra and some lit pixels for the leaking and darkening means
    truth[3:6] = 0.99
    estimate = np.clip(truth + rng.normal(0, 0.1, truth.shape), 0, 1).astype(np.float32)
    mask = (rng.random(truth.shape) > 0.3).astype(np.float32)
    e, t, counted = estimate.astype(np.float64), truth.astype(np.float64), mask > 0.5
    err = (e - t)[counted]
    assert ref.rmse(estimate, truth, mask) == pytest.approx(math.sqrt(np.mean(err ** 2)), rel=1e-12)
    assert ref.rmse(estimate, truth) == pytest.approx(math.sqrt(np.mean((e - t) ** 2)), rel=1e-12)
    ranked = np.sort(np.abs(err))
    assert ref.p99_abs_error(estimate, truth, mask) == pytest.approx(ranked[math.ceil(0.99 * ranked.size) - 1],
                                                                     rel=1e-6)
    dark, lit = counted & (t < 0.05), counted & (t > 0.95)
    assert ref.light_leaking(estimate, truth, mask) == pytest.approx(np.mean(np.maximum(e - t, 0)[dark]), rel=1e-12)
    assert ref.over_darkening(estimate, truth, mask) == pytest.approx(np.mean(np.maximum(t - e, 0)[lit]), rel=1e-12)
    with pytest.raises(penumbra.Error):
        ref.rmse(estimate, truth[:, :5])


def test_a_scene_shaded_and_measured():
    assert "contact" in ref.scenes() and "hair" in ref.scenes("deep")
    with pytest.raises(penumbra.Error, match="contact"):
        ref.scene("no-such-scene")
    scene = ref.scene("contact")
    depth = ref.render_shadow_map(scene, 128, 128)
    assert depth.shape == (128, 128) and depth.min() >= 0 and depth.max() <= 1
    rx = ref.render_receivers(scene, 40, 30)
    assert rx["light_uvz"].shape == (3, 30, 40) and rx["mask"].shape == (30, 40)
    assert rx["light_uvz"].base is not None  # over the library's image, not a copy
    truth = ref.ground_truth(scene, 40, 30, strata=4)
    inside = rx["mask"] > 0.5
    assert np.all((truth[inside] >= 0) & (truth[inside] <= 1))
    assert np.any(truth[inside] == 1) and np.any(truth[inside] < 0.5)  # lit ground and a shadow
    vsm = penumbra.shade(penumbra.Context("scalar"), "vsm", depth, rx["light_uvz"], radius=2)
    assert ref.rmse(vsm, truth, rx["mask"]) < 0.3
