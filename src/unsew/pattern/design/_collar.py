"""Collars of a design's top: a hood of two side panels, or a standing (turtle) collar of a front
and a back band, sewn to the neckline's halves (the front's and the back's necklines cut at the
centre line, :func:`unsew.pattern.design._top.top_panels` with ``split_neck``).

A hood's side panel, panel frame (x forward for the right panel, y up, the side neck point at
the origin), counter-clockwise seen from outside::

    vertices: B (centre back neck), S (side neck point), F (centre front neck), T (the face
    opening's top), K (the top seam's back end)
    edges: 0 B->S back_neckline, 1 S->F front_neckline (both sewn to the neckline), 2 F->T
    face (left open), 3 T->K top, 4 K->B back (a curve round the back of the head; top and
    back sewn to the other panel's)

The left panel is the right one's mirror image. Both stand flat in a plane beside the head, as
GarmentCode lays out its hoods (``left_hood``, ``right_hood``); the placement keeps panels above
the neck where they are (:func:`unsew.body.placement.panel_roles`: "free") and the sewing pulls
them onto the neckline and over the head.

A turtle band, panel frame (x across, y up, y = 0 at its lower edge)::

    vertices: (-w, 0), (0, 0), (w, 0), (w, h), (-w, h)
    edges: 0 and 1 the lower edge's -x and +x halves (sewn to the neckline's halves), 2 the +x
    side, 3 the top (left open), 4 the -x side (sides sewn to the other band's)

laid flat in front of and behind the neck, from the neck points' height up.
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.base._build import cubic, loop_panel, mirror_panel, place, rot_y180, stitch
from unsew.pattern.base._frame import BodyFrame
from unsew.pattern.curves import edge_length
from unsew.pattern.measurements import Measurements
from unsew.pattern.model import Panel

__all__ = [
    "collar_set",
    "head_girth",
    "HEAD_GIRTH_PER_HEIGHT",
    "HOOD_TOP_EASE",
    "HOOD_DEPTH_EASE",
    "TURTLE_HEIGHT",
]

#: The head's girth (its fullest horizontal section above the head joint) over its height from
#: the base of the neck to the crown [-] (docs/decisions/036-collars.md).
HEAD_GIRTH_PER_HEIGHT = 2.2
#: A hood's side panel rises this much [m] above the head's height (the neck's base to the
#: crown): the way over the side of the head to the top seam, and room above the crown.
HOOD_TOP_EASE = 0.08
#: A hood's side panel is this much [m] deeper (front to back) than the head's width (its girth
#: over pi).
HOOD_DEPTH_EASE = 0.07
#: The face opening leans forward this much [m] from the front neck to the hood's top.
HOOD_FRONT_LEAN = 0.02
#: A hood's side panels stand this far [m] outside the head's half width (its girth over 2 pi).
HOOD_CLEARANCE = 0.03
#: A turtle collar's default height [m] (the design's ``collar_height``).
TURTLE_HEIGHT = 0.08
#: The turtle's bands stand this far [m] outside the neck's radius.
TURTLE_CLEARANCE = 0.05


def head_girth(m: Measurements) -> float:
    """The head's girth [m] from its height over the base of the neck (:data:`HEAD_GIRTH_PER_HEIGHT`)."""
    return HEAD_GIRTH_PER_HEIGHT * (m.height - m.neck_height)


def _neck_halves(panel: Panel) -> dict:
    """{"right": edge index, "left": edge index} of a front's or back's neckline halves."""
    out = {}
    for i, e in enumerate(panel.edges):
        for side in ("right", "left"):
            if e.label == f"{side}_neckline":
                out[side] = i
    if set(out) != {"right", "left"}:
        raise ValueError(f"{panel.name}: a collar needs the neckline cut in halves (split_neck)")
    return out


def _hood_side(m: Measurements, back_len: float, front_len: float, depths: tuple[float, float]) -> Panel:
    """The right hood panel (frame of the module docstring), its neck edges ``back_len`` and
    ``front_len`` [m] long, their ends ``depths`` [m] (back, front) below the neck point."""
    db, df = depths
    g = head_girth(m)
    top = (m.height - m.neck_height) + HOOD_TOP_EASE
    width = g / np.pi + HOOD_DEPTH_EASE
    B = np.array([-np.sqrt(back_len**2 - db**2), -db])
    F = np.array([np.sqrt(front_len**2 - df**2), -df])
    T = np.array([F[0] + HOOD_FRONT_LEAN, top])
    back_x = T[0] - width  # the back of the head, seen from the side
    K = np.array([T[0] - width / 2, top])
    back = cubic(K, B, (back_x, top), (back_x, B[1] + 0.3 * (top - B[1])))
    labels = ["back_neckline", "front_neckline", "face", "top", "back"]
    return loop_panel("right_hood", [B, np.zeros(2), F, T, K], {4: back}, labels)


def _hood(m: Measurements, f: BodyFrame, front: Panel, back: Panel, depths) -> tuple[list, list]:
    """Left and right hood panels sewn to ``front``'s and ``back``'s neckline halves."""
    fh, bh = _neck_halves(front), _neck_halves(back)
    # front +x is the body's left, back +x (seen from behind) its right: the right hood meets the
    # back's right half and the front's left half
    right = _hood_side(m, edge_length(back, bh["right"]), edge_length(front, fh["left"]), depths)
    left = mirror_panel(right, "left_hood")
    x = head_girth(m) / (2 * np.pi) + HOOD_CLEARANCE
    # the right panel's x runs forward (+z), its normal out to -x; the left's mirrored
    place(right, np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]), (-x, f.neck_y, 0.0))
    place(left, np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]), (x, f.neck_y, 0.0))
    r = {e.label: i for i, e in enumerate(right.edges)}
    lft = {e.label: i for i, e in enumerate(left.edges)}
    st = [
        stitch("right_hood", r["top"], "left_hood", lft["top"], "hood_top"),
        stitch("right_hood", r["back"], "left_hood", lft["back"], "hood_back"),
        stitch("right_hood", r["back_neckline"], "back", bh["right"], "right_hood_back_neck"),
        stitch("right_hood", r["front_neckline"], "front", fh["left"], "right_hood_front_neck"),
        stitch("left_hood", lft["back_neckline"], "back", bh["left"], "left_hood_back_neck"),
        stitch("left_hood", lft["front_neckline"], "front", fh["right"], "left_hood_front_neck"),
    ]
    return [left, right], st


def _turtle(m: Measurements, f: BodyFrame, front: Panel, back: Panel, height: float) -> tuple[list, list]:
    """A front and a back band ``height`` [m] high, each as wide as its neckline, sewn to it and
    to each other at the sides."""
    z = m.neck / (2 * np.pi) + TURTLE_CLEARANCE
    panels, st = [], []
    for side, torso, R, sign in (("front", front, np.eye(3), 1.0), ("back", back, rot_y180(), -1.0)):
        h = _neck_halves(torso)
        wl, wr = edge_length(torso, h["left"]), edge_length(torso, h["right"])
        band = loop_panel(
            f"turtle_{side}",
            [(-wl, 0.0), (0.0, 0.0), (wr, 0.0), (wr, height), (-wl, height)],
            None,
            ["neckline_left", "neckline_right", "right_side", "top", "left_side"],
        )
        place(band, R, (0.0, f.neck_y, sign * z))
        panels.append(band)
        st += [
            stitch(side, h["right"], band.name, 1, f"turtle_{side}_right"),
            stitch(side, h["left"], band.name, 0, f"turtle_{side}_left"),
        ]
    # front +x is the body's left, the back's -x side too
    st += [
        stitch("turtle_front", 2, "turtle_back", 4, "turtle_left_side"),
        stitch("turtle_back", 2, "turtle_front", 4, "turtle_right_side"),
    ]
    return panels, st


def collar_set(design, m: Measurements, f: BodyFrame, front: Panel, back: Panel, depths) -> tuple[list, list]:
    """The collar of ``design`` (``collar``: ``hood`` or ``turtle``; ``collar_height`` [m] of a
    turtle) sewn to ``front``'s and ``back``'s neckline halves (:func:`_neck_halves`), and its
    stitches; ``depths``: (back, front) neckline depths [m] below the neck points. No panels for
    ``collar == "none"``."""
    if design.collar == "hood":
        return _hood(m, f, front, back, depths)
    if design.collar == "turtle":
        return _turtle(m, f, front, back, design.collar_height)
    return [], []
