"""Waistbands: a front and a back band (straight rectangles) sewn to a lower garment's waist
edges and to each other at the sides. A band is a flat strip; it sits on the body from the
natural waist down to BAND_HEIGHT below it, so the garment under it starts that much lower.

Band panel frame (x across, y up, y = 0 at its lower edge), seen from outside::

    vertices: (-w, 0), [(0, 0) when split, or one per cut], (w, 0), (w, h), (-w, h)
    edges: the lower edge (one, two halves split at x = 0 for trousers whose centre seam
    meets the band, or pieces between given cuts for a darted skirt's top pieces), the +x side,
    the top (left open: the waist opening), the -x side.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from unsew.pattern.base._build import loop_panel, place, rot_y180, stitch
from unsew.pattern.model import Panel, Stitch

__all__ = ["BAND_HEIGHT", "band_panels", "band_stitches"]

#: Height of a waistband [m] (a common finished width is 3-5 cm).
BAND_HEIGHT = 0.04


def _band(name: str, half_width: float, height: float, split: bool, cuts: Sequence[float] | None) -> Panel:
    w, h = half_width, height
    if split:
        v = [(-w, 0.0), (0.0, 0.0), (w, 0.0), (w, h), (-w, h)]
        labels = ["seam_right_half", "seam_left_half", "right_side", "top", "left_side"]
    elif cuts:
        v = [(-w, 0.0)] + [(float(x), 0.0) for x in cuts] + [(w, 0.0), (w, h), (-w, h)]
        labels = [f"seam_{k}" for k in range(len(cuts) + 1)] + ["right_side", "top", "left_side"]
    else:
        v = [(-w, 0.0), (w, 0.0), (w, h), (-w, h)]
        labels = ["seam", "right_side", "top", "left_side"]
    return loop_panel(name, np.array(v), labels=labels)


def band_panels(
    half_width: float,
    waist_y: float,
    depth_z: float,
    *,
    split: bool = False,
    height: float = BAND_HEIGHT,
    cuts: Sequence[float] | None = None,
) -> tuple[Panel, Panel]:
    """Front and back waistbands, each ``2 * half_width`` [m] wide and ``height`` [m] high, their
    top at the world height ``waist_y`` [m], laid flat at z = +/- ``depth_z`` [m].
    ``split``: the lower edge in two halves (for trousers: one half per leg panel); ``cuts``:
    else the lower edge cut at these x [m] (increasing, within +-half_width), one piece per top
    piece of a darted skirt."""
    if cuts is not None and not (np.diff([-half_width, *cuts, half_width]) > 0).all():
        raise ValueError("band cuts must increase strictly within the band")
    front = _band("waistband_front", half_width, height, split, cuts)
    back = _band("waistband_back", half_width, height, split, cuts)
    place(front, np.eye(3), (0.0, waist_y - height, depth_z))
    place(back, rot_y180(), (0.0, waist_y - height, -depth_z))
    return front, back


def band_stitches(split: bool = False, pieces: int = 1) -> list[Stitch]:
    """The two side seams joining the front and back bands (front +x is the body's left, back
    +x seen from behind the body's right); ``pieces``: of the lower edge, when cut (``cuts``)."""
    r, top = (2, 3) if split else (pieces, pieces + 1)
    left = top + 1
    return [
        stitch("waistband_front", r, "waistband_back", left, "left_band_side"),
        stitch("waistband_back", r, "waistband_front", left, "right_band_side"),
    ]
