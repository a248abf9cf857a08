"""Meshes with known geometry for the loss tests."""

import numpy as np


def open_cylinder(r=0.2, h=0.5, nu=64, nv=20):
    """Open cylinder along +Y: verts (nv*nu, 3) [m], faces (F, 3) outward."""
    th = np.linspace(0, 2 * np.pi, nu, endpoint=False)
    y = np.linspace(0, h, nv)
    T, Y = np.meshgrid(th, y)
    V = np.stack([r * np.cos(T), Y, r * np.sin(T)], -1).reshape(-1, 3)
    F = []
    for j in range(nv - 1):
        for i in range(nu):
            a, b = j * nu + i, j * nu + (i + 1) % nu
            F += [[a, a + nu, b], [b, a + nu, b + nu]]
    return V, np.array(F)
