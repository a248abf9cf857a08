"""The pattern sized to the target's surface area (not in the paper; the fit's ``area: target``).

Cloth barely stretches, so a draped garment's surface area is close to its pattern's total panel
area, while the Chamfer distance cannot see area folded away (docs/decisions/004).
:func:`scale_to_area` scales every panel about its own
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


def scale_to_area(pattern, area: float, *, bands=()):
    """(a copy of ``pattern`` (a Pattern; its panel vertices (N, 2) float64 [m]) whose total panel
    area is ``area`` [m^2], the length factor s [-]). The input is not changed.

    Every panel is scaled by s = sqrt(area / current area) about its own area centroid (module
    docstring); s is clipped to [1 / MAX_AREA_SCALE, MAX_AREA_SCALE].

    bands: names of waistband panels (:func:`unsew.grading.grade.waistbands`). A band keeps its
    graded size, and the edges sewn to it keep their girth (:func:`_band_seams_kept`), so s is
    found again (a few rounds) for the other panels to take the whole change. A band sits where
    its girth meets the body: scaled with the rest, it loses grading's girth edit and hangs where
    that girth puts it.
    """
    if not area > 0:
        raise ValueError(f"area must be positive, got {area}")
    now = pattern_area(pattern)
    if not now > 0:
        raise ValueError("the pattern has no area")
    bands = [b for b in bands if b in pattern.panels]
    s = _clipped(math.sqrt(area / now))
    out = _scaled(pattern, s, bands)
    for _ in range(8 if bands else 0):  # the bands' area does not follow s: correct it
        got = pattern_area(out)
        s_next = _clipped(s * math.sqrt(area / got))
        if abs(s_next - s) < 1e-9:
            break
        s = s_next
        out = _scaled(pattern, s, bands)
    return out, s


def _clipped(s: float) -> float:
    return min(MAX_AREA_SCALE, max(1.0 / MAX_AREA_SCALE, s))


def _scaled(pattern, s: float, bands) -> object:
    """A copy of ``pattern`` with every panel but ``bands`` scaled by ``s`` about its area
    centroid, and the edges sewn to a band given back their girth."""
    out = pattern.copy()
    for name, panel in out.panels.items():
        if name in bands:
            continue
        c = panel_centroid2d(panel)
        panel.vertices = c + s * (np.asarray(panel.vertices, dtype=np.float64) - c)
        for e in panel.edges:
            if e.curvature is not None and e.curvature.kind == "circle":
                e.curvature.params[0] = float(e.curvature.params[0]) * s
    if bands:
        _band_seams_kept(out, set(bands), s)
    return out


def _band_seams_kept(pattern, bands: set, s: float) -> None:
    """In place: on every panel sewn to a band in ``bands`` (names), the vertices of the edges
    sewn to it are moved back along the panel's girth direction (perpendicular to the direction
    its placement points up) to 1/s of their scaled spread about their mean, and those edges'
    circular arcs get their radius back: the seam keeps its graded girth, matching the unscaled
    band, while the panel below it keeps its scaled length. A panel placed lying down is left
    as scaled."""
    from unsew.grading.grade import upright

    sewn: dict[str, set[int]] = {}
    for st in pattern.stitches:
        for a, b in ((st.a, st.b), (st.b, st.a)):
            if a.panel in bands and b.panel not in bands:
                sewn.setdefault(b.panel, set()).add(b.edge)
    for name, edges in sewn.items():
        panel = pattern.panels[name]
        up = upright(panel)
        if up is None:
            continue
        girth = np.array([up[1], -up[0]])
        idx = sorted({v for k in edges for v in (panel.edges[k].start, panel.edges[k].end)})
        v = np.asarray(panel.vertices, dtype=np.float64).copy()
        along = (v[idx] - v[idx].mean(axis=0)) @ girth
        v[idx] -= np.outer(along * (1.0 - 1.0 / s), girth)
        panel.vertices = v
        for k in edges:
            e = panel.edges[k]
            if e.curvature is not None and e.curvature.kind == "circle":
                e.curvature.params[0] = float(e.curvature.params[0]) / s


def clip_note(s: float, area: float, pattern) -> str | None:
    """One line for the user when :func:`scale_to_area` clipped its factor ``s`` (the pattern it
    returned, ``pattern``, is not at the target's ``area`` [m^2]), else None."""
    if abs(abs(math.log(s)) - math.log(MAX_AREA_SCALE)) > 1e-9:
        return None
    return (
        f"warning: the target's surface area {area:.3f} m^2 is beyond what the area scaling may reach "
        f"(lengths x{s:.2f} at most); the graded pattern keeps {pattern_area(pattern):.3f} m^2"
    )
