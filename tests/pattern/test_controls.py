"""Control points: corners (tangent turns) and join points (stitched edge ends), CCW per panel."""

from __future__ import annotations

import numpy as np
from helpers import assert_close
from meshing.handmade_patterns import loop_edges, mini_shirt, pentagon, two_squares

from unsew.pattern.controls import corner_turn_angles, find_control_points
from unsew.pattern.model import Curvature, Panel, Pattern


def test_square_corners_and_joins():
    c = find_control_points(two_squares())
    assert c.count_per_panel() == {"A": 4, "B": 4}
    # A's edge 1 (vertices 1, 2) is stitched: those are corners and join points
    a = c.of_panel(0)
    assert c.vertex[a].tolist() == [0, 1, 2, 3]
    assert c.kind[a].tolist() == [1, 3, 3, 1]
    assert_close(c.positions[a], two_squares().panels["A"].vertices)


def test_turn_angles():
    v = pentagon().panels["H"].vertices
    turn = corner_turn_angles(pentagon().panels["H"])
    d = np.roll(v, -1, axis=0) - v  # edge directions
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    expect = np.degrees(np.arccos(np.clip((np.roll(d, 1, axis=0) * d).sum(1), -1, 1)))  # turn at each vertex
    assert_close(turn, expect, atol=1e-6)
    assert_close(turn[:2], [90.0, 90.0], atol=1e-6)


def test_smooth_unstitched_junction_is_not_a_control_point():
    # a rectangle whose top is made of two collinear edges: the midpoint of the top is smooth
    v = np.array([[0, 0], [0.4, 0], [0.4, 0.3], [0.2, 0.3], [0, 0.3]], float)
    pat = Pattern("r", {"R": Panel("R", v, loop_edges(5))})
    c = find_control_points(pat)
    assert c.vertex.tolist() == [0, 1, 2, 4]
    # ... unless a seam ends there: then it is a join point
    from unsew.pattern.model import Stitch, StitchSide

    pat.stitches.append(Stitch(StitchSide("R", 2), StitchSide("R", 0)))
    c = find_control_points(pat)
    assert c.vertex.tolist() == [0, 1, 2, 3, 4]
    assert c.kind.tolist() == [3, 3, 3, 2, 1]


def test_tangent_continuous_curve_junction():
    # a panel whose top is two quadratic edges meeting with a common tangent at the top vertex
    v = np.array([[0, 0], [0.4, 0], [0.4, 0.3], [0.2, 0.4], [0, 0.3]], float)
    # edge 2 from (0.4,0.3) to (0.2,0.4): control point at (0.3, 0.4) -> tangent at end is (-1, 0)
    # edge 3 from (0.2,0.4) to (0,0.3): control point at (0.1, 0.4) -> tangent at start is (-1, 0)
    from unsew.pattern.curves import absolute_to_relative

    c2 = absolute_to_relative(v[2], v[3], np.array([0.3, 0.4]))
    c3 = absolute_to_relative(v[3], v[4], np.array([0.1, 0.4]))
    curv = {2: Curvature("quadratic", [c2.tolist()]), 3: Curvature("quadratic", [c3.tolist()])}
    pat = Pattern("dome", {"D": Panel("D", v, loop_edges(5, curv))})
    turn = corner_turn_angles(pat.panels["D"])
    assert turn[3] < 1e-3
    c = find_control_points(pat)
    assert 3 not in c.vertex.tolist() and len(c) == 4


def test_panel_without_corners_gets_two():
    # a disc made of two half-circle arcs: no corner, no seam
    v = np.array([[0, 0], [0.2, 0]], float)
    curv = {0: Curvature("circle", [0.1, False, True]), 1: Curvature("circle", [0.1, False, True])}
    pat = Pattern("disc", {"O": Panel("O", v, loop_edges(2, curv))})
    c = find_control_points(pat)
    assert len(c) == 2 and c.kind.tolist() == [0, 0]


def test_ordering_is_ccw_and_offsets():
    pat = mini_shirt()
    c = find_control_points(pat)
    assert c.offsets.tolist() == [0, 8, 16, 20, 24]
    for p, name in enumerate(c.panel_names):
        idx = c.of_panel(p)
        order = [e.start for e in pat.panels[name].edges]
        pos = [order.index(v) for v in c.vertex[idx]]
        assert pos == sorted(pos)
        x, y = c.positions[idx].T
        assert 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) > 0
