"""Mean curvature of a triangle mesh and the curvature weights of the weighted Chamfer (eq. 7).

Mean curvature by the cotangent Laplacian with the mixed Voronoi area (Meyer, Desbrun, Schroeder,
Barr 2003, "Discrete differential-geometry operators for triangulated 2-manifolds")::

    K(x_i) = 1 / (2 A_mixed(i)) * sum_j (cot a_ij + cot b_ij) (x_i - x_j) = 2 H(x_i) n(x_i)
    |H(x_i)| = |K(x_i)| / 2

so a sphere of radius r has |H| = 1/r and a cylinder |H| = 1/(2r). On a mesh boundary (a hem, a
cuff) the cotangent formula measures the boundary's pull, not the surface's bending; a boundary
vertex therefore takes the mean |H| of its interior one-ring neighbours (the mesh-wide mean if it
has none).

Curvature weights (our normalisation; the paper uses kappa directly)::

    w_i = (|H_i| + Hbar) / (2 Hbar),   Hbar = sum_i A_i |H_i| / sum_i A_i

The area-weighted mean of w is exactly 1, so the weighted Chamfer keeps the scale of the plain
one; flat regions keep half the mean weight (they are never ignored) and the most curved folds
count most. A target whose mean curvature is zero to rounding (``Hbar * sqrt(area) <``
:data:`unsew.tolerances.FLAT_CURVATURE_TOL`) gets all weights exactly 1, and the weighted Chamfer
then equals the plain Chamfer exactly.
"""

from __future__ import annotations

import numpy as np

from unsew.losses._arrays import mesh_arrays

__all__ = ["mean_curvature", "curvature_weights", "mixed_areas"]


def _corner_cotangents(v, f):
    """Cotangent of the angle at each corner, shape (F, 3), and face areas (F,) [m^2]."""
    p0, p1, p2 = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    cots = np.empty((len(f), 3))
    twice_area = np.linalg.norm(np.cross(p1 - p0, p2 - p0), axis=1)  # (F,)
    safe = np.where(twice_area > 0, twice_area, np.inf)
    for c, (a, b, o) in enumerate(((p1, p2, p0), (p2, p0, p1), (p0, p1, p2))):
        # corner o with edges to a and b: cot = dot / |cross|
        cots[:, c] = ((a - o) * (b - o)).sum(axis=1) / safe
    return cots, 0.5 * twice_area


def mixed_areas(verts, faces) -> np.ndarray:
    """Mixed Voronoi area of each vertex (Meyer et al. 2003).

    verts: (V, 3) float64 [m]; faces: (F, 3) int. Returns (V,) float64 [m^2]; the areas sum to
    the mesh's area.
    """
    v, f = mesh_arrays(verts, faces)
    cots, area = _corner_cotangents(v, f)
    el2 = np.stack(  # squared length of the edge opposite each corner, (F, 3)
        [
            ((v[f[:, 1]] - v[f[:, 2]]) ** 2).sum(1),
            ((v[f[:, 2]] - v[f[:, 0]]) ** 2).sum(1),
            ((v[f[:, 0]] - v[f[:, 1]]) ** 2).sum(1),
        ],
        axis=1,
    )
    # Voronoi share of corner c: (|e_opp(c+1)|^2 cot(c+1) + |e_opp(c+2)|^2 cot(c+2)) / 8
    vor = np.empty_like(cots)
    for c in range(3):
        c1, c2 = (c + 1) % 3, (c + 2) % 3
        vor[:, c] = (el2[:, c1] * cots[:, c1] + el2[:, c2] * cots[:, c2]) / 8.0
    obtuse = cots < 0  # (F, 3) corner angle > 90 degrees
    any_obtuse = obtuse.any(axis=1)
    share = np.where(any_obtuse[:, None], np.where(obtuse, area[:, None] / 2, area[:, None] / 4), vor)
    out = np.zeros(len(v))
    np.add.at(out, f.ravel(), share.ravel())
    return out


def mean_curvature(verts, faces) -> np.ndarray:
    """Unsigned mean curvature |H| at each vertex, by the cotangent Laplacian (module docstring).

    verts: (V, 3) float64 [m] (numpy or torch); faces: (F, 3) int.
    Returns: (V,) float64 numpy [1/m]; vertices in no face get 0.
    """
    v, f = mesh_arrays(verts, faces)
    n = len(v)
    cots, _ = _corner_cotangents(v, f)
    K = np.zeros((n, 3))
    for c in range(3):  # corner c weighs the opposite edge (c+1, c+2)
        j, k = f[:, (c + 1) % 3], f[:, (c + 2) % 3]
        d = cots[:, c : c + 1] * (v[j] - v[k])  # (F, 3)
        np.add.at(K, j, d)
        np.add.at(K, k, -d)
    A = mixed_areas(v, f)
    used = A > 0
    H = np.zeros(n)
    H[used] = np.linalg.norm(K[used], axis=1) / (2.0 * A[used]) / 2.0
    from unsew.geometry.topology import boundary_vertices, unique_edges

    bnd = boundary_vertices(f, n)
    if bnd.any():
        edges = unique_edges(f)[0]
        interior = used & ~bnd
        # mean |H| over interior one-ring neighbours, for each boundary vertex
        a, b = edges[:, 0], edges[:, 1]
        s = np.zeros(n)
        c = np.zeros(n)
        for p, q in ((a, b), (b, a)):
            m = interior[q]
            np.add.at(s, p[m], H[q[m]])
            np.add.at(c, p[m], 1.0)
        fallback = (A[interior] * H[interior]).sum() / A[interior].sum() if interior.any() else 0.0
        H[bnd] = np.where(c[bnd] > 0, s[bnd] / np.maximum(c[bnd], 1), fallback)
    return H


def curvature_weights(verts, faces):
    """Per-vertex weights for the curvature-weighted Chamfer (eq. 7), normalisation in the module
    docstring: ``w = (|H| + Hbar) / (2 Hbar)``, area-weighted mean 1, exactly 1 on a flat mesh.

    verts: target vertices (V, 3) float64 [m], numpy or torch; faces: (F, 3) int.
    Returns: (V,) float64 dimensionless, a torch tensor (no gradient, on ``verts``' device) if
    ``verts`` is a torch tensor, else numpy.
    """
    from unsew.tolerances import FLAT_CURVATURE_TOL

    v, f = mesh_arrays(verts, faces)
    H = mean_curvature(v, f)
    A = mixed_areas(v, f)
    total = A.sum()
    hbar = float((A * H).sum() / total) if total > 0 else 0.0
    if not np.isfinite(hbar) or hbar * np.sqrt(total) < FLAT_CURVATURE_TOL:
        w = np.ones(len(v))
    else:
        w = (H + hbar) / (2.0 * hbar)
    try:
        import torch

        if isinstance(verts, torch.Tensor):
            return torch.as_tensor(w, dtype=torch.float64, device=verts.device)
    except ImportError:  # pragma: no cover
        pass
    return w
