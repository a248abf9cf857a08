"""Darts and separate bands of a design: V notches cut into a straight edge of a panel and sewn
shut (:func:`dart_edge`), and a band whose top and bottom edges are cut to meet the pieces of the
panels sewn above and below it (:func:`band_between`).

A dart is a V notch: its mouth, ``width`` [m] wide, lies on the edge, its tip ``depth`` [m] inside
the panel; its two legs (mouth to tip, tip to mouth) are sewn to each other, so the edge's sewn
length is its cut length less the darts' widths.
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.base._build import loop_panel, place, rot_y180, stitch
from unsew.pattern.model import Edge, Panel, Stitch

__all__ = ["Dart", "dart_edge", "dart_pieces", "band_between", "BODICE_DART", "SKIRT_DART"]

#: (share of the girth difference the darts take, dart centre as a share of the panel's half
#: width, dart length as a share of the height it shapes) of a bodice's waist darts (the bust to
#: the hem) and of a skirt's (the hips to the top); the side seams take the rest.
BODICE_DART = (0.5, 0.45, 0.6)
SKIRT_DART = (0.5, 0.5, 0.6)
#: Darts narrower than this [m] are not cut.
MIN_DART_WIDTH = 0.005


class Dart(tuple):
    """(centre [m] along the edge from its start, mouth width [m], depth [m])."""

    __slots__ = ()

    def __new__(cls, centre: float, width: float, depth: float):
        return super().__new__(cls, (float(centre), float(width), float(depth)))


def dart_edge(panel: Panel, edge: int, darts: list, label: str) -> tuple[Panel, list[Stitch], list[int]]:
    """``panel`` with its straight edge ``edge`` cut by the V notches ``darts`` (:class:`Dart`,
    increasing centres, mouths inside the edge), the notches pointing into the panel (to the left
    of the edge's direction: the panel is counter-clockwise).

    Returns the new panel (edge ``edge`` becomes ``1 + 3 len(darts)`` edges: a piece of the edge
    labelled ``label_j``, then the dart's legs, ..., the last piece; every later edge's index
    shifted by ``3 len(darts)``), the darts' stitches (leg against leg) and the new indices of the
    edge's pieces, in order along the edge."""
    e = panel.edges[edge]
    if e.curvature is not None:
        raise ValueError(f"panel {panel.name!r}: darts are cut into straight edges only")
    v = panel.vertices
    a, b = v[e.start], v[e.end]
    length = float(np.linalg.norm(b - a))
    u = (b - a) / length
    n = np.array([-u[1], u[0]])  # into the panel
    new_pts = []
    for c, w, d in darts:
        if not (w / 2 < c < length - w / 2):
            raise ValueError(f"panel {panel.name!r}: a dart's mouth leaves its edge")
        new_pts += [a + (c - w / 2) * u, a + c * u + d * n, a + (c + w / 2) * u]
    k = len(new_pts)
    # the new vertices go right after the edge's start vertex (index e.start)
    s = e.start
    verts = np.concatenate([v[: s + 1], np.asarray(new_pts).reshape(-1, 2), v[s + 1 :]])
    shift = lambda i: i if i <= s else i + k  # noqa: E731  old vertex index -> new
    chain = [s] + list(range(s + 1, s + 1 + k)) + [shift(e.end)]
    pieces, labels = [], []
    for j in range(len(chain) - 1):
        q, r = divmod(j, 3)
        labels.append(f"{label}_{q}" if r == 0 else f"{label}_dart_{q}_{'out' if r == 1 else 'in'}")
        pieces.append(Edge(chain[j], chain[j + 1], None, labels[-1]))
    edges = (
        [Edge(shift(x.start), shift(x.end), x.curvature, x.label) for x in panel.edges[:edge]]
        + pieces
        + [Edge(shift(x.start), shift(x.end), x.curvature, x.label) for x in panel.edges[edge + 1 :]]
    )
    out = Panel(panel.name, verts, edges, panel.translation, panel.rotation, panel.label)
    st = [
        stitch(panel.name, edge + 3 * q + 1, panel.name, edge + 3 * q + 2, f"{panel.name}_{label}_dart_{q}")
        for q in range(len(darts))
    ]
    return out, st, [edge + 3 * q for q in range(len(darts) + 1)]


def dart_pieces(length: float, darts: list) -> list[float]:
    """Lengths [m] of the pieces an edge of ``length`` [m] is cut into by ``darts``, in order."""
    cuts = [0.0]
    for c, w, _ in darts:
        cuts += [c - w / 2, c + w / 2]
    cuts.append(length)
    return [cuts[i + 1] - cuts[i] for i in range(0, len(cuts), 2)]


def symmetric_darts(half: float, width: float, depth: float, at: float) -> list[Dart]:
    """Two darts on an edge ``2 half`` [m] long, centred ``at`` x ``half`` [m] either side of its
    middle, each ``width`` [m] wide at the mouth and ``depth`` [m] deep; none when narrower than
    :data:`MIN_DART_WIDTH`."""
    if width < MIN_DART_WIDTH:
        return []
    return [Dart(half - at * half, width, depth), Dart(half + at * half, width, depth)]


def _band_panel(name: str, hw: float, h: float, bottom: list[float], top: list[float]) -> Panel:
    """A band ``2 hw`` [m] wide and ``h`` [m] high, its bottom edge cut into pieces of lengths
    ``bottom`` (left to right, +x) and its top edge into ``top`` (right to left, -x).

    Edges: the bottom pieces, the right side, the top pieces, the left side."""
    xb = -hw + np.cumsum([0.0, *bottom])
    xt = hw - np.cumsum([0.0, *top])
    if abs(xb[-1] - hw) > 1e-6 or abs(xt[-1] + hw) > 1e-6:
        raise ValueError(f"band {name!r}: its pieces do not add up to its width")
    pts = [(x, 0.0) for x in xb[:-1]] + [(hw, 0.0)] + [(x, h) for x in xt[:-1]] + [(-hw, h)]
    labels = [f"bottom_{j}" for j in range(len(bottom))] + ["right_side"]
    labels += [f"top_{j}" for j in range(len(top))] + ["left_side"]
    return loop_panel(name, pts, None, labels)


def band_between(
    below: dict, above: dict, *, bottom_y: float, height: float, depth_z: float
) -> tuple[dict, list[Stitch]]:
    """Front and back bands (``waistband_front``, ``waistband_back``) ``height`` [m] high, their
    bottom at the world height ``bottom_y`` [m], laid flat at z = +/- ``depth_z`` [m], sewn to
    the pieces below and above them and to each other at the sides.

    below, above: {"front": [(panel, edge, length [m])], "back": [...]}: the edges the band's
    bottom and top meet, in the band's +x order (front +x is the body's left, back +x seen from
    behind its right); their lengths add up to the band's width on each side (the top's to the
    bottom's)."""
    panels, st = {}, []
    for side, R, z in (("front", np.eye(3), depth_z), ("back", rot_y180(), -depth_z)):
        bot = [p[2] for p in below[side]]
        top = [p[2] for p in above[side]][::-1]
        hw = 0.5 * sum(bot)
        band = _band_panel(f"waistband_{side}", hw, height, bot, top)
        place(band, R, (0.0, bottom_y, z))
        panels[band.name] = band
        nb, nt = len(bot), len(top)
        for j, (pn, e, _) in enumerate(below[side]):
            st.append(stitch(band.name, j, pn, e, f"{side}_band_bottom_{j}"))
        for j, (pn, e, _) in enumerate(above[side]):
            # the top's pieces run right to left: the j-th from the left is number nt - 1 - j
            st.append(stitch(pn, e, band.name, nb + 1 + (nt - 1 - j), f"{side}_band_top_{j}"))
    nf, nbk = len(below["front"]), len(below["back"])
    ntf, ntb = len(above["front"]), len(above["back"])
    st += [
        stitch("waistband_front", nf, "waistband_back", nbk + ntb + 1, "left_band_side"),
        stitch("waistband_back", nbk, "waistband_front", nf + ntf + 1, "right_band_side"),
    ]
    return panels, st
