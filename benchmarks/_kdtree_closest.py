"""The closest-point search unsew used before the geometry core (metrics/surface.py up to 420bd86),
kept only as the "before" row of bench_geometry.py.

A KD-tree of triangle centroids: the k nearest centroids give an upper bound ``u`` on the distance;
queries not certified by ``d_k - r_max`` (``r_max`` the LARGEST centroid-to-corner radius of the
mesh) are re-searched with every triangle whose centroid lies within ``u + r_max``. One large
triangle or a query far from the mesh makes that candidate list grow to (queries x triangles).
"""

from __future__ import annotations

import numpy as np

K = 8


def closest_points_kdtree(points, verts, faces):
    """points (P, 3), verts (V, 3) float64 [m], faces (F, 3) int -> (closest (P, 3), distance (P,),
    face (P,))."""
    from scipy.spatial import cKDTree

    from unsew.body.sdf import closest_point_on_triangles

    v = np.asarray(verts, np.float64)
    f = np.asarray(faces, np.int64)
    p = np.asarray(points, np.float64)
    A, B, C = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    cen = (A + B + C) / 3.0
    r_max = float(np.sqrt(max(((X - cen) ** 2).sum(1).max() for X in (A, B, C))))
    tree = cKDTree(cen)
    k = min(K, len(f))
    dk, ik = tree.query(p, k=k, workers=-1)
    dk, ik = dk.reshape(len(p), k), ik.reshape(len(p), k)
    P = len(p)
    rows = np.repeat(np.arange(P), k)
    cand = ik.ravel()
    q, _ = closest_point_on_triangles(p[rows], A[cand], B[cand], C[cand])
    d = np.linalg.norm(q - p[rows], axis=1).reshape(P, k)
    j = d.argmin(1)
    best_d = d[np.arange(P), j]
    best_f = ik[np.arange(P), j]
    best_q = q.reshape(P, k, 3)[np.arange(P), j]
    if k < len(f):
        unsure = np.nonzero(best_d > dk[:, -1] - r_max)[0]
        if len(unsure):
            lists = tree.query_ball_point(p[unsure], best_d[unsure] + r_max + 1e-12, workers=-1)
            counts = np.array([len(x) for x in lists])
            rr = np.repeat(unsure, counts)
            ff = np.concatenate([np.asarray(x, dtype=np.int64) for x in lists])
            qq, _ = closest_point_on_triangles(p[rr], A[ff], B[ff], C[ff])
            dd = np.linalg.norm(qq - p[rr], axis=1)
            order = np.lexsort((dd, rr))
            first = np.concatenate([[True], rr[order][1:] != rr[order][:-1]])
            sel = order[first]
            better = dd[sel] < best_d[rr[sel]]
            tgt = rr[sel][better]
            best_d[tgt] = dd[sel][better]
            best_f[tgt] = ff[sel][better]
            best_q[tgt] = qq[sel][better]
    return best_q, best_d, best_f
