"""Base dresses: a t-shirt-like top running into a long flared skirt, with short sleeves
(``dress``) or none (``dress_sleeveless``); and a sleeveless bodice sewn at the waist to a
straight skirt (``dress_waist``), the way GarmentCode builds every dress.

``dress`` / ``dress_sleeveless``: front and back are single mirror-symmetric panels from hem to
neck; the side seam has two edges (hem to hip: the flare; hip to underarm: curved in at the
waist). Sleeves, armholes, shoulders and neckline as in :mod:`unsew.pattern.base.tshirt`.

``dress_waist``: bodice ``front`` / ``back`` from the natural waist to the neck (straight side
seams from the waist to the underarm, armholes cut in as a sleeveless top's), skirt
``skirt_front`` / ``skirt_back``: sectors of an annulus as in :mod:`unsew.pattern.base.skirt`
(edges 0 hem, 1 right side, 2 waist, 3 left side), flared just enough to clear the hips; each
skirt's waist arc is as long as its bodice's hem and sewn to it.
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.measurements import Measurements
from unsew.pattern.base._build import place, quad, rot_y180, stitch
from unsew.pattern.base._frame import body_frame
from unsew.pattern.base.skirt import sector_panel
from unsew.pattern.base.tshirt import BUST_EASE, TopSpec, sleeveless_frame, top_pattern
from unsew.pattern.model import Pattern

__all__ = ["make_dress", "make_dress_sleeveless", "make_dress_waist"]

#: Ease over waist and hip girths [m].
WAIST_EASE = 0.10
HIP_EASE = 0.08
#: Hem height above the floor [m] (mid-calf) and hem width per panel [m] (the flare).
HEM_HEIGHT = 0.35
HEM_FLARE = 0.18
#: ``dress_waist``: the skirt's flare beyond what the hips need [rad of the whole cone's
#: unrolled angle] (small: a straight skirt that still walks).
WAIST_SEAM_SKIRT_FLARE = 0.15


def make_dress(m: Measurements | None = None, *, sleeves: str = "short") -> Pattern:
    """A long flared dress with short sleeves sized to ``m`` (default: the default body);
    ``sleeves="none"``: without sleeves (pattern ``dress_sleeveless``, armholes cut in as
    :func:`unsew.pattern.base.tshirt.sleeveless_frame`)."""
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
    c = 2 * mid - (hip + under) / 2
    spec = TopSpec(lower=(tuple(hem), tuple(hip)), lower_curves=(None, quad(hip, under, c)), hem_y=hem_y)
    return top_pattern("dress", m, f0, spec, sleeves)


def make_dress_sleeveless(m: Measurements | None = None) -> Pattern:
    """The flared dress without sleeves."""
    return make_dress(m, sleeves="none")


def make_dress_waist(m: Measurements | None = None) -> Pattern:
    """A sleeveless bodice sewn at the natural waist to a straight mid-calf skirt, sized to ``m``
    (module docstring)."""
    m = m or Measurements()
    f0 = body_frame(m)
    waist_w = (m.waist + WAIST_EASE) / 4
    spec = TopSpec(lower=((waist_w, 0.0),), lower_curves=(None,), hem_y=f0.waist_y)
    top_p = top_pattern("dress", m, f0, spec, "none")
    panels, st = dict(top_p.panels), list(top_p.stitches)
    hem_y = HEM_HEIGHT * m.height / 1.70
    top, hip = 4 * waist_w, m.hip + HIP_EASE
    drop = f0.waist_y - f0.hip_y
    theta = max(hip - top, 0.0) / drop + WAIST_SEAM_SKIRT_FLARE  # unrolled angle of the whole cone [rad]
    r_w = top / theta  # its waist arc is top / 2 per panel: the bodice's hem
    r_h = r_w + f0.waist_y - hem_y
    for name, R, z, bodice in (("skirt_front", np.eye(3), f0.hip_z, "front"), ("skirt_back", rot_y180(), -f0.hip_z, "back")):
        sk = sector_panel(name, r_w, r_h, theta / 4)
        place(sk, R, (0.0, f0.waist_y, z), (0.0, r_h - r_w))  # the waist arc's lowest point at the waist
        panels[name] = sk
        st.append(stitch(bodice, 0, name, 2, f"{bodice}_waist"))
    st += [stitch("skirt_front", 1, "skirt_back", 3, "skirt_left_side"),
           stitch("skirt_back", 1, "skirt_front", 3, "skirt_right_side")]
    return Pattern("dress_waist", panels, st, properties=dict(top_p.properties))
