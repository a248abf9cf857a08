"""Differentiable drape (paper 3.4.1) and the non-differentiated sewing phase.

``drape`` runs ``steps`` implicit Euler steps (integrator.step) from a state, differentiable
w.r.t. the rest shape uv, Gamma, density and the initial state. ``sew`` closes the seams of
placed, unsewn panels with zero-length springs, gravity ramped in and optional held vertices
(shared/STACK.md "Dressing a body"), without gradients; ``merge_sewn`` maps its result onto the
sewn topology (the mean of the unsewn copies of each sewn vertex).
"""

from __future__ import annotations

import numpy as np
import torch

from unsew.errors import InputError
from unsew.sim.integrator import StepParams, rest_data, step
from unsew.sim.material import check_gamma
from unsew.sim.model import SimModel
from unsew.sim.state import SimState
from unsew.tolerances import COLLISION_THICKNESS

__all__ = ["drape", "sew", "merge_sewn", "check_drape_inputs"]


def check_drape_inputs(model: SimModel, state: SimState, sdf, uv, gamma) -> None:
    """Boundary checks before any simulation; raise InputError with what to fix."""
    if sdf is None or not callable(getattr(sdf, "query", None)):
        raise InputError("no body SDF given: pass an object with query(x) -> (d, n), e.g. unsew.body.sdf.BodySDF")
    if not torch.is_tensor(uv) or uv.dim() != 2 or uv.shape != (model.n_rest, 2):
        raise InputError(f"uv must be a torch tensor of shape ({model.n_rest}, 2) [m], got {getattr(uv, 'shape', type(uv))}")
    if not torch.is_tensor(gamma) or gamma.shape != (5,):
        raise InputError("gamma must be a torch tensor (5,) = (H00, H01, H11, H22, k); see Material.gamma()")
    check_gamma(gamma.detach().cpu())
    for name, t in (("x", state.x), ("v", state.v)):
        if t.shape != (model.n, 3):
            raise InputError(f"state.{name} must have shape ({model.n}, 3), got {tuple(t.shape)}")
        if t.dtype != torch.float64:
            raise InputError(f"state.{name} must be float64 (solves and adjoints need it), got {t.dtype}")
        if not bool(torch.isfinite(t).all()):
            raise InputError(f"state.{name} holds NaN or inf")


def drape(
    model: SimModel,
    state: SimState,
    sdf,
    *,
    uv: torch.Tensor,
    gamma: torch.Tensor,
    density,
    steps: int = 20,
    dt: float = 0.05,
    gravity: float = 9.81,
    friction: float = 0.3,
    contact_stiffness: float = 1e7,
    contact_threshold: float = 5e-3,
    thickness: float = COLLISION_THICKNESS,
    max_speed: float = 50.0,
    backend: str = "auto",
    checkpoint: bool = False,
    callback=None,
    fused: bool = True,
    friction_eps: float = StepParams.friction_eps,
) -> SimState:
    """Drape the cloth for ``steps`` implicit Euler steps.

    Args:
        model: :class:`SimModel` of the sewn mesh (faces into N sim vertices, faces_uv into Nu).
        state: initial :class:`SimState`, x and v (N, 3) float64 [m], [m/s].
        sdf: body, ``query(x (N,3)) -> (d (N,) [m], n (N,3))``, differentiable.
        uv: rest positions (Nu, 2) float64 [m] (may require grad).
        gamma: (5,) float64 (H00, H01, H11, H22 [N/m], k [N*m]) (may require grad).
        density: areal density [kg/m^2] (float or 0-d tensor).
        steps: number of steps. dt: step [s]. gravity: [m/s^2] along -Y.
        friction, contact_stiffness [N/m^4], contact_threshold [m], thickness [m], max_speed [m/s],
        backend, friction_eps [m/s]: see :class:`~unsew.sim.integrator.StepParams`.
        checkpoint: recompute each step in the backward pass instead of storing it (less
            memory, about one more forward in time).
        callback: called as ``callback(k, state)`` after each step k (e.g. a progress bar).
        fused: one Function per step for assembly + solve with a structured adjoint (default,
            faster backward; step_solve.py), or separate assembly Functions and ``sparse_solve``.

    Returns:
        the final :class:`SimState` (differentiable w.r.t. uv, gamma, density and state).

    Raises:
        InputError: missing SDF, bad shapes, bad material. PatternError: degenerate rest
        triangles. SimulationError: divergence (names the step and the worst vertex).
    """
    check_drape_inputs(model, state, sdf, uv, gamma)
    if steps < 0:
        raise InputError(f"steps must be >= 0, got {steps}")
    params = StepParams(
        dt=dt,
        gravity=gravity,
        friction=friction,
        friction_eps=friction_eps,
        contact_stiffness=contact_stiffness,
        contact_threshold=contact_threshold,
        thickness=thickness,
        max_speed=max_speed,
        backend=backend,
        fused=fused,
    )
    rest = rest_data(model, uv, density)
    for k in range(steps):
        if checkpoint and torch.is_grad_enabled():
            from torch.utils.checkpoint import checkpoint as _ckpt

            def _f(x, v, gamma_, *rest_t, _k=k):
                from unsew.sim.integrator import RestData

                s = step(model, RestData(*rest_t), SimState(x, v), sdf, gamma_, params, index=_k)
                return s.x, s.v

            xv = _ckpt(_f, state.x, state.v, gamma, rest.area, rest.B, rest.coef, rest.mass, rest.vert_area, use_reentrant=False)
            state = SimState(*xv)
        else:
            state = step(model, rest, state, sdf, gamma, params, index=k)
        if callback is not None:
            callback(k, state)
    return state


def merge_sewn(x_unsewn, x_of_u, n_x: int) -> torch.Tensor:
    """Positions of the sewn vertices as the mean of their unsewn copies.

    Args:
        x_unsewn: (Nu, 3) [m] positions on the unsewn topology (torch or numpy).
        x_of_u: (Nu,) int sewn vertex of each unsewn vertex.
        n_x: number of sewn vertices.

    Returns:
        (n_x, 3) float64 torch [m].
    """
    xu = torch.as_tensor(np.asarray(x_unsewn) if not torch.is_tensor(x_unsewn) else x_unsewn, dtype=torch.float64)
    idx = torch.as_tensor(np.asarray(x_of_u), dtype=torch.int64)
    s = xu.new_zeros(n_x, 3).index_add(0, idx, xu)
    c = xu.new_zeros(n_x).index_add(0, idx, torch.ones_like(idx, dtype=xu.dtype))
    if bool((c == 0).any()):
        raise InputError(f"sewn vertex {int(torch.nonzero(c == 0)[0])} has no unsewn copy; x_of_u does not cover 0..n_x-1")
    return s / c[:, None]


def sew(
    model_unsewn: SimModel,
    x_unsewn,
    sdf,
    *,
    uv: torch.Tensor,
    gamma: torch.Tensor,
    density,
    steps: int = 60,
    dt: float = 0.02,
    hold=None,
    hold_steps: int = 20,
    ramp_steps: int = 30,
    gravity: float = 9.81,
    spring_stiffness: float = 100.0,
    friction: float = 0.3,
    contact_stiffness: float = 1e7,
    contact_threshold: float = 5e-3,
    thickness: float = COLLISION_THICKNESS,
    max_speed: float = 50.0,
    backend: str = "auto",
    callback=None,
) -> torch.Tensor:
    """Sewing phase (no gradients): close the seams of placed panels on the body.

    Args:
        model_unsewn: :class:`SimModel` built on the unsewn topology: ``SimModel.build(faces_uv,
            faces_uv, springs=seam_pairs)`` (sim vertices = rest vertices, Nu of them).
        x_unsewn: (Nu, 3) [m] placed panels (e.g. ``place_garment``), torch or numpy.
        sdf: body SDF. uv: (Nu, 2) [m]. gamma: (5,). density: [kg/m^2].
        steps: number of steps. dt: [s] (smaller than the drape's: seams move fast).
        hold: (Nu,) bool or (P,) int vertices held still for the first ``hold_steps`` steps
            (e.g. a waistline). ramp_steps: gravity rises linearly from 0 over these steps.
        spring_stiffness: zero-length seam springs [N/m].
        other arguments: as :func:`drape`.

    Returns:
        (Nu, 3) float64 torch [m] positions on the unsewn topology (see :func:`merge_sewn`).
    """
    x0 = torch.as_tensor(np.asarray(x_unsewn) if not torch.is_tensor(x_unsewn) else x_unsewn, dtype=torch.float64)
    state = SimState.at_rest(x0.detach().clone())
    with torch.no_grad():
        uv = uv.detach()
        gamma = gamma.detach()
        check_drape_inputs(model_unsewn, state, sdf, uv, gamma)
        params = StepParams(
            dt=dt,
            gravity=gravity,
            friction=friction,
            contact_stiffness=contact_stiffness,
            contact_threshold=contact_threshold,
            thickness=thickness,
            spring_stiffness=spring_stiffness,
            max_speed=max_speed,
            backend=backend,
        )
        held = None
        if hold is not None and hold_steps > 0:
            held = SimModel.build(
                model_unsewn.faces,
                model_unsewn.faces_uv,
                springs=model_unsewn.springs,
                pinned=hold,
                n=model_unsewn.n,
                n_rest=model_unsewn.n_rest,
                bending_stencil=model_unsewn.bending_stencil,
            )
        rest = rest_data(model_unsewn, uv, density)
        for k in range(steps):
            g = gravity * min(1.0, (k + 1) / max(ramp_steps, 1))
            m = held if (held is not None and k < hold_steps) else model_unsewn
            state = step(m, rest, state, sdf, gamma, params, index=k, gravity=g)
            if callback is not None:
                callback(k, state)
    return state.x
