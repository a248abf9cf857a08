"""curves.py against GarmentCode's conventions: relative frame and circle-arc flags."""

import numpy as np
import pytest

from helpers import assert_close
from unsew.pattern.curves import absolute_to_relative, edge_length, relative_to_absolute, sample_edge
from unsew.pattern.model import Curvature, Edge, Panel


def _edge_panel(curv, a=(0.0, 0.0), b=(0.4, 0.0)):
    v = np.array([a, b, (0.2, -1.0)])
    return Panel("p", v, [Edge(0, 1, curv), Edge(1, 2), Edge(2, 0)])


def test_relative_frame_is_garmentcodes():
    a, b = np.array([1.0, 2.0]), np.array([3.0, 2.0])
    # (s, t): a + s*(b - a) + t*perp(b - a), perp(x, y) = (-y, x)
    assert_close(relative_to_absolute(a, b, np.array([0.5, 0.25])), [2.0, 2.5])
    p = np.array([[0.3, -0.7], [4.0, 1.0]])
    assert_close(relative_to_absolute(a, b, absolute_to_relative(a, b, p)), p, atol=1e-12)


@pytest.mark.parametrize("large, right", [(False, True), (False, False), (True, True), (True, False)])
def test_circle_mid_point_matches_from_points_radius(large, right):
    # GarmentCode's CircleEdgeFactory.from_points_radius stores the arc's middle point at relative
    # (0.5, y) with |y| = (r -/+ sqrt(r^2 - d^2/4)) / d, negative when `right`.
    r, d = 0.3, 0.4
    pan = _edge_panel(Curvature("circle", [r, large, right]))
    mid = sample_edge(pan, 0, 2)[1]  # equal arc length: the arc's middle
    h = np.sqrt(r * r - d * d / 4)
    y = ((r + h) if large else (r - h)) / d * (-1 if right else 1)
    assert_close(absolute_to_relative(pan.vertices[0], pan.vertices[1], mid), [0.5, y], atol=1e-9)
    theta = 2 * np.arcsin(d / 2 / r)
    assert edge_length(pan, 0) == pytest.approx(r * (2 * np.pi - theta if large else theta), rel=1e-5)


def test_sample_edge_equal_arc_length():
    pan = _edge_panel(Curvature("cubic", [[0.1, 0.5], [0.8, -0.3]]))
    # Fine enough that chords equal arcs to ~1e-4: the spacing along the curve is uniform.
    pts = sample_edge(pan, 0, 200)
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    assert_close(seg, np.full(200, seg.mean()), rtol=2e-4)
    assert seg.sum() == pytest.approx(edge_length(pan, 0), rel=1e-4)  # 200 chords vs 1024
    assert_close(pts[[0, -1]], pan.vertices[[0, 1]])
