"""The printed sheet of a sewing pattern, shared by the SVG, DXF and PDF writers: every piece
with its cut and sew lines, notches on both, grain line, fold line, name and cutting note, seam
labels, laid out side by side, and a 10 cm test square.

Everything here is in metres in the sheet frame (x right, y up); the writers convert to
millimetres. A piece's own lines are in its panel frame; ``offset`` places them on the sheet
(sheet point = panel point + offset), the same for every writer, so a DXF block inserted at
``offset`` and an SVG group shifted by it hold the same drawing.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from unsew.io.cutlines import (
    CuttingNote,
    PieceLines,
    cutting_notes,
    piece_lines,
    seam_allowances,
)
from unsew.pattern.curves import edge_length, sample_edge
from unsew.pattern.model import Pattern

__all__ = [
    "Sheet",
    "Piece",
    "Label",
    "make_sheet",
    "relayout",
    "seam_marks",
    "SeamMark",
    "edge_point",
    "stitch_code",
    "TEST_SQUARE_M",
    "NOTCH_LENGTH",
    "SIZE_TEXT",
]

#: Gap between laid-out pieces [m]; width after which a new row starts [m].
LAYOUT_GAP = 0.04
ROW_WIDTH = 1.6
#: Notch tick length [m] on the sew line; spacing between the notches of one seam [m].
NOTCH_LENGTH = 0.008
NOTCH_SPACING = 0.012
#: Side of the scale check square [m].
TEST_SQUARE_M = 0.10
#: The size written on every piece: unsew fits one wearer, there is no size run.
SIZE_TEXT = "made to measure (one size)"


def stitch_code(k: int) -> str:
    """Seam label of stitch ``k``: A..Z, then AA, AB, ..."""
    s = ""
    k += 1
    while k:
        k, r = divmod(k - 1, 26)
        s = chr(65 + r) + s
    return s


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


@dataclass
class Label:
    """A text on a piece: ``pos`` (2,) [m] panel frame, ``height`` [m], ``kind`` one of
    ``name`` (the piece name), ``note`` (quantity, size, allowance) or ``seam`` (a seam label,
    centred on ``pos``; the others start at it)."""

    pos: np.ndarray
    height: float
    text: str
    kind: str


@dataclass
class Piece:
    """One piece as drawn, panel frame [m]: its lines (:class:`unsew.io.cutlines.PieceLines`),
    cutting note, notches on the sew line and on the cut line (lists of (2, 2) segments, from
    the line into the piece), grain line (2, 2) arrowed at both ends, fold line (2, 2) or None,
    labels, and its sheet ``offset`` (2,)."""

    name: str
    lines: PieceLines
    note: CuttingNote
    notches_sew: list[np.ndarray]
    notches_cut: list[np.ndarray]
    grain: np.ndarray
    fold: np.ndarray | None
    labels: list[Label]
    offset: np.ndarray = field(default_factory=lambda: np.zeros(2))


@dataclass
class Sheet:
    """The whole drawing: pieces in ``pattern.panel_order``, the sheet's size (2,) [m] (x, y
    from 0), and the test square's lower-left corner (2,) [m]."""

    name: str
    pieces: list[Piece]
    size: np.ndarray
    square: np.ndarray


def _chord(poly: np.ndarray, x: float) -> tuple[float, float] | None:
    """The longest interval of the vertical line at ``x`` inside the closed polygon (M, 2)."""
    a, b = poly, np.roll(poly, -1, axis=0)
    m = (a[:, 0] - x) * (b[:, 0] - x) < 0
    if not m.any():
        return None
    t = (x - a[m, 0]) / (b[m, 0] - a[m, 0])
    ys = np.sort(a[m, 1] + t * (b[m, 1] - a[m, 1]))
    spans = [(ys[i], ys[i + 1]) for i in range(0, len(ys) - 1, 2)]
    return max(spans, key=lambda s: s[1] - s[0]) if spans else None


def _piece(
    pattern: Pattern, name: str, allowance: np.ndarray, note: CuttingNote, marks: list[SeamMark]
) -> Piece:
    pan = pattern.panels[name]
    lines = piece_lines(pan, allowance)
    sew = lines.sew
    lo, hi = sew.min(0), sew.max(0)
    w, h = hi - lo
    # grain line: a vertical chord well left of the centre, away from the seam labels (edge
    # midpoints) and the text block (which starts right of it)
    gx = lo[0] + 0.22 * w
    ch = _chord(sew, gx) or (lo[1], hi[1])
    gl = ch[1] - ch[0]
    grain = np.array([[gx, ch[0] + 0.15 * gl], [gx, ch[1] - 0.15 * gl]])
    fold = None
    if note.fold is not None:
        p0, d = note.fold
        s = (sew - p0) @ d
        fold = np.array([p0 + s.min() * d, p0 + s.max() * d])
    font = float(np.clip(min(w, h) / 22.0, 0.003, 0.008))
    size = ", ".join(f"{100 * x:g}" for x in sorted(set(np.round(lines.allowance, 4))))
    tx = gx + 0.006
    cy = lo[1] + 0.5 * h
    texts = [(name, 1.3 * font, "name")] + [(t, font, "note") for t in note.text.split("; ")]
    texts.append((f"size: {SIZE_TEXT}", 0.8 * font, "note"))
    texts.append((f"seam allowance {size} cm, included", 0.8 * font, "note"))
    labels, y = [], cy + 0.6 * font
    for t, fh, kind in texts:
        labels.append(Label(np.array([tx, y]), fh, t, kind))
        y -= 1.5 * fh
    notches_sew, notches_cut = [], []
    inset = min(0.018, 0.25 * h)
    for mk in marks:
        if mk.panel != name:
            continue
        wa = float(allowance[mk.edge])
        for f in mk.fractions:
            p, nrm = edge_point(pan, mk.edge, f)
            notches_sew.append(np.array([p, p + NOTCH_LENGTH * nrm]))
            if wa > 0:
                q = p - wa * nrm
                notches_cut.append(np.array([q, q + min(NOTCH_LENGTH, 0.6 * wa) * nrm]))
        p, nrm = edge_point(pan, mk.edge, 0.5)
        labels.append(Label(p + inset * nrm, 0.007, mk.code, "seam"))
    return Piece(name, lines, note, notches_sew, notches_cut, grain, fold, labels)


def make_sheet(
    pattern: Pattern,
    *,
    allowance: float | None = None,
    hem: float | None = None,
    gap: float = LAYOUT_GAP,
    row_width: float = ROW_WIDTH,
) -> Sheet:
    """Lay out every piece of ``pattern`` with its seam allowance (``allowance``, ``hem`` [m] as
    :func:`unsew.io.cutlines.seam_allowances`): side by side in rows by their cut lines, no
    overlap, a margin ``gap`` [m] all round, the test square in a row of its own above them."""
    widths = seam_allowances(pattern, default=allowance, hem=hem)
    notes = cutting_notes(pattern)
    marks = seam_marks(pattern)
    pieces = [_piece(pattern, n, widths[n], notes[n], marks) for n in pattern.panel_order]
    return relayout(Sheet(pattern.name, pieces, np.zeros(2), np.zeros(2)), gap=gap, row_width=row_width)


def relayout(
    sheet: Sheet,
    *,
    gap: float = LAYOUT_GAP,
    row_width: float = ROW_WIDTH,
    tallest_first: bool = False,
    square: bool = True,
) -> Sheet:
    """The same pieces laid out again (a new Sheet; the pieces' offsets change): in rows no wider
    than ``row_width`` [m] where possible, in pattern order or, ``tallest_first``, by decreasing
    height (fewer rows of mixed heights); ``square``: the test square in a row of its own above
    (False: none, its corner at the origin)."""
    import copy

    pieces = [copy.copy(pc) for pc in sheet.pieces]
    order = sorted(pieces, key=lambda pc: -float(np.ptp(pc.lines.cut[:, 1]))) if tallest_first else pieces
    x, y, row_h = gap, gap, 0.0
    for pc in order:
        lo, hi = pc.lines.cut.min(0), pc.lines.cut.max(0)
        w, h = hi - lo
        if x > gap and x + w > row_width:
            x, y, row_h = gap, y + row_h + gap, 0.0
        pc.offset = np.array([x, y]) - lo
        x += w + gap
        row_h = max(row_h, h)
    top = max((pc.lines.cut.max(0)[1] + pc.offset[1] for pc in pieces), default=0.0)
    right = max(
        [pc.lines.cut.max(0)[0] + pc.offset[0] for pc in pieces]
        + [gap + (2.5 * TEST_SQUARE_M if square else 0)]
    )
    if not square:
        return Sheet(sheet.name, pieces, np.array([right + gap, top + gap]), np.zeros(2))
    corner = np.array([gap, top + gap])
    return Sheet(sheet.name, pieces, np.array([right + gap, corner[1] + TEST_SQUARE_M + gap]), corner)
