"""Mean value coordinates (Floater 2003; Hormann & Floater 2006 for non-convex polygons).

For a point x strictly inside a closed polygon v_0..v_{m-1} (any simple polygon, convex or not),

    w_j = (tan(a_{j-1}/2) + tan(a_j/2)) / |v_j - x|,    lambda_j = w_j / sum_k w_k,

where a_j is the signed angle at x from v_j to v_{j+1}. The coordinates sum to one and reproduce
linear functions exactly: sum_j lambda_j v_j = x. We use tan(a/2) = sin a / (1 + cos a)
= cross(d_j, d_j+1) / (|d_j| |d_j+1| + d_j . d_j+1) with d_j = v_j - x, which is finite for every
x off the outline. Paper 3.3 uses them to move a panel's interior vertices with its outline.
"""

from __future__ import annotations

import numpy as np

__all__ = ["mean_value_coordinates"]


def mean_value_coordinates(points: np.ndarray, polygon: np.ndarray, *, chunk: int = 2_000_000) -> np.ndarray:
    """Mean value coordinates of points w.r.t. a closed polygon.

    points: query points [m], shape (n, 2), float64, strictly inside the polygon.
    polygon: closed polygon [m], shape (m, 2), float64, last vertex not repeated (either orientation).
    chunk: largest n*m block computed at once (memory bound).

    Returns weights (n, m) float64 (dimensionless), rows summing to 1, with
    ``weights @ polygon == points`` up to rounding.
    """
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    polygon = np.asarray(polygon, dtype=np.float64).reshape(-1, 2)
    n, m = len(points), len(polygon)
    out = np.empty((n, m))
    step = max(1, chunk // max(m, 1))
    for s in range(0, n, step):
        x = points[s : s + step]
        d = polygon[None, :, :] - x[:, None, :]  # (k, m, 2)
        r = np.linalg.norm(d, axis=-1)  # (k, m)
        dn = np.roll(d, -1, axis=1)
        rn = np.roll(r, -1, axis=1)
        cross = d[..., 0] * dn[..., 1] - d[..., 1] * dn[..., 0]
        dot = (d * dn).sum(-1)
        t = cross / (r * rn + dot)  # tan(a_j / 2), (k, m)
        w = (np.roll(t, 1, axis=1) + t) / r
        out[s : s + step] = w / w.sum(axis=1, keepdims=True)
    return out
