"""Triangulation of one flat panel with Shewchuk's Triangle (the ``triangle`` package).

The panel's outline arrives already sampled (a closed polygon, counter-clockwise, last point not
repeated). Triangle is called as a constrained, quality-conforming Delaunay triangulation with
no Steiner points on the boundary (switch ``Y``), so the outline's vertices are exactly the
first vertices of the result and seams sampled identically on two panels stay vertex to vertex.
"""

from __future__ import annotations

import math

import numpy as np

from unsew.errors import PatternError

__all__ = ["triangulate_polygon", "triangle_min_angles", "signed_areas"]


#: Narrowest panel [m] (mean width: twice the area over the perimeter) handed to Triangle: a
#: sliver (a panel whose corners lie on one line, curved edges giving it 0.1 mm of width)
#: crashed Triangle with a segmentation fault, taking the whole process down.
MIN_MEAN_WIDTH = 1e-3

#: Decimals of a metre (1 nm) of the outline Triangle refines (see triangulate_polygon).
GRID_DECIMALS = 9


def _check_meshable(boundary: np.ndarray, name: str) -> None:
    """Refuse outlines Triangle cannot take safely: repeated consecutive points, no area, or a
    sliver narrower than :data:`MIN_MEAN_WIDTH` on average. boundary: (M, 2) [m]."""
    d = np.linalg.norm(np.roll(boundary, -1, axis=0) - boundary, axis=1)  # (M,) segment lengths
    perimeter = float(d.sum())
    if not np.isfinite(boundary).all():
        raise PatternError(f"panel {name!r}: outline has non-finite coordinates; check its vertices")
    if (d <= 1e-9 * max(perimeter, 1e-12)).any():
        raise PatternError(
            f"panel {name!r}: outline repeats a point; check for duplicate vertices or zero-length edges"
        )
    back, ahead = np.roll(boundary, 1, axis=0) - boundary, np.roll(boundary, -1, axis=0) - boundary
    cos = (back * ahead).sum(axis=1) / (np.linalg.norm(back, axis=1) * np.linalg.norm(ahead, axis=1))
    spikes = np.flatnonzero(cos > math.cos(math.radians(0.5)))  # the outline turns back on itself
    if spikes.size:
        raise PatternError(
            f"panel {name!r}: outline folds back on itself at outline point {int(spikes[0])} of "
            f"{len(boundary)} (a spike of zero width); check its vertices and curvature"
        )
    crossing = _first_crossing(boundary)
    if crossing is not None:
        raise PatternError(
            f"panel {name!r}: outline crosses itself (outline segments {crossing[0]} and {crossing[1]} of "
            f"{len(boundary)}); check its vertices and curvature"
        )
    x, y = boundary[:, 0], boundary[:, 1]
    area = 0.5 * abs(float(x @ np.roll(y, -1) - y @ np.roll(x, -1)))
    width = 2.0 * area / perimeter
    if width < MIN_MEAN_WIDTH:
        raise PatternError(
            f"panel {name!r} has {area * 1e4:.3g} cm^2 over a {perimeter * 100:.3g} cm outline (a sliver "
            f"{width * 1000:.2g} mm wide on average); check its vertices"
        )


def _first_crossing(b: np.ndarray, *, chunk: int = 256) -> tuple[int, int] | None:
    """The first pair (i, j) of non-adjacent segments of the closed polyline ``b`` (M, 2) that
    cross or touch, or None. Segment i runs from b[i] to b[i+1]; all pairs are tested with
    orientation signs, ``chunk`` rows at a time (O(M^2) memory-bounded)."""
    m = len(b)
    p, q = b, np.roll(b, -1, axis=0)  # (M, 2) segment ends
    scale = float(np.abs(b).max()) or 1.0
    eps = 1e-12 * scale * scale

    def orient(a, c, d):  # sign of cross((c - a), (d - a)), broadcast
        return (c[..., 0] - a[..., 0]) * (d[..., 1] - a[..., 1]) - (c[..., 1] - a[..., 1]) * (
            d[..., 0] - a[..., 0]
        )

    idx = np.arange(m)
    for s in range(0, m, chunk):
        i = idx[s : s + chunk, None]  # (C, 1)
        pi, qi = p[s : s + chunk, None], q[s : s + chunk, None]  # (C, 1, 2)
        pj, qj = p[None], q[None]  # (1, M, 2)
        d1, d2 = orient(pi, qi, pj), orient(pi, qi, qj)  # (C, M)
        d3, d4 = orient(pj, qj, pi), orient(pj, qj, qi)
        hit = (d1 * d2 < -eps) & (d3 * d4 < -eps)  # proper crossings
        near = (np.abs(idx[None] - i) <= 1) | (np.abs(idx[None] - i) == m - 1)  # a segment and its neighbours
        hit &= ~near & (idx[None] > i)
        if hit.any():
            r, c = np.argwhere(hit)[0]
            return int(s + r), int(c)
    return None


def _on_grid(points: np.ndarray) -> np.ndarray:
    """Points (M, 2) [m] rounded to the GRID_DECIMALS grid."""
    return np.round(points, GRID_DECIMALS)


def triangulate_polygon(
    boundary: np.ndarray, *, edge_length: float, min_angle: float = 20.0, name: str = "panel"
) -> tuple[np.ndarray, np.ndarray]:
    """Triangulate the inside of a simple closed polygon.

    boundary: outline [m], shape (M, 2), float64, counter-clockwise, last point not repeated.
    edge_length: target edge length h [m]; triangles get a maximum area of sqrt(3)/4 * h^2.
    min_angle: quality bound [deg] passed to Triangle (Triangle guarantees up to about 33 deg;
        corners of the outline sharper than this bound keep their angle).
    name: panel name used in error messages.

    Returns (verts (V, 2) float64 [m], tris (T, 3) int64): the first M vertices are ``boundary``
    itself, unchanged; triangles are counter-clockwise. Triangle is given the outline rounded to
    a 1 nm grid (GRID_DECIMALS), so that an outline off in its last bits (another CPU's
    arithmetic, a file written in cm and read in m) gets the same triangles and the same
    interior vertices: its refinement otherwise changes the whole panel's mesh with them.
    """
    import triangle

    boundary = np.ascontiguousarray(boundary, dtype=np.float64)
    m = len(boundary)
    if m < 3:
        raise PatternError(f"panel {name!r}: outline has {m} points, need at least 3; check its edges")
    _check_meshable(boundary, name)
    seg = np.stack([np.arange(m), (np.arange(m) + 1) % m], axis=1).astype(np.int32)
    max_area = math.sqrt(3.0) / 4.0 * edge_length**2
    # p: PSLG, q: quality (min angle), a: max area, Y: no Steiner points on segments, Q: quiet.
    opts = f"pq{min_angle:.6f}a{max_area:.15f}YQ"  # fixed point: Triangle reads no exponents
    grid = _on_grid(boundary)
    try:
        out = triangle.triangulate({"vertices": grid, "segments": seg}, opts)
    except Exception as exc:  # Triangle reports bad input as generic errors
        raise PatternError(
            f"panel {name!r}: triangulation failed ({exc}); check that its outline does not cross itself"
        ) from None
    verts = np.asarray(out.get("vertices", np.zeros((0, 2))), dtype=np.float64)
    tris = np.asarray(out.get("triangles", np.zeros((0, 3))), dtype=np.int64)
    if len(tris) == 0 or len(verts) < m or not np.array_equal(verts[:m], grid):
        raise PatternError(
            f"panel {name!r}: triangulation lost its outline; check for repeated or crossing outline points"
        )
    verts[:m] = boundary
    area = signed_areas(verts, tris)
    flip = area < 0
    if flip.any():
        tris[flip] = tris[flip][:, [0, 2, 1]]
    return verts, tris


def signed_areas(verts: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """Signed areas [m^2], shape (T,), of triangles tris (T, 3) int over verts (V, 2) [m];
    positive for counter-clockwise triangles."""
    a, b, c = verts[tris[:, 0]], verts[tris[:, 1]], verts[tris[:, 2]]
    e1, e2 = b - a, c - a
    return 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])


def triangle_min_angles(verts: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """Smallest interior angle [deg] of each triangle, shape (T,), for verts (V, 2 or 3) [m]
    and tris (T, 3) int."""
    p = verts[tris]  # (T, 3, d)
    ang = []
    for k in range(3):
        u = p[:, (k + 1) % 3] - p[:, k]
        v = p[:, (k + 2) % 3] - p[:, k]
        cosv = (u * v).sum(-1) / np.maximum(np.linalg.norm(u, axis=-1) * np.linalg.norm(v, axis=-1), 1e-300)
        ang.append(np.degrees(np.arccos(np.clip(cosv, -1.0, 1.0))))
    return np.min(np.stack(ang, axis=1), axis=1)
