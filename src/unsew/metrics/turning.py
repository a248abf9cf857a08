"""Turning-function distance between polygons (Arkin, Chew, Huttenlocher, Kedem, Mitchell 1991,
"An efficiently computable metric for comparing polygonal shapes"), our own implementation.

The turning function Theta_A(s) of a polygon gives the direction [rad] of its boundary at arc
length s, with the perimeter normalised to 1; it starts at the direction of the first edge,
steps by the signed turning angle at each vertex (left turns positive) and, for a
counter-clockwise simple polygon, rises by 2 pi over the loop, continuing as
Theta(s + 1) = Theta(s) + 2 pi. The distance is::

    d(A, B) = min_{t in [0,1), theta}  ( int_0^1 (Theta_A(s + t) - Theta_B(s) + theta)^2 ds )^(1/2)

It is invariant to translation, rotation, scale and start vertex, and a collinear extra vertex
changes nothing. For a fixed shift t the best rotation is closed-form (theta* = -mean of the
difference), leaving the variance of f_t(s) = Theta_A(s + t) - Theta_B(s); Arkin et al. show
the minimum over t lies where a breakpoint of A meets one of B, t = a_i - b_j (mod 1). We
evaluate all m*n such shifts exactly in O(mn (log m + n)) with the cumulative integrals of
Theta_A and Theta_A^2 (vectorised), then re-evaluate the best few shifts by merging the two
step functions, which keeps identical shapes at distance 0 to rounding.

Both outlines are made counter-clockwise first (a panel's orientation is not part of its shape).
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.curves import panel_outline

__all__ = ["turning_function", "turning_distance", "panel_turning_distance"]

_CHUNK = 1 << 21  # candidate-shift x piece evaluations per vectorised chunk
_REFINE = 16  # best candidate shifts re-evaluated exactly
_SNAP = 1e-11  # breakpoints closer than this (fraction of the perimeter) are merged


def turning_function(poly) -> tuple[np.ndarray, np.ndarray]:
    """Turning function of a closed polygon, normalised to perimeter 1.

    poly: vertices of a closed polygon, shape (n, 2), float64, any unit (scale-free), the last
        vertex not repeating the first (a repeated one is dropped). Made counter-clockwise.
    Returns: (breaks (k,) float64 in [0, 1), breaks[0] = 0; angles (k,) float64 [rad]):
        Theta(s) = angles[i] on [breaks[i], breaks[i+1]).
    Raises ValueError for fewer than 3 distinct vertices, non-finite input or zero area.
    """
    p = np.asarray(poly, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"polygon must have shape (n, 2), got {p.shape}")
    if not np.isfinite(p).all():
        raise ValueError("polygon has non-finite vertices")
    e = np.roll(p, -1, axis=0) - p  # (n, 2) edge vectors
    L = np.linalg.norm(e, axis=1)
    scale = L.sum()
    keep = L > 1e-12 * max(scale, 1e-300)  # drop repeated vertices (zero-length edges)
    p = p[keep]
    if len(p) < 3:
        raise ValueError("polygon needs at least 3 distinct vertices")
    x, y = p[:, 0], p[:, 1]
    area2 = float((x * np.roll(y, -1) - np.roll(x, -1) * y).sum())
    if abs(area2) <= 1e-12 * scale * scale:
        raise ValueError("polygon has zero area")
    if area2 < 0:
        p = p[::-1]
    e = np.roll(p, -1, axis=0) - p
    L = np.linalg.norm(e, axis=1)
    breaks = np.concatenate([[0.0], np.cumsum(L)[:-1]]) / L.sum()
    en = np.roll(e, -1, axis=0)
    turn = np.arctan2(e[:, 0] * en[:, 1] - e[:, 1] * en[:, 0], (e * en).sum(1))  # at vertex i+1
    angles = np.arctan2(e[0, 1], e[0, 0]) + np.concatenate([[0.0], np.cumsum(turn[:-1])])
    return breaks, angles


def _exact_var(a, alpha, b, beta, t):
    """Variance over s in [0,1) of Theta_A(s + t) - Theta_B(s), by merging the step functions."""
    ka = np.concatenate([a, a + 1.0])
    va = np.concatenate([alpha, alpha + 2 * np.pi])
    cuts = np.unique(np.concatenate([b, (a - t) % 1.0, [0.0, 1.0]]))
    # breakpoints that meet up to rounding are one breakpoint: a sliver of width 1e-16 under a
    # jump of ~1 rad would add ~1e-16 to the variance, 1e-8 to the distance
    keep = np.concatenate([[True], np.diff(cuts) > _SNAP])
    keep[-1] = True
    cuts = cuts[keep]
    if len(cuts) > 2 and cuts[-1] - cuts[-2] <= _SNAP:
        cuts = np.delete(cuts, -2)
    w = np.diff(cuts)
    mid = 0.5 * (cuts[:-1] + cuts[1:])
    fa = va[np.searchsorted(ka, mid + t, side="right") - 1]
    fb = beta[np.searchsorted(b, mid, side="right") - 1]
    f = fa - fb
    mean = (w * f).sum()
    return float((w * (f - mean) ** 2).sum())


def turning_distance(poly_a, poly_b) -> float:
    """Arkin et al.'s turning-function distance between two closed polygons (module docstring).

    poly_a: (n, 2) float64; poly_b: (m, 2) float64; any common or different units (scale-free).
    Returns: distance [rad], >= 0; 0 for similar polygons (translation, rotation, scale, start
    vertex, collinear vertices). Not symmetric in floating point only.
    """
    a, alpha = turning_function(poly_a)
    b, beta = turning_function(poly_b)
    twopi = 2 * np.pi
    # Theta_A extended over [0, 2]: knots, values, cumulative integrals of Theta_A and Theta_A^2
    ka = np.concatenate([a, a + 1.0, [2.0]])
    va = np.concatenate([alpha, alpha + twopi])
    dk = np.diff(ka)
    FA = np.concatenate([[0.0], np.cumsum(va * dk)])
    GA = np.concatenate([[0.0], np.cumsum(va * va * dk)])

    def F(x, cum, vals):  # piecewise-linear cumulative integral at x in [0, 2]
        k = np.clip(np.searchsorted(ka, x, side="right") - 1, 0, len(vals) - 1)
        return cum[k] + vals[k] * (x - ka[k])

    db = np.diff(np.concatenate([b, [1.0]]))  # (n,)
    IB = float((beta * db).sum())
    IB2 = float((beta * beta * db).sum())
    bb = np.concatenate([b, [1.0]])
    shifts = np.unique(((a[:, None] - b[None, :]) % 1.0).ravel())
    h2 = np.empty(len(shifts))
    rows = max(1, _CHUNK // len(bb))
    for s0 in range(0, len(shifts), rows):
        t = shifts[s0 : s0 + rows]
        Fb = F(bb[None, :] + t[:, None], FA, va)  # (T, n+1)
        C = (beta[None, :] * np.diff(Fb, axis=1)).sum(1)  # int Theta_A(s+t) Theta_B(s) ds
        IA = F(1.0 + t, FA, va) - F(t, FA, va)
        IA2 = F(1.0 + t, GA, va * va) - F(t, GA, va * va)
        mean = IA - IB
        h2[s0 : s0 + rows] = IA2 - 2 * C + IB2 - mean * mean
    order = np.argsort(h2)
    best = order[:_REFINE]
    near = np.nonzero(h2 <= h2[order[0]] + 1e-9)[0][: 4 * _REFINE]
    cand = np.unique(np.concatenate([best, near]))
    v = min(_exact_var(a, alpha, b, beta, shifts[i]) for i in cand)
    return float(np.sqrt(max(v, 0.0)))


def panel_turning_distance(panel_a, panel_b, *, points_per_edge: int = 32) -> float:
    """Turning distance between two panels' outlines (curved edges sampled).

    panel_a, panel_b: :class:`unsew.pattern.model.Panel`. points_per_edge: segments per curved
    edge (straight edges keep their two ends). Returns: distance [rad].
    """
    return turning_distance(
        panel_outline(panel_a, points_per_edge=points_per_edge),
        panel_outline(panel_b, points_per_edge=points_per_edge),
    )
