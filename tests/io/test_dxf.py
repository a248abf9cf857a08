"""DXF export: ezdxf audit clean, one block per piece, ASTM layers, millimetres, cut line outside
the sew line by the seam allowance, notches on both lines, the AAMA texts."""

import numpy as np
import pytest

from unsew.io.dxf import LAYERS, write_dxf
from unsew.io.garmentcode import load_pattern
from unsew.pattern.base import make_base_pattern
from unsew.pattern.curves import panel_outline

ezdxf = pytest.importorskip("ezdxf")


@pytest.mark.parametrize("source", ["tshirt", "pants", "handmade"])
def test_dxf_audit_blocks_layers_units(source, tmp_path):
    p = (
        load_pattern("tests/data/handmade_specification.json")
        if source == "handmade"
        else make_base_pattern(source)
    )
    f = tmp_path / "p.dxf"
    write_dxf(p, f)
    doc = ezdxf.readfile(f)
    auditor = doc.audit()
    assert not auditor.has_errors, [str(e) for e in auditor.errors]
    assert doc.header["$INSUNITS"] == 4  # millimetres
    assert {layer.dxf.name for layer in doc.layers} >= {"1", "2", "4", "7", "14", "15"} == set(LAYERS) - {"6"}
    inserts = doc.modelspace().query("INSERT")
    assert sorted(i.dxf.name for i in inserts) == sorted(p.panels)
    for name, pan in p.panels.items():
        blk = doc.blocks.get(name)
        cut, sew = blk.query("LWPOLYLINE[layer=='1']"), blk.query("LWPOLYLINE[layer=='14']")
        assert len(cut) == 1 and cut[0].closed and len(sew) == 1 and sew[0].closed
        pts = np.array([v[:2] for v in sew[0].get_points()])
        exact = panel_outline(pan, points_per_edge=4000) * 1000.0
        np.testing.assert_allclose(pts.max(0) - pts.min(0), exact.max(0) - exact.min(0), atol=0.1)
        cpts = np.array([v[:2] for v in cut[0].get_points()])
        # the cut line is larger by at least the 1 cm allowance on every side
        assert (cpts.max(0) - pts.max(0) >= 10.0 - 1e-6).all() and (
            pts.min(0) - cpts.min(0) >= 10.0 - 1e-6
        ).all()
        assert len(blk.query("POINT[layer=='2']")) >= len(pan.vertices)
        assert len(blk.query("LINE[layer=='7']")) == 1
        texts = [t.dxf.text for t in blk.query("TEXT[layer=='1']")]
        assert (
            f"Piece Name: {name}" in texts
            and "Quantity: 1" in texts
            and any(t.startswith("Size: ") for t in texts)
        )
        assert any(t.dxf.text.startswith("cut 1") for t in blk.query("TEXT[layer=='15']"))
    notches = sum(len(doc.blocks.get(n).query("LINE[layer=='4']")) for n in p.panels)
    assert notches == 2 * 2 * sum(k % 3 + 1 for k in range(len(p.stitches)))  # both sides, both lines


def test_mirrored_pair_and_fold_are_noted(tmp_path):
    p = make_base_pattern("pants")
    f = tmp_path / "p.dxf"
    write_dxf(p, f)
    doc = ezdxf.readfile(f)
    notes = {n: " ".join(t.dxf.text for t in doc.blocks.get(n).query("TEXT[layer=='15']")) for n in p.panels}
    assert "mirror of right_front" in notes["left_front"] and "mirror of left_back" in notes["right_back"]
    t = make_base_pattern("tshirt")
    write_dxf(t, f)
    doc = ezdxf.readfile(f)
    front = doc.blocks.get("front")
    assert "cut 1 on fold" in " ".join(x.dxf.text for x in front.query("TEXT[layer=='15']"))
    fold = front.query("LINE[layer=='6']")
    assert len(fold) == 1 and abs(fold[0].dxf.start[0] - fold[0].dxf.end[0]) < 1e-6  # the front's centre line
