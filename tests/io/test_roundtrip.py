"""Round trips: the sew line of every piece read back from our DXF (with ezdxf, audit clean) and
from our SVG lies within 0.1 mm of the pattern in pattern.json; the cut line lies outside it by
the seam allowance."""

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from unsew.io.garmentcode import load_pattern, save_pattern
from unsew.io.sheet import edge_point
from unsew.pattern.base import make_base_pattern
from unsew.pattern.curves import panel_outline

NS = {"s": "http://www.w3.org/2000/svg"}


def _seg_dist(pts, poly):
    """Distance (N,) from each point (N, 2) to the closed polyline poly (M, 2)."""
    a, b = poly, np.roll(poly, -1, axis=0)
    d = b - a
    out = np.empty(len(pts))
    for i in range(0, len(pts), 512):
        ap = pts[i : i + 512, None, :] - a[None]
        t = np.clip((ap * d).sum(-1) / (d * d).sum(-1), 0.0, 1.0)
        out[i : i + 512] = np.linalg.norm(ap - t[..., None] * d, axis=-1).min(1)
    return out


def _close(read_mm, panel):
    """Largest distance [mm] between the read polyline and the panel's true outline, both ways."""
    exact = panel_outline(panel, points_per_edge=2000) * 1000.0
    return max(_seg_dist(read_mm, exact).max(), _seg_dist(exact, read_mm).max())


def _patterns(tmp_path):
    out = []
    for src in ("tshirt", "pants", "handmade"):
        p = (
            load_pattern("tests/data/handmade_specification.json")
            if src == "handmade"
            else make_base_pattern(src)
        )
        save_pattern(p, tmp_path / f"{src}.json")
        out.append((src, load_pattern(tmp_path / f"{src}.json")))
    return out


def test_dxf_round_trip_sew_lines_within_a_tenth_of_a_millimetre(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    from unsew.io.dxf import write_dxf

    for src, p in _patterns(tmp_path):
        f = tmp_path / f"{src}.dxf"
        write_dxf(p, f)
        doc = ezdxf.readfile(f)
        assert not doc.audit().has_errors
        for ins in doc.modelspace().query("INSERT"):
            blk = doc.blocks.get(ins.dxf.name)
            sew = np.array([v[:2] for v in blk.query("LWPOLYLINE[layer=='14']")[0].get_points()])
            assert _close(sew, p.panels[ins.dxf.name]) < 0.1, (src, ins.dxf.name)
            cut = np.array([v[:2] for v in blk.query("LWPOLYLINE[layer=='1']")[0].get_points()])
            d = _seg_dist(cut, sew)
            assert d.min() > 10.0 - 0.01  # nowhere closer than the smallest allowance (1 cm)


def test_svg_round_trip_sew_lines_within_a_tenth_of_a_millimetre(tmp_path):
    from unsew.io.svg import write_svg

    for src, p in _patterns(tmp_path):
        f = tmp_path / f"{src}.svg"
        write_svg(p, f)
        root = ET.parse(f).getroot()
        H = float(root.get("height")[:-2])
        groups = {g.get("id")[6:]: g for g in root.findall("s:g[@class='panel']", NS)}
        assert set(groups) == set(p.panels)
        for name, g in groups.items():
            ox, oy = (float(v) for v in g.get("data-offset-mm").split(","))
            d = g.find("s:path[@class='sew-line']", NS).get("d")
            xy = np.array([float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", d)]).reshape(-1, 2)
            sew = np.stack([xy[:, 0] - ox, H - xy[:, 1] - oy], axis=1)
            assert _close(sew, p.panels[name]) < 0.1, (src, name)


def test_seam_allowance_from_the_command_line_and_the_pattern(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    from unsew.io.dxf import write_dxf

    p = make_base_pattern("skirt")
    p.unsew["seam_allowance"] = {"panels": {"front": {"waist": 0.005}}}
    f = tmp_path / "s.dxf"
    write_dxf(p, f, allowance=0.015)
    doc = ezdxf.readfile(f)
    for name in ("front", "back"):
        blk = doc.blocks.get(name)
        cut = np.array([v[:2] for v in blk.query("LWPOLYLINE[layer=='1']")[0].get_points()])
        pan = p.panels[name]
        for label, want in (("hem", 20.0), ("waist", 5.0 if name == "front" else 15.0), ("right_side", 15.0)):
            i = next(k for k, e in enumerate(pan.edges) if e.label == label)
            mid, _ = edge_point(pan, i, 0.5)  # the cut line lies the edge's allowance away from it
            assert _seg_dist(1000.0 * mid[None], cut)[0] == pytest.approx(want, abs=0.01), (name, label)
