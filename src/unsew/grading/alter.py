"""Known alterations of a pattern: lengthen or shorten an open edge (a hem, a cuff, a leg
opening) and change its width, by exact amounts. Used to make grading targets whose true
changes are known (tests, ``benchmarks/bench_grading.py``).

The alteration works on the panel vertices directly (not through K): each chosen edge's two end
vertices move by ``length`` along the edge's outward normal (perpendicular to its chord, away
from the panel) and apart along the chord so the edge's length changes by ``girth`` times its
length. The edges next to it (side seams, underarm seams, inseams) stretch or shrink with it.
Applied to mirror-image edges alike, symmetric patterns stay symmetric and stitched edges keep
matching lengths.
"""

from __future__ import annotations

import numpy as np

from unsew.errors import InputError
from unsew.grading.curves import stitched_edges
from unsew.pattern.model import Pattern

__all__ = ["open_edges", "alter_pattern", "alteration_groups"]


def open_edges(pattern: Pattern, label: str, *, panels=None) -> list[tuple[str, int]]:
    """(panel, edge index) of the unstitched edges labelled ``label`` (e.g. ``"hem"``), in the
    panels named in ``panels`` (default: all)."""
    sewn = stitched_edges(pattern)
    out = []
    for name in pattern.panel_order:
        if panels is not None and name not in panels:
            continue
        for i, e in enumerate(pattern.panels[name].edges):
            if e.label == label and (name, i) not in sewn:
                out.append((name, i))
    return out


def alter_pattern(pattern: Pattern, edges, *, length: float = 0.0, girth: float = 0.0) -> Pattern:
    """A copy of ``pattern`` with each edge in ``edges`` moved outward and widened.

    edges: (panel name, edge index) pairs (see :func:`open_edges`); unstitched edges only.
    length: outward move of the edges [m] (negative: inward, a shorter hem).
    girth: relative change of each edge's length (0.1 = 10 % wider), applied as a change of
        its chord about the chord's midpoint.
    """
    out = pattern.copy()
    sewn = stitched_edges(pattern)
    for name, i in edges:
        if (name, i) in sewn:
            raise InputError(f"edge {i} of panel {name!r} is stitched; alter only open edges")
        panel = out.panels[name]
        e = panel.edges[i]
        a, b = panel.vertices[e.start].copy(), panel.vertices[e.end].copy()
        chord = float(np.linalg.norm(b - a))
        w = (b - a) / chord
        normal = np.array([w[1], -w[0]])  # right of a -> b: outward for a CCW panel
        dchord = girth * chord
        panel.vertices[e.start] = a + length * normal - 0.5 * dchord * w
        panel.vertices[e.end] = b + length * normal + 0.5 * dchord * w
    return out


def alteration_groups(pattern: Pattern) -> dict[str, list[tuple[str, int]]]:
    """The open ``hem`` edges of a base pattern grouped by what they finish: ``"hem"`` (the body
    hem of a top, dress or skirt), ``"sleeves"`` (cuffs) or ``"legs"`` (leg openings of pants and
    shorts: panels named ``*_front``/``*_back`` with an inseam). Empty groups are left out."""
    out: dict[str, list] = {}
    for name, i in open_edges(pattern, "hem"):
        panel = pattern.panels[name]
        if "sleeve" in name:
            key = "sleeves"
        elif any(e.label == "inseam" for e in panel.edges):
            key = "legs"
        else:
            key = "hem"
        out.setdefault(key, []).append((name, i))
    return out
