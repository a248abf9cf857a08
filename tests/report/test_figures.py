"""Loss curves, pattern overlays, histograms: written, sized, checked inputs."""

import numpy as np
import pytest

from unsew.errors import InputError
from unsew.pattern.model import Curvature, Edge, Panel, Pattern
from unsew.report.figures import (
    pattern_outlines,
    plot_histogram,
    plot_loss_curves,
    plot_patterns,
)


def _pattern(scale=1.0):
    """Two panels [m]: a rectangle, and a quad whose top edge is a quadratic curve."""
    rect = Panel(
        "sleeve",
        np.array([[0, 0], [0.4, 0], [0.4, 0.25], [0, 0.25]]) * scale,
        [Edge(i, (i + 1) % 4) for i in range(4)],
    )
    edges = [Edge(0, 1), Edge(1, 2), Edge(2, 3, Curvature("quadratic", [[0.5, -0.3]])), Edge(3, 0)]
    body = Panel("front", np.array([[0, 0], [0.5, 0], [0.5, 0.7], [0, 0.7]]) * scale, edges)
    return Pattern("t", {"sleeve": rect, "front": body}, panel_order=["front", "sleeve"])


def test_loss_curves_are_written(tmp_path, meshes):
    it = np.arange(60)
    history = {
        "total": list(1e-2 * np.exp(-it / 20) + 1e-4),
        "chamfer": list(8e-3 * np.exp(-it / 20)),
        "seam": [None] * 20 + list(1e-5 * np.ones(40)),
        "material": [0.0] * 60,
    }
    p = plot_loss_curves(
        tmp_path / "loss.png", history, phases=[(0, "pattern"), (30, "material")], size_px=(640, 360)
    )
    img = meshes.read_png(p)
    assert img.shape[:2] == (360, 640)
    assert meshes.ink_mask(img).mean() > 0.02
    lin = plot_loss_curves(tmp_path / "lin.png", {"total": [3.0, 2.0, -1.0]}, log=False)
    assert lin.is_file()
    with pytest.raises(InputError):
        plot_loss_curves(tmp_path / "none.png", {})
    with pytest.raises(InputError):
        plot_loss_curves(tmp_path / "none.png", {"total": []})
    assert not (tmp_path / "none.png").exists()


def test_pattern_outlines_follow_panel_order():
    out = pattern_outlines(_pattern(), points_per_edge=8)
    assert [n for n, _ in out] == ["front", "sleeve"]
    front, sleeve = out[0][1], out[1][1]
    assert sleeve.shape == (4, 2) and front.shape == (3 + 8, 2)
    np.testing.assert_allclose(front[0], [0, 0])
    assert front[:, 1].max() > 0.7  # the curve bulges above the straight top edge


def test_patterns_overlay_in_true_proportions(tmp_path, meshes):
    # one pattern with one 0.4 x 0.25 m rectangle: its drawn box keeps the 1.6 aspect
    rect = [("sleeve", np.array([[0, 0], [0.4, 0], [0.4, 0.25], [0, 0.25]]))]
    p = plot_patterns(tmp_path / "one.png", [("final", rect)], title=None, width_px=600)
    img = meshes.read_png(p)
    dark = img.max(axis=2) < 0.3  # the black outline (and the short scale bar below it)
    rows = np.flatnonzero(dark.sum(axis=1) > 300)  # the two long horizontal sides
    cols = np.flatnonzero(dark.sum(axis=0) > 150)  # the two vertical sides
    w, h = cols[-1] - cols[0], rows[-1] - rows[0]
    assert w / h == pytest.approx(0.4 / 0.25, rel=0.04)

    pats = [
        ("base", pattern_outlines(_pattern())),
        ("graded", pattern_outlines(_pattern(1.05))),
        ("final", pattern_outlines(_pattern(1.08))),
        ("ground truth", pattern_outlines(_pattern(1.1))),
    ]
    p = plot_patterns(tmp_path / "all.png", pats)
    img = meshes.read_png(p)
    assert img.shape[1] == 1100
    red = (img[..., 0] > 0.7) & (img[..., 1] < 0.4) & (img[..., 2] < 0.4)
    blue = (img[..., 2] > 0.6) & (img[..., 0] < 0.4)
    assert red.sum() > 200 and blue.sum() > 200  # truth and graded are both visible
    placed = [(lbl, [(n, o, (i * 0.6, 0.0)) for i, (n, o) in enumerate(panels)]) for lbl, panels in pats]
    assert plot_patterns(tmp_path / "placed.png", placed, layout="placed").is_file()


def test_patterns_reject_bad_outlines(tmp_path):
    with pytest.raises(InputError, match="outline"):
        plot_patterns(tmp_path / "x.png", [("final", [("a", np.zeros((2, 2)))])])
    with pytest.raises(InputError, match="NaN"):
        plot_patterns(tmp_path / "x.png", [("final", [("a", np.full((4, 2), np.nan))])])
    with pytest.raises(InputError):
        plot_patterns(tmp_path / "x.png", [])
    assert not (tmp_path / "x.png").exists()


def test_histogram(tmp_path, meshes):
    rng = np.random.default_rng(1)
    d = np.abs(rng.normal(0, 2, 2000))
    d[:5] = np.nan
    p = plot_histogram(tmp_path / "h.png", d, size_px=(500, 300))
    assert meshes.read_png(p).shape[:2] == (300, 500)
    with pytest.raises(InputError):
        plot_histogram(tmp_path / "n.png", np.full(4, np.nan))
