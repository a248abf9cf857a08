"""Geometry of panel edges: sampling points along straight, Bezier and circular-arc edges.

All positions are 2D in the panel frame [m]. See :mod:`unsew.pattern.model` for the
relative-coordinate convention of curvature parameters.
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.model import Curvature, Panel

__all__ = [
    "relative_to_absolute",
    "absolute_to_relative",
    "edge_point_fn",
    "sample_edge",
    "edge_length",
    "panel_outline",
    "arc_center",
]


def _perp(v: np.ndarray) -> np.ndarray:
    return np.array([-v[1], v[0]])


def relative_to_absolute(a: np.ndarray, b: np.ndarray, st: np.ndarray) -> np.ndarray:
    """Relative control point(s) ``st`` (..., 2) of edge a->b to absolute 2D positions [m]."""
    st = np.asarray(st, dtype=np.float64)
    e = b - a
    return a + st[..., :1] * e + st[..., 1:2] * _perp(e)


def absolute_to_relative(a: np.ndarray, b: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Inverse of :func:`relative_to_absolute`: absolute points (..., 2) -> relative (s, t)."""
    e = b - a
    L2 = float(e @ e)
    d = np.asarray(p, dtype=np.float64) - a
    return np.stack([d @ e / L2, d @ _perp(e) / L2], axis=-1)


def arc_center(a: np.ndarray, b: np.ndarray, radius: float, large_arc: bool, right: bool):
    """Centre [m] and signed sweep [rad] of the circular arc from a to b (see model docstring).

    The arc's midpoint bulges to the right of a->b when ``right``; ``large_arc`` picks the arc
    longer than half the circle. Returns (center (2,), start angle, sweep) with the arc traced
    as ``center + r*(cos(th0 + s*sweep), sin(...))`` for s in [0, 1].
    """
    chord = b - a
    d = float(np.linalg.norm(chord))
    r = max(float(radius), d / 2)
    h = np.sqrt(max(r * r - d * d / 4, 0.0))
    mid = (a + b) / 2
    n_left = _perp(chord) / d  # unit normal to the left of a->b
    bulge_dir = -n_left if right else n_left
    # The arc's midpoint lies on the bulge side; the centre is on the same side for a large arc.
    center = mid - bulge_dir * h if not large_arc else mid + bulge_dir * h
    th0 = np.arctan2(*(a - center)[::-1])
    th1 = np.arctan2(*(b - center)[::-1])
    sweep = th1 - th0
    # Choose the sweep direction that passes through the bulge point.
    bulge_pt = mid + bulge_dir * (r - h if not large_arc else r + h)
    thm = np.arctan2(*(bulge_pt - center)[::-1])

    def _between(s: float) -> bool:
        rel = (thm - th0) % (2 * np.pi) if s > 0 else (th0 - thm) % (2 * np.pi)
        return rel <= abs(s) + 1e-12

    ccw = sweep % (2 * np.pi)
    cw = -((-sweep) % (2 * np.pi))
    sweep = ccw if _between(ccw) else cw
    return center, th0, sweep


def edge_point_fn(a: np.ndarray, b: np.ndarray, curvature: Curvature | None):
    """A function t (n,) in [0,1] -> points (n, 2) [m] along the edge a->b."""
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    if curvature is None:
        return lambda t: a + np.asarray(t)[:, None] * (b - a)
    kind = curvature.kind
    if kind == "quadratic":
        c = relative_to_absolute(a, b, np.asarray(curvature.params[0]))

        def f(t):
            t = np.asarray(t)[:, None]
            return (1 - t) ** 2 * a + 2 * (1 - t) * t * c + t**2 * b

        return f
    if kind == "cubic":
        c1 = relative_to_absolute(a, b, np.asarray(curvature.params[0]))
        c2 = relative_to_absolute(a, b, np.asarray(curvature.params[1]))

        def f(t):
            t = np.asarray(t)[:, None]
            return (1 - t) ** 3 * a + 3 * (1 - t) ** 2 * t * c1 + 3 * (1 - t) * t**2 * c2 + t**3 * b

        return f
    if kind == "circle":
        radius, large_arc, right = curvature.params
        center, th0, sweep = arc_center(a, b, float(radius), bool(large_arc), bool(right))
        r = float(np.linalg.norm(a - center))

        def f(t):
            th = th0 + np.asarray(t) * sweep
            return center + r * np.stack([np.cos(th), np.sin(th)], axis=-1)

        return f
    raise ValueError(f"unknown curvature type {kind!r}")


def _dense(a, b, curvature, n=256):
    f = edge_point_fn(a, b, curvature)
    return f(np.linspace(0.0, 1.0, n))


def edge_length(panel: Panel, i: int) -> float:
    """Arc length [m] of edge ``i`` of ``panel``."""
    e = panel.edges[i]
    pts = _dense(panel.vertices[e.start], panel.vertices[e.end], e.curvature, 1025 if e.curvature else 2)
    return float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())


def sample_edge(panel: Panel, i: int, n_segments: int) -> np.ndarray:
    """Points (n_segments + 1, 2) [m] along edge ``i``, equally spaced in arc length,
    from its start vertex to its end vertex (both included, exactly)."""
    e = panel.edges[i]
    a, b = panel.vertices[e.start], panel.vertices[e.end]
    if e.curvature is None:
        t = np.linspace(0.0, 1.0, n_segments + 1)
        return a + t[:, None] * (b - a)
    f = edge_point_fn(a, b, e.curvature)
    tt = np.linspace(0.0, 1.0, 2049)
    pts = f(tt)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    targets = np.linspace(0.0, s[-1], n_segments + 1)
    t = np.interp(targets, s, tt)
    out = f(t)
    out[0], out[-1] = a, b
    return out


def panel_outline(panel: Panel, *, points_per_edge: int = 32) -> np.ndarray:
    """Closed outline polyline (M, 2) [m] of the panel, each edge sampled with
    ``points_per_edge`` segments (straight edges with one), last point not repeated."""
    parts = []
    for i, e in enumerate(panel.edges):
        n = points_per_edge if e.curvature is not None else 1
        parts.append(sample_edge(panel, i, n)[:-1])
    return np.concatenate(parts, axis=0)
