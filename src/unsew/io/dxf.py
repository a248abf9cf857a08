"""DXF export of a sewing pattern in the AAMA / ASTM D6673 style (via ezdxf), millimetres.

One block per piece (block name = panel name), each inserted once in modelspace at the same
side-by-side layout as the SVG and PDF (:mod:`unsew.io.sheet`); block coordinates are the
panel's own [mm]. Units: millimetres (``$INSUNITS`` = 4, ``$MEASUREMENT`` = 1). Layers are
named by their ASTM D6673 / AAMA numbers:

====== ======================= ================================================================
layer  ASTM meaning            what unsew writes there
====== ======================= ================================================================
``1``  piece boundary          the cut line (closed polyline: sew line plus seam allowance,
                               :mod:`unsew.io.cutlines`) and the AAMA attribute texts
                               ``Piece Name: front``, ``Size: ...``, ``Quantity: 1``
``2``  turn points             a POINT at every corner of the cut line
``4``  notches                 matching notches of stitched edges, on the cut line and on the
                               sew line (short LINEs into the piece)
``6``  mirror line             the fold line of a piece symmetric about a line
``7``  grain line              one LINE along the panel's y axis
``14`` sew line                the pattern's outline (closed polyline; curves sampled <= 1 mm)
``15`` annotation text         the cutting note ('cut 1', 'cut 1 on fold', 'mirror of ...'),
                               size and allowance, and the seam labels (one code per stitch,
                               written at both edges)
====== ======================= ================================================================
"""

from __future__ import annotations

import os

from unsew.errors import InputError
from unsew.io.atomic import atomic_write
from unsew.io.sheet import SIZE_TEXT, make_sheet
from unsew.pattern.model import Pattern

__all__ = ["write_dxf", "LAYERS"]

#: ASTM D6673 layer number -> (meaning, ACI colour) for the layers unsew writes.
LAYERS = {
    "1": ("piece boundary (cut line)", 7),
    "2": ("turn points", 3),
    "4": ("notches", 1),
    "6": ("mirror line", 4),
    "7": ("grain line", 5),
    "14": ("sew line", 8),
    "15": ("annotation text", 6),
}


def _block_name(name: str) -> str:
    bad = '<>/\\":;?*|=`'
    return "".join("_" if c in bad else c for c in name) or "panel"


def write_dxf(
    pattern: Pattern, path: str | os.PathLike, *, allowance: float | None = None, hem: float | None = None
) -> None:
    """Write ``pattern`` as an AAMA/ASTM-style DXF in millimetres, atomically. allowance, hem:
    seam allowance of plain and hem edges [m] (default: the pattern's ``unsew.seam_allowance``,
    else 1 and 2 cm)."""
    try:
        import ezdxf
    except ImportError as exc:  # pragma: no cover
        raise InputError("DXF export needs the ezdxf package: pip install ezdxf") from exc
    from ezdxf import units

    sheet = make_sheet(pattern, allowance=allowance, hem=hem)
    doc = ezdxf.new("R2000")
    doc.units = units.MM
    doc.header["$MEASUREMENT"] = 1
    for name, (meaning, color) in LAYERS.items():
        layer = doc.layers.add(name, color=color)
        layer.description = meaning
    mm = 1000.0
    msp = doc.modelspace()
    for pc in sheet.pieces:
        blk = doc.blocks.new(name=_block_name(pc.name))
        blk.add_lwpolyline([tuple(p) for p in pc.lines.cut * mm], close=True, dxfattribs={"layer": "1"})
        blk.add_lwpolyline([tuple(p) for p in pc.lines.sew * mm], close=True, dxfattribs={"layer": "14"})
        for v in pc.lines.cut[pc.lines.cut_corner] * mm:
            blk.add_point(tuple(v), dxfattribs={"layer": "2"})
        for a, b in pc.notches_cut + pc.notches_sew:
            blk.add_line(tuple(a * mm), tuple(b * mm), dxfattribs={"layer": "4"})
        blk.add_line(tuple(pc.grain[0] * mm), tuple(pc.grain[1] * mm), dxfattribs={"layer": "7"})
        if pc.fold is not None:
            blk.add_line(tuple(pc.fold[0] * mm), tuple(pc.fold[1] * mm), dxfattribs={"layer": "6"})
        name_label = next(lb for lb in pc.labels if lb.kind == "name")
        x0, y0 = name_label.pos * mm
        hh = name_label.height * mm
        # the AAMA attribute texts a cutting system reads, on the boundary layer, under the note
        for k, line in enumerate(
            (f"Piece Name: {pc.name}", f"Size: {SIZE_TEXT}", f"Quantity: {pc.note.quantity}")
        ):
            blk.add_text(
                line, height=0.6 * hh, dxfattribs={"layer": "1", "insert": (x0, y0 - (3.2 + 1.1 * k) * hh)}
            )
        for lb in pc.labels:
            blk.add_text(
                lb.text, height=lb.height * mm, dxfattribs={"layer": "15", "insert": tuple(lb.pos * mm)}
            )
        msp.add_blockref(blk.name, tuple(pc.offset * mm), dxfattribs={"layer": "1"})
    with atomic_write(path) as tmp:
        doc.saveas(tmp)
