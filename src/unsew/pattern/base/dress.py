"""Base dresses: a t-shirt-like top running into a long flared skirt, with short sleeves
(``dress``) or none (``dress_sleeveless``); and a straight, unwaisted knee-length dress (a shift
or tunic: ``dress_straight``, ``dress_straight_sleeveless``).

Front and back are single mirror-symmetric panels from hem to neck; the side seam has two
edges (hem to hip: the flare; hip to underarm: curved in at the waist, or straight on the
unwaisted dress). Sleeves, armholes, shoulders and neckline as in
:mod:`unsew.pattern.base.tshirt`.
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.measurements import Measurements
from unsew.pattern.base._build import quad
from unsew.pattern.base._frame import body_frame
from unsew.pattern.base.tshirt import BUST_EASE, TopSpec, sleeveless_frame, top_pattern
from unsew.pattern.model import Pattern

__all__ = ["make_dress", "make_dress_sleeveless", "make_dress_straight", "make_dress_straight_sleeveless"]

#: Ease over waist and hip girths [m].
WAIST_EASE = 0.10
HIP_EASE = 0.08
#: Hem height above the floor [m] (mid-calf) and hem width per panel [m] (the flare).
HEM_HEIGHT = 0.35
HEM_FLARE = 0.18
#: The straight dress: hem height above the floor [m] (at the knee) and its hem's width over the
#: hip's per panel [m] (a slight flare, so that the hem clears the thighs in a stride).
STRAIGHT_HEM_HEIGHT = 0.48
STRAIGHT_FLARE = 0.03


def make_dress(
    m: Measurements | None = None,
    *,
    sleeves: str = "short",
    waist_point: bool = False,
    necklines: tuple[str, str] = ("round", "round"),
) -> Pattern:
    """A long flared dress with short sleeves sized to ``m`` (default: the default body);
    ``sleeves="none"``: without sleeves (pattern ``dress_sleeveless``, armholes cut in as
    :func:`unsew.pattern.base.tshirt.sleeveless_frame`). ``waist_point``: the side seam from
    the hips to the underarm as two straight edges meeting at the waist (a control point, as
    GarmentCode's bodices have it) instead of one curve through it. ``necklines``: front and
    back, of :data:`unsew.pattern.base.tshirt.NECKLINES`."""
    m = m or Measurements()
    f0 = body_frame(m)
    f = sleeveless_frame(f0) if sleeves == "none" else f0
    hem_y = HEM_HEIGHT * m.height / 1.70
    hip_w = (m.hip + HIP_EASE) / 4
    waist_w = (m.waist + WAIST_EASE) / 4
    bust_w = (m.bust + BUST_EASE) / 4
    hip = np.array([hip_w, f.hip_y - hem_y])
    hem = np.array([hip_w + HEM_FLARE, 0.0])
    under = np.array([bust_w, f.armpit_y - hem_y])
    # Quadratic through the waist: its middle (a + 2c + b)/4 sits at the waist width.
    mid = np.array([waist_w, f.waist_y - hem_y])
    if waist_point:
        lower, curves = (tuple(hem), tuple(hip), tuple(mid)), (None, None, None)
    else:
        c = 2 * mid - (hip + under) / 2
        lower, curves = (tuple(hem), tuple(hip)), (None, quad(hip, under, c))
    spec = TopSpec(lower=lower, lower_curves=curves, hem_y=hem_y)
    return top_pattern("dress", m, f0, spec, sleeves, necklines=necklines)


def make_dress_sleeveless(m: Measurements | None = None, **kw) -> Pattern:
    """The flared dress without sleeves (``kw``: :func:`make_dress`'s)."""
    return make_dress(m, sleeves="none", **kw)


def make_dress_straight(
    m: Measurements | None = None, *, sleeves: str = "short", necklines: tuple[str, str] = ("round", "round")
) -> Pattern:
    """A straight knee-length dress with short sleeves sized to ``m``: no waist shaping, the
    side seam straight from the underarm to the hips and barely flared below them (a shift or
    tunic dress, which the waisted :func:`make_dress` stands out from at the hips);
    ``sleeves="none"``: without sleeves (``dress_straight_sleeveless``)."""
    m = m or Measurements()
    f0 = body_frame(m)
    f = sleeveless_frame(f0) if sleeves == "none" else f0
    hem_y = STRAIGHT_HEM_HEIGHT * m.height / 1.70
    hip_w = (m.hip + HIP_EASE) / 4
    hip = (hip_w, f.hip_y - hem_y)
    hem = (hip_w + STRAIGHT_FLARE, 0.0)
    spec = TopSpec(lower=(hem, hip), lower_curves=(None, None), hem_y=hem_y)
    return top_pattern("dress_straight", m, f0, spec, sleeves, necklines=necklines)


def make_dress_straight_sleeveless(m: Measurements | None = None, **kw) -> Pattern:
    """The straight dress without sleeves (``kw``: :func:`make_dress_straight`'s necklines)."""
    return make_dress_straight(m, sleeves="none", **kw)
