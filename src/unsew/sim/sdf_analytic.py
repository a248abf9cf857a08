"""Analytic signed distance functions with the body SDF's ``query`` protocol (tests, verification).

``query(x (N,3) [m] torch float64) -> (d (N,) [m], n (N,3) unit)``, negative inside,
differentiable in x (n = grad d away from the medial set)."""

from __future__ import annotations

import torch

__all__ = ["SphereSDF", "PlaneSDF", "CapsuleSDF"]


def _t(a, like):
    return torch.as_tensor(a, dtype=like.dtype, device=like.device)


def _unit(v):
    nrm = v.norm(dim=-1, keepdim=True)
    return v / nrm.clamp_min(1e-12), nrm[..., 0]


class SphereSDF:
    """Sphere of centre (3,) [m] and radius [m]."""

    def __init__(self, center=(0.0, 0.0, 0.0), radius: float = 0.1):
        self.center = tuple(float(c) for c in center)
        self.radius = float(radius)

    def query(self, x: torch.Tensor):
        n, r = _unit(x - _t(self.center, x))
        return r - self.radius, n


class PlaneSDF:
    """Half-space below the plane through ``point`` with unit ``normal`` pointing outside."""

    def __init__(self, point=(0.0, 0.0, 0.0), normal=(0.0, 1.0, 0.0)):
        self.point = tuple(float(c) for c in point)
        nv = torch.tensor(normal, dtype=torch.float64)
        self.normal = tuple((nv / nv.norm()).tolist())

    def query(self, x: torch.Tensor):
        nrm = _t(self.normal, x)
        d = (x - _t(self.point, x)) @ nrm
        return d, nrm.expand_as(x)


class CapsuleSDF:
    """Capsule around segment a-b (3,) [m] with radius [m] (a limb)."""

    def __init__(self, a, b, radius: float):
        self.a = tuple(float(c) for c in a)
        self.b = tuple(float(c) for c in b)
        self.radius = float(radius)

    def query(self, x: torch.Tensor):
        a, b = _t(self.a, x), _t(self.b, x)
        ab = b - a
        t = ((x - a) @ ab / (ab @ ab)).clamp(0.0, 1.0)
        n, r = _unit(x - (a + t[:, None] * ab))
        return r - self.radius, n
