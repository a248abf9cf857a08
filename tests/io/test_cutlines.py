"""The cut line: the sew line offset outward edge by edge, mitred, clipped at sharp corners,
without loops in concave corners."""

import numpy as np
import pytest

from unsew.errors import InputError
from unsew.io.cutlines import MITER_LIMIT, offset_polygon, seam_allowances
from unsew.pattern.base import make_base_pattern


def _simple(q):
    """True when no two non-adjacent segments of the closed polyline q cross."""
    n = len(q)
    for i in range(n):
        a, b = q[i], q[(i + 1) % n]
        for k in range(i + 2, n):
            if i == 0 and k == n - 1:
                continue
            c, d = q[k], q[(k + 1) % n]
            r, s = b - a, d - c
            den = r[0] * s[1] - r[1] * s[0]
            if abs(den) < 1e-15:
                continue
            t = ((c - a)[0] * s[1] - (c - a)[1] * s[0]) / den
            u = ((c - a)[0] * r[1] - (c - a)[1] * r[0]) / den
            if 0 < t < 1 and 0 < u < 1:
                return False
    return True


def test_rectangle_with_a_deeper_hem_grows_by_each_edges_allowance():
    sq = np.array([[0, 0], [0.4, 0], [0.4, 0.6], [0, 0.6]], float)
    cut, corner = offset_polygon(sq, np.array([0.02, 0.01, 0.01, 0.01]), np.arange(4))
    np.testing.assert_allclose(cut.min(0), [-0.01, -0.02], atol=1e-12)
    np.testing.assert_allclose(cut.max(0), [0.41, 0.61], atol=1e-12)
    assert len(cut) == 4 and corner.all()


def test_sharp_corner_is_clipped_and_concave_notch_leaves_no_loop():
    tri = np.array([[0, 0], [0.3, 0.0], [0.0, 0.05]], float)  # about 9.5 degrees at (0.3, 0)
    cut, _ = offset_polygon(tri, np.full(3, 0.01))
    u = (tri[1] - tri[0]) / 0.3 + (tri[1] - tri[2]) / np.linalg.norm(tri[1] - tri[2])
    u /= np.linalg.norm(u)  # the corner's outward bisector: the mitre would reach 12 cm along it
    assert ((cut - tri[1]) @ u).max() == pytest.approx(MITER_LIMIT * 0.01) and len(cut) == 4
    # a slot 1 cm wide: offset by 1 cm outward both sides of it meet, the loop must go
    slot = np.array(
        [[0, 0], [0.2, 0], [0.2, 0.1], [0.105, 0.1], [0.105, 0.03], [0.095, 0.03], [0.095, 0.1], [0, 0.1]],
        float,
    )
    cut, _ = offset_polygon(slot, np.full(len(slot), 0.01))
    assert _simple(cut)
    from matplotlib.path import Path

    assert Path(cut).contains_points(slot * 0.999 + 0.0001).all()


@pytest.mark.parametrize("garment", ["tshirt", "dress", "pants", "skirt"])
def test_base_patterns_give_simple_cut_lines(garment):
    from unsew.io.cutlines import piece_lines

    p = make_base_pattern(garment)
    widths = seam_allowances(p)
    for name in p.panel_order:
        lines = piece_lines(p.panels[name], widths[name])
        assert _simple(lines.cut[::3]) or _simple(lines.cut), name


def test_bad_allowances_are_refused():
    p = make_base_pattern("skirt")
    with pytest.raises(InputError, match="0..10 cm"):
        seam_allowances(p, default=-0.01)
    p.unsew["seam_allowance"] = {"panels": {"front": {"armhole": 0.01}}}
    with pytest.raises(InputError, match="neither an edge label"):
        seam_allowances(p)


@pytest.mark.parametrize("garment", ["tshirt", "pants", "skirt"])
def test_unlabelled_hems_are_found_where_the_labels_put_them(garment):
    p = make_base_pattern(garment)
    hems = {(n, i) for n, pan in p.panels.items() for i, e in enumerate(pan.edges) if e.label == "hem"}
    for pan in p.panels.values():  # GarmentCode's own patterns label no edge
        for e in pan.edges:
            e.label = ""
    widths = seam_allowances(p)
    assert {(n, i) for n, w in widths.items() for i in np.nonzero(w == 0.02)[0]} == hems
