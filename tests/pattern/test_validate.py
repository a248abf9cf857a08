"""validate_pattern: errors name the panel and edge; clockwise panels mirrored in place; length warnings."""

import numpy as np
import pytest

from helpers import assert_close
from unsew.errors import PatternError
from unsew.pattern.curves import sample_edge
from unsew.pattern.model import Curvature, Edge, Panel, Pattern, Stitch, StitchSide, mirror_curvature
from unsew.pattern.validate import find_self_intersection, signed_area, validate_pattern


def _square(name="sq", size=1.0, curv=None):
    v = np.array([[0, 0], [size, 0], [size, size], [0, size]], dtype=float)
    edges = [Edge(i, (i + 1) % 4, (curv or {}).get(i)) for i in range(4)]
    return Panel(name, v, edges)


def _two_squares(size_b=1.0):
    a, b = _square("a"), _square("b", size_b)
    return Pattern("p", {"a": a, "b": b}, [Stitch(StitchSide("a", 1), StitchSide("b", 3))])


def test_good_pattern_no_warnings():
    assert validate_pattern(_two_squares()) == []


def test_empty_pattern():
    with pytest.raises(PatternError, match="no panels"):
        validate_pattern(Pattern("e", {}))


def test_too_few_vertices():
    p = Panel("t", np.array([[0, 0], [1, 0]], dtype=float), [Edge(0, 1), Edge(1, 0)])
    with pytest.raises(PatternError, match="panel 't' has 2 vertices"):
        validate_pattern(Pattern("x", {"t": p}))


def test_nan_coordinates():
    p = _square()
    p.vertices[2, 0] = np.nan
    with pytest.raises(PatternError, match="panel 'sq' has NaN"):
        validate_pattern(Pattern("x", {"sq": p}))


def test_open_loop():
    p = _square()
    p.edges[2] = Edge(2, 0)
    with pytest.raises(
        PatternError,
        match="panel 'sq' is not a closed loop: edge 2 ends at vertex 0 but edge 3 starts at vertex 3",
    ):
        validate_pattern(Pattern("x", {"sq": p}))


def test_self_intersection_names_both_edges():
    # A bow tie: edges 1 and 3 cross.
    v = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], dtype=float)
    p = Panel("bow", v, [Edge(i, (i + 1) % 4) for i in range(4)])
    assert find_self_intersection(p) == (1, 3)
    with pytest.raises(PatternError, match="panel 'bow' outline intersects itself: edge 1 crosses edge 3"):
        validate_pattern(Pattern("x", {"bow": p}))


def test_curved_self_intersection():
    # Edge 0 bulges so far up (t = 1.5 of a unit edge) that it crosses the top edge 2.
    p = _square(curv={0: Curvature("quadratic", [[0.5, 2.5]])})
    assert find_self_intersection(p) is not None
    # A modest bulge outward (down) is fine.
    assert find_self_intersection(_square(curv={0: Curvature("quadratic", [[0.5, -0.3]])})) is None


def test_stitch_errors():
    p = _two_squares()
    p.stitches.append(Stitch(StitchSide("a", 1), StitchSide("b", 0)))
    with pytest.raises(PatternError, match="edge 1 of panel 'a' is stitched twice"):
        validate_pattern(p)
    p = _two_squares()
    p.stitches[0] = Stitch(StitchSide("a", 4), StitchSide("b", 0))
    with pytest.raises(PatternError, match="edge 4 of panel 'a', which has 4 edges"):
        validate_pattern(p)
    p = _two_squares()
    p.stitches[0] = Stitch(StitchSide("c", 0), StitchSide("b", 0))
    with pytest.raises(PatternError, match="missing panel 'c'"):
        validate_pattern(p)


def test_length_mismatch_warning():
    assert validate_pattern(_two_squares(1.04)) == []
    w = validate_pattern(_two_squares(1.2))
    assert len(w) == 1 and "stitch 0" in w[0] and "panel 'b'" in w[0]


def test_clockwise_panel_mirrored_in_place():
    """A clockwise panel (drawn from inside, as GarmentCode draws backs) is mirrored: the same
    points in 3D, the same edge numbers and directions, counter-clockwise in 2D."""
    curv = {0: Curvature("cubic", [[0.2, -0.2], [0.7, -0.1]]), 2: Curvature("circle", [0.9, False, True])}
    ccw = _square(curv=curv)
    cw = ccw.copy()
    cw.vertices = cw.vertices * [-1.0, 1.0]  # mirrored outline: clockwise
    cw.edges = [
        Edge(e.start, e.end, mirror_curvature(e.curvature) if e.curvature else None) for e in ccw.edges
    ]
    cw.translation = np.array([0.1, 0.9, -0.2])
    cw.rotation = np.array([10.0, 20.0, 30.0])
    assert signed_area(cw) < 0
    before = [cw.to_world(sample_edge(cw, i, 16)) for i in range(4)]
    normal_before = cw.rotation_matrix()[:, 2]
    pat = Pattern("x", {"sq": cw, "o": _square("o")}, [Stitch(StitchSide("sq", 3), StitchSide("o", 0))])
    w = validate_pattern(pat)
    assert len(w) == 1 and "'sq' was clockwise" in w[0]
    q = pat.panels["sq"]
    assert signed_area(q) > 0
    for i in range(4):
        assert_close(q.to_world(sample_edge(q, i, 16)), before[i], atol=1e-12)
    # the panel's normal flipped (it now faces away from where the clockwise one faced)
    assert_close(q.rotation_matrix()[:, 2], -normal_before, atol=1e-12)
    assert pat.stitches[0].a == StitchSide("sq", 3)
