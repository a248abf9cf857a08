"""Mean value coordinates: partition of unity and exact reproduction of linear functions, also on
non-convex panels."""

from __future__ import annotations

import numpy as np
from helpers import assert_close
from meshing.handmade_patterns import curved_panel, nonconvex_panel

from unsew.meshing import mesh_pattern
from unsew.pattern.mvc import mean_value_coordinates


def _interior_and_outline(pat, h=0.03):
    m = mesh_pattern(pat, edge_length=h)
    return m.uv[m.interior(0)], m.uv[m.boundary_loop(0)]


def test_reproduces_linear_functions_on_nonconvex_panel():
    x, poly = _interior_and_outline(nonconvex_panel())
    assert len(x) > 20
    W = mean_value_coordinates(x, poly)
    assert W.shape == (len(x), len(poly))
    assert_close(W.sum(axis=1), 1.0, atol=1e-12, rtol=0)
    assert_close(W @ poly, x, atol=1e-10, rtol=0, what="x = sum w_j v_j: ")
    f = lambda p: 3.0 * p[:, 0] - 7.0 * p[:, 1] + 0.25  # noqa: E731
    assert_close(W @ f(poly), f(x), atol=1e-10, rtol=0)
    # some weights are negative in the concave part: the test really covers the non-convex case
    assert (W < 0).any()


def test_curved_panel_and_chunking_agree():
    x, poly = _interior_and_outline(curved_panel(), h=0.02)
    W = mean_value_coordinates(x, poly)
    W2 = mean_value_coordinates(x, poly, chunk=len(poly) * 7)  # 7 rows at a time
    assert_close(W2, W, atol=1e-15)
    assert_close(W @ poly, x, atol=1e-10, rtol=0)


def test_point_collinear_with_an_outline_edge_is_finite():
    # square with a notch: the point (0.5, 0.25) lies on the line through the notch's top edge
    poly = np.array(
        [[0, 0], [1, 0], [1, 1], [0.6, 1], [0.6, 0.25 + 0.5], [0.4, 0.75], [0.4, 1], [0, 1]], float
    )
    poly[4] = [0.6, 0.75]
    x = np.array([[0.8, 0.75], [0.5, 0.3]])  # the first is on the line of edge (0.6,.75)-(0.4,.75)
    W = mean_value_coordinates(x, poly)
    assert np.isfinite(W).all()
    assert_close(W @ poly, x, atol=1e-12, rtol=0)
