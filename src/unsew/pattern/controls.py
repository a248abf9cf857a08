"""Control points of a sewing pattern (paper 3.2, "Parameterization", Figure 3).

A panel's control points are its *corners* (C0 discontinuities of the outline: vertices where the
tangent turns by more than ``corner_angle`` degrees) and its *join points* (endpoints of stitched
edges, merged with seam counterparts when sewing). Both are panel vertices, so a control point is
named by (panel, vertex index); within a panel they are listed counter-clockwise, in outline
order from the start of edge 0. Panel vertices that are neither (a smooth, unstitched junction of
two edges) stay plain outline points, driven by the control points around them
(:mod:`unsew.pattern.params`).

A panel always gets at least two control points (a curve frame needs two ends): if the rules give
fewer, the panel's vertices farthest apart are added.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from unsew.pattern.curves import edge_point_fn
from unsew.pattern.model import Panel, Pattern

__all__ = ["ControlPoints", "find_control_points", "corner_turn_angles", "CORNER_ANGLE_DEG"]

#: A panel vertex whose outline tangent turns by more than this is a corner [deg].
CORNER_ANGLE_DEG = 10.0

_KIND_CORNER = 1
_KIND_JOIN = 2


@dataclass
class ControlPoints:
    """All control points of a pattern, panel by panel in ``panel_order``, CCW within a panel.

    panel_names: = pattern.panel_order.
    panel: panel index of each control point, (Nc,) int64.
    vertex: panel-vertex index of each control point, (Nc,) int64.
    positions: 2D positions in the panel frame [m], (Nc, 2) float64.
    kind: bit field per control point, (Nc,) int64: 1 corner, 2 join point (3 both; 0 only for
        points added so a panel has two).
    offsets: first control point of each panel and Nc at the end, (P+1,) int64.
    """

    panel_names: list[str]
    panel: np.ndarray
    vertex: np.ndarray
    positions: np.ndarray
    kind: np.ndarray
    offsets: np.ndarray

    def __len__(self) -> int:
        return int(len(self.positions))

    def of_panel(self, p: int) -> np.ndarray:
        """Global indices (k,) int64 of panel ``p``'s control points, CCW."""
        return np.arange(int(self.offsets[p]), int(self.offsets[p + 1]), dtype=np.int64)

    def count_per_panel(self) -> dict[str, int]:
        """Panel name -> number of control points."""
        return {n: int(self.offsets[p + 1] - self.offsets[p]) for p, n in enumerate(self.panel_names)}


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v)
    return v / n if n > 0 else v


def _end_tangents(panel: Panel, i: int) -> tuple[np.ndarray, np.ndarray]:
    """Unit tangents (2,) at the start and at the end of edge i, in its direction of travel."""
    e = panel.edges[i]
    a, b = panel.vertices[e.start], panel.vertices[e.end]
    f = edge_point_fn(a, b, e.curvature)
    eps = 1e-5
    p = f(np.array([0.0, eps, 1.0 - eps, 1.0]))
    return _unit(p[1] - p[0]), _unit(p[3] - p[2])


def corner_turn_angles(panel: Panel) -> np.ndarray:
    """Turn of the outline's tangent [deg], (N,) float64, at each panel vertex (0 for a vertex
    where the outline is smooth, 90 at a square corner). Vertices not on the loop get 0."""
    out = np.zeros(len(panel.vertices))
    n = len(panel.edges)
    for i in range(n):
        _, t_in = _end_tangents(panel, i)
        t_out, _ = _end_tangents(panel, (i + 1) % n)
        c = float(np.clip(t_in @ t_out, -1.0, 1.0))
        out[panel.edges[i].end] = np.degrees(np.arccos(c))
    return out


def find_control_points(pattern: Pattern, *, corner_angle: float = CORNER_ANGLE_DEG) -> ControlPoints:
    """Control points of every panel (corners and join points), CCW per panel.

    pattern: the sewing pattern.
    corner_angle: tangent turn [deg] above which a panel vertex is a corner.

    Returns a :class:`ControlPoints` (shapes in its docstring).
    """
    joins: dict[str, set] = {n: set() for n in pattern.panel_order}
    for s in pattern.stitches:
        for side in (s.a, s.b):
            if side.panel in pattern.panels and 0 <= side.edge < len(pattern.panels[side.panel].edges):
                e = pattern.panels[side.panel].edges[side.edge]
                joins[side.panel].update((e.start, e.end))
    panel_idx, vert_idx, kinds, offsets = [], [], [], [0]
    for p, name in enumerate(pattern.panel_order):
        panel = pattern.panels[name]
        turn = corner_turn_angles(panel)
        order = [e.start for e in panel.edges]  # outline order, CCW, from edge 0's start
        chosen = []
        for v in order:
            k = (_KIND_CORNER if turn[v] > corner_angle else 0) | (_KIND_JOIN if v in joins[name] else 0)
            if k:
                chosen.append((v, k))
        if len(chosen) < 2:
            have = {v for v, _ in chosen}
            pts = panel.vertices[order]
            d = np.linalg.norm(pts[:, None] - pts[None], axis=-1)
            i, j = np.unravel_index(int(np.argmax(d)), d.shape)
            for v in (order[i], order[j]):
                if v not in have and len(chosen) < 2:
                    chosen.append((v, 0))
                    have.add(v)
            pos = {v: k for k, v in enumerate(order)}
            chosen.sort(key=lambda vk: pos[vk[0]])
        for v, k in chosen:
            panel_idx.append(p)
            vert_idx.append(v)
            kinds.append(k)
        offsets.append(len(vert_idx))
    panel_idx = np.asarray(panel_idx, dtype=np.int64)
    vert_idx = np.asarray(vert_idx, dtype=np.int64)
    pos = np.array(
        [pattern.panels[pattern.panel_order[p]].vertices[v] for p, v in zip(panel_idx, vert_idx)],
        dtype=np.float64,
    ).reshape(-1, 2)
    return ControlPoints(
        list(pattern.panel_order),
        panel_idx,
        vert_idx,
        pos,
        np.asarray(kinds, dtype=np.int64),
        np.asarray(offsets, dtype=np.int64),
    )
