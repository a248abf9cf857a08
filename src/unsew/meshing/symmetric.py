"""Symmetric panel meshes: a panel with a mirror axis is triangulated on one half and mirrored,
and the second panel of a symmetric pair gets the first one's triangulation moved onto it.

Why: two meshes of one symmetric garment triangulated independently are asymmetric, and
buckling loose cloth amplifies that asymmetry. Measured on the altered t-shirt of
bench_grading at 3 cm: the draped garment differed from its own left-right mirror image by
4.7-7.5 mm (Chamfer), as much as two drapes of the same pattern on 2.9 and 3.0 cm meshes
differed from each other. With mirrored meshes a symmetric pattern on a symmetric body drapes
symmetrically, and the remaining mesh-to-mesh noise is that of the symmetric fold modes.

Both functions take and return panel-frame coordinates [m] and follow the contract of
:func:`unsew.meshing.triangulate.triangulate_polygon`: the first M vertices of the result are
the outline (which they may move by at most ``snap`` to make it exactly symmetric), triangles
are counter-clockwise. They return None when the outline is not symmetric within the
tolerance; the caller then triangulates the panel on its own.
"""

from __future__ import annotations

import math

import numpy as np

from unsew.meshing.triangulate import signed_areas, triangulate_polygon

__all__ = ["triangulate_mirrored", "transport_mesh", "reflect"]

#: An outline sample whose mirror image lies within this fraction of the edge length of
#: another sample is taken as its symmetric partner [-].
MATCH_REL = 1e-3
#: Outline samples that symmetrisation would move by less than this keep their value [m].
SNAP_KEEP = 1e-12


def reflect(pts: np.ndarray, point: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """Mirror image of points (n, 2) [m] across the line through ``point`` along ``direction``."""
    d = np.asarray(direction, dtype=np.float64)
    d = d / np.linalg.norm(d)
    r = np.asarray(pts, dtype=np.float64) - point
    return point + 2.0 * np.outer(r @ d, d) - r


def _mirror_permutation(outline: np.ndarray, point, direction, tol: float) -> np.ndarray | None:
    """sigma (M,) with reflect(outline[i]) ~ outline[sigma[i]], an involution; None if none."""
    from scipy.spatial import cKDTree

    dist, sigma = cKDTree(outline).query(reflect(outline, point, direction))
    if not np.all(dist <= tol) or not np.array_equal(sigma[sigma], np.arange(len(outline))):
        return None
    return sigma.astype(np.int64)


def triangulate_mirrored(
    outline: np.ndarray, point, direction, *, edge_length: float, min_angle: float = 20.0, name: str = "panel"
) -> tuple[np.ndarray, np.ndarray] | None:
    """Triangulate a polygon symmetric about an axis: one half, then its mirror image.

    outline: (M, 2) [m], counter-clockwise, last point not repeated, crossing the axis exactly at
    two of its samples. point, direction: (2,) the axis [m]. edge_length, min_angle, name: as
    :func:`triangulate_polygon` (the axis chord is sampled at ``edge_length``).

    Returns (verts (V, 2) float64, tris (T, 3) int64) or None when the outline is not symmetric
    sample for sample (within MATCH_REL * edge_length) or does not cross the axis at two samples.
    The outline is made exactly symmetric: samples on the axis are projected onto it, and the
    samples of the second half are the reflections of the first half's.
    """
    outline = np.asarray(outline, dtype=np.float64)
    m = len(outline)
    d = np.asarray(direction, dtype=np.float64)
    d = d / np.linalg.norm(d)
    c = np.asarray(point, dtype=np.float64)
    sigma = _mirror_permutation(outline, c, d, MATCH_REL * edge_length)
    if sigma is None:
        return None
    fixed = np.flatnonzero(sigma == np.arange(m))
    if len(fixed) != 2:
        return None
    ia, ib = int(fixed[0]), int(fixed[1])
    arc = (ia + np.arange(ib - ia + 1)) % m  # one half's outline, ia -> ib, CCW (either half will do)
    if len(arc) < 3:
        return None
    # exact symmetry of the outline
    out = outline.copy()
    for i in (ia, ib):
        out[i] = c + d * float((outline[i] - c) @ d)
    inner = arc[1:-1]
    out[sigma[inner]] = reflect(out[inner], c, d)
    # samples already symmetric to rounding keep their exact values (pattern corners stay exact)
    keep = np.abs(out - outline).max(axis=1) <= SNAP_KEEP
    out[keep] = outline[keep]
    a, b = out[arc[0]], out[arc[-1]]
    n_chord = max(1, math.ceil(float(np.linalg.norm(b - a)) / edge_length - 1e-9))
    t = np.arange(1, n_chord)[:, None] / n_chord
    chord = b + t * (a - b)  # from the arc's end back to its start, on the axis
    chord = c + np.outer((chord - c) @ d, d)
    half = np.concatenate([out[arc], chord], axis=0)
    try:
        hv, ht = triangulate_polygon(half, edge_length=edge_length, min_angle=min_angle, name=name)
    except Exception:
        return None
    la, lc = len(arc), len(chord)
    interior = hv[la + lc :]
    li = len(interior)
    verts = np.concatenate([out, chord, interior, reflect(interior, c, d)], axis=0)
    to_full = np.concatenate([arc, m + np.arange(lc), m + lc + np.arange(li)]).astype(np.int64)
    mirror = np.concatenate([sigma, m + np.arange(lc), m + lc + li + np.arange(li), m + lc + np.arange(li)])
    t1 = to_full[ht]
    t2 = mirror[t1][:, [0, 2, 1]]
    tris = np.concatenate([t1, t2], axis=0).astype(np.int64)
    if (signed_areas(verts, tris) <= 0).any() or len(np.unique(tris, axis=0)) != len(tris):
        return None
    return verts, tris


def transport_mesh(
    src_outline: np.ndarray,
    src_verts: np.ndarray,
    src_tris: np.ndarray,
    dst_outline: np.ndarray,
    *,
    mirrored: bool,
    edge_length: float,
) -> tuple[np.ndarray, np.ndarray] | None:
    """The triangulation of one panel moved onto a congruent (or mirror-congruent) panel.

    src_outline: (M, 2) the source's outline [m]; src_verts (V, 2), src_tris (T, 3): its mesh
    (first M vertices = the outline). dst_outline: (M, 2) the other panel's outline, CCW.
    mirrored: the two are related by a reflection (outline order reversed).

    Returns (verts, tris) for the destination, or None when no rigid motion (with reflection when
    ``mirrored``) maps the source outline onto the destination's sample for sample within
    0.1 * edge_length. When the fit is within MATCH_REL * edge_length the destination outline is
    replaced by the moved source outline (exact congruence); otherwise the destination keeps its
    own outline and only the interior and the triangles come from the source.
    """
    from unsew.pattern.symmetry import procrustes

    s = np.asarray(src_outline, dtype=np.float64)
    t = np.asarray(dst_outline, dtype=np.float64)
    m = len(s)
    if len(t) != m or m < 3:
        return None
    det = -1 if mirrored else 1
    ms, mt = s.mean(axis=0), t.mean(axis=0)
    xs, yt = s - ms, t - mt
    best = None
    for shift in range(m):
        # destination sample i corresponds to source sample perm[i]
        perm = (shift - np.arange(m)) % m if mirrored else (np.arange(m) + shift) % m
        r, _ = procrustes(xs[perm], yt, det=det)
        worst = float(np.linalg.norm(xs[perm] @ r.T - yt, axis=1).max())
        if best is None or worst < best[0]:
            best = (worst, perm, r)
    worst, perm, r = best
    if worst > 0.1 * edge_length:
        return None
    inv = np.empty(m, dtype=np.int64)
    inv[perm] = np.arange(m)  # source outline sample j -> destination sample inv[j]
    moved = (np.asarray(src_verts, dtype=np.float64) - ms) @ r.T + mt
    outline = moved[perm] if worst <= MATCH_REL * edge_length else t
    verts = np.concatenate([outline, moved[m:]], axis=0)
    index = np.concatenate([inv, np.arange(m, len(src_verts))]).astype(np.int64)
    tris = index[np.asarray(src_tris, dtype=np.int64)]
    if mirrored:
        tris = tris[:, [0, 2, 1]]
    if (signed_areas(verts, tris) <= 0).any():
        return None
    return verts, tris
