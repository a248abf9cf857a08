"""Helpers shared by the base-pattern generators: curves from absolute control points,
mirror-symmetric panels, mirrored copies, placement in 3D, and seam-length matching."""

from __future__ import annotations

from typing import Callable, Sequence

import numpy as np

from unsew.pattern.curves import absolute_to_relative, edge_length
from unsew.pattern.model import (
    Curvature,
    Edge,
    Panel,
    Stitch,
    StitchSide,
    matrix_to_euler_xyz,
    mirror_curvature,
    reverse_curvature,
)

__all__ = [
    "quad",
    "cubic",
    "loop_panel",
    "symmetric_panel",
    "mirror_panel",
    "place",
    "rot_y180",
    "stitch",
    "solve_length",
]


def _p(x) -> np.ndarray:
    return np.asarray(x, dtype=np.float64)


def quad(a, b, c) -> Curvature:
    """Quadratic Bezier edge a->b with absolute control point ``c`` (all (2,) [m])."""
    st = absolute_to_relative(_p(a), _p(b), _p(c))
    return Curvature("quadratic", [[float(st[0]), float(st[1])]])


def cubic(a, b, c1, c2) -> Curvature:
    """Cubic Bezier edge a->b with absolute control points ``c1``, ``c2`` (all (2,) [m])."""
    st = absolute_to_relative(_p(a), _p(b), np.stack([_p(c1), _p(c2)]))
    return Curvature("cubic", [[float(s), float(t)] for s, t in st])


def loop_panel(
    name: str, verts, curves: dict[int, Curvature] | None = None, labels: Sequence[str] = ()
) -> Panel:
    """A panel whose edge i runs from vertex i to vertex i+1 (closing back to 0).

    verts: (N, 2) [m], counter-clockwise. curves: edge index -> curvature (others straight).
    """
    verts = _p(verts)
    n = len(verts)
    curves = curves or {}
    labels = list(labels) + [""] * (n - len(labels))
    edges = [Edge(i, (i + 1) % n, curves.get(i), labels[i]) for i in range(n)]
    return Panel(name, verts, edges)


def symmetric_panel(
    name: str,
    half: Sequence,
    side_curves: Sequence[Curvature | None],
    *,
    bottom: Curvature | None = None,
    top: Curvature | None = None,
    half_labels: Sequence[str] = (),
    bottom_label: str = "",
    top_label: str = "",
) -> tuple[Panel, Callable[[int], int]]:
    """A panel mirror-symmetric about x = 0, from its right half.

    half: points H0..Hk (k+1, 2) [m] up the right (x > 0) side; Hk may lie on x = 0 (an apex).
    side_curves: the k curvatures of H_i -> H_{i+1}. ``bottom``: curvature of the edge
    mirror(H0) -> H0, ``top``: of Hk -> mirror(Hk) (both must be self-symmetric).
    Returns the panel (vertices ``[m(H0), H0, ..., Hk, (m(Hk)), m(H_{k-1}), ..., m(H1)]``,
    counter-clockwise) and ``left(i)``: the edge index of the mirror image of side segment i.
    Edge 0 is the bottom edge, edge i + 1 the right side segment i.
    """
    H = _p(half)
    k = len(H) - 1
    apex = abs(H[-1, 0]) < 1e-12
    mir = H * np.array([-1.0, 1.0])
    verts = [mir[0]] + list(H)
    if not apex:
        verts.append(mir[k])
    verts += [mir[i] for i in range(k - 1, 0, -1)]
    n = len(verts)
    labels = list(half_labels) + [""] * (k - len(half_labels))
    edges = [Edge(0, 1, bottom, bottom_label)]
    for i in range(k):
        edges.append(Edge(i + 1, i + 2, side_curves[i], labels[i]))
    if not apex:
        edges.append(Edge(k + 1, k + 2, top, top_label))
    first_left = len(edges)
    for i in range(k - 1, -1, -1):  # mirror of segment i, traversed downwards
        j = len(edges)
        c = side_curves[i]
        edges.append(
            Edge(
                j,
                (j + 1) % n,
                reverse_curvature(mirror_curvature(c)) if c else None,
                labels[i].replace("right", "left"),
            )
        )
    assert len(edges) == n

    def left(i: int) -> int:
        return first_left + (k - 1 - i)

    return Panel(name, np.array(verts), edges), left


def mirror_panel(panel: Panel, name: str) -> Panel:
    """The mirror image of ``panel`` about its x = 0 line, still counter-clockwise: vertex i keeps
    its index (x negated); edge i of the result is the mirror of edge ``n - 1 - i`` of ``panel``,
    traversed the other way."""
    n = len(panel.edges)
    edges = []
    for i in range(n):
        e = panel.edges[n - 1 - i]
        c = reverse_curvature(mirror_curvature(e.curvature)) if e.curvature else None
        lab = e.label.replace("left", "\0").replace("right", "left").replace("\0", "right")
        edges.append(Edge(e.end, e.start, c, lab))
    return Panel(name, panel.vertices * np.array([-1.0, 1.0]), edges, label=panel.label)


def rot_y180() -> np.ndarray:
    """Rotation (3, 3) that turns a panel to face -Z (a back panel seen from behind)."""
    return np.diag([-1.0, 1.0, -1.0])


def place(panel: Panel, R: np.ndarray, world, local=(0.0, 0.0)) -> Panel:
    """Set the panel's placement so panel point ``local`` (2,) [m] lands on ``world`` (3,) [m]
    with rotation ``R`` (3, 3) (columns: the panel's x, y and outward normal in the world)."""
    R = np.asarray(R, dtype=np.float64)
    panel.rotation = matrix_to_euler_xyz(R)
    lp = np.array([local[0], local[1], 0.0])
    panel.translation = _p(world) - R @ lp
    return panel


def stitch(a_panel: str, a_edge: int, b_panel: str, b_edge: int, label: str = "") -> Stitch:
    """A stitch (a.start meets b.end)."""
    return Stitch(StitchSide(a_panel, a_edge), StitchSide(b_panel, b_edge), label)


def solve_length(make: Callable[[float], Panel], edge: int, target: float, lo: float, hi: float) -> float:
    """The parameter in [lo, hi] for which ``edge_length(make(x), edge) == target`` [m], by
    bisection (the length must increase with x)."""
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if edge_length(make(mid), edge) < target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)
