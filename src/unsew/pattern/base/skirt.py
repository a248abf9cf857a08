"""Base A-line skirt: front and back, each a sector of an annulus (paper Fig. 2c).

The waist and hem are concentric circular arcs (GarmentCode ``circle`` edges), so the skirt
is a cone: its flare is chosen so that the cone's girth at hip depth clears the hips. Panel
frame: x across, y up, the centre of the circles on x = 0 above the panel.

Edges of each panel: 0 hem (arc), 1 right side seam, 2 waist (arc), 3 left side seam.
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.measurements import Measurements
from unsew.pattern.base._build import loop_panel, place, rot_y180, stitch
from unsew.pattern.base._frame import body_frame
from unsew.pattern.model import Curvature, Pattern

__all__ = ["make_skirt"]

WAIST_EASE = 0.02  #: [m]
HIP_EASE = 0.06  #: [m]
#: Skirt length below the waist, as a fraction of the leg length (knee length).
LENGTH_PER_LEG = 0.75
#: Extra flare over what the hips need [rad of the full cone's unrolled angle].
EXTRA_FLARE = 0.35


def _panel(name: str, r_w: float, r_h: float, half_angle: float):
    s, c = np.sin(half_angle), np.cos(half_angle)
    # Circle centre at (0, r_h): hem corners at radius r_h, waist corners at r_w, below it.
    cy = r_h
    v = np.array([(-r_h * s, cy - r_h * c), (r_h * s, cy - r_h * c), (r_w * s, cy - r_w * c), (-r_w * s, cy - r_w * c)])
    curves = {
        0: Curvature("circle", [r_h, False, True]),  # hem: bulges down, to the right of -> (+x)
        2: Curvature("circle", [r_w, False, False]),  # waist: bulges down, to the left of <- (-x)
    }
    return loop_panel(name, v, curves, ["hem", "right_side", "waist", "left_side"])


def make_skirt(m: Measurements | None = None) -> Pattern:
    """A knee-length A-line skirt sized to ``m`` (default: the default body)."""
    m = m or Measurements()
    f = body_frame(m)
    waist = m.waist + WAIST_EASE
    hip = m.hip + HIP_EASE
    drop = f.waist_y - f.hip_y  # waist to hip along the body [m]
    theta = (hip - waist) / drop + EXTRA_FLARE  # unrolled angle of the whole cone [rad]
    r_w = waist / theta
    r_h = r_w + LENGTH_PER_LEG * m.leg_length
    front = _panel("front", r_w, r_h, theta / 4)
    back = _panel("back", r_w, r_h, theta / 4)
    local_waist = (0.0, r_h - r_w)  # centre of the waist arc (its lowest point) at the waist
    place(front, np.eye(3), (0.0, f.waist_y, f.hip_z), local_waist)
    place(back, rot_y180(), (0.0, f.waist_y, -f.hip_z), local_waist)
    st = [stitch("front", 1, "back", 3, "left_side"), stitch("back", 1, "front", 3, "right_side")]
    return Pattern("skirt", {"front": front, "back": back}, st, properties={"units_in_meter": 100, "curvature_coords": "relative"})
