"""DXF export of a sewing pattern in the AAMA / ASTM D6673 style (via ezdxf), millimetres.

One block per panel (block name = panel name), each inserted once in modelspace at the same
side-by-side layout as the SVG (:func:`unsew.io.svg.layout_panels`). Units: millimetres
(``$INSUNITS`` = 4, ``$MEASUREMENT`` = 1). Layers are named by their ASTM D6673 / AAMA numbers:

====== ======================= ================================================================
layer  ASTM meaning            what unsew writes there
====== ======================= ================================================================
``1``  piece boundary          the panel outline (closed polyline; curves sampled <= 1 mm apart)
                               and the piece name text
``2``  turn points             a POINT at every panel corner (the pattern's vertices)
``3``  curve points            POINTs along curved edges (every 10 mm)
``4``  notches                 matching notches of stitched edges (short LINEs into the panel)
``7``  grain line              one LINE along the panel's y axis
``15`` annotation text         seam labels (one code per stitch, written at both edges)
====== ======================= ================================================================

The outline is the net sewing outline (unsew patterns carry no seam allowance), so no separate
sew line (layer 14) is written.
"""

from __future__ import annotations

import os

import numpy as np

from unsew.errors import InputError
from unsew.io.atomic import atomic_write
from unsew.io.svg import NOTCH_LENGTH, edge_point, layout_panels, panel_polyline, seam_marks
from unsew.pattern.curves import edge_length, sample_edge
from unsew.pattern.model import Pattern

__all__ = ["write_dxf", "LAYERS"]

#: ASTM D6673 layer number -> (meaning, ACI colour) for the layers unsew writes.
LAYERS = {
    "1": ("piece boundary", 7),
    "2": ("turn points", 3),
    "3": ("curve points", 4),
    "4": ("notches", 1),
    "7": ("grain line", 5),
    "15": ("annotation text", 6),
}


def _block_name(name: str) -> str:
    bad = '<>/\\":;?*|=`'
    return "".join("_" if c in bad else c for c in name) or "panel"


def write_dxf(pattern: Pattern, path: str | os.PathLike) -> None:
    """Write ``pattern`` as an AAMA/ASTM-style DXF in millimetres, atomically."""
    try:
        import ezdxf
    except ImportError as exc:  # pragma: no cover

        raise InputError("DXF export needs the ezdxf package: pip install ezdxf") from exc
    from ezdxf import units

    doc = ezdxf.new("R2000")
    doc.units = units.MM
    doc.header["$MEASUREMENT"] = 1
    for name, (meaning, color) in LAYERS.items():
        layer = doc.layers.add(name, color=color)
        layer.description = meaning
    mm = 1000.0
    offsets = layout_panels(pattern)
    marks = seam_marks(pattern)
    msp = doc.modelspace()
    for n in pattern.panel_order:
        pan = pattern.panels[n]
        blk = doc.blocks.new(name=_block_name(n))
        outline = panel_polyline(pan) * mm
        blk.add_lwpolyline([tuple(p) for p in outline], close=True, dxfattribs={"layer": "1"})
        for v in pan.vertices * mm:
            blk.add_point(tuple(v), dxfattribs={"layer": "2"})
        for i, e in enumerate(pan.edges):
            if e.curvature is None:
                continue
            k = max(2, int(np.ceil(edge_length(pan, i) / 0.01)))
            for p in sample_edge(pan, i, k)[1:-1] * mm:
                blk.add_point(tuple(p), dxfattribs={"layer": "3"})
        lo, hi = outline.min(0), outline.max(0)
        c = (lo + hi) / 2
        blk.add_line((c[0], lo[1] + 0.2 * (hi[1] - lo[1])), (c[0], lo[1] + 0.8 * (hi[1] - lo[1])), dxfattribs={"layer": "7"})
        blk.add_text(f"Piece Name: {n}", height=10.0, dxfattribs={"layer": "1", "insert": (c[0] + 10.0, c[1])})
        for mk in marks:
            if mk.panel != n:
                continue
            for f in mk.fractions:
                p, nrm = edge_point(pan, mk.edge, f)
                blk.add_line(tuple(p * mm), tuple((p + NOTCH_LENGTH * nrm) * mm), dxfattribs={"layer": "4"})
            p, nrm = edge_point(pan, mk.edge, 0.5)
            q = (p + 0.018 * nrm) * mm
            blk.add_text(mk.code, height=7.0, dxfattribs={"layer": "15", "insert": (q[0], q[1])})
        msp.add_blockref(blk.name, tuple(offsets[n] * mm), dxfattribs={"layer": "1"})
    with atomic_write(path) as tmp:
        doc.saveas(tmp)
