"""One implicit Euler step (paper eq. 1), batched, differentiable.

Paper eq. 1, (M - dt^2 J) dv = dt (f + dt J v), with J = -K (K the stiffness, the sum of
PSD-projected element Hessians), is the same as solving for the new velocity

    (M + dt D + dt^2 K) v' = M v + dt f(x, v),       x' = x + dt v',

where D is the lagged friction damping (friction is applied implicitly, see
energies/contact.py). Pinned vertices keep their velocity (rows/cols replaced by identity).
After the step, vertices inside the body are projected out (paper eq. 4) and lose the
normal component of their velocity that points into the body (an inelastic impact; the paper
does not say what it does with velocities).

The linear system is one Newton step on the incremental potential of the step (in the new
velocity w, x fixed at the start of the step):

    Phi(w) = 1/2 (w - v)^T M (w - v) + dt/2 w^T D w + E(x + dt w),

from w = 0: Phi's Hessian there is the system matrix (positive definite: masses plus PSD
blocks) and its gradient is -(M v + dt f), so the solution v' is a descent direction. Far from
the linearization (cloth crushed into a fold, then popping open: the Green-strain membrane
stiffens as the fourth power of stretch) the full step can overshoot and tear edges to many times
their length. The step is therefore backtracked (``StepParams.line_search``): v' is scaled by the
largest alpha in 1, 1/2, 1/4, ... (``max_halvings``) with

    Phi(alpha v') <= Phi(0) + alpha |Phi'(0) . v'|,   Phi'(0) . v' = -(M v + dt f) . v'

(free dofs; pinned ones keep their velocity), the last tried alpha if none qualifies: a step may
raise Phi by at most what its linear model promised to lower it; a larger rise means the
linearization is far off, an explosion starting. A sound drape's steps pass at alpha = 1 and are
unchanged (why not Armijo's strict decrease: docs/decisions/017-step-line-search.md); the adjoint
treats alpha as a constant.

All of it is torch: a loss on the result back-propagates to the rest shape (through areas, B,
masses, bending coefficients), to Gamma, and to the state, with the linear solve's adjoint
reusing the forward factorization (solve.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import torch

from unsew.errors import PatternError, SimulationError
from unsew.sim.assembly import (
    assemble_membrane,
    assemble_outer,
    outer_adjoint_map,
    scatter_blocks,
    scatter_vertex,
)
from unsew.sim.energies.bending import bending_rest, energy_bending
from unsew.sim.energies.contact import energy_contact, friction_damping, project_out
from unsew.sim.energies.gravity import energy_gravity
from unsew.sim.energies.membrane import energy_membrane, membrane_rest
from unsew.sim.energies.anchor import energy_anchor
from unsew.sim.energies.spring import energy_spring
from unsew.sim.model import SimModel
from unsew.sim.solve import SparsePattern, resolve_backend, sparse_solve
from unsew.sim.state import SimState
from unsew.sim.step_solve import step_solve

__all__ = ["StepParams", "RestData", "rest_data", "step", "force", "forces", "total_energy"]


@dataclass(frozen=True)
class StepParams:
    """Settings of a step (SI units).

    Attributes:
        dt: time step [s].
        gravity: gravitational acceleration along -Y [m/s^2].
        friction: Coulomb coefficient with the body [-].
        contact_stiffness: kc of the repulsion [N/m^4].
        contact_threshold: distance below which repulsion acts [m].
        thickness: collision thickness delta of eq. 4 [m].
        spring_stiffness: zero-length seam springs [N/m] (sewing phase).
        max_speed: a vertex faster than this means divergence [m/s].
        friction_eps: slip speed below which friction is viscous [m/s].
        backend: linear solver, "auto", "cholmod", "cholespy" or "scipy" (solve.py).
        fused: assemble, factorize and solve in one Function with a structured adjoint
            (step_solve.py); False: separate assembly Functions + ``sparse_solve``. Either way
            the assembly runs on the state's device and the factorization on the CPU.
        line_search: backtrack a step that raises the step's incremental potential by more
            than its linear model promised to lower it (module docstring); False: always the full
            linearized step.
        max_halvings: most halvings of the step the line search tries [-].
        anchor: vertices held at a height (:mod:`unsew.sim.energies.anchor`): (idx (A,) int64,
            heights (A,) [m], stiffness [N/m]) in the model's vertex numbering, or None.
        edge_contact: the body also repels each mesh edge's midpoint (an edge whose ends lie
            on the body either side of a fold, across a limb, is pushed out with them).
    """

    dt: float = 0.05
    gravity: float = 9.81
    friction: float = 0.3
    contact_stiffness: float = 1e7
    contact_threshold: float = 5e-3
    thickness: float = 1e-3
    spring_stiffness: float = 100.0
    max_speed: float = 50.0
    friction_eps: float = 1e-2
    backend: str = "auto"
    fused: bool = True
    line_search: bool = True
    max_halvings: int = 8
    anchor: tuple | None = None
    edge_contact: bool = False


@dataclass
class RestData:
    """Rest-shape quantities (differentiable in uv and density).

    area (F,) [m^2]; B (F, 3, 2) [1/m]; coef (H,) bending coefficients; mass (N,) [kg];
    vert_area (N,) [m^2]."""

    area: torch.Tensor
    B: torch.Tensor
    coef: torch.Tensor
    mass: torch.Tensor
    vert_area: torch.Tensor

    def detached(self) -> RestData:
        """The same quantities without their autograd graph."""
        return RestData(
            self.area.detach(),
            self.B.detach(),
            self.coef.detach(),
            self.mass.detach(),
            self.vert_area.detach(),
        )


def rest_data(model: SimModel, uv: torch.Tensor, density) -> RestData:
    """Rest quantities from the pattern uv (Nu, 2) [m] and density [kg/m^2].

    Raises PatternError on a degenerate or clockwise (inverted) rest triangle."""
    area, B, signed = membrane_rest(uv, model.faces_uv)
    with torch.no_grad():
        u = uv[model.faces_uv]
        e2 = torch.stack([(u[:, 1] - u[:, 0]), (u[:, 2] - u[:, 1]), (u[:, 0] - u[:, 2])], 1).pow(2).sum(-1)
        quality = 2.0 * signed / e2.max(dim=1).values.clamp_min(1e-300)  # height / longest edge
        bad = quality < 1e-4
        if bool(bad.any()):
            i = int(torch.nonzero(bad)[0])
            kind = "inverted (clockwise)" if float(signed[i]) < 0 else "degenerate"
            raise PatternError(
                f"rest triangle {i} of the pattern mesh is {kind} (height/edge {float(quality[i]):.2e}); "
                f"{int(bad.sum())} such triangles: remesh the pattern or fix the panel outline"
            )
    vert_area = scatter_vertex(model.n, model.faces, (area / 3.0)[:, None, None].expand(-1, 3, 3))[:, 0]
    mass = vert_area * density
    rigid = model.pinned[model.faces].all(1) if bool(model.pinned.any()) else None
    coef = bending_rest(uv, model.faces_uv, model.hinge_faces, model.hinge_uv_edges, area, rigid_faces=rigid)
    return RestData(area=area, B=B, coef=coef, mass=mass, vert_area=vert_area)


def _pattern(model: SimModel) -> SparsePattern:
    p = getattr(model, "_pattern_cache", None)
    if p is None:
        p = SparsePattern(3 * model.n, model.rows, model.cols, device=model.device)
        pin = torch.zeros(p.rows.shape[0], dtype=torch.float64, device=model.device)
        pdofs = torch.nonzero(model.pinned.repeat_interleave(3))[:, 0]
        pin[model.diag_dst[pdofs]] = 1.0
        p.pin_diag = pin
        model._pattern_cache = p
    return p


def _tri_maps(model: SimModel):
    """Cached :func:`~unsew.sim.assembly.outer_adjoint_map` of the triangle blocks (per topology)."""
    maps = getattr(model, "_tri_maps_cache", None)
    if maps is None:
        maps = outer_adjoint_map(model.nnz, model.tri_src, model.tri_dst, model.faces.shape[0], 9)
        model._tri_maps_cache = maps
    return maps


def _hinge_maps(model: SimModel):
    """Cached :func:`~unsew.sim.assembly.outer_adjoint_map` of the hinge blocks (per topology)."""
    maps = getattr(model, "_hinge_maps_cache", None)
    if maps is None:
        w = _ring_weight(model.keep) if model.bending_stencil == "ring" else None
        maps = outer_adjoint_map(model.nnz, model.hinge_src, model.hinge_dst, model.hinges.shape[0], 12, w)
        model._hinge_maps_cache = maps
    return maps


def _ring_corner_weight(like: torch.Tensor) -> torch.Tensor:
    """(4, 4) hinge corner weights of the "ring" stencil: (x2, x2), (x3, x3) doubled, (x2, x3) dropped."""
    w = torch.ones(4, 4, dtype=like.dtype, device=like.device)
    w[2, 2] = w[3, 3] = 2.0
    w[2, 3] = w[3, 2] = 0.0
    return w


def _ring_weight(like: torch.Tensor) -> torch.Tensor:
    """(12, 12) weights turning a hinge's Gauss-Newton block into the "ring" block (model.py)."""
    w = torch.ones(12, 12, dtype=like.dtype, device=like.device)
    w[6:9, 6:9] = 2.0
    w[9:12, 9:12] = 2.0
    return w


def _mesh_edges(model: SimModel):
    """Cached unique edges (E, 2) int64 of the model's triangles (per topology)."""
    e = getattr(model, "_edges_cache", None)
    if e is None:
        f = model.faces
        pairs = torch.cat([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], 0)
        e = torch.unique(torch.sort(pairs, dim=1).values, dim=0)
        model._edges_cache = e
    return e


def _edge_contact(model, rest, x, sdf, params: StepParams, *, hessian: bool):
    """Repulsion of the edges' midpoints (StepParams.edge_contact), each weighted by the mean
    of its ends' rest areas [m^2]: energy [J], gradient (N, 3) [N], lumped vertex blocks
    (N, 3, 3) [N/m] or None, and each vertex's share of the midpoints' normal forces (N,) [N]
    (half of each of its edges', for friction). A midpoint's block h enters each end's diagonal
    as h / 2 (above the exact [[h, h], [h, h]] / 4: PSD, and no entries the system lacks)."""
    e = _mesh_edges(model)
    ends = e.reshape(-1)
    a = 0.5 * (rest.vert_area[e[:, 0]] + rest.vert_area[e[:, 1]])
    d, n = sdf.query(0.5 * (x[e[:, 0]] + x[e[:, 1]]))
    ec, ge, He, fe = energy_contact(
        d, n, a, stiffness=params.contact_stiffness, threshold=params.contact_threshold, hessian=hessian
    )
    g = x.new_zeros(model.n, 3).index_add(0, ends, (0.5 * ge).repeat_interleave(2, dim=0))
    fn = x.new_zeros(model.n).index_add(0, ends, (0.5 * fe).repeat_interleave(2))
    if He is None:
        return ec, g, None, fn
    Hv = x.new_zeros(model.n, 3, 3).index_add(0, ends, (0.5 * He).repeat_interleave(2, dim=0))
    return ec, g, Hv, fn


@dataclass
class _Terms:
    """The energies' terms at one x: f (N, 3) [N] (internal + gravity + contact + springs,
    without friction); energies (membrane, bending, contact, springs and anchors) [J]; the Hessian
    factors Hm (G, H, Pgeo), Hb (g, s), spring blocks Hs or None, contact (and anchor) blocks Hc
    (N, 3, 3) (None without Hessians); the contact normal force fn (N,) and the SDF values d (N,),
    n (N, 3)."""

    f: torch.Tensor
    energies: tuple
    Hm: tuple | None
    Hb: tuple | None
    Hs: torch.Tensor | None
    Hc: torch.Tensor | None
    fn: torch.Tensor
    d: torch.Tensor
    n: torch.Tensor


def _terms(model, rest, x, sdf, gamma, params: StepParams, *, hessian: bool) -> _Terms:
    """Energies, forces and (``hessian``) element Hessian factors at x (N, 3) [m]."""
    g = params.gravity
    d, n = sdf.query(x)
    em, gm, Hm = energy_membrane(x, model.faces, rest.area, rest.B, gamma, hessian=hessian, parts=True)
    eb, gb, Hb = energy_bending(x, model.hinges, rest.coef, gamma, hessian=hessian, parts=True)
    ec, gc, Hc, fn = energy_contact(
        d,
        n,
        rest.vert_area,
        stiffness=params.contact_stiffness,
        threshold=params.contact_threshold,
        hessian=hessian,
    )
    grad = scatter_vertex(model.n, model.faces, gm) + scatter_vertex(model.n, model.hinges, gb) + gc
    if params.edge_contact:
        ee, ge, He, fe = _edge_contact(model, rest, x, sdf, params, hessian=hessian)
        ec, grad, fn = ec + ee, grad + ge, fn + fe
        Hc = Hc + He if He is not None else Hc
    Hs = None
    es = 0.0
    if model.springs.shape[0]:
        es, gs, Hs = energy_spring(x, model.springs, params.spring_stiffness, hessian=hessian)
        grad = grad + scatter_vertex(model.n, model.springs, gs)
    if params.anchor is not None:
        idx, height, ka = params.anchor
        ea, ga, Ha = energy_anchor(x, idx, height, ka, hessian=hessian)
        es = es + ea
        grad = grad.index_add(0, idx, ga)
        if Hc is not None:
            Hc = Hc.index_add(0, idx, Ha)
    f = -grad
    f = torch.cat([f[:, :1], f[:, 1:2] - g * rest.mass[:, None], f[:, 2:]], 1)
    return _Terms(f=f, energies=(em, eb, ec, es), Hm=Hm, Hb=Hb, Hs=Hs, Hc=Hc, fn=fn, d=d, n=n)


def force(model, rest, x, sdf, gamma, params: StepParams) -> torch.Tensor:
    """Forces f (N, 3) [N] at x (N, 3) [m] (internal + gravity + contact + springs, without
    friction), with their autograd graph and without any stiffness blocks."""
    return _terms(model, rest, x, sdf, gamma, params, hessian=False).f


def forces(model, rest, state: SimState, sdf, gamma, params: StepParams, *, parts=False, energy=False):
    """Forces and system blocks at (x, v) = (state.x, state.v).

    Returns f (N, 3) [N] (internal + gravity + contact + springs, without friction),
    K values (nnz,) [N/m] (PSD stiffness, lower triangle), vertex blocks (N, 3, 3) [N/m] of
    contact stiffness, friction damping D (N, 3, 3) [kg/s], and the SDF values (d, n).
    With ``parts=True`` K is replaced by (membrane factors (G, H, Pgeo, area), bending factors
    (g, s), spring values (nnz,) or None) for :func:`~unsew.sim.step_solve.step_solve`.
    With ``energy=True`` a sixth item follows: the total potential energy [J] (as
    :func:`total_energy`; a float). :func:`force` gives f alone."""
    x, v = state.x, state.v
    t = _terms(model, rest, x, sdf, gamma, params, hessian=True)
    extra = ()
    if energy:
        em, eb, ec, es = t.energies
        with torch.no_grad():
            extra = (float(em + eb + ec + es + energy_gravity(x, rest.mass, params.gravity)[0]),)
    nnz = model.nnz
    D = friction_damping(v, t.n, t.fn, params.friction, eps_v=params.friction_eps)
    if parts:
        Ks = scatter_blocks(nnz, model.spring_src, model.spring_dst, t.Hs) if t.Hs is not None else None
        return (t.f, ((*t.Hm, rest.area), t.Hb, Ks), t.Hc, D, (t.d, t.n), *extra)
    # element blocks go straight into the system values; the hand-written backward of the
    # assembly (assembly.py) never materialises the (E, m, m) blocks' autograd graph
    K = assemble_membrane(nnz, model.tri_src, model.tri_dst, *t.Hm, rest.area, maps=_tri_maps(model))
    # "ring": doubled (x2, x2), (x3, x3) blocks; (x2, x3) not in the pattern (model.py)
    w = _ring_weight(x) if model.bending_stencil == "ring" else None
    K = K + assemble_outer(
        nnz, model.hinge_src, model.hinge_dst, t.Hb[0], t.Hb[1], w, maps=_hinge_maps(model)
    )
    if t.Hs is not None:
        K = K + scatter_blocks(nnz, model.spring_src, model.spring_dst, t.Hs)
    return (t.f, K, t.Hc, D, (t.d, t.n), *extra)


def total_energy(model, rest, x, sdf, gamma, params: StepParams):
    """Total potential energy [J] (membrane + bending + contact + gravity + springs) at x (N, 3) [m]."""
    g = params.gravity
    d, n = sdf.query(x)
    e = energy_membrane(x, model.faces, rest.area, rest.B, gamma, hessian=False)[0]
    e = e + energy_bending(x, model.hinges, rest.coef, gamma, hessian=False)[0]
    e = (
        e
        + energy_contact(
            d,
            n,
            rest.vert_area,
            stiffness=params.contact_stiffness,
            threshold=params.contact_threshold,
            hessian=False,
        )[0]
    )
    if params.edge_contact:
        e = e + _edge_contact(model, rest, x, sdf, params, hessian=False)[0]
    e = e + energy_gravity(x, rest.mass, g)[0]
    if model.springs.shape[0]:
        e = e + energy_spring(x, model.springs, params.spring_stiffness, hessian=False)[0]
    if params.anchor is not None:
        e = e + energy_anchor(x, *params.anchor, hessian=False)[0]
    return e


def _backtrack(model, rest, state: SimState, w, sdf, gamma, params: StepParams, lin) -> float:
    """The step length alpha in (0, 1] of the new velocity w (N, 3) [m/s] (module docstring):
    the first of 1, 1/2, 1/4, ... whose incremental potential Phi rises by at most
    alpha |Phi'(0) . w|, or the last one tried. lin = (rhs, D, E0): rhs (N, 3) = M v + dt f
    [kg m/s]; D (N, 3, 3) friction damping [kg/s]; E0 the potential energy at x [J]
    (:func:`total_energy`)."""
    rhs, D, E0 = lin
    dt = params.dt
    x = state.x
    with torch.no_grad():
        free = (~model.pinned)[:, None].to(x)
        w, v = w.detach(), state.v.detach()
        m = rest.mass.detach()[:, None]
        slope = -float((rhs.detach() * w * free).sum())  # Phi'(0) . w < 0 (A positive definite)
        if not slope < 0.0:
            return 1.0
        phi0 = 0.5 * float((m * v * v * free).sum()) + E0
        wDw = float((w * torch.einsum("nij,nj->ni", D.detach(), w) * free).sum())
        rest_d, x_d, gamma_d = rest.detached(), x.detach(), gamma.detach()
        alpha = 1.0
        for _ in range(params.max_halvings + 1):
            wa = torch.where(free > 0, alpha * w, w)
            dw = (wa - v) * free
            E = float(total_energy(model, rest_d, x_d + dt * wa, sdf, gamma_d, params))
            phi = 0.5 * float((m * dw * dw).sum()) + 0.5 * dt * alpha * alpha * wDw + E
            if phi <= phi0 - alpha * slope:  # a rise of at most |Phi'(0) . alpha w| (module docstring)
                return alpha
            alpha *= 0.5
        return 2.0 * alpha


def _solve(model: SimModel, K, vblk, rhs, params: StepParams) -> torch.Tensor:
    """The new velocity v' (N, 3) [m/s] from the system's parts: K as :func:`forces` returns it
    (its parts when ``params.fused``), vertex blocks vblk (N, 3, 3) [kg], rhs (N, 3) [kg m/s]."""
    dt = params.dt
    N = model.n
    pat = _pattern(model)
    if params.fused:  # assembly + factorization + structured adjoint in one Function (step_solve.py)
        mem, bend, Ks = K
        w4 = _ring_corner_weight(rhs) if model.bending_stencil == "ring" else None
        extra = (dt * dt) * Ks if Ks is not None else None
        return step_solve(
            model,
            pat,
            blocks=(mem, bend, vblk, extra),
            rhs=rhs.reshape(-1),
            dt=dt,
            w4=w4,
            backend=resolve_backend(params.backend),
        ).reshape(N, 3)
    A = (dt * dt) * K + scatter_blocks(model.nnz, model.vert_src, model.vert_dst, vblk)
    A = A * model.keep.to(A) + pat.pin_diag.to(A)
    return sparse_solve(A, rhs.reshape(-1), pat, backend=params.backend).reshape(N, 3)


def _check_speed(v_new: torch.Tensor, params: StepParams, index: int) -> None:
    """Raise SimulationError when a speed of v_new (N, 3) [m/s] is not finite or over params.max_speed."""
    with torch.no_grad():
        speed = v_new.norm(dim=1)
        bad = ~torch.isfinite(speed) | (speed > params.max_speed)
        if bool(bad.any()):
            s = torch.where(torch.isfinite(speed), speed, torch.full_like(speed, float("inf")))
            i = int(torch.argmax(s))
            raise SimulationError(
                f"simulation diverged at step {index}: vertex {i} speed {float(speed[i]):.3g} m/s "
                f"(limit {params.max_speed:g}); lower dt, check the material stiffness and the initial state"
            )


def step(
    model: SimModel,
    rest: RestData,
    state: SimState,
    sdf,
    gamma,
    params: StepParams,
    *,
    index: int = 0,
) -> SimState:
    """Advance one implicit Euler step of length params.dt.

    Args:
        model: static model. rest: :func:`rest_data` output. state: x, v (N, 3) [m], [m/s].
        sdf: object with ``query(x) -> (d (N,), n (N, 3))``. gamma: (5,) Gamma.
        params: :class:`StepParams` (the sewing phase ramps gravity in by ``dataclasses.replace``).
        index: step number (for error messages).

    Returns:
        the new :class:`SimState`.

    Raises:
        SimulationError: NaN or a vertex faster than params.max_speed.
    """
    dt = params.dt
    x, v = state.x, state.v
    f, K, Hc, D, _, E0 = forces(model, rest, state, sdf, gamma, params, parts=params.fused, energy=True)
    eye = torch.eye(3, dtype=x.dtype, device=x.device)
    vblk = rest.mass[:, None, None] * eye + dt * D + (dt * dt) * Hc  # (N, 3, 3)
    rhs = rest.mass[:, None] * v + dt * f  # (N, 3) [kg m/s]
    pinned = model.pinned[:, None].to(x.device)
    rhs = torch.where(pinned, v, rhs)
    v_new = _solve(model, K, vblk, rhs, params)
    if params.line_search:
        alpha = _backtrack(model, rest, state, v_new, sdf, gamma, params, (rhs, D, E0))
        if alpha < 1.0:
            v_new = torch.where(pinned, v_new, alpha * v_new)
    _check_speed(v_new, params, index)
    x_new = x + dt * v_new
    d, n = sdf.query(x_new)
    x_new = project_out(x_new, d, n, thickness=params.thickness)
    # projected vertices lose their velocity into the body (inelastic)
    vn = (v_new * n).sum(-1, keepdim=True)
    v_new = torch.where((d < 0)[:, None] & (vn < 0), v_new - vn * n, v_new)
    return SimState(x_new, v_new)
