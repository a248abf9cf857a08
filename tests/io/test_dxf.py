"""DXF export: ezdxf audit clean, one block per panel, ASTM layers, millimetres."""

import numpy as np
import pytest

ezdxf = pytest.importorskip("ezdxf")

from unsew.io.dxf import LAYERS, write_dxf  # noqa: E402
from unsew.io.garmentcode import load_pattern  # noqa: E402
from unsew.pattern.base import make_base_pattern  # noqa: E402
from unsew.pattern.curves import panel_outline  # noqa: E402


@pytest.mark.parametrize("source", ["tshirt", "pants", "handmade"])
def test_dxf_audit_blocks_layers_units(source, tmp_path):
    p = load_pattern("tests/data/handmade_specification.json") if source == "handmade" else make_base_pattern(source)
    f = tmp_path / "p.dxf"
    write_dxf(p, f)
    doc = ezdxf.readfile(f)
    auditor = doc.audit()
    assert not auditor.has_errors, [str(e) for e in auditor.errors]
    assert doc.header["$INSUNITS"] == 4  # millimetres
    assert {layer.dxf.name for layer in doc.layers} >= set(LAYERS)
    inserts = doc.modelspace().query("INSERT")
    assert sorted(i.dxf.name for i in inserts) == sorted(p.panels)
    for name, pan in p.panels.items():
        blk = doc.blocks.get(name)
        polys = blk.query("LWPOLYLINE[layer=='1']")
        assert len(polys) == 1 and polys[0].closed
        pts = np.array([v[:2] for v in polys[0].get_points()])
        exact = panel_outline(pan, points_per_edge=4000) * 1000.0
        np.testing.assert_allclose(pts.max(0) - pts.min(0), exact.max(0) - exact.min(0), atol=0.1)
        assert len(blk.query("POINT[layer=='2']")) == len(pan.vertices)
        assert len(blk.query("LINE[layer=='7']")) == 1
    notches = sum(len(doc.blocks.get(n).query("LINE[layer=='4']")) for n in p.panels)
    assert notches == 2 * sum(k % 3 + 1 for k in range(len(p.stitches)))
