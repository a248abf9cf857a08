"""Tops and bodices of a design: front and back with any of four necklines, a hem that may be cut
in pieces (to meet a skirt's or trousers' waist), sleeves in one or two pieces, cuffs.

Front and back, panel frame (x across, y up, y = 0 at the hem), counter-clockwise from the hem:
the hem (P pieces, left to right), the right side (k segments below the underarm), the right
armhole, the right shoulder, the neckline, then the mirror images down the left side. The
neckline is one curve (``round``, ``boat``), two straight edges meeting at a point on the centre
line (``v``), or a straight edge down from each neck point and one across (``square``, whose two
corners are its lowest points); under a collar a round neckline is the same curve cut at the
centre line (``right_neckline``, ``left_neckline``), each half sewn to the collar. Built with
:func:`unsew.pattern.base._build.symmetric_panel`, as the library's tops
(:mod:`unsew.pattern.base.tshirt`), which a round or V neckline reproduces.

A two-piece sleeve is the one-piece sleeve cut along its centre line (cap top to hem): the +x
half (edges 0 hem, 1 underarm, 2 cap, 3 centre seam) and its mirror image, the -x half (edges 0
centre seam, 1 cap, 2 underarm, 3 hem), each turned down about the centre line to face the
front or the back of the arm (as the placement wraps sleeve halves). A cuff is a rectangle below
the sleeve's hem, sewn to itself at its side; its top is cut at x = 0 under a two-piece sleeve.
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.base._build import (
    cubic,
    loop_panel,
    mirror_panel,
    place,
    rot_y180,
    stitch,
    symmetric_panel,
)
from unsew.pattern.base._frame import BodyFrame
from unsew.pattern.base.tshirt import (
    BACK_NECK_DEPTH,
    BUST_EASE,
    BACK_V_DEPTH,
    FRONT_NECK_DEPTH,
    FRONT_V_DEPTH,
    LONG_SLEEVE_EXTRA,
    SHORT_SLEEVE_LENGTH,
    WRIST_EASE,
    WRIST_PER_UPPER_ARM,
    TopSpec,
    _armhole,
    _neckline,
    side_and_shoulder_stitches,
    sleeve_panels,
)
from unsew.pattern.curves import panel_outline, relative_to_absolute
from unsew.pattern.measurements import Measurements
from unsew.pattern.model import Edge, Panel, Stitch, matrix_to_euler_xyz

__all__ = [
    "top_panels",
    "strapless_panels",
    "hem_cuts",
    "top_stitches",
    "sleeve_set",
    "CUFF_HEIGHT",
    "NECK_DEPTHS",
]

#: Neckline depth below the neck points [m], front and back, per shape (a V's to its point, a
#: square's to its corners). round and v are the library tops' (:mod:`unsew.pattern.base.tshirt`).
NECK_DEPTHS = {
    "round": (FRONT_NECK_DEPTH, BACK_NECK_DEPTH),
    "v": (FRONT_V_DEPTH, BACK_V_DEPTH),
    "square": (0.10, 0.05),
    "boat": (0.03, 0.015),
}
#: Neck points' distance from the centre line beyond the neck's radius [m] (the library tops'),
#: and how much further out a boat neck puts them [m].
NECK_WIDTH_EASE = 0.015
BOAT_WIDEN = 0.05
#: A cuff's height [m].
CUFF_HEIGHT = 0.05


def _neck_half_width(m: Measurements, necklines: tuple[str, str]) -> float:
    """Neck points' x [m]: the neck's radius plus ease, wider when either side is a boat neck."""
    w = m.neck / (2 * np.pi) + NECK_WIDTH_EASE
    return w + (BOAT_WIDEN if "boat" in necklines else 0.0)


def _torso_panel(
    name: str, half: list, curves: list, labels: list, shape: str, depth: float, split: bool = False
) -> Panel:
    """One front or back: ``half`` runs up the right side to the neck point (its last point);
    the neckline of ``shape`` dips ``depth`` [m] below the neck points; a round one cut at the
    centre line into ``right_neckline`` and ``left_neckline`` when ``split`` (under a collar)."""
    neck = half[-1]
    if shape == "v":
        return symmetric_panel(
            name,
            half + [np.array([0.0, neck[1] - depth])],
            curves + [None],
            half_labels=labels + ["right_neckline"],
            bottom_label="hem",
        )[0]
    if shape == "square":
        return symmetric_panel(
            name,
            half + [np.array([neck[0], neck[1] - depth])],
            curves + [None],
            half_labels=labels + ["right_neckline"],
            bottom_label="hem",
            top_label="neckline",
        )[0]
    top = _neckline(neck, neck * np.array([-1.0, 1.0]), depth)
    if split:  # the same curve cut at the centre line: a collar's seam meets each half
        c1, c2 = relative_to_absolute(neck, neck * np.array([-1.0, 1.0]), np.asarray(top.params))
        p01, p12 = (neck + c1) / 2, (c1 + c2) / 2
        p012 = (p01 + p12) / 2
        mid = np.array([0.0, neck[1] - depth])  # the cubic's midpoint (de Casteljau at t = 1/2)
        return symmetric_panel(
            name,
            half + [mid],
            curves + [cubic(neck, mid, p01, p012)],
            half_labels=labels + ["right_neckline"],
            bottom_label="hem",
        )[0]
    return symmetric_panel(
        name, half, curves, top=top, half_labels=labels, bottom_label="hem", top_label="neckline"
    )[0]


def hem_cuts(panel: Panel, cuts, label: str) -> Panel:
    """``panel`` with its straight edge 0 cut at the x positions ``cuts`` [m] (increasing, inside
    the edge): edge 0 becomes ``len(cuts) + 1`` edges labelled ``label_0``, ``label_1``, ... (or
    ``label`` when there is no cut), every later edge's index shifted by ``len(cuts)``."""
    c = len(cuts)
    v = panel.vertices
    y0 = v[panel.edges[0].start, 1]
    verts = np.concatenate([v[:1], np.array([(float(x), y0) for x in cuts]).reshape(-1, 2), v[1:]])
    shift = lambda i: i if i == 0 else i + c  # noqa: E731  old vertex index -> new
    pieces = [Edge(j, j + 1, None, f"{label}_{j}" if c else label) for j in range(c + 1)]
    rest = [Edge(shift(e.start), shift(e.end), e.curvature, e.label) for e in panel.edges[1:]]
    return Panel(panel.name, verts, pieces + rest, panel.translation, panel.rotation, panel.label)


def strapless_panels(m: Measurements, f: BodyFrame, spec: TopSpec, drop: float):
    """Front and back of a strapless top [m] (placed around the body of frame ``f``): up the
    sides to ``drop`` [m] below the armpits, as wide there as a top at its underarm, and straight
    across (``strapless_top``); and k, the number of side segments."""
    corner = np.array([(m.bust + BUST_EASE) / 4, f.armpit_y - drop - spec.hem_y])
    k = len(spec.lower)
    half = [np.asarray(p) for p in spec.lower] + [corner]
    panels = [
        symmetric_panel(
            name,
            half,
            list(spec.lower_curves),
            half_labels=["right_side"] * k,
            bottom_label="hem",
            top_label="strapless_top",
        )[0]
        for name in ("front", "back")
    ]
    place(panels[0], np.eye(3), (0.0, spec.hem_y, f.chest_z))
    place(panels[1], rot_y180(), (0.0, spec.hem_y, -f.chest_z))
    return panels[0], panels[1], k


def top_panels(
    m: Measurements, f: BodyFrame, spec: TopSpec, necklines: tuple[str, str], *, split_neck: bool = False
):
    """Front and back of a top [m] (placed around the body of frame ``f``) and the number k of
    side segments below the underarm; ``necklines``: front's and back's shapes; ``split_neck``:
    round necklines cut in halves at the centre line (a collar is sewn to each half)."""
    w = (m.bust + BUST_EASE) / 4
    neck_w = _neck_half_width(m, necklines)
    under = np.array([w, f.armpit_y - spec.hem_y])
    tip = np.array([f.shoulder_x + 0.01, f.shoulder_y - spec.hem_y])
    neck = np.array([neck_w, f.neck_y - spec.hem_y])
    k = len(spec.lower)
    labels = ["right_side"] * k + ["right_armhole", "right_shoulder"]
    panels = []
    for side, (name, shape) in enumerate(zip(("front", "back"), necklines)):
        half = [np.asarray(p) for p in spec.lower] + [under, tip, neck]
        curves = list(spec.lower_curves) + [_armhole(under, tip), None]
        depth = NECK_DEPTHS[shape][side]
        panels.append(_torso_panel(name, half, curves, list(labels), shape, depth, split_neck))
    front, back = panels
    place(front, np.eye(3), (0.0, spec.hem_y, f.chest_z))
    place(back, rot_y180(), (0.0, spec.hem_y, -f.chest_z))
    return front, back, k


def top_stitches(
    front: Panel, back: Panel, k: int, hem_pieces: int = 1, *, shoulders: bool = True
) -> list[Stitch]:
    """Side and shoulder seams of :func:`top_panels`' front and back (hem in ``hem_pieces``), the
    side seams alone for :func:`strapless_panels`' (``shoulders=False``).
    Front +x is the body's left, back +x (seen from behind) the body's right."""
    n = {"front": len(front.vertices), "back": len(back.vertices)}
    return side_and_shoulder_stitches(n, k, hem_pieces, shoulders=shoulders)


def _armholes(front: Panel, back: Panel, k: int, hem_pieces: int) -> dict:
    """Per arm: the (panel, edge) of the armhole met by the sleeve's -x and +x cap halves.
    The left sleeve's +x side faces the back, the right sleeve's the front."""
    nf, nb = len(front.vertices), len(back.vertices)
    fr, fl = ("front", k + hem_pieces), ("front", nf - 1 - k)
    br, bl = ("back", k + hem_pieces), ("back", nb - 1 - k)
    return {"left": (fr, bl), "right": (br, fl)}


def _fold_angle(half: Panel) -> float:
    """The angle [rad] a sleeve half turns about its centre line (x = 0) down beside the arm: on
    a tube whose girth is twice the half's width w, with the centre seam on top, the half's area
    centroid (at x = c) sits pi * c / w round from the top, and the half faces out there."""
    o = panel_outline(half)
    q = np.roll(o, -1, axis=0)
    cross = o[:, 0] * q[:, 1] - q[:, 0] * o[:, 1]
    c = float(np.sum((o[:, 0] + q[:, 0]) * cross) / (3.0 * np.sum(cross)))
    return float(np.pi * abs(c) / np.abs(o[:, 0]).max())


def _sleeve_halves(sleeve: Panel, name_plus: str, name_minus: str) -> tuple[Panel, Panel]:
    """The +x and -x halves of a one-piece sleeve, cut along x = 0, each turned about that line
    (:func:`_fold_angle`) down beside the arm: the +x half towards where the sleeve's +x pointed,
    the -x half the other way (the front and the back of the arm)."""
    v = sleeve.vertices  # hem -x, hem +x, underarm +x, cap top, underarm -x
    half = loop_panel(
        name_plus,
        [(0.0, v[1, 1]), v[1], v[2], v[3]],
        {1: sleeve.edges[1].curvature, 2: sleeve.edges[2].curvature},
        ["hem", "right_underarm", "right_cap", "centre"],
    )
    other = mirror_panel(half, name_minus)
    R = sleeve.rotation_matrix()
    a = _fold_angle(half)
    for p, turn in ((half, a), (other, -a)):
        c, s = np.cos(turn), np.sin(turn)  # a turn about the panel's own y axis
        fold = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
        p.translation, p.rotation = sleeve.translation.copy(), matrix_to_euler_xyz(R @ fold)
    return half, other


def _cuff(name: str, sleeve: Panel, hem_half: float, split: bool) -> Panel:
    """A cuff as wide as the sleeve's hem (2 ``hem_half`` [m]), CUFF_HEIGHT high, placed below
    the hem in the sleeve's plane; its top cut at x = 0 when ``split``."""
    w, h = hem_half, CUFF_HEIGHT
    top = [(w, h), (0.0, h), (-w, h)] if split else [(w, h), (-w, h)]
    labels = ["hem", "right_side"] + (["top_right", "top_left"] if split else ["top"]) + ["left_side"]
    cuff = loop_panel(name, [(-w, 0.0), (w, 0.0)] + top, None, labels)
    hem_y = float(sleeve.vertices[1, 1])
    place(cuff, sleeve.rotation_matrix(), sleeve.to_world([(0.0, hem_y)])[0], (0.0, h))
    return cuff


def _arm(side: str, sleeve: Panel, holes: tuple, pieces: int, cuffs: bool):
    """Panels, armhole stitches and other stitches of one arm's sleeve (``side``: left/right)."""
    minus, plus = holes
    hem_half = float(sleeve.vertices[1, 0])
    if pieces == 1:
        panels = [sleeve]
        arm = [(minus, (sleeve.name, 3)), (plus, (sleeve.name, 2))]
        rest = [stitch(sleeve.name, 1, sleeve.name, 4, f"{side}_underarm")]
        hems = [(sleeve.name, 0)]
    else:
        # the left sleeve's +x half faces the back, the right sleeve's the front
        names = ("back", "front") if side == "left" else ("front", "back")
        p, q = _sleeve_halves(sleeve, f"{side}_sleeve_{names[0]}", f"{side}_sleeve_{names[1]}")
        panels = [p, q]
        arm = [(minus, (q.name, 1)), (plus, (p.name, 2))]
        rest = [
            stitch(p.name, 1, q.name, 2, f"{side}_underarm"),
            stitch(p.name, 3, q.name, 0, f"{side}_sleeve_top"),
        ]
        hems = [(p.name, 0), (q.name, 3)]
    if side == "right":
        arm = arm[::-1]  # the front armhole's stitch first
    arm_st = [
        stitch(a[0], a[1], b[0], b[1], f"{side}_armhole_{fb}") for (a, b), fb in zip(arm, ("front", "back"))
    ]
    if cuffs:
        cuff = _cuff(f"{side}_cuff", sleeve, hem_half, pieces == 2)
        panels.append(cuff)
        tops = (2, 3) if pieces == 2 else (2,)
        for (pn, e), t in zip(hems, tops):
            rest.append(stitch(pn, e, cuff.name, t, f"{side}_cuff" + (f"_{t - 2}" if pieces == 2 else "")))
        rest.append(stitch(cuff.name, 1, cuff.name, len(cuff.edges) - 1, f"{side}_cuff_side"))
    return panels, arm_st, rest


def sleeve_set(
    m: Measurements, f: BodyFrame, front: Panel, back: Panel, k: int, *, hem_pieces: int = 1, design
) -> tuple[list[Panel], list[Stitch]]:
    """The sleeves of ``design`` (sleeves, sleeve_pieces, cuffs) sized to the armholes of
    ``front`` and ``back`` (built with ``k`` side segments and ``hem_pieces``), and their
    stitches: armholes of both arms first (left front, left back, right front, right back), then
    underarm, sleeve-top and cuff seams."""
    if design.sleeves == "none":
        return [], []
    from unsew.pattern.curves import edge_length

    armhole = edge_length(front, k + hem_pieces)
    if design.sleeves == "short":
        length, hem_half = SHORT_SLEEVE_LENGTH, None
    else:
        length = m.arm_length + LONG_SLEEVE_EXTRA
        hem_half = (WRIST_PER_UPPER_ARM * m.upper_arm + WRIST_EASE) / 2
    if design.cuffs:
        length -= CUFF_HEIGHT
    left, right = sleeve_panels(m, f, armhole, length=length, hem_half=hem_half)
    holes = _armholes(front, back, k, hem_pieces)
    panels, arm_st, rest = [], [], []
    for side, sleeve in (("left", left), ("right", right)):
        p, a, r = _arm(side, sleeve, holes[side], design.sleeve_pieces, design.cuffs)
        panels += p
        arm_st += a
        rest += r
    return panels, arm_st + rest
