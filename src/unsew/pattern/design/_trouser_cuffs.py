"""Cuffs on a design's trouser legs: below each leg panel's hem a band
:data:`~unsew.pattern.design._top.CUFF_HEIGHT` high and as wide as the hem, in the leg panel's own
frame and placement (it hangs on where the leg would run on); a leg's front and back cuffs are
sewn to each other where its inseam and outseam run on, a tube whose lower edge is the leg's
opening. The legs are drafted that much shorter (:mod:`unsew.pattern.design._draft`), so the
opening stays where it was asked for.

Cuff panel frame (the leg panel's: x across, y up), seen from outside::

    vertices: the hem's end b, its start a, a and b lowered by the cuff's height
    edges: 0 top (sewn to the hem), 1 the side under a, 2 the lower edge (open, ``hem``),
           3 the side under b; each side labelled as the leg seam it continues
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.design._top import CUFF_HEIGHT
from unsew.pattern.base._build import stitch
from unsew.pattern.model import Edge, Panel, Pattern

__all__ = ["cuff_legs", "LEG_PANELS"]

#: The leg panels of a design's trousers (:func:`unsew.pattern.base.pants._legs`).
LEG_PANELS = ("left_front", "left_back", "right_front", "right_back")
#: The leg seams a cuff's sides continue.
LEG_SEAMS = ("inseam", "outseam_lower")


def _edge_labelled(panel: Panel, label: str) -> int:
    return next(i for i, e in enumerate(panel.edges) if e.label == label)


def _cuff(leg: Panel, height: float) -> tuple[Panel, int]:
    """The cuff under ``leg``'s hem (``height`` [m]) and the hem's edge index. The leg is
    counter-clockwise with the hem at its bottom, so its hem runs a -> b towards +x and the cuff,
    on the other side of it, runs it b -> a."""
    k = _edge_labelled(leg, "hem")
    n = len(leg.edges)
    hem = leg.edges[k]
    a, b = leg.vertices[hem.start], leg.vertices[hem.end]
    down = np.array([0.0, height])
    verts = np.array([b, a, a - down, b - down])
    side_a, side_b = leg.edges[(k - 1) % n].label, leg.edges[(k + 1) % n].label
    top = hem.reversed()  # the same curve run b -> a
    edges = [
        Edge(0, 1, top.curvature, "top"),
        Edge(1, 2, None, side_a),
        Edge(2, 3, hem.curvature.copy() if hem.curvature else None, "hem"),
        Edge(3, 0, None, side_b),
    ]
    cuff = Panel(f"{leg.name}_cuff", verts, edges, leg.translation.copy(), leg.rotation.copy(), leg.label)
    return cuff, k


def cuff_legs(p: Pattern, height: float = CUFF_HEIGHT) -> Pattern:
    """``p`` (trousers or a jumpsuit: :data:`LEG_PANELS` each with a ``hem`` edge between an
    ``inseam`` and an ``outseam_lower``) with a cuff ``height`` [m] high under each leg panel,
    sewn to its hem, a leg's front and back cuffs sewn together along both sides."""
    cuffs = {}
    for name in LEG_PANELS:
        cuff, k = _cuff(p.panels[name], height)
        cuffs[name] = cuff
        p.panels[cuff.name] = cuff
        p.panel_order.append(cuff.name)
        p.stitches.append(stitch(name, k, cuff.name, 0, f"{name}_cuff"))
    for side in ("left", "right"):
        front, back = cuffs[f"{side}_front"], cuffs[f"{side}_back"]
        for seam in LEG_SEAMS:
            ef, eb = _edge_labelled(front, seam), _edge_labelled(back, seam)
            p.stitches.append(stitch(front.name, ef, back.name, eb, f"{side}_cuff_{seam}"))
    return p

