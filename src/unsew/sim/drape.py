"""Differentiable drape (paper 3.4.1) and the non-differentiated sewing phase.

``drape`` runs ``steps`` implicit Euler steps (integrator.step) from a state, differentiable
w.r.t. the rest shape uv, Gamma, density and the initial state. ``sew`` closes the seams of
placed, unsewn panels with zero-length springs, gravity ramped in and optional held vertices
(shared/STACK.md "Dressing a body"), without gradients; ``merge_sewn`` maps its result onto the
sewn topology (the mean of the unsewn copies of each sewn vertex).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import torch
from torch.utils.checkpoint import checkpoint as torch_checkpoint

from unsew.errors import InputError
from unsew.sim.integrator import RestData, StepParams, rest_data, step
from unsew.sim.material import check_gamma
from unsew.sim.model import SimModel
from unsew.sim.seam_guide import GuidedSeams, through_pairs
from unsew.sim.state import SimState
from unsew.tolerances import COLLISION_THICKNESS

__all__ = ["Cloth", "DrapeSettings", "drape", "sew", "merge_sewn", "check_drape_inputs"]


@dataclass(frozen=True)
class Cloth:
    """The cloth a drape moves: its rest shape and its material, as the simulator takes them.

    Attributes:
        uv: rest positions (Nu, 2) float64 torch [m] (may require grad).
        gamma: (5,) float64 torch (H00, H01, H11, H22 [N/m], k [N*m]) (may require grad);
            ``Material.gamma()``.
        density: areal density [kg/m^2], float or 0-d tensor (may require grad).
        friction: Coulomb coefficient with the body [-].
        anchors: rest vertices held at a height, (uv indices (A,) int64 torch, heights (A,) float64
            torch [m]), or None (:func:`unsew.dress.attached_vertices`; held by springs of
            ANCHOR_STIFFNESS while sewing and draping).
    """

    uv: torch.Tensor
    gamma: torch.Tensor
    density: float | torch.Tensor
    friction: float = 0.3
    anchors: tuple | None = None


#: Vertical spring holding an anchored vertex at its height [N/m]: a 0.2 kg garment hung from
#: 40 such vertices sags 0.2 mm.
ANCHOR_STIFFNESS = 300.0


def _anchor(cloth: Cloth, model: SimModel):
    """StepParams.anchor for ``model`` (sim vertices = rest vertices while sewing, else the sewn
    vertices: each anchored rest vertex's sim vertex, read from the model's two face arrays)."""
    if cloth.anchors is None or not len(cloth.anchors[0]):
        return None
    idx, height = cloth.anchors
    if model.n != model.n_rest or not torch.equal(model.faces, model.faces_uv):
        x_of_u = torch.full((model.n_rest,), -1, dtype=torch.int64, device=model.faces.device)
        x_of_u[model.faces_uv.reshape(-1)] = model.faces.reshape(-1)
        idx = x_of_u[idx.to(x_of_u.device)]
        idx, first = np.unique(idx.cpu().numpy(), return_index=True)
        idx, height = torch.as_tensor(idx), height[torch.as_tensor(first)]
    dev = model.faces.device
    return idx.to(dev), height.to(device=dev, dtype=torch.float64), ANCHOR_STIFFNESS


def check_drape_inputs(model: SimModel, state: SimState, sdf, uv, gamma) -> None:
    """Boundary checks before any simulation; raise InputError with what to fix."""
    if sdf is None or not callable(getattr(sdf, "query", None)):
        raise InputError(
            "no body SDF given: pass an object with query(x) -> (d, n), e.g. unsew.body.sdf.BodySDF"
        )
    if not torch.is_tensor(uv) or uv.dim() != 2 or uv.shape != (model.n_rest, 2):
        raise InputError(
            f"uv must be a torch tensor of shape ({model.n_rest}, 2) [m], got "
            f"{getattr(uv, 'shape', type(uv))}"
        )
    if not torch.is_tensor(gamma) or gamma.shape != (5,):
        raise InputError("gamma must be a torch tensor (5,) = (H00, H01, H11, H22, k); see Material.gamma()")
    check_gamma(gamma.detach().cpu())
    dev = model.device
    for name, t in (("uv", uv), ("gamma", gamma), ("state.x", state.x), ("state.v", state.v)):
        if t.device != dev:
            raise InputError(
                f"{name} is on {t.device}, the SimModel on {dev}: move the model with "
                f"model.to({str(t.device)!r}) (or the tensors to its device)"
            )
    for name, t in (("x", state.x), ("v", state.v)):
        if t.shape != (model.n, 3):
            raise InputError(f"state.{name} must have shape ({model.n}, 3), got {tuple(t.shape)}")
        if t.dtype != torch.float64:
            raise InputError(f"state.{name} must be float64 (solves and adjoints need it), got {t.dtype}")
        if not bool(torch.isfinite(t).all()):
            raise InputError(f"state.{name} holds NaN or inf")


@dataclass(frozen=True)
class DrapeSettings:
    """How a garment is meshed, sewn, settled and draped: one value shared by :func:`drape`,
    :func:`sew`, :func:`unsew.dress.dress`, :func:`unsew.grading.grade.grade` and ``FitConfig.drape``.

    The defaults are the fit's. Material properties (stiffness, density, friction coefficient)
    are not settings: they come with the :class:`~unsew.sim.material.Material`.
    """

    edge_length: float = 0.025  #: target triangle edge length of the panel meshes [m]
    dt: float = 0.05  #: time step of settling and of the differentiable drapes [s]
    steps: int = 15  #: implicit Euler steps of one differentiable drape (the fit's phase two) [-]
    sew_steps: int = 80  #: steps of the sewing phase [-]
    settle_steps: int = 40  #: steps of plain draping after sewing [-]
    sew_dt: float = 0.02  #: time step of the sewing phase [s] (smaller: seams move fast)
    #: zero-length seam springs while sewing [N/m] (100 left seams 2-4 mm open)
    spring_stiffness: float = 1000.0
    hold_steps: int = 20  #: sewing steps a lower garment's waistline is held still [-]
    ramp_steps: int = 30  #: sewing steps over which gravity rises to full [-]
    gravity: float = 9.81  #: gravitational acceleration along -Y [m/s^2]
    friction_eps: float = StepParams.friction_eps  #: slip speed below which friction is viscous [m/s]
    contact_stiffness: float = 1e7  #: body repulsion kc [N/m^4]
    contact_threshold: float = 5e-3  #: distance below which repulsion acts [m]
    thickness: float = COLLISION_THICKNESS  #: collision thickness [m]
    max_speed: float = 50.0  #: a vertex faster than this means divergence [m/s]
    backend: str = "auto"  #: linear solver (see :class:`~unsew.sim.integrator.StepParams`)
    fused: bool = True  #: one Function per step for assembly + solve (step_solve.py)
    line_search: bool = True  #: backtrack a step far off its linearization (integrator.py)
    #: sew seams whose copies start on either side of the body around it (sim/seam_guide.py)
    seam_guide: bool = True
    #: the body repels the mesh edges' midpoints too (StepParams.edge_contact; :func:`unsew.dress.dress`
    #: dresses an unsound drape again so, docs/decisions/042)
    edge_contact: bool = False
    #: :func:`unsew.dress.dress` dresses a drape still unsound after its other fallbacks again with
    #: ``edge_contact`` (off for the fit's grading drapes, which only measure lengths, 042)
    edge_fallback: bool = True
    #: :func:`unsew.dress.dress` judges each drape on its way (which fallback is tried, which drape
    #: is kept) against the pattern's own placement, as ``unsew drape`` judges the one it writes:
    #: a top fallen from where that placement puts it is unsound too (docs/decisions/060), and so
    #: is a sleeve that does not go round the arm that placement puts it on (062)
    judge_placement: bool = False

    def replace(self, **changes) -> "DrapeSettings":
        """A copy with ``changes`` applied."""
        return dataclasses.replace(self, **changes)

    def step_params(self, *, friction: float, sewing: bool = False) -> StepParams:
        """The integrator's :class:`StepParams` for a drape (or, ``sewing=True``, the sewing
        phase: its time step and seam springs) with the material's Coulomb ``friction`` [-]."""
        return StepParams(
            dt=self.sew_dt if sewing else self.dt,
            gravity=self.gravity,
            friction=friction,
            contact_stiffness=self.contact_stiffness,
            contact_threshold=self.contact_threshold,
            thickness=self.thickness,
            spring_stiffness=self.spring_stiffness,
            max_speed=self.max_speed,
            friction_eps=self.friction_eps,
            backend=self.backend,
            fused=self.fused,
            line_search=self.line_search,
            edge_contact=self.edge_contact,
        )


DEFAULT_SETTINGS = DrapeSettings()


def drape(
    model: SimModel,
    state: SimState,
    sdf,
    cloth: Cloth,
    *,
    settings: DrapeSettings = DEFAULT_SETTINGS,
    steps: int | None = None,
    checkpoint: bool = False,
    callback=None,
) -> SimState:
    """Drape the cloth for ``steps`` implicit Euler steps.

    Args:
        model: :class:`SimModel` of the sewn mesh (faces into N sim vertices, faces_uv into Nu).
        state: initial :class:`SimState`, x and v (N, 3) float64 [m], [m/s].
        sdf: body, ``query(x (N,3)) -> (d (N,) [m], n (N,3))``, differentiable.
        cloth: :class:`Cloth`: uv (Nu, 2) float64 [m], gamma (5,) float64 (H00, H01, H11, H22
            [N/m], k [N*m]) and density [kg/m^2] (each may require grad), and the material's
            Coulomb friction with the body [-].
        settings: :class:`DrapeSettings` (dt, gravity, contact, solver); ``settings.steps``
            steps unless ``steps`` is given.
        steps: number of steps (default ``settings.steps``).
        checkpoint: recompute each step in the backward pass instead of storing it (less
            memory, about one more forward in time).
        callback: called as ``callback(k, state)`` after each step k (e.g. a progress bar).

    Returns:
        the final :class:`SimState` (differentiable w.r.t. uv, gamma, density and state).

    Raises:
        InputError: missing SDF, bad shapes, bad material. PatternError: degenerate rest
        triangles. SimulationError: divergence (names the step and the worst vertex).
    """
    uv, gamma = cloth.uv, cloth.gamma
    check_drape_inputs(model, state, sdf, uv, gamma)
    steps = settings.steps if steps is None else steps
    if steps < 0:
        raise InputError(f"steps must be >= 0, got {steps}")
    params = dataclasses.replace(settings.step_params(friction=cloth.friction), anchor=_anchor(cloth, model))
    rest = rest_data(model, uv, cloth.density)
    for k in range(steps):
        if checkpoint and torch.is_grad_enabled():
            state = _checkpointed_step(model, rest, state, sdf, gamma, params, k)
        else:
            state = step(model, rest, state, sdf, gamma, params, index=k)
        if callback is not None:
            callback(k, state)
    return state


def _checkpointed_step(
    model, rest: RestData, state: SimState, sdf, gamma, params: StepParams, k: int
) -> SimState:
    """One step whose intermediate values are recomputed in the backward pass."""

    def _f(x, v, gamma_, *rest_t):
        s = step(model, RestData(*rest_t), SimState(x, v), sdf, gamma_, params, index=k)
        return s.x, s.v

    xv = torch_checkpoint(
        _f,
        state.x,
        state.v,
        gamma,
        rest.area,
        rest.B,
        rest.coef,
        rest.mass,
        rest.vert_area,
        use_reentrant=False,
    )
    return SimState(*xv)


def merge_sewn(x_unsewn, x_of_u, n_x: int) -> torch.Tensor:
    """Positions of the sewn vertices as the mean of their unsewn copies.

    Args:
        x_unsewn: (Nu, 3) [m] positions on the unsewn topology (torch or numpy).
        x_of_u: (Nu,) int sewn vertex of each unsewn vertex.
        n_x: number of sewn vertices.

    Returns:
        (n_x, 3) float64 torch [m].
    """
    xu = torch.as_tensor(
        np.asarray(x_unsewn) if not torch.is_tensor(x_unsewn) else x_unsewn, dtype=torch.float64
    )
    idx = torch.as_tensor(np.asarray(x_of_u), dtype=torch.int64, device=xu.device)
    s = xu.new_zeros(n_x, 3).index_add(0, idx, xu)
    c = xu.new_zeros(n_x).index_add(0, idx, torch.ones_like(idx, dtype=xu.dtype))
    if bool((c == 0).any()):
        raise InputError(
            f"sewn vertex {int(torch.nonzero(c == 0)[0])} has no unsewn copy; x_of_u does not cover 0..n_x-1"
        )
    return s / c[:, None]


def sew(
    model_unsewn: SimModel,
    x_unsewn,
    sdf,
    cloth: Cloth,
    *,
    settings: DrapeSettings = DEFAULT_SETTINGS,
    hold=None,
    callback=None,
) -> torch.Tensor:
    """Sewing phase (no gradients): close the seams of placed panels on the body.

    Args:
        model_unsewn: :class:`SimModel` built on the unsewn topology: ``SimModel.build(faces_uv,
            faces_uv, springs=seam_pairs)`` (sim vertices = rest vertices, Nu of them).
        x_unsewn: (Nu, 3) [m] placed panels (e.g. ``place_garment``), torch or numpy.
        sdf: body SDF. cloth: :class:`Cloth` (uv (Nu, 2) [m], gamma (5,), density [kg/m^2],
            friction [-]); its tensors are used detached.
        settings: :class:`DrapeSettings`: ``sew_steps`` steps of ``sew_dt`` [s] with seam springs
            of ``spring_stiffness`` [N/m]; gravity rises linearly from 0 over ``ramp_steps``;
            with ``seam_guide`` the pairs whose line starts through the body are sewn round it
            (:mod:`unsew.sim.seam_guide`).
        hold: (Nu,) bool or (P,) int vertices held still for the first ``settings.hold_steps``
            steps (e.g. a waistline).
        callback: ``callback(k, state)``.

    Returns:
        (Nu, 3) float64 torch [m] positions on the unsewn topology (see :func:`merge_sewn`).
    """
    x0 = torch.as_tensor(
        np.asarray(x_unsewn) if not torch.is_tensor(x_unsewn) else x_unsewn, dtype=torch.float64
    )
    state = SimState.at_rest(x0.detach().clone())
    with torch.no_grad():
        uv = cloth.uv.detach()
        gamma = cloth.gamma.detach()
        check_drape_inputs(model_unsewn, state, sdf, uv, gamma)
        params = settings.step_params(friction=cloth.friction, sewing=True)
        anchor = _anchor(cloth, model_unsewn)
        guide, model, held = _sewing_models(model_unsewn, state.x, sdf, settings, hold)
        rest = rest_data(model, uv, cloth.density)
        n = model_unsewn.n
        for k in range(settings.sew_steps):
            g = settings.gravity * min(1.0, (k + 1) / max(settings.ramp_steps, 1))
            m = held if (held is not None and k < settings.hold_steps) else model
            if guide is not None:  # the waypoints found again from the copies' positions
                v = torch.cat([state.v[:n], state.v.new_zeros(m.n - n, 3)])
                state = SimState(guide.extend(state.x[:n]), v)
            k_params = dataclasses.replace(params, gravity=g, anchor=_anchor_at(anchor, x0, k, settings))
            state = step(m, rest, state, sdf, gamma, k_params, index=k)
            if callback is not None:
                callback(k, SimState(state.x[:n], state.v[:n]))
    return state.x[:n]


def _anchor_at(anchor, x0, k: int, settings: DrapeSettings):
    """StepParams.anchor at sewing step k: the anchored vertices' heights carried from where the
    placement x0 (Nu, 3) [m] put them to their own over ``settings.ramp_steps``, as gravity rises
    (a placement that starts a waist elsewhere moves it there while the seams close)."""
    if anchor is None:
        return None
    idx, height, ka = anchor
    t = min(1.0, (k + 1) / max(settings.ramp_steps, 1))
    y0 = x0[idx.to(x0.device), 1].to(height.device)
    return idx, y0 + t * (height - y0), ka


def _sewing_models(model_unsewn: SimModel, x0, sdf, settings: DrapeSettings, hold):
    """The sewing phase's models: (GuidedSeams or None, the model, the model with ``hold`` pinned
    too or None) for the placed panels x0 (Nu, 3) [m] (see :func:`sew`)."""
    hold = hold if settings.hold_steps > 0 else None
    guided = through_pairs(x0, model_unsewn.springs, sdf) if settings.seam_guide else None
    if guided is not None and bool(guided.any()):  # no pair across the body: the plain models
        guide = GuidedSeams(model_unsewn, x0, sdf, hold=hold, guided=guided)
        return guide, guide.model, guide.held
    held = None
    if hold is not None:
        held = SimModel.build(
            model_unsewn.faces,
            model_unsewn.faces_uv,
            springs=model_unsewn.springs,
            pinned=hold,
            n=model_unsewn.n,
            n_rest=model_unsewn.n_rest,
            bending_stencil=model_unsewn.bending_stencil,
        ).to(model_unsewn.device)
    return None, model_unsewn, held
