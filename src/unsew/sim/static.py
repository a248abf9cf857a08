"""Quasi-static drape: the equilibrium of the total energy, with gradients by the implicit
function theorem (not in the paper).

Energy (the dynamic drape's, without kinetic terms and friction), at positions x (N, 3) [m]:

    E(x; uv, Gamma, rho) = membrane + bending + contact + gravity (+ seam springs if the model has them),

the contact term being the C2 penalty a_i kc/3 relu(thr - d_i)^3 of energies/contact.py (smooth,
zero outside the band, no projection step). Pinned vertices (``model.pinned``) stay at x0.

Solve: Newton's method on the free dofs with a backtracking (Armijo) line search on E. Each
direction solves (H + mu M) p = -grad E by truncated conjugate gradients on exact Hessian
products, preconditioned by the Cholesky factor of the projected matrix of the dynamic step
(PSD membrane blocks, Gauss-Newton bending, contact n n^T blocks) + mu M; negative curvature met
at once falls back to the projected step (Newton-CG, Nocedal and Wright 2006, Alg. 7.1). With
the projected matrix alone convergence was linear (ratio ~0.9 per iteration on the test
curtain); with the exact products it is superlinear (19 iterations to 1e-8). mu M (M the lumped
masses) is a Levenberg-Marquardt term, mu shrinking 10x after a full step and growing 10x after a
backtracked one: a slack flat sheet has no out-of-plane stiffness. Converged when
max |grad E| over free vertices <= tol * max(m_i g) (forces relative to the heaviest vertex weight).

Gradients (implicit function theorem). At the solution f(x*, theta) = -grad_x E = 0 on the free
dofs, so for a loss L(x*):

    H lambda = dL/dx*   (free dofs),   H = d2E/dx2 = -df/dx,
    dL/dtheta = lambda^T df/dtheta,    theta = uv, Gamma, density,
    dL/dx0 = 0 on free vertices (the equilibrium does not depend on the starting guess);
    on pinned vertices dL/dx0_p = dL/dx*_p + lambda^T df/dx_p.

``adjoint="exact"`` (default) solves with the exact Hessian: products H v = -(df/dx) v by one
reverse pass through the analytic forces (no second derivatives of energies needed), by
conjugate gradients preconditioned with the Cholesky factor of the projected matrix at x*. It is
the true derivative of x*. ``adjoint="projected"`` uses that factor alone (one solve, cheaper,
approximate: the projection drops compressive stress, the bending curvature term and the SDF's
curvature). tests/gradients/test_sim_static_grad.py checks the exact one against central
differences (1e-5 relative); the projected one is only roughly aligned with it. The exact products
assume the SDF's normal is the gradient of its distance (true of the analytic SDFs; the body
grid's trilinear distance and its normals agree only to the grid's accuracy).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch

from unsew.errors import InputError, SimulationError
from unsew.sim.assembly import scatter_blocks
from unsew.sim.drape import Cloth, check_drape_inputs
from unsew.sim.integrator import StepParams, _pattern, force, forces, rest_data, total_energy
from unsew.sim.model import SimModel
from unsew.sim.solve import _Factor, resolve_backend
from unsew.sim.state import SimState

__all__ = ["drape_static", "StaticInfo", "StaticSettings"]

ADJOINTS = ("exact", "projected")


@dataclass(frozen=True)
class StaticSettings:
    """How :func:`drape_static` finds the equilibrium and its gradients (SI units).

    Attributes:
        tol: max |grad E| on free vertices relative to the heaviest vertex weight max(m_i g) [-].
        max_iter: Newton iterations [-].
        gravity: gravitational acceleration along -Y [m/s^2].
        contact_stiffness: body repulsion kc [N/m^4] (as :func:`~unsew.sim.drape.drape`).
        contact_threshold: distance below which repulsion acts [m].
        spring_stiffness: zero-length seam springs [N/m].
        mu0: initial Levenberg-Marquardt weight [1/s^2] on the masses.
        adjoint: "exact" (PCG on exact Hessian products) or "projected" (module docstring).
        adjoint_rtol: relative residual at which the "exact" adjoint's PCG stops [-].
        adjoint_max_iter: most PCG iterations of the "exact" adjoint [-].
        backend: linear solver (solve.py).
    """

    tol: float = 1e-8
    max_iter: int = 100
    gravity: float = 9.81
    contact_stiffness: float = 1e7
    contact_threshold: float = 5e-3
    spring_stiffness: float = 100.0
    mu0: float = 100.0
    adjoint: str = "exact"
    adjoint_rtol: float = 1e-10
    adjoint_max_iter: int = 500
    backend: str = "auto"


@dataclass(frozen=True)
class _Problem:
    """What the Newton solve and its adjoint share: the model, body, the step's energy settings
    (StepParams), :class:`StaticSettings`, the resolved solver backend, the info filled in and
    the callback (or None)."""

    model: SimModel
    sdf: object
    params: StepParams
    settings: StaticSettings
    backend: str
    info: StaticInfo
    callback: object = None


class StaticInfo:
    """What :func:`drape_static` did: iterations, final relative residual, energies [J] per
    iteration, and (after a backward pass) the adjoint's CG iterations and relative residual."""

    def __init__(self):
        self.iterations = 0
        self.residual = float("nan")
        self.energies: list[float] = []
        self.adjoint_iterations = 0
        self.adjoint_residual = float("nan")

    def __repr__(self):
        return (
            f"StaticInfo(iterations={self.iterations}, residual={self.residual:.2e}, "
            f"adjoint_iterations={self.adjoint_iterations}, adjoint_residual={self.adjoint_residual:.2e})"
        )


def _system(model, rest, x, sdf, gamma, params, mu, backend):
    """Projected matrix K + Hc + mu M at x (pinned rows identity) and its factor; f = -grad E."""
    f, K, Hc, _, _ = forces(model, rest, SimState(x, torch.zeros_like(x)), sdf, gamma, params)
    eye = torch.eye(3, dtype=x.dtype)
    vblk = Hc + mu * rest.mass[:, None, None] * eye
    A = K + scatter_blocks(model.nnz, model.vert_src, model.vert_dst, vblk)
    pat = _pattern(model)
    A = A * model.keep + pat.pin_diag
    return f, _Factor(pat, A.numpy(), backend)


def _forces_graph(model, rest, x, sdf, gamma, params):
    """f(x) = -grad E with a graph in x, and the exact Hessian product v -> H v = -(df/dx)^T v."""
    xs = x.detach().requires_grad_()
    with torch.enable_grad():
        f = force(model, rest, xs, sdf, gamma, params)

    def hvp(v):
        (jv,) = torch.autograd.grad(f, xs, grad_outputs=v, retain_graph=True)
        return -jv

    return f.detach(), hvp


def _newton(prob: _Problem, rest, x0, gamma):
    """Newton-CG: directions by truncated PCG on the exact Hessian (+ mu M), preconditioned by the
    projected factorization; negative curvature met first falls back to the projected Newton step
    (Nocedal and Wright 2006, Alg. 7.1, with a preconditioner). Armijo backtracking on E."""
    model, sdf, params, info, backend = prob.model, prob.sdf, prob.params, prob.info, prob.backend
    tol, max_iter, mu0 = prob.settings.tol, prob.settings.max_iter, prob.settings.mu0
    free = (~model.pinned)[:, None].to(x0.dtype)  # (N, 1)
    x = x0.clone()
    fscale = float((rest.mass * params.gravity).max()) if params.gravity > 0 else 1.0
    mu, mu_min, mu_max = mu0, 1e-6 * mu0, 1e6 * mu0
    E = float(total_energy(model, rest, x, sdf, gamma, params))
    info.energies = [E]
    massv = rest.mass[:, None]
    for it in range(max_iter + 1):
        f, hvp_exact = _forces_graph(model, rest, x, sdf, gamma, params)
        r = f * free
        res = float(r.abs().max()) / fscale
        info.iterations, info.residual = it, res
        if not np.isfinite(res):
            raise SimulationError(f"static drape diverged at Newton iteration {it} (non-finite forces)")
        if res <= tol or it == max_iter:
            break
        _, fac = _system(model, rest, x, sdf, gamma, params, mu, backend)

        def precond(v):
            return torch.from_numpy(fac.solve(v.reshape(-1).numpy())).reshape_as(v) * free

        def hvp(v):
            return (hvp_exact(v) + mu * massv * v) * free

        eta = min(0.5, res**0.5)
        p, _, _ = _pcg(hvp, r, precond, rtol=eta, max_iter=50, truncate=True)
        slope = -float((r * p).sum())  # grad E . p < 0
        if not slope < 0:
            p = precond(r)
            slope = -float((r * p).sum())
        alpha, accepted = 1.0, False
        for _ in range(40):
            xt = x + alpha * p
            Et = float(total_energy(model, rest, xt, sdf, gamma, params))
            if Et <= E + 1e-4 * alpha * slope or abs(Et - E) <= 1e-14 * max(abs(E), 1e-300):
                accepted = True
                break
            alpha *= 0.5
        if not accepted:
            mu = min(mu * 100.0, mu_max)
            continue
        x, E = xt, Et
        info.energies.append(E)
        mu = max(mu / 10.0, mu_min) if alpha == 1.0 else min(mu * 10.0, mu_max)
        if prob.callback is not None:
            prob.callback(it, x)
    if info.residual > tol:
        raise SimulationError(
            f"static drape did not converge in {max_iter} Newton iterations (relative force residual "
            f"{info.residual:.2e} > tol {tol:.1e}); raise max_iter or start closer to equilibrium"
        )
    return x, mu


def _pcg(hvp, b, precond, *, rtol, max_iter, truncate=False):
    """Preconditioned CG for H x = b. Returns x, iterations, relative residual.

    At negative curvature (p^T H p <= 0): with ``truncate`` (a Newton direction) stop and return
    the last iterate, or the preconditioned b if met at once; otherwise (an adjoint solve, which
    needs H positive definite) raise SimulationError.
    """
    x = torch.zeros_like(b)
    bn = float(b.norm())
    if bn == 0.0:
        return x, 0, 0.0
    r = b.clone()
    z = precond(r)
    p = z.clone()
    rz = float((r * z).sum())
    k = 0
    for k in range(1, max_iter + 1):
        Hp = hvp(p)
        pHp = float((p * Hp).sum())
        if pHp <= 0:
            if truncate:
                return (z if k == 1 else x), k, float(r.norm()) / bn
            raise SimulationError(
                "the exact Hessian at the static solution is not positive definite (not a stable "
                "equilibrium); use adjoint='projected' or pin the cloth"
            )
        a = rz / pHp
        x = x + a * p
        r = r - a * Hp
        if float(r.norm()) <= rtol * bn:
            break
        z = precond(r)
        rz_new = float((r * z).sum())
        p = z + (rz_new / rz) * p
        rz = rz_new
    return x, k, float(r.norm()) / bn


class _StaticDrape(torch.autograd.Function):
    @staticmethod
    def forward(ctx, x0, uv, gamma, density, prob: _Problem):
        with torch.no_grad():
            rest = rest_data(prob.model, uv.detach(), density.detach())
            x, mu = _newton(prob, rest, x0.detach(), gamma.detach())
        ctx.prob = prob
        ctx.mu = mu  # the final Levenberg-Marquardt weight (mu0 * 1e-6 after a converged run)
        ctx.save_for_backward(x, uv, gamma, density)
        return x

    @staticmethod
    @torch.autograd.function.once_differentiable
    def backward(ctx, gx):
        prob = ctx.prob
        model, sdf, params, opts, info = prob.model, prob.sdf, prob.params, prob.settings, prob.info
        x, uv, gamma, density = ctx.saved_tensors
        free = (~model.pinned)[:, None].to(x.dtype)
        with torch.enable_grad():
            xs = x.detach().requires_grad_()
            uv_ = uv.detach().requires_grad_(ctx.needs_input_grad[1])
            gam_ = gamma.detach().requires_grad_(ctx.needs_input_grad[2])
            den_ = density.detach().requires_grad_(ctx.needs_input_grad[3])
            rest = rest_data(model, uv_, den_)
            f = force(model, rest, xs, sdf, gam_, params)
            b = gx * free
            with torch.no_grad():
                # projected H at x*
                _, fac = _system(model, rest, x, sdf, gamma.detach(), params, ctx.mu, prob.backend)

            def precond(r):
                return torch.from_numpy(fac.solve(r.reshape(-1).numpy())).reshape_as(r) * free

            if opts.adjoint == "projected":
                lam = precond(b)
                info.adjoint_iterations, info.adjoint_residual = 1, float("nan")
            else:

                def hvp(v):  # H v = -(df/dx)^T v (H symmetric), free dofs only
                    (jv,) = torch.autograd.grad(f, xs, grad_outputs=v, retain_graph=True)
                    return -jv * free

                lam, its, rr = _pcg(hvp, b, precond, rtol=opts.adjoint_rtol, max_iter=opts.adjoint_max_iter)
                info.adjoint_iterations, info.adjoint_residual = its, rr
            want = [xs] + [
                t
                for t, need in (
                    (uv_, ctx.needs_input_grad[1]),
                    (gam_, ctx.needs_input_grad[2]),
                    (den_, ctx.needs_input_grad[3]),
                )
                if need
            ]
            grads = list(torch.autograd.grad(f, want, grad_outputs=lam, allow_unused=True))
        gxs = grads.pop(0)
        pinned = 1.0 - free
        g_x0 = (gx + (gxs if gxs is not None else 0.0)) * pinned if ctx.needs_input_grad[0] else None
        out = [g_x0]
        for need, like in (
            (ctx.needs_input_grad[1], uv),
            (ctx.needs_input_grad[2], gamma),
            (ctx.needs_input_grad[3], density),
        ):
            if need:
                gi = grads.pop(0)
                out.append(torch.zeros_like(like) if gi is None else gi)
            else:
                out.append(None)
        return (*out, None)


def drape_static(
    model: SimModel,
    x0,
    sdf,
    cloth: Cloth,
    *,
    settings: StaticSettings = StaticSettings(),
    info: StaticInfo | None = None,
    callback=None,
) -> torch.Tensor:
    """Equilibrium positions of the cloth, differentiable by the implicit function theorem.

    Args:
        model: :class:`SimModel` (pinned vertices stay at x0; pin some, or let contact and a
            unique minimum hold the cloth: a free cloth on a frictionless body has sliding modes).
        x0: (N, 3) float64 [m] starting positions (torch; a SimState is accepted and its x used).
        sdf: body, ``query(x) -> (d (N,) [m], n (N, 3))``.
        cloth: :class:`~unsew.sim.drape.Cloth`: uv (Nu, 2) float64 [m] rest shape, gamma (5,)
            float64 Gamma, density [kg/m^2] float or 0-d tensor; all three may require grad.
            Its friction does not act (an equilibrium without sliding).
        settings: :class:`StaticSettings` (tolerances, energy settings, adjoint, solver).
        info: a :class:`StaticInfo` filled in (optional).
        callback: ``callback(it, x)`` after each accepted Newton step.

    Returns:
        x*: (N, 3) float64 [m], differentiable w.r.t. uv, gamma, density (and x0 at pinned vertices).

    Raises:
        InputError: bad inputs. SimulationError: no convergence, or an unstable equilibrium
            for the exact adjoint.
    """
    if isinstance(x0, SimState):
        x0 = x0.x
    x0 = torch.as_tensor(x0, dtype=torch.float64)
    uv, gamma = cloth.uv, cloth.gamma
    check_drape_inputs(model, SimState(x0.detach(), torch.zeros_like(x0.detach())), sdf, uv, gamma)
    tol, max_iter = settings.tol, settings.max_iter
    if settings.adjoint not in ADJOINTS:
        raise InputError(f"adjoint must be one of {ADJOINTS}, got {settings.adjoint!r}")
    if not tol > 0 or max_iter < 1:
        raise InputError(f"need tol > 0 and max_iter >= 1, got tol={tol}, max_iter={max_iter}")
    density = torch.as_tensor(cloth.density, dtype=torch.float64)
    params = StepParams(
        gravity=settings.gravity,
        contact_stiffness=settings.contact_stiffness,
        contact_threshold=settings.contact_threshold,
        spring_stiffness=settings.spring_stiffness,
        friction=0.0,
        backend=settings.backend,
    )
    info = StaticInfo() if info is None else info
    prob = _Problem(model, sdf, params, settings, resolve_backend(settings.backend), info, callback)
    return _StaticDrape.apply(x0, uv, gamma, density, prob)
