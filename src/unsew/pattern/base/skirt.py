"""Base skirts: front and back, each a sector of an annulus (paper Fig. 2c).

Variants: ``skirt`` (knee-length A-line), ``skirt_band`` (the same under a waistband,
:mod:`unsew.pattern.base._band`), ``skirt_circle`` (a half-circle skirt, its cone unrolled to
pi, under a waistband), ``skirt_pencil`` (straight from the hips down, under a waistband: not a
cone, see :func:`make_skirt_pencil`), ``skirt_darts`` (an A-line shaped to the waist by two
darts per panel, under a waistband: :func:`make_skirt_darts`).

The waist and hem are concentric circular arcs (GarmentCode ``circle`` edges), so the skirt
is a cone: its flare is chosen so that the cone's girth at hip depth clears the hips. Panel
frame: x across, y up, the centre of the circles on x = 0 above the panel.

Edges of each panel: 0 hem (arc), 1 right side seam, 2 waist (arc), 3 left side seam.
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.measurements import Measurements
from unsew.pattern.base._band import BAND_HEIGHT, band_panels, band_stitches
from unsew.pattern.base._build import loop_panel, place, rot_y180, stitch
from unsew.pattern.base._frame import body_frame
from unsew.pattern.curves import edge_length, sample_edge
from unsew.pattern.model import Curvature, Pattern

__all__ = ["make_skirt", "make_skirt_band", "make_skirt_circle", "make_skirt_pencil", "make_skirt_darts"]

WAIST_EASE = 0.02  #: [m]
HIP_EASE = 0.06  #: [m]
#: Skirt length below the waist, as a fraction of the leg length (knee length).
LENGTH_PER_LEG = 0.75
#: Extra flare over what the hips need [rad of the full cone's unrolled angle].
EXTRA_FLARE = 0.35
#: The darted skirt: share of the hip-to-waist difference its darts take (the side seams take
#: the rest), its hem's flare beyond the hips per side seam [m], a dart's length below the
#: skirt's top as a share of the hips' depth below it.
DART_SHARE = 0.5
DART_FLARE = 0.05
DART_DEPTH = 0.6


def _panel(name: str, r_w: float, r_h: float, half_angle: float):
    s, c = np.sin(half_angle), np.cos(half_angle)
    # Circle centre at (0, r_h): hem corners at radius r_h, waist corners at r_w, below it.
    cy = r_h
    v = np.array(
        [(-r_h * s, cy - r_h * c), (r_h * s, cy - r_h * c), (r_w * s, cy - r_w * c), (-r_w * s, cy - r_w * c)]
    )
    curves = {
        0: Curvature("circle", [r_h, False, True]),  # hem: bulges down, to the right of -> (+x)
        2: Curvature("circle", [r_w, False, False]),  # waist: bulges down, to the left of <- (-x)
    }
    return loop_panel(name, v, curves, ["hem", "right_side", "waist", "left_side"])


def _girths(m: Measurements, top_drop: float):
    """The body frame, the skirt's top height [m] (``top_drop`` [m] below the waist), the
    skirt's girth there and at the hips with their ease [m], and the hips' depth below the waist [m]."""
    f = body_frame(m)
    drop = f.waist_y - f.hip_y  # waist to hip along the body [m]
    # girth where the skirt's top sits: linear between waist and hips
    top = m.waist + (m.hip - m.waist) * top_drop / drop + WAIST_EASE
    return f, f.waist_y - top_drop, top, m.hip + HIP_EASE, drop


def _skirt(m: Measurements, name: str, *, band: bool, theta: float | None = None) -> Pattern:
    """Two-panel conical skirt; ``theta``: the cone's unrolled angle [rad] (None: what the hips
    need plus EXTRA_FLARE); ``band``: with a waistband, the skirt starting BAND_HEIGHT lower."""
    top_drop = BAND_HEIGHT if band else 0.0
    f, top_y, top, hip, drop = _girths(m, top_drop)
    if theta is None:
        theta = (hip - top) / (drop - top_drop) + EXTRA_FLARE  # unrolled angle of the whole cone [rad]
    r_w = top / theta
    r_h = r_w + LENGTH_PER_LEG * m.leg_length - top_drop
    front = _panel("front", r_w, r_h, theta / 4)
    back = _panel("back", r_w, r_h, theta / 4)
    local_waist = (0.0, r_h - r_w)  # centre of the waist arc (its lowest point) at the waist
    if band:
        # the arc's mean height at the band's lower edge: wrapped round the body the arc is level,
        # and the placement joins horizontal seams at their mean heights
        local_waist = (0.0, float(sample_edge(front, 2, 64)[:, 1].mean()))
    place(front, np.eye(3), (0.0, top_y, f.hip_z), local_waist)
    place(back, rot_y180(), (0.0, top_y, -f.hip_z), local_waist)
    st = [stitch("front", 1, "back", 3, "left_side"), stitch("back", 1, "front", 3, "right_side")]
    panels = {"front": front, "back": back}
    if band:
        bf, bb = band_panels(edge_length(front, 2) / 2, f.waist_y, f.hip_z)
        panels.update({bf.name: bf, bb.name: bb})
        # band lower edge (+x) against the skirt's waist arc (-x)
        st += [stitch(bf.name, 0, "front", 2, "front_waist"), stitch(bb.name, 0, "back", 2, "back_waist")]
        st += band_stitches()
    return Pattern(name, panels, st, properties={"units_in_meter": 100, "curvature_coords": "relative"})


def _banded_sizes(m: Measurements):
    """The sizes of a straight-sided skirt under a waistband (pencil, darted): the body frame,
    the skirt's top height [m], its length [m], half widths of a panel at its top and at the hips
    [m], and the hips' depth below its top [m]."""
    f, top_y, top, hip, drop = _girths(m, BAND_HEIGHT)
    return f, top_y, LENGTH_PER_LEG * m.leg_length - BAND_HEIGHT, top / 4, hip / 4, drop - BAND_HEIGHT


def _front_back(v: np.ndarray, labels: list[str], f, top_y: float, length: float, hip: tuple[int, int]):
    """Front and back panels of outline ``v`` ((n, 2) [m], hem at y = 0, top at ``length``),
    placed with their top at ``top_y`` [m], and their side seams: edges 1 and ``hip[0]`` (hem to
    hips, hip line) of one panel against ``hip[1]`` + 1 and ``hip[1]`` of the other."""
    front, back = loop_panel("front", v, None, labels), loop_panel("back", v, None, labels)
    place(front, np.eye(3), (0.0, top_y, f.hip_z), (0.0, length))
    place(back, rot_y180(), (0.0, top_y, -f.hip_z), (0.0, length))
    a, b = hip
    st = [
        stitch("front", 1, "back", b + 1, "left_side"),
        stitch("front", a, "back", b, "left_hip"),
        stitch("back", 1, "front", b + 1, "right_side"),
        stitch("back", a, "front", b, "right_hip"),
    ]
    return front, back, st


def _pencil(m: Measurements) -> Pattern:
    """Two-panel pencil skirt under a waistband: each panel a hexagon, straight and as wide as
    the hips (with HIP_EASE) from the hem up to hip depth, then narrowing to the waist along a
    straight hip line. A cone (:func:`_skirt`) narrow enough at the hem for a pencil target is too
    narrow at the hips of a curvy body, and grading, which edits the hem and the waist, cannot put
    the width back between them: here the side seam has a corner at the hips.

    Edges of each panel: 0 hem, 1 right side (hem to hips), 2 right hip line, 3 waist, 4 left hip
    line, 5 left side."""
    f, top_y, length, t, h, d = _banded_sizes(m)
    v = np.array([(-h, 0.0), (h, 0.0), (h, length - d), (t, length), (-t, length), (-h, length - d)])
    labels = ["hem", "right_side", "right_hip", "waist", "left_hip", "left_side"]
    front, back, st = _front_back(v, labels, f, top_y, length, (2, 4))
    bf, bb = band_panels(t, f.waist_y, f.hip_z)
    st += [stitch(bf.name, 0, "front", 3, "front_waist"), stitch(bb.name, 0, "back", 3, "back_waist")]
    st += band_stitches()
    return Pattern(
        "skirt_pencil",
        {"front": front, "back": back, bf.name: bf, bb.name: bb},
        st,
        properties={"units_in_meter": 100, "curvature_coords": "relative"},
    )


#: Edge labels of a darted skirt panel, counter-clockwise from the hem (see :func:`_darted`).
_DARTED_LABELS = (
    "hem",
    "right_side",
    "right_hip",
    "top_right",
    "right_dart_out",
    "right_dart_in",
    "top_middle",
    "left_dart_out",
    "left_dart_in",
    "top_left",
    "left_hip",
    "left_side",
)


def _darted(m: Measurements) -> Pattern:
    """Two-panel A-line skirt under a waistband, shaped to the waist by two darts per panel: each
    panel straight from the hem (DART_FLARE wider than the hips per side) up to hip depth, then a
    straight hip line to the top; the darts take DART_SHARE of the hip-to-waist difference, so
    the side seam turns less at the hips than the pencil's, and the cloth over the hips and
    seat is shaped as a darted design's is: a dartless skirt cut to a darted design's outline
    drapes differently.

    Edges of each panel (counter-clockwise from the hem): 0 hem, 1 right side, 2 right hip
    line, 3 top right of the darts, 4-5 right dart's legs, 6 top between the darts, 7-8 left
    dart's legs, 9 top left of the darts, 10 left hip line, 11 left side. The band's lower edge
    is cut in three to meet the three top pieces."""
    f, top_y, length, t, h, d = _banded_sizes(m)
    dw = DART_SHARE * (h - t)  # one dart's width at the top [m] (one per half panel)
    tc = t + dw  # top corner, the dart's cloth included [m]
    xd, dl = 0.5 * tc, DART_DEPTH * d  # a dart's centre [m] and length [m]
    hh = h + DART_FLARE
    top_pieces = [tc - xd - dw / 2, 2 * (xd - dw / 2), tc - xd - dw / 2]  # right, middle, left [m]
    v = np.array(
        [
            (-hh, 0.0),
            (hh, 0.0),
            (h, length - d),
            (tc, length),
            (xd + dw / 2, length),
            (xd, length - dl),
            (xd - dw / 2, length),
            (-xd + dw / 2, length),
            (-xd, length - dl),
            (-xd - dw / 2, length),
            (-tc, length),
            (-h, length - d),
        ]
    )
    front, back, st = _front_back(v, list(_DARTED_LABELS), f, top_y, length, (2, 10))
    for pn in ("front", "back"):
        st += [stitch(pn, 4, pn, 5, f"{pn}_right_dart"), stitch(pn, 7, pn, 8, f"{pn}_left_dart")]
    bf, bb = band_panels(t, f.waist_y, f.hip_z, cuts=[-t + top_pieces[2], t - top_pieces[0]])
    for band, pn in ((bf, "front"), (bb, "back")):
        # band lower edge pieces left to right (+x) against the skirt's top pieces (-x)
        st += [stitch(band.name, k, pn, e, f"{pn}_waist_{k}") for k, e in enumerate((9, 6, 3))]
    st += band_stitches(pieces=3)
    return Pattern(
        "skirt_darts",
        {"front": front, "back": back, bf.name: bf, bb.name: bb},
        st,
        properties={"units_in_meter": 100, "curvature_coords": "relative"},
    )


def make_skirt(m: Measurements | None = None) -> Pattern:
    """A knee-length A-line skirt sized to ``m`` (default: the default body)."""
    return _skirt(m or Measurements(), "skirt", band=False)


def make_skirt_band(m: Measurements | None = None) -> Pattern:
    """The knee-length A-line skirt under a waistband (front and back bands)."""
    return _skirt(m or Measurements(), "skirt_band", band=True)


def make_skirt_circle(m: Measurements | None = None) -> Pattern:
    """A knee-length half-circle skirt (two quarter-circle panels) under a waistband."""
    return _skirt(m or Measurements(), "skirt_circle", band=True, theta=np.pi)


def make_skirt_pencil(m: Measurements | None = None) -> Pattern:
    """A knee-length pencil skirt (straight from the hips down) under a waistband."""
    return _pencil(m or Measurements())


def make_skirt_darts(m: Measurements | None = None) -> Pattern:
    """A knee-length A-line skirt with two darts per panel under a waistband."""
    return _darted(m or Measurements())
