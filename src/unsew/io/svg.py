"""Printable SVG of a sewing pattern at true scale (millimetres).

The drawing's ``width``/``height`` are in ``mm`` and its ``viewBox`` is in millimetres, so one
user unit is one millimetre on paper. Each piece is a group ``<g id="panel-NAME">`` holding
its cut line (``class="cut-line"``, solid: the sew line plus the seam allowance,
:mod:`unsew.io.cutlines`), its sew line (``class="sew-line"``, dashed: the pattern's outline),
matching notches on both lines (``class="notch"``, short ticks into the piece), the grain line
arrowed at both ends, a fold line where the piece is symmetric, its name, cutting note
('cut 1', 'cut 1 on fold', 'mirror of ...'), size and allowance, and seam labels (one letter
code per stitch, written inside both stitched edges). The group's ``data-offset-mm`` is the
piece's placement: a sheet point (X, Y) in mm is panel point ((X - ox), (H - Y) - oy) mm, so the
pattern's coordinates can be read back. A 10 cm test square above the pieces checks the print
scale. Outlines are polylines sampled at most 1 mm apart along curves (straight edges exactly),
so they deviate from the true curves by far less than 0.1 mm.

The layout and marks are shared with the DXF and PDF writers (:mod:`unsew.io.sheet`).
"""

from __future__ import annotations

import os
from pathlib import Path
from xml.sax.saxutils import escape

import numpy as np

from unsew.io.atomic import atomic_write
from unsew.io.sheet import (
    TEST_SQUARE_M,
    SeamMark,
    edge_point,
    make_sheet,
    seam_marks,
    stitch_code,
)
from unsew.pattern.model import Pattern

__all__ = ["write_svg", "seam_marks", "SeamMark", "edge_point", "stitch_code"]


def _fmt(v: float) -> str:
    return f"{v:.4f}".rstrip("0").rstrip(".")


class _Page:
    """SVG text on a page H [mm] high: metres with y up in, millimetres with y down out."""

    def __init__(self, H: float):
        self.H = H

    def xy(self, p) -> str:
        return f"{_fmt(p[0] * 1000)},{_fmt(self.H - p[1] * 1000)}"

    def poly(self, pts) -> str:
        return "M" + " L".join(self.xy(p) for p in pts) + " Z"

    def text(self, p, h, s, cls, *, anchor="start", fill="black") -> str:
        return (
            f'<text class="{cls}" x="{_fmt(p[0] * 1000)}" y="{_fmt(self.H - p[1] * 1000)}" '
            f'font-size="{_fmt(h * 1000)}" font-family="sans-serif" text-anchor="{anchor}" '
            f'dominant-baseline="middle" fill="{fill}" stroke="white" stroke-width="{_fmt(0.25 * h * 1000)}" '
            f'paint-order="stroke">{escape(s)}</text>'
        )


def _piece_svg(pc, page: _Page) -> list[str]:
    """The SVG group of one laid-out piece: cut and sew lines, notches, grainline, fold line and
    labels."""
    xy, poly, text = page.xy, page.poly, page.text
    off = pc.offset
    out = [
        f'<g id="panel-{escape(pc.name)}" class="panel" data-offset-mm="{_fmt(off[0] * 1000)},'
        f'{_fmt(off[1] * 1000)}" data-quantity="{pc.note.quantity}">',
        f'<path class="cut-line" d="{poly(pc.lines.cut + off)}" fill="none" stroke="black" '
        'stroke-width="0.5"/>',
        f'<path class="sew-line" d="{poly(pc.lines.sew + off)}" fill="none" stroke="#555" '
        'stroke-width="0.3" stroke-dasharray="3,1.5"/>',
    ]
    for a, b in pc.notches_sew + pc.notches_cut:
        out.append(f'<path class="notch" d="M{xy(a + off)} L{xy(b + off)}" stroke="red" stroke-width="0.4"/>')
    g0, g1 = pc.grain + off
    out.append(
        f'<path class="grainline" d="M{xy(g0)} L{xy(g1)}" stroke="black" stroke-width="0.4" '
        'marker-start="url(#arrow)" marker-end="url(#arrow)"/>'
    )
    if pc.fold is not None:
        f0, f1 = pc.fold + off
        out.append(
            f'<path class="fold-line" d="M{xy(f0)} L{xy(f1)}" stroke="#2f6fd0" stroke-width="0.3" '
            'stroke-dasharray="6,2,1,2"/>'
        )
    for lb in pc.labels:
        if lb.kind == "seam":
            out.append(text(lb.pos + off, lb.height, lb.text, "seam-label", anchor="middle", fill="red"))
        else:
            cls = "panel-name" if lb.kind == "name" else "cutting-note"
            out.append(text(lb.pos + off, lb.height, lb.text, cls))
    out.append("</g>")
    return out


def write_svg(
    pattern: Pattern, path: str | os.PathLike, *, allowance: float | None = None, hem: float | None = None
) -> None:
    """Write ``pattern`` as a true-scale SVG (mm), atomically. allowance, hem: seam allowance of
    plain and hem edges [m] (default: the pattern's ``unsew.seam_allowance``, else 1 and 2 cm)."""
    sheet = make_sheet(pattern, allowance=allowance, hem=hem)
    W, H = sheet.size * 1000.0  # [mm]
    page = _Page(H)
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_fmt(W)}mm" height="{_fmt(H)}mm" '
        f'viewBox="0 0 {_fmt(W)} {_fmt(H)}" data-units="mm">',
        f"<title>{escape(pattern.name)} (unsew sewing pattern, 1 unit = 1 mm; solid: cut line, "
        "dashed: sew line)</title>",
        '<defs><marker id="arrow" viewBox="0 0 10 10" refX="10" refY="5" markerWidth="4" markerHeight="4" '
        'orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="black"/></marker></defs>',
    ]
    for pc in sheet.pieces:
        out += _piece_svg(pc, page)
    s0, s = sheet.square, TEST_SQUARE_M
    sq = np.array([s0, s0 + [s, 0], s0 + [s, s], s0 + [0, s]])
    out.append(
        '<g id="test-square" class="test-square">'
        f'<path d="{page.poly(sq)}" fill="none" stroke="black" stroke-width="0.3"/>'
        + page.text(s0 + [s + 0.01, 0.6 * s], 0.006, "10 cm x 10 cm test square:", "note")
        + page.text(s0 + [s + 0.01, 0.45 * s], 0.005, "print at 100 % (actual size) and measure", "note")
        + "</g>"
    )
    out.append("</svg>")
    with atomic_write(path) as tmp:
        Path(tmp).write_text("\n".join(out) + "\n", encoding="utf-8")
