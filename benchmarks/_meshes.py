"""Synthetic garment-like meshes and query points for bench_geometry.py and bench_memory.py.

A "tube" is an open, flared, wavy cylinder (a skirt-like surface with two boundary loops), Y up,
radius about 16 cm, 60 cm tall. ``uneven=True`` replaces its lowest 10 cm by a band of triangles
10x wider and 10x taller than the rest (area 100x the median), not sharing vertices with it, as a
CAD export or a decimated scan can have.
"""

from __future__ import annotations

import math

import numpy as np

RADIUS = 0.16  # [m]
HEIGHT = 0.6  # [m]


def _grid(nu: int, nv: int, y0: float, y1: float, *, radius: float) -> tuple[np.ndarray, np.ndarray]:
    th = np.linspace(0.0, 2 * math.pi, nu, endpoint=False)
    y = np.linspace(y0, y1, nv + 1)
    T, Y = np.meshgrid(th, y)  # (nv + 1, nu)
    r = radius * (1.0 + 0.08 * np.sin(5 * T)) + 0.1 * (HEIGHT - Y)  # flared towards the hem
    verts = np.stack([r * np.cos(T), Y, r * np.sin(T)], axis=-1).reshape(-1, 3)
    i = np.arange(nv)[:, None] * nu
    j = np.arange(nu)[None, :]
    a = (i + j).ravel()
    b = (i + (j + 1) % nu).ravel()
    c, d = a + nu, b + nu
    faces = np.concatenate([np.stack([a, b, d], 1), np.stack([a, d, c], 1)])
    return verts, faces.astype(np.int64)


def _split(n_faces: int) -> tuple[int, int]:
    nu = max(8, round(math.sqrt(n_faces / 2 * (2 * math.pi * RADIUS / HEIGHT))))
    return nu, max(1, round(n_faces / (2 * nu)))


def tube(n_faces: int, *, uneven: bool = False, radius: float = RADIUS) -> tuple[np.ndarray, np.ndarray]:
    """About ``n_faces`` triangles: (verts (V, 3) float64 [m], faces (F, 3) int64)."""
    nu, nv = _split(n_faces)
    if not uneven:
        return _grid(nu, nv, 0.0, HEIGHT, radius=radius)
    y_cut = 0.1
    nv_f = max(1, round(nv * (HEIGHT - y_cut) / HEIGHT))
    vf, ff = _grid(nu, nv_f, y_cut, HEIGHT, radius=radius)
    dv = (HEIGHT - y_cut) / nv_f
    vc, fc = _grid(max(3, nu // 10), max(1, round(y_cut / (10 * dv))), 0.0, y_cut, radius=radius)
    return np.concatenate([vf, vc]), np.concatenate([ff, fc + len(vf)])


def tube_with_verts(n_verts: int, *, uneven: bool = False, radius: float = RADIUS):
    """A tube with about ``n_verts`` vertices (about 2 triangles per vertex)."""
    return tube(2 * n_verts, uneven=uneven, radius=radius)


def face_areas(verts: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """(F,) triangle areas [m^2]."""
    v = verts[faces]
    return 0.5 * np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1)


def surface_points(verts, faces, n: int, *, seed: int = 0) -> np.ndarray:
    """(n, 3) area-uniform random points on the mesh [m]."""
    rng = np.random.default_rng(seed)
    a = face_areas(verts, faces)
    fi = rng.choice(len(faces), size=n, p=a / a.sum())
    r1, r2 = np.sqrt(rng.random(n)), rng.random(n)
    A, B, C = (verts[faces[fi, k]] for k in range(3))
    return (1 - r1)[:, None] * A + (r1 * (1 - r2))[:, None] * B + (r1 * r2)[:, None] * C


def queries(verts, faces, n: int, *, away: float = 0.0, seed: int = 0) -> np.ndarray:
    """(n, 3) query points [m]: surface points jittered by up to 1 cm, then moved ``away`` metres
    outwards from the tube's axis (``away=0.3``: a result 30 cm from the target)."""
    rng = np.random.default_rng(seed + 1)
    p = surface_points(verts, faces, n, seed=seed) + rng.uniform(-0.01, 0.01, (n, 3))
    radial = p * np.array([1.0, 0.0, 1.0])
    radial /= np.maximum(np.linalg.norm(radial, axis=1, keepdims=True), 1e-12)
    return p + away * radial
