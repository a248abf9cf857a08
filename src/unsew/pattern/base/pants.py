"""Base pants and shorts: left/right front and back legs (paper Fig. 2b).

Each leg panel, in its own frame (x across with the outseam at +x, the centre front/back seam
near x = 0, y up, y = 0 at the hem), seen from outside::

    v0 hem inner, v1 hem outer, v2 hip side, v3 waist side, v4 centre waist, v5 crotch point
    edges: 0 hem, 1 outseam below the hip, 2 outseam above the hip (curved), 3 waist,
           4 crotch curve (centre waist down to the crotch point), 5 inseam

The left front and right back legs use this frame as is; the right front and left back are
its mirror images (edge i of a mirrored panel is the mirror of edge 5 - i, traversed the
other way). ``pants_band`` and ``shorts_band`` start BAND_HEIGHT below the waist under a front and
a back waistband (:mod:`unsew.pattern.base._band`). Front and back share the outseam and inseam geometry, so
sewn edges have equal lengths; the back is wider through a longer crotch extension.
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.measurements import Measurements
from unsew.pattern.base._band import BAND_HEIGHT, band_panels, band_stitches
from unsew.pattern.base._build import cubic, loop_panel, mirror_panel, place, quad, rot_y180, stitch
from unsew.pattern.base._frame import body_frame
from unsew.pattern.curves import edge_length
from unsew.pattern.model import Pattern

__all__ = ["make_pants", "make_shorts", "make_pants_band", "make_shorts_band"]

WAIST_EASE = 0.04  #: [m]
HIP_EASE = 0.08  #: [m]
#: Crotch extensions past the centre line, as fractions of the hip girth.
FRONT_CROTCH_EXT = 1.0 / 16
BACK_CROTCH_EXT = 1.0 / 9
#: Crotch point below the body's crotch [m] (ease).
CROTCH_DROP = 0.02
#: Hem height above the floor for pants at a height of 1.70 m [m] (scaled with the height), and
#: the shorts' inseam length [m]. The wearer is barefoot: the hem (PANTS_HEM_GIRTH, a ring of
#: about 6.7 cm radius around the leg) must clear the foot under it, which on the default body
#: rises to 6.6 cm at that radius (ankle joint at 7.0 cm); at 5 cm the hem rested on the instep.
PANTS_HEM_HEIGHT = 0.085
SHORTS_INSEAM = 0.12
#: Hem girth per leg for pants [m].
PANTS_HEM_GIRTH = 0.42
#: Extra width of the shorts' hem over the thigh girth per leg [m].
SHORTS_HEM_EASE = 0.06


def _leg(name: str, m: Measurements, f, hem_y: float, ext: float, hem_half: float, top_drop: float = 0.0):
    """One leg panel in the base frame (outseam at +x). hem_half: half of its hem width [m];
    top_drop: how far below the natural waist its top edge sits [m] (under a waistband)."""
    y_w = f.waist_y - top_drop - hem_y
    y_h = f.hip_y - hem_y
    y_c = f.crotch_y - CROTCH_DROP - hem_y
    x_h = (m.hip + HIP_EASE) / 4
    # girth at the top edge: linear between waist and hips
    x_w = (m.waist + (m.hip - m.waist) * top_drop / (f.waist_y - f.hip_y) + WAIST_EASE) / 4
    front_ext = FRONT_CROTCH_EXT * m.hip
    # Leg centre line half-way between the front crotch point and the hip side; shared by front
    # and back so that outseam and inseam have the same shape on both.
    centre = (x_h - front_ext) / 2
    hem_in, hem_out = centre - hem_half, centre + hem_half
    x_c = -ext
    # The inseam of the back runs from its (further out) crotch point; shift it to the front's
    # inseam by keeping the same offset from crotch point to inner hem.
    hem_in = hem_in - (ext - front_ext)
    v = np.array([(hem_in, 0.0), (hem_out, 0.0), (x_h, y_h), (x_w, y_w), (0.0, y_w), (x_c, y_c)])
    curves = {
        2: quad(v[2], v[3], (x_h + 0.15 * (x_h - x_w), 0.5 * (y_h + y_w))),
        # Crotch curve: straight down the centre, then sweeping out to the crotch point.
        4: cubic(v[4], v[5], (0.0, y_c + 0.45 * (y_w - y_c)), (0.25 * x_c, y_c)),
    }
    labels = ["hem", "outseam_lower", "outseam_upper", "waist", "crotch", "inseam"]
    return loop_panel(name, v, curves, labels)


def _legs(m: Measurements, hem_y: float, hem_half_front: float, name: str, band: bool = False) -> Pattern:
    f = body_frame(m)
    ext_f, ext_b = FRONT_CROTCH_EXT * m.hip, BACK_CROTCH_EXT * m.hip
    drop = BAND_HEIGHT if band else 0.0
    front = _leg("left_front", m, f, hem_y, ext_f, hem_half_front, drop)
    back = _leg("right_back", m, f, hem_y, ext_b, hem_half_front, drop)
    rf = mirror_panel(front, "right_front")
    lb = mirror_panel(back, "left_back")
    for p in (front, rf):
        place(p, np.eye(3), (0.0, hem_y, f.hip_z))
    for p in (back, lb):
        place(p, rot_y180(), (0.0, hem_y, -f.hip_z))
    # Front +x is the body's left; back +x (seen from behind) the body's right.
    st = [
        stitch("left_front", 1, "left_back", 4, "left_outseam_lower"),
        stitch("left_front", 2, "left_back", 3, "left_outseam_upper"),
        stitch("left_front", 5, "left_back", 0, "left_inseam"),
        stitch("right_back", 1, "right_front", 4, "right_outseam_lower"),
        stitch("right_back", 2, "right_front", 3, "right_outseam_upper"),
        stitch("right_back", 5, "right_front", 0, "right_inseam"),
        stitch("left_front", 4, "right_front", 1, "front_crotch"),
        stitch("right_back", 4, "left_back", 1, "back_crotch"),
    ]
    panels = {p.name: p for p in (front, rf, lb, back)}
    if band:
        # One band per side, its lower edge split at the centre seam: the +x half meets the leg
        # whose panel frame is unmirrored (left front, right back), the -x half the mirrored one.
        bf, bb = band_panels(edge_length(front, 3), f.waist_y, f.hip_z, split=True)
        panels.update({bf.name: bf, bb.name: bb})
        st += [
            stitch(bf.name, 0, "right_front", 2, "right_front_waist"),
            stitch(bf.name, 1, "left_front", 3, "left_front_waist"),
            stitch(bb.name, 0, "left_back", 2, "left_back_waist"),
            stitch(bb.name, 1, "right_back", 3, "right_back_waist"),
        ] + band_stitches(split=True)
    return Pattern(name, panels, st, properties={"units_in_meter": 100, "curvature_coords": "relative"})


def make_pants(m: Measurements | None = None) -> Pattern:
    """Full-length pants sized to ``m`` (default: the default body)."""
    m = m or Measurements()
    return _legs(m, PANTS_HEM_HEIGHT * m.height / 1.70, PANTS_HEM_GIRTH / 4 - 0.01, "pants")


def make_pants_band(m: Measurements | None = None) -> Pattern:
    """The full-length pants under a waistband (front and back bands)."""
    m = m or Measurements()
    return _legs(m, PANTS_HEM_HEIGHT * m.height / 1.70, PANTS_HEM_GIRTH / 4 - 0.01, "pants_band", band=True)


def make_shorts(m: Measurements | None = None, *, band: bool = False) -> Pattern:
    """Shorts with a short inseam, same topology as the pants (``band``: under a waistband)."""
    m = m or Measurements()
    f = body_frame(m)
    hem_y = f.crotch_y - CROTCH_DROP - SHORTS_INSEAM
    return _legs(
        m, hem_y, (m.thigh + SHORTS_HEM_EASE) / 4 - 0.01, "shorts_band" if band else "shorts", band=band
    )


def make_shorts_band(m: Measurements | None = None) -> Pattern:
    """The shorts under a waistband (front and back bands)."""
    return make_shorts(m, band=True)
