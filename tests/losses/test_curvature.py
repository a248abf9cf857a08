"""Mean curvature and curvature weights on shapes with known curvature."""

import numpy as np
import pytest
import torch
import trimesh

from helpers import assert_close
from losses._loss_meshes import open_cylinder
from unsew.losses.curvature import curvature_weights, mean_curvature, mixed_areas


@pytest.mark.parametrize("sub,tol", [(3, 1e-4), (4, 2e-5)])
def test_sphere_curvature_and_constant_weights(sub, tol):
    r = 0.3
    m = trimesh.creation.icosphere(subdivisions=sub, radius=r)
    H = mean_curvature(m.vertices, m.faces)
    assert_close(H, 1.0 / r, rtol=tol)
    w = curvature_weights(m.vertices, m.faces)
    assert_close(w, 1.0, rtol=tol)


def test_sphere_tolerance_shrinks_with_refinement():
    errs = []
    for sub in (2, 3, 4):
        m = trimesh.creation.icosphere(subdivisions=sub, radius=1.0)
        errs.append(np.abs(mean_curvature(m.vertices, m.faces) - 1.0).max())
    assert errs[0] > errs[1] > errs[2]


def test_cylinder_half_inverse_radius_including_rims():
    r = 0.2
    V, F = open_cylinder(r=r)
    H = mean_curvature(V, F)
    assert_close(H, 1.0 / (2 * r), rtol=1e-9)
    assert_close(curvature_weights(V, F), 1.0, rtol=1e-9)


def test_weights_mean_one_and_favour_curved_regions():
    # a plane with a bump: weights have area-weighted mean 1, larger on the bump
    n = 30
    s = np.linspace(-1, 1, n)
    X, Z = np.meshgrid(s, s)
    Y = 0.2 * np.exp(-((X**2 + Z**2) / 0.05))
    V = np.stack([X.ravel(), Y.ravel(), Z.ravel()], 1)
    F = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            F += [[a, a + n, a + 1], [a + 1, a + n, a + n + 1]]
    F = np.array(F)
    w = curvature_weights(V, F)
    A = mixed_areas(V, F)
    assert_close((A * w).sum() / A.sum(), 1.0, rtol=1e-12)
    centre = np.argmin(np.abs(V[:, 0]) + np.abs(V[:, 2]))
    corner = 0
    assert w[centre] > 2 * w[corner]
    assert w.min() >= 0.5 - 1e-12


def test_mixed_areas_sum_to_area():
    m = trimesh.creation.icosphere(subdivisions=2, radius=0.5)
    assert_close(mixed_areas(m.vertices, m.faces).sum(), m.area, rtol=1e-12)


def test_torch_in_torch_out():
    m = trimesh.creation.icosphere(subdivisions=1)
    w = curvature_weights(torch.tensor(m.vertices), torch.tensor(m.faces))
    assert isinstance(w, torch.Tensor) and w.dtype == torch.float64 and w.shape == (len(m.vertices),)
