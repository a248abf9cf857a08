"""Waistbands: a front and a back band (straight rectangles) sewn to a lower garment's waist
edges and to each other at the sides. A band is a flat strip; it sits on the body from the
natural waist down to BAND_HEIGHT below it, so the garment under it starts that much lower.

Band panel frame (x across, y up, y = 0 at its lower edge), seen from outside::

    vertices: (-w, 0), [(0, 0) when split], (w, 0), (w, h), (-w, h)
    edges: the lower edge (one, or two halves split at x = 0 for trousers whose centre seam
    meets the band), the +x side, the top (left open: the waist opening), the -x side.
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.base._build import loop_panel, place, rot_y180, stitch
from unsew.pattern.model import Panel, Stitch

__all__ = ["BAND_HEIGHT", "band_panels", "band_stitches"]

#: Height of a waistband [m] (a common finished width is 3-5 cm).
BAND_HEIGHT = 0.04


def _band(name: str, half_width: float, height: float, split: bool) -> Panel:
    w, h = half_width, height
    if split:
        v = [(-w, 0.0), (0.0, 0.0), (w, 0.0), (w, h), (-w, h)]
        labels = ["seam_right_half", "seam_left_half", "right_side", "top", "left_side"]
    else:
        v = [(-w, 0.0), (w, 0.0), (w, h), (-w, h)]
        labels = ["seam", "right_side", "top", "left_side"]
    return loop_panel(name, np.array(v), labels=labels)


def band_panels(half_width: float, waist_y: float, depth_z: float, *, split: bool = False,
                height: float = BAND_HEIGHT) -> tuple[Panel, Panel]:
    """Front and back waistbands, each ``2 * half_width`` [m] wide and ``height`` [m] high, their
    top at the world height ``waist_y`` [m], laid flat at z = +/- ``depth_z`` [m].
    ``split``: the lower edge in two halves (for trousers: one half per leg panel)."""
    front = _band("waistband_front", half_width, height, split)
    back = _band("waistband_back", half_width, height, split)
    place(front, np.eye(3), (0.0, waist_y - height, depth_z))
    place(back, rot_y180(), (0.0, waist_y - height, -depth_z))
    return front, back


def band_stitches(split: bool = False) -> list[Stitch]:
    """The two side seams joining the front and back bands (front +x is the body's left, back
    +x seen from behind the body's right)."""
    r, top = (2, 3) if split else (1, 2)
    left = top + 1
    return [
        stitch("waistband_front", r, "waistband_back", left, "left_band_side"),
        stitch("waistband_back", r, "waistband_front", left, "right_band_side"),
    ]
