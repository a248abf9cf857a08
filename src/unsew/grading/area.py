"""The pattern sized to the target's surface area (not in the paper; the fit's ``area: target``).

Cloth barely stretches, so a draped garment's surface area is close to its pattern's total panel
area, while the Chamfer distance cannot see area folded away (how close: docs/benchmarks.md,
"The target's area"). :func:`scale_to_area` scales every panel about its own
area centroid by one factor s so that the pattern's total area is the target's. Every length
changes by s, so sewn edges still match; Bezier curvature is relative to its edge and follows, a
circular arc's radius [m] is scaled with it. A panel's area centroid keeps its place on the body
(placement maps the panel frame to 3D by a rigid motion).
"""

from __future__ import annotations

import math

import numpy as np

from unsew.metrics.panels import panel_area, panel_centroid2d

__all__ = ["pattern_area", "scale_to_area", "clip_note", "MAX_AREA_SCALE"]

#: Largest change of lengths the area scaling makes, s in [1 / MAX, MAX]: a target area more
#: than 1.3^2 = 1.69 times off the graded pattern's is no garment of this base (a scan with holes,
#: a doubled layer), and the scaling would wreck what grading matched.
MAX_AREA_SCALE = 1.3


def pattern_area(pattern) -> float:
    """Total area [m^2] of a :class:`~unsew.pattern.model.Pattern`'s panels, curved edges included."""
    return float(sum(panel_area(p) for p in pattern.panels.values()))


def scale_to_area(pattern, area: float):
    """(a copy of ``pattern`` (a Pattern; its panel vertices (N, 2) float64 [m]) whose total panel
    area is ``area`` [m^2], the length factor s [-]). The input is not changed.

    Every panel is scaled by s = sqrt(area / current area) about its own area centroid (module
    docstring); s is clipped to [1 / MAX_AREA_SCALE, MAX_AREA_SCALE]."""
    if not area > 0:
        raise ValueError(f"area must be positive, got {area}")
    now = pattern_area(pattern)
    if not now > 0:
        raise ValueError("the pattern has no area")
    s = min(MAX_AREA_SCALE, max(1.0 / MAX_AREA_SCALE, math.sqrt(area / now)))
    out = pattern.copy()
    for panel in out.panels.values():
        c = panel_centroid2d(panel)
        panel.vertices = c + s * (np.asarray(panel.vertices, dtype=np.float64) - c)
        for e in panel.edges:
            if e.curvature is not None and e.curvature.kind == "circle":
                e.curvature.params[0] = float(e.curvature.params[0]) * s
    return out, s


def clip_note(s: float, area: float, pattern) -> str | None:
    """One line for the user when :func:`scale_to_area` clipped its factor ``s`` (the pattern it
    returned, ``pattern``, is not at the target's ``area`` [m^2]), else None."""
    if abs(abs(math.log(s)) - math.log(MAX_AREA_SCALE)) > 1e-9:
        return None
    return (f"warning: the target's surface area {area:.3f} m^2 is beyond what the area scaling may reach "
            f"(lengths x{s:.2f} at most); the graded pattern keeps {pattern_area(pattern):.3f} m^2")
