"""Checks of a foreign-benchmark drape and its preview image.

- inside: share of target vertices inside the body (trimesh's ray containment);
- stretch: per-triangle stretch of the draped mesh against the 2D rest panels (largest singular
  value of the deformation gradient minus 1), percentiles;
- seams through a limb: seam segments (edges joining two sewn seam vertices) whose midpoint is
  inside the body, and edges of the whole garment crossing the body (both ends outside, midpoint
  inside: a seam or panel cut through an arm or leg);
- preview: front and side views of garment over body (matplotlib, PNG).
"""

from __future__ import annotations

import numpy as np


def inside_mask(points: np.ndarray, body_v: np.ndarray, body_f: np.ndarray) -> np.ndarray:
    """(N,) bool: points (N, 3) [m] inside the closed body mesh (trimesh ray parity with embree;
    on 3000 random points it agreed with the exact winding number on all of the 300 compared)."""
    import trimesh

    return np.asarray(
        trimesh.Trimesh(body_v, body_f, process=False).contains(np.asarray(points, np.float64)), bool
    )


def stretch(x: np.ndarray, faces: np.ndarray, uv: np.ndarray, faces_uv: np.ndarray) -> np.ndarray:
    """(F,) largest principal stretch - 1 of each triangle: 3D positions x (N, 3) [m] on
    ``faces`` against rest uv (Nu, 2) [m] on ``faces_uv``."""
    X = x[faces]
    U = uv[faces_uv]
    dX = np.stack([X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]], axis=2)  # (F, 3, 2)
    dU = np.stack([U[:, 1] - U[:, 0], U[:, 2] - U[:, 0]], axis=2)  # (F, 2, 2)
    Fg = dX @ np.linalg.inv(dU)
    return np.linalg.svd(Fg, compute_uv=False)[:, 0] - 1.0


def edges_through_body(x, faces, body_v, body_f, *, seam_vertices=None, ins_v=None):
    """Count of garment edges whose midpoint is inside the body while both ends are outside
    (an edge cut through a limb), and of those that join two seam vertices. ``ins_v``: the
    vertices' inside mask when already known."""
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    e = np.unique(np.sort(e, axis=1), axis=0)
    if ins_v is None:
        ins_v = inside_mask(x, body_v, body_f)
    cand = e[~ins_v[e[:, 0]] & ~ins_v[e[:, 1]]]
    mid = inside_mask(0.5 * (x[cand[:, 0]] + x[cand[:, 1]]), body_v, body_f)
    bad = cand[mid]
    n_seam = 0
    if seam_vertices is not None and len(bad):
        s = np.zeros(len(x), bool)
        s[seam_vertices] = True
        n_seam = int((s[bad[:, 0]] & s[bad[:, 1]]).sum())
    return int(len(bad)), n_seam


def preview(path, x, faces, body_v, body_f, *, title=""):
    """Write a PNG: front (x-y) and side (z-y) views, body in grey, garment shaded by normal."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    fig, axes = plt.subplots(1, 2, figsize=(9, 7.5))
    light = np.array([0.3, 0.5, 0.8])
    light /= np.linalg.norm(light)
    for ax, (i, depth, sgn), name in zip(
        axes, ((0, 2, 1.0), (2, 0, -1.0)), ("front", "side (from the body's left)")
    ):
        j = 1
        polys, cols, keys = [], [], []
        for v, f, base in (
            (body_v, body_f, np.array([0.75, 0.75, 0.75])),
            (x, faces, np.array([0.25, 0.45, 0.85])),
        ):
            T = v[f]
            n = np.cross(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0])
            n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)
            view = np.zeros(3)
            view[depth] = sgn
            lam = np.abs(n @ (light if depth == 2 else light[[2, 1, 0]] * [1, 1, 1]))
            shade = 0.35 + 0.65 * lam
            xs = T[:, :, i] * (1 if depth == 2 else -1)
            polys.append(np.stack([xs, T[:, :, j]], axis=2))
            cols.append(shade[:, None] * base[None])
            keys.append(sgn * T[:, :, depth].mean(axis=1))
        P = np.concatenate(polys)
        C = np.concatenate(cols)
        order = np.argsort(np.concatenate(keys))
        ax.add_collection(PolyCollection(P[order], facecolors=np.clip(C[order], 0, 1), edgecolors="none"))
        allp = np.concatenate([body_v, x])
        ax.set_xlim(
            (allp[:, i] * (1 if depth == 2 else -1)).min() - 0.05,
            (allp[:, i] * (1 if depth == 2 else -1)).max() + 0.05,
        )
        ax.set_ylim(allp[:, 1].min() - 0.02, allp[:, 1].max() + 0.02)
        ax.set_aspect("equal")
        ax.set_title(name, fontsize=9)
        ax.axis("off")
    fig.suptitle(title, fontsize=9)
    fig.savefig(path, dpi=80, bbox_inches="tight")
    plt.close(fig)
    shrink_png(path)


def shrink_png(path):
    """Re-save a PNG with a 64-colour palette (about a third of the size; the committed cases
    keep their previews small)."""
    from PIL import Image

    Image.open(path).convert("RGB").quantize(64).save(path, optimize=True)
