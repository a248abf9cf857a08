"""SVG export: true scale in mm, panel sizes to 0.1 mm, no overlap of the cut pieces, labels and notches on
both sides of a seam and on both lines, the test square."""

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from unsew.io.garmentcode import load_pattern
from unsew.io.svg import edge_point, seam_marks, write_svg
from unsew.pattern.base import make_base_pattern
from unsew.pattern.curves import panel_outline

NS = {"s": "http://www.w3.org/2000/svg"}


def _parse(path):
    root = ET.parse(path).getroot()
    return root, {g.get("id")[6:]: g for g in root.findall("s:g[@class='panel']", NS)}


def _path_points(d):
    assert re.fullmatch(r"M[^A-LN-Za-z]*(L[^A-Za-z]*)*Z?", d.replace(" ", "")), d[:80]
    nums = [float(x) for x in re.findall(r"-?\d+(?:\.\d+)?", d)]
    return np.array(nums).reshape(-1, 2)


@pytest.mark.parametrize("garment", ["tshirt", "skirt", "pants"])
def test_true_scale_and_panel_sizes(garment, tmp_path):
    p = make_base_pattern(garment)
    f = tmp_path / "p.svg"
    write_svg(p, f)
    root, groups = _parse(f)
    W, H = float(root.get("width")[:-2]), float(root.get("height")[:-2])
    assert root.get("width").endswith("mm") and root.get("height").endswith("mm")
    assert [float(v) for v in root.get("viewBox").split()] == [0.0, 0.0, W, H]
    assert set(groups) == set(p.panels)
    boxes = []
    for name, g in groups.items():
        pts = _path_points(g.find("s:path[@class='sew-line']", NS).get("d"))
        size = pts.max(0) - pts.min(0)
        exact = panel_outline(p.panels[name], points_per_edge=4000) * 1000.0  # [mm]
        np.testing.assert_allclose(size, exact.max(0) - exact.min(0), atol=0.1)
        cut = _path_points(g.find("s:path[@class='cut-line']", NS).get("d"))
        assert (cut >= 0).all() and (cut[:, 0] <= W).all() and (cut[:, 1] <= H).all()
        assert (cut.max(0) - cut.min(0) >= size + 2 * 10.0 - 1e-6).all()  # 1 cm allowance at least, each side
        boxes.append((cut.min(0), cut.max(0)))
        assert g.find("s:text[@class='panel-name']", NS).text == name
        assert g.find("s:path[@class='grainline']", NS) is not None
    sq = _path_points(root.find("s:g[@id='test-square']/s:path", NS).get("d"))
    np.testing.assert_allclose(sq.max(0) - sq.min(0), [100.0, 100.0])  # the 10 cm test square
    boxes.append((sq.min(0), sq.max(0)))
    for i in range(len(boxes)):  # no two pieces' boxes overlap
        for j in range(i + 1, len(boxes)):
            (a0, a1), (b0, b1) = boxes[i], boxes[j]
            assert (a1 < b0).any() or (b1 < a0).any()


def test_seam_labels_and_notches_on_both_sides(tmp_path):
    p = load_pattern("tests/data/handmade_specification.json")
    f = tmp_path / "h.svg"
    write_svg(p, f)
    _, groups = _parse(f)
    labels = {
        n: sorted(t.text for t in g.findall("s:text[@class='seam-label']", NS)) for n, g in groups.items()
    }
    assert labels == {"front": ["A", "B"], "back": ["A", "B"]}
    notches = {n: len(g.findall("s:path[@class='notch']", NS)) for n, g in groups.items()}
    assert notches == {"front": 2 * (1 + 2), "back": 2 * (1 + 2)}  # A one notch, B two; on both lines


def test_notches_match_along_the_seam():
    p = make_base_pattern("tshirt")
    marks = seam_marks(p)
    from unsew.pattern.curves import edge_length

    for ma, mb in zip(marks[0::2], marks[1::2]):
        assert ma.code == mb.code and len(ma.fractions) == len(mb.fractions)
        la = edge_length(p.panels[ma.panel], ma.edge)
        lb = edge_length(p.panels[mb.panel], mb.edge)
        for fa, fb in zip(ma.fractions, mb.fractions):
            # Side b runs the other way: the notch at a's arc length s sits at b's length L - s.
            assert fb == pytest.approx(1 - fa)
            assert abs(fa * la - (1 - fb) * lb) < 0.05 * la
        # and the notch normal points into the panel
        q, n = edge_point(p.panels[ma.panel], ma.edge, ma.fractions[0])
        from matplotlib.path import Path

        assert Path(panel_outline(p.panels[ma.panel], points_per_edge=64)).contains_point(q + 0.005 * n)
