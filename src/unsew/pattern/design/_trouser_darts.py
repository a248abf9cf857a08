"""Back waist darts of a design's trousers: one V notch in the middle of each back leg panel's
waist, the waist cut wider at the centre back by the dart's width (the back crotch seam, the same
on both back panels, starts that much further in), so the waist's sewn length, the outseams and
the stitches to the front legs stay as drafted. Under a waistband the back band's lower edge is
cut to meet the darted waists' pieces."""

from __future__ import annotations

import numpy as np

from unsew.pattern.base._band import band_panels
from unsew.pattern.base._frame import body_frame
from unsew.pattern.base._build import stitch
from unsew.pattern.curves import edge_length
from unsew.pattern.design._darts import SKIRT_DART, Dart, dart_edge
from unsew.pattern.measurements import Measurements
from unsew.pattern.model import Panel, Pattern, StitchSide

__all__ = ["dart_trousers"]

#: The back legs, in the back band's +x order (the back seen from behind: the body's left first).
BACKS = ("left_back", "right_back")


def _darted_back(pan: Panel, dw: float, depth: float) -> tuple[Panel, list, list[int], int]:
    """``pan`` with its waist widened by ``dw`` [m] at its centre-back end and one dart of width
    ``dw`` and ``depth`` [m] in its middle; its dart stitches, the waist pieces' edges and the
    waist's old edge index."""
    e = next(i for i, x in enumerate(pan.edges) if x.label == "waist")
    crotch = next(x for x in pan.edges if x.label == "crotch")
    w = pan.edges[e]
    centre, side = (w.end, w.start) if w.end in (crotch.start, crotch.end) else (w.start, w.end)
    v = pan.vertices.copy()
    u = (v[centre] - v[side]) / np.linalg.norm(v[centre] - v[side])
    length = float(np.linalg.norm(v[centre] - v[side])) + dw
    v[centre] = v[centre] + dw * u
    widened = Panel(pan.name, v, pan.edges, pan.translation, pan.rotation, pan.label)
    out, st, pieces = dart_edge(widened, e, [Dart(length / 2, dw, depth)], "waist")
    return out, st, pieces, e


def dart_trousers(p: Pattern, m: Measurements, *, band: bool) -> Pattern:
    """Trousers ``p`` (:func:`unsew.pattern.base.pants._legs`, drafted for ``m``) with a back
    waist dart per back leg taking :data:`SKIRT_DART`'s share of a leg panel's hip-to-waist
    difference; ``band``: ``p`` has front and back waistbands."""
    share, _, depth = SKIRT_DART
    f = body_frame(m)
    waist = edge_length(p.panels["right_back"], 3)
    dw = share * max((m.hip - m.waist) / 4, 0.0)
    hip_depth = f.waist_y - f.hip_y
    pieces = {}
    for name in BACKS:
        pan, dart_st, pieces[name], e = _darted_back(p.panels[name], dw, depth * hip_depth)
        p.panels[name] = pan
        for st in p.stitches:
            for side in ("a", "b"):
                s = getattr(st, side)
                if s.panel == name and s.edge > e:
                    setattr(st, side, StitchSide(name, s.edge + 3))
        p.stitches += dart_st
    if band:
        _cut_back_band(p, pieces, waist, f)
    return p


def _cut_back_band(p: Pattern, pieces: dict, waist: float, f) -> None:
    """Replace ``p``'s back band by one whose lower edge is cut to meet the back legs' waist
    pieces (each back waist runs towards the centre back, against the band's +x)."""
    order = [(n, e) for n in BACKS for e in pieces[n][::-1]]
    lengths = [edge_length(p.panels[n], e) for n, e in order]
    cuts = list(-waist + np.cumsum(lengths)[:-1])
    _, back = band_panels(waist, f.waist_y, f.hip_z, cuts=cuts)
    p.panels[back.name] = back
    p.stitches = [s for s in p.stitches if back.name not in (s.a.panel, s.b.panel)]
    nb = len(order)
    p.stitches += [stitch(back.name, j, n, e, f"{n}_waist_{j}") for j, (n, e) in enumerate(order)]
    p.stitches += [
        stitch("waistband_front", 2, back.name, nb + 2, "left_band_side"),
        stitch(back.name, nb, "waistband_front", 4, "right_band_side"),
    ]
