"""Printable SVG of a sewing pattern at true scale (millimetres).

The drawing's ``width``/``height`` are in ``mm`` and its ``viewBox`` is in millimetres, so one
user unit is one millimetre on paper. Panels are laid side by side (rows, no overlap), each
with its name, a grain line (the panel's y axis, arrowed at both ends), seam labels (one letter
code per stitch, written inside both stitched edges) and matching notches (short ticks into
the panel at the same arc-length fractions on both edges of a stitch, mirrored because the
two edges run against each other). Outlines are polylines sampled at most 1 mm apart along
curves (straight edges exactly), so they deviate from the true curves by far less than 0.1 mm.

The layout and seam marks are shared with :mod:`unsew.io.dxf`.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from xml.sax.saxutils import escape

import numpy as np

from unsew.io.atomic import atomic_write
from unsew.pattern.curves import edge_length, sample_edge
from unsew.pattern.model import Pattern

__all__ = ["write_svg", "layout_panels", "seam_marks", "SeamMark", "edge_point", "panel_polyline", "stitch_code"]

#: Gap between laid-out panels [m]; width after which a new row starts [m].
LAYOUT_GAP = 0.04
ROW_WIDTH = 1.6
#: Notch tick length [m] and spacing between the notches of one seam [m].
NOTCH_LENGTH = 0.008
NOTCH_SPACING = 0.012
#: Maximum distance between polyline points along curved edges [m].
CURVE_STEP = 0.001


def stitch_code(k: int) -> str:
    """Seam label of stitch ``k``: A..Z, then AA, AB, ..."""
    s = ""
    k += 1
    while k:
        k, r = divmod(k - 1, 26)
        s = chr(65 + r) + s
    return s


def panel_polyline(panel, *, step: float = CURVE_STEP) -> np.ndarray:
    """Closed outline (M, 2) [m] of ``panel``: corners exactly, curves sampled at most ``step``
    apart (last point not repeated)."""
    parts = []
    for i, e in enumerate(panel.edges):
        n = 1 if e.curvature is None else max(8, int(np.ceil(edge_length(panel, i) / step)))
        parts.append(sample_edge(panel, i, n)[:-1])
    return np.concatenate(parts)


def edge_point(panel, i: int, frac: float) -> tuple[np.ndarray, np.ndarray]:
    """Point (2,) [m] at arc-length fraction ``frac`` of edge ``i``, and the unit normal (2,)
    pointing into the panel (left of the edge direction, panels being counter-clockwise)."""
    n = 400
    pts = sample_edge(panel, i, n)
    x = frac * n
    j = min(int(x), n - 1)
    p = pts[j] + (x - j) * (pts[j + 1] - pts[j])
    t = pts[j + 1] - pts[j]
    t = t / np.linalg.norm(t)
    return p, np.array([-t[1], t[0]])


@dataclass
class SeamMark:
    """Marks of one stitched edge: its seam label and notch positions (arc-length fractions)."""

    panel: str
    edge: int
    code: str
    fractions: list[float]


def seam_marks(pattern: Pattern) -> list[SeamMark]:
    """Seam labels and notches for every stitch, both sides.

    Stitch k gets ``(k % 3) + 1`` notches around the middle of side a, spaced
    :data:`NOTCH_SPACING` apart along it; side b gets them at ``1 - f`` (it runs the other way),
    so matching notches meet when the seam is sewn.
    """
    out = []
    for k, s in enumerate(pattern.stitches):
        la = edge_length(pattern.panels[s.a.panel], s.a.edge)
        cnt = k % 3 + 1
        step = min(NOTCH_SPACING / la, 0.2)
        fr = [0.5 + (j - (cnt - 1) / 2) * step for j in range(cnt)]
        code = stitch_code(k)
        out.append(SeamMark(s.a.panel, s.a.edge, code, fr))
        out.append(SeamMark(s.b.panel, s.b.edge, code, [1.0 - f for f in fr]))
    return out


def layout_panels(pattern: Pattern, *, gap: float = LAYOUT_GAP, row_width: float = ROW_WIDTH) -> dict[str, np.ndarray]:
    """Offsets (2,) [m] per panel that lay the panels out side by side in rows without overlap:
    panel point p is drawn at ``p + offset``; the drawing spans x, y >= 0 with a margin ``gap``."""
    boxes = {n: panel_polyline(pattern.panels[n], step=0.005) for n in pattern.panel_order}
    offsets, x, y, row_h = {}, gap, gap, 0.0
    for n in pattern.panel_order:
        lo, hi = boxes[n].min(0), boxes[n].max(0)
        w, h = hi - lo
        if x > gap and x + w > row_width:
            x, y, row_h = gap, y + row_h + gap, 0.0
        offsets[n] = np.array([x, y]) - lo
        x += w + gap
        row_h = max(row_h, h)
    return offsets


def _fmt(v: float) -> str:
    return f"{v:.4f}".rstrip("0").rstrip(".")


def write_svg(pattern: Pattern, path: str | os.PathLike) -> None:
    """Write ``pattern`` as a true-scale SVG (mm), atomically."""
    from pathlib import Path

    offsets = layout_panels(pattern)
    outlines = {n: panel_polyline(pattern.panels[n]) + offsets[n] for n in pattern.panel_order}
    hi = np.max([o.max(0) for o in outlines.values()], axis=0) + LAYOUT_GAP
    W, H = hi * 1000.0  # [mm]

    def xy(p) -> str:  # metres, y up -> SVG millimetres, y down
        return f"{_fmt(p[0] * 1000)},{_fmt(H - p[1] * 1000)}"

    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_fmt(W)}mm" height="{_fmt(H)}mm" '
        f'viewBox="0 0 {_fmt(W)} {_fmt(H)}" data-units="mm">',
        f"<title>{escape(pattern.name)} (unsew sewing pattern, 1 unit = 1 mm)</title>",
        "<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"10\" refY=\"5\" markerWidth=\"4\" markerHeight=\"4\" "
        'orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="black"/></marker></defs>',
    ]
    marks = seam_marks(pattern)
    for n in pattern.panel_order:
        pan, off = pattern.panels[n], offsets[n]
        out.append(f'<g id="panel-{escape(n)}" class="panel">')
        pts = outlines[n]
        d = "M" + " L".join(xy(p) for p in pts) + " Z"
        out.append(f'<path class="outline" d="{d}" fill="none" stroke="black" stroke-width="0.5"/>')
        lo, hi_ = pts.min(0), pts.max(0)
        c = (lo + hi_) / 2
        g0, g1 = np.array([c[0], lo[1] + 0.2 * (hi_[1] - lo[1])]), np.array([c[0], lo[1] + 0.8 * (hi_[1] - lo[1])])
        out.append(
            f'<path class="grainline" d="M{xy(g0)} L{xy(g1)}" stroke="black" stroke-width="0.4" '
            'marker-start="url(#arrow)" marker-end="url(#arrow)"/>'
        )
        tp = np.array([c[0] + 0.01, c[1]])
        out.append(f'<text class="panel-name" x="{_fmt(tp[0] * 1000)}" y="{_fmt(H - tp[1] * 1000)}" font-size="12" font-family="sans-serif">{escape(n)}</text>')
        for mk in marks:
            if mk.panel != n:
                continue
            for f in mk.fractions:
                p, nrm = edge_point(pan, mk.edge, f)
                a, b = p + off, p + off + NOTCH_LENGTH * nrm
                out.append(f'<path class="notch" d="M{xy(a)} L{xy(b)}" stroke="red" stroke-width="0.4"/>')
            p, nrm = edge_point(pan, mk.edge, 0.5)
            q = p + off + 0.018 * nrm
            out.append(
                f'<text class="seam-label" x="{_fmt(q[0] * 1000)}" y="{_fmt(H - q[1] * 1000)}" font-size="7" '
                f'font-family="sans-serif" text-anchor="middle" dominant-baseline="middle" fill="red">{mk.code}</text>'
            )
        out.append("</g>")
    out.append("</svg>")
    with atomic_write(path) as tmp:
        Path(tmp).write_text("\n".join(out) + "\n", encoding="utf-8")
