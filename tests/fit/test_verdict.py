"""A fit that ends far from its target says so: ``"ok": false`` and the reason."""

import numpy as np

from unsew.fit.outputs import FAR_MM, fit_verdict
from unsew.metrics.surface import surface_metrics


def _sheet(n=20):
    g = np.linspace(0.0, 0.5, n)
    x, y = np.meshgrid(g, g)
    v = np.stack([x.ravel(), y.ravel() + 0.8, np.zeros(n * n)], axis=1)
    i = np.arange(n - 1)
    a = (i[:, None] * n + i[None, :]).ravel()
    f = np.concatenate([np.stack([a, a + 1, a + n], 1), np.stack([a + 1, a + n + 1, a + n], 1)])
    return v, f


def test_a_drape_on_its_target_is_ok_and_one_5_cm_off_is_a_miss():
    v, f = _sheet()
    near = fit_verdict(surface_metrics(v + [0, 0, 0.002], f, v, f, n_samples=2000))
    far = fit_verdict(surface_metrics(v + [0, 0, 0.05], f, v, f, n_samples=2000))
    assert near == {"ok": True, "miss": None}
    assert far["ok"] is False and "mm from its target" in far["miss"]


def test_a_drape_without_a_distance_is_a_miss():
    assert fit_verdict({"chamfer_mm": float("nan")})["ok"] is False
    assert fit_verdict({"chamfer_mm": FAR_MM + 1})["ok"] is False
