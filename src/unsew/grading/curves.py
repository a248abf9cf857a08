"""From a 3D open contour to the 2D open curves of the pattern that form it (paper 3.3, Fig. 4).

A contour of the sewn mesh X is a loop of boundary vertices. Its 2D counterparts are the panel
edges that are sewn to nothing (stitched edges are merged, never on a boundary) whose samples
(``mesh.edge_verts``, through ``mesh.x_of_u``) lie on that loop. On each panel, the edges of one
contour that follow each other along the outline form one *open curve*: a hem crossing the front
and the back panels gives two curves, a sleeve's cuff one.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from unsew.pattern.controls import ControlPoints
from unsew.pattern.curves import edge_length
from unsew.pattern.model import Pattern

__all__ = ["OpenCurve", "stitched_edges", "curves_of_contour", "rest_length"]


@dataclass
class OpenCurve:
    """Consecutive unstitched edges of one panel that lie on one open contour.

    panel: panel name; panel_index: its index in ``mesh.panel_names``.
    edges: edge indices, in outline (counter-clockwise) order.
    start, end: panel-vertex indices of the curve's two ends (start of the first edge, end of the
        last).
    controls: global control-point indices (into the pattern's :class:`ControlPoints`) lying on
        the curve, ends included, in outline order.
    length3d: length of the curve on the 3D mesh [m].
    """

    panel: str
    panel_index: int
    edges: list
    start: int
    end: int
    controls: np.ndarray
    length3d: float


def stitched_edges(pattern: Pattern) -> set:
    """(panel name, edge index) of every edge that is part of a stitch."""
    out = set()
    for s in pattern.stitches:
        out.add((s.a.panel, s.a.edge))
        out.add((s.b.panel, s.b.edge))
    return out


def _runs(edges: list[int], n: int) -> list[list[int]]:
    """Split a set of edge indices of an n-edge loop into runs of consecutive edges."""
    es = set(edges)
    if len(es) == n:
        return [list(range(n))]
    runs = []
    for e in sorted(es):
        if (e - 1) % n in es:
            continue
        run = [e]
        while (run[-1] + 1) % n in es:
            run.append((run[-1] + 1) % n)
        runs.append(run)
    return runs


def curves_of_contour(
    contour_indices: np.ndarray,
    verts: np.ndarray,
    pattern: Pattern,
    mesh,
    controls: ControlPoints,
    *,
    min_fraction: float = 0.6,
) -> list[OpenCurve]:
    """The open curves of the pattern that form one contour of the sewn mesh.

    contour_indices: (k,) int sewn-vertex indices of the contour (``Contour.indices`` on X).
    verts: (n_x, 3) float64 [m] sewn-vertex positions (for the 3D lengths).
    pattern, mesh: the pattern and its :class:`~unsew.meshing.sew.GarmentMesh`.
    controls: the pattern's control points.
    min_fraction: an edge belongs to the contour when at least this fraction of its samples do.

    Returns the curves, one per run of consecutive edges per panel (usually one per panel).
    """
    on = np.zeros(mesh.n_x, dtype=bool)
    on[np.asarray(contour_indices, dtype=np.int64)] = True
    sewn = stitched_edges(pattern)
    v = np.asarray(verts, dtype=np.float64)
    out = []
    for p, name in enumerate(mesh.panel_names):
        panel = pattern.panels[name]
        mine = []
        for e in range(len(panel.edges)):
            if (name, e) in sewn:
                continue
            xs = mesh.x_of_u[mesh.edge_verts[(name, e)]]
            if on[xs].mean() >= min_fraction:
                mine.append(e)
        if not mine:
            continue
        cidx = controls.of_panel(p)
        for run in _runs(mine, len(panel.edges)):
            verts_on = [panel.edges[e].start for e in run] + [panel.edges[run[-1]].end]
            pos = {vv: k for k, vv in enumerate(verts_on)}
            on_curve = [g for g in cidx if int(controls.vertex[g]) in pos]
            on_curve.sort(key=lambda g: pos[int(controls.vertex[g])])
            length = 0.0
            for e in run:
                xs = mesh.x_of_u[mesh.edge_verts[(name, e)]]
                length += float(np.linalg.norm(np.diff(v[xs], axis=0), axis=1).sum())
            out.append(
                OpenCurve(
                    panel=name,
                    panel_index=p,
                    edges=list(run),
                    start=int(panel.edges[run[0]].start),
                    end=int(panel.edges[run[-1]].end),
                    controls=np.asarray(on_curve, dtype=np.int64),
                    length3d=length,
                )
            )
    return out


def rest_length(pattern: Pattern, curves: list[OpenCurve]) -> float:
    """Total arc length [m] of the pattern edges that form ``curves`` (in 2D, at rest): the cloth
    edge a contour is made of (0.0 for no curves)."""
    return float(sum(edge_length(pattern.panels[c.panel], e) for c in curves for e in c.edges))
