"""Seams sewn around the body, not through it.

A zero-length seam spring pulls its two copies straight at each other. When the straight line
between them passes through the body (a shoulder seam's front and back ends on either side of the
shoulder, a godet laid out beside the skirt beyond a leg), the first sewing steps drag the cloth
through the body. A guided seam pair is instead pulled, both copies, to a waypoint: a point a
little outside the body's surface next to the deepest point of that line. Each step the waypoint
is found again from the copies' current positions, and once the line between them no longer
passes through the body the waypoint is their midpoint (each copy is pulled to it as hard as the
seam spring would pull it to the other copy).

The waypoints are extra sim vertices held still in the step (pinned, massless, in no triangle),
each joined to its pair's two copies by zero-length springs: the integrator is unchanged.
"""

from __future__ import annotations

import numpy as np
import torch

from unsew.sim.model import SimModel

__all__ = ["GUIDE_DEPTH", "GUIDE_CLEARANCE", "through_pairs", "waypoints", "GuidedSeams"]

#: A seam pair is guided while a point of the line between its copies is this far inside [m].
GUIDE_DEPTH = 0.01
#: A waypoint lies this far outside the body's surface [m].
GUIDE_CLEARANCE = 0.01
#: Points sampled along the line between a pair's copies, ends excluded [-].
_SAMPLES = 9
#: Steps out along the SDF's normal from the deepest point to the waypoint [-].
_PUSHES = 4


def _deepest(x, pairs, sdf) -> tuple[torch.Tensor, torch.Tensor]:
    """The deepest sample of the line between each pair's copies: (points (S, 3) [m], signed
    distances (S,) [m]); x (N, 3) [m] torch, pairs (S, 2) int64 torch."""
    ts = torch.linspace(0.0, 1.0, _SAMPLES + 2, dtype=x.dtype, device=x.device)[1:-1]  # (T,)
    a, b = x[pairs[:, 0]], x[pairs[:, 1]]
    pts = a[:, None] * (1 - ts[None, :, None]) + b[:, None] * ts[None, :, None]  # (S, T, 3)
    d = sdf.query(pts.reshape(-1, 3))[0].reshape(len(pairs), -1)  # (S, T)
    k = d.argmin(dim=1)
    i = torch.arange(len(pairs), device=x.device)
    return pts[i, k], d[i, k]


def through_pairs(x, pairs, sdf, *, depth: float = GUIDE_DEPTH) -> torch.Tensor:
    """Which seam pairs' straight lines pass more than ``depth`` [m] inside the body.

    x: (N, 3) float64 torch [m]; pairs: (S, 2) int64 torch; sdf: ``query(x) -> (d, n)``.
    Returns (S,) bool torch."""
    if len(pairs) == 0:
        return torch.zeros(0, dtype=torch.bool, device=x.device)
    with torch.no_grad():
        return _deepest(x, pairs, sdf)[1] < -depth


def waypoints(x, pairs, sdf, *, depth: float = GUIDE_DEPTH, clearance: float = GUIDE_CLEARANCE):
    """Where each pair's copies are pulled: outside the body next to the deepest point of the
    line between them while it passes more than ``depth`` [m] inside, else their midpoint.

    x: (N, 3) float64 torch [m]; pairs: (S, 2) int64 torch. Returns (S, 3) float64 torch [m]."""
    with torch.no_grad():
        p, d = _deepest(x, pairs, sdf)
        mid = 0.5 * (x[pairs[:, 0]] + x[pairs[:, 1]])
        for _ in range(_PUSHES):
            dd, n = sdf.query(p)
            p = p + n * (clearance - dd).clamp_min(0.0)[:, None]
        return torch.where((d < -depth)[:, None], p, mid)


class GuidedSeams:
    """The sewing model with the seam pairs through the body at the start guided (module
    docstring), and the waypoints' positions per step.

    model: SimModel on the unsewn topology with springs = seam pairs (``SimModel.build(faces_uv,
    faces_uv, springs=seam_pairs)``); x0: (Nu, 3) float64 torch [m] placed panels; sdf: the body's
    SDF; hold: optional (Nu,) bool or (P,) int vertices to pin as well; guided: optional (S,) bool
    torch, :func:`through_pairs` of x0 when already known. ``pairs`` (G, 2) are the guided pairs
    (their line through the body at the start); ``model`` / ``held`` have Nu + G vertices (the
    last G the waypoints).
    """

    def __init__(self, model: SimModel, x0: torch.Tensor, sdf, *, hold=None, guided=None):
        self.n = model.n
        self.sdf = sdf
        springs = model.springs
        guided = through_pairs(x0, springs, sdf) if guided is None else guided
        self.pairs = springs[guided]  # (G, 2)
        g = len(self.pairs)
        ghost = torch.arange(self.n, self.n + g, dtype=torch.int64, device=springs.device)
        # each copy linked twice: at the midpoint a copy is pulled as hard as by the seam spring
        link = torch.cat([torch.stack([self.pairs[:, k], ghost], 1) for k in (0, 1)])
        links = torch.cat([link, link])
        self.springs = torch.cat([springs[~guided], links]).cpu().numpy()
        self.model = self._build(model, None)
        self.held = self._build(model, hold) if hold is not None else None

    def _build(self, model: SimModel, hold) -> SimModel:
        n_all = self.n + len(self.pairs)
        pin = np.zeros(n_all, dtype=bool)
        pin[self.n :] = True
        if hold is not None:
            h = np.asarray(hold.cpu() if torch.is_tensor(hold) else hold)
            pin[: self.n][h if h.dtype != bool else np.flatnonzero(h)] = True
        return SimModel.build(
            model.faces.cpu(),
            model.faces_uv.cpu(),
            springs=self.springs,
            pinned=pin,
            n=n_all,
            n_rest=model.n_rest,
            bending_stencil=model.bending_stencil,
        ).to(model.device)

    def extend(self, x: torch.Tensor) -> torch.Tensor:
        """x (Nu, 3) [m] with the waypoints of its guided pairs appended: (Nu + G, 3)."""
        if not len(self.pairs):
            return x
        return torch.cat([x, waypoints(x, self.pairs.to(x.device), self.sdf)])
