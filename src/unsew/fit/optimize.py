"""Phase two of the fit (paper 3.4-3.5): the effective control points K and, from
``material.start_iteration``, the material Gamma refined by Adam through differentiable drapes
warm-started from the previous iteration's result.

Loss (eqs. 5-9): L = L_CF(X, T) [curvature-weighted, eq. 7] + lambda_open L_CF(X_open, T_open)
+ lambda_mat relu(1e-6 - Gamma) + lambda_seam L_seam(U(K)) (+ lambda_prior, lambda_area, the
pattern's total area against the target's surface area, and lambda_panel, each panel's area against
its graded area, all off by default). With ``area:
target`` every step ends on the start's total rest area (:class:`AreaHold`): the Chamfer then
moves area between panels and places, never adds or drops it.

Material parameterisation (a deviation from the paper, which does not say how Gamma is scaled):
the four stiffness entries H00, H11, H22, k are optimised as log-factors on the starting
material, Gamma_i = Gamma0_i * exp(theta_i), so one learning rate suits values that differ by
seven orders of magnitude and they stay positive; H01 = 0.995 tanh(phi0 + theta_1) sqrt(H00 H11),
so H stays positive definite. The material range penalty of the paper is kept on Gamma itself.

Steps of the control points are line searched (a deviation from the paper, whose Adam keeps
every step; ``OptimizerSettings.retries`` > 0): the start drape is draped once more before the first
gradient, each step follows the gradient's running sum scaled to the learning rate on the point
moving most (not Adam's sign-like first steps), and a step whose drape has a higher loss than the
iterate it left is retried at half its length, up to ``retries`` times, else not taken
(:meth:`PhaseTwo._line_search`; docs/decisions/018). The material keeps Adam.

The result is the iterate of lowest loss, pattern-only or with the material; when a pattern-only
iterate wins, the reported material is the start material.
"""

from __future__ import annotations

import copy
import dataclasses
import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
import torch

from unsew.errors import InputError
from unsew.fit.config import FitConfig, material_mask
from unsew.fit.material import MaterialChoice
from unsew.fit.target import Target
from unsew.grading.grade import upright, waistbands
from unsew.losses.area import loss_area, rest_area
from unsew.losses.chamfer import loss_chamfer
from unsew.losses.contours import loss_open_contours, open_contours
from unsew.losses.curvature import curvature_weights
from unsew.losses.material import loss_material
from unsew.losses.panel_area import loss_panel_area, panel_areas
from unsew.losses.prior import loss_prior
from unsew.losses.seam import loss_seam, seam_segment_pairs
from unsew.losses.stretch import loss_stretch, triangle_edges
from unsew.metrics.panels import panel_area
from unsew.pattern.curves import edge_length
from unsew.pattern.params import PatternParams, check_inverted
from unsew.pattern.seams import SeamHold
from unsew.sim.drape import Cloth, drape
from unsew.sim.material import Material
from unsew.sim.model import SimModel
from unsew.sim.state import SimState
from unsew.tolerances import MIN_TRIANGLE_QUALITY

__all__ = [
    "PhaseTwo",
    "AreaHold",
    "step_scales",
    "band_projectors",
    "LossTerms",
    "Iterate",
    "Iteration",
    "material_params",
    "LOSS_TERMS",
]

#: Names of the loss terms, in the order of :class:`LossTerms` (and of ``FitResult.history``).
LOSS_TERMS = ("total", "chamfer", "open", "seam", "material", "prior", "area", "panel_area", "stretch")

#: Steps of each drape that probes and settles phase two's start (:meth:`PhaseTwo._start_at_rest`) [-].
REST_CHUNK = 10

#: Weight of the earlier gradients in the running sum line-searched steps follow (PhaseTwo._step_k) [-].
MOMENTUM = 0.5
#: Factor on the next step's length after a step kept whole, and the most that length grows to, in
#: learning rates (PhaseTwo._line_search) [-].
GROW, GROW_CAP = 1.5, 3.0


@dataclass
class LossTerms:
    """The loss of one drape, term by term (0-d torch tensors): ``total`` is the weighted sum
    of ``chamfer`` [m^2], ``open`` [m^2], ``seam`` [m^2], ``material``, ``prior`` [m^2], ``area`` [-],
    ``panel_area`` [-] and ``stretch`` [-]."""

    total: torch.Tensor
    chamfer: torch.Tensor
    open: torch.Tensor
    seam: torch.Tensor
    material: torch.Tensor
    prior: torch.Tensor
    area: torch.Tensor
    panel_area: torch.Tensor
    stretch: torch.Tensor

    def floats(self) -> dict[str, float]:
        """The terms as plain floats, keyed by :data:`LOSS_TERMS`."""
        return {k: float(getattr(self, k).detach()) for k in LOSS_TERMS}


@dataclass
class Iterate:
    """A point of phase two: its loss, control points K (Nk, 2) [m], Gamma (5,), drape x (Nx, 3)
    [m], the iteration (-1: the start) and whether the material was a variable then."""

    loss: float
    K: torch.Tensor
    gamma: torch.Tensor
    x: torch.Tensor
    iteration: int = -1
    material_on: bool = False


@dataclass
class Iteration:
    """What the per-iteration callback receives: the iteration's index, its loss terms (floats),
    the control points K it draped (Nk, 2) [m], its Gamma (5,), its drape x (Nx, 3) [m] on
    ``faces``, and whether it was the last one (budget spent or converged)."""

    iteration: int
    terms: dict
    K: torch.Tensor
    gamma: torch.Tensor
    x: torch.Tensor
    faces: np.ndarray
    last: bool = False


def material_params(gamma0: torch.Tensor):
    """Gamma as a function of unconstrained parameters theta (5,), zero at the start material.

    H00, H11, H22, k = start * exp(theta); H01 = tanh(phi0 + theta_1) * sqrt(H00 H11) with
    tanh(phi0) the start's H01 / sqrt(H00 H11), so the membrane stiffness stays positive
    definite for every theta (|H01| < sqrt(H00 H11)). Returns (theta (5,) leaf, gamma_of).
    """
    theta = torch.zeros(5, dtype=torch.float64, device=gamma0.device, requires_grad=True)
    r0 = float(gamma0[1]) / math.sqrt(float(gamma0[0]) * float(gamma0[2]))
    phi0 = math.atanh(max(-0.99, min(0.99, r0 / 0.995)))

    def gamma_of(th):
        g = gamma0 * torch.exp(th)
        g01 = 0.995 * torch.tanh(phi0 + th[1]) * torch.sqrt(g[0] * g[2])
        return torch.stack([g[0], g01, g[2], g[3], g[4]])

    return theta, gamma_of


def step_scales(params, panel_width: float) -> torch.Tensor:
    """(Nk, 1) float64 factors on Adam's step of each effective control point: min(1, w /
    ``panel_width``) for the narrowest panel it moves, w = area / half perimeter of the panel's
    outline [m] (a long strip's short side; :func:`unsew.metrics.panels.panel_area`,
    :func:`unsew.pattern.curves.edge_length`); all 1 when ``panel_width`` [m] is 0.

    Why: Adam moves every coordinate by about lr per step whatever its gradient's size, and the
    same move is a small change of a 30 cm wide trouser leg but a large one of a 4 cm waistband;
    scaled, each panel's relative edit per step is about the same."""
    nk = params.n_k
    if panel_width <= 0:
        return torch.ones(nk, 1, dtype=torch.float64)
    c = params.controls
    width = np.empty(len(c.panel_names))
    for p, name in enumerate(c.panel_names):
        panel = params.pattern.panels[name]
        half_perimeter = 0.5 * sum(edge_length(panel, i) for i in range(len(panel.edges)))
        width[p] = panel_area(panel) / half_perimeter if half_perimeter > 0 else panel_width
    moves = _moves(params)
    w = np.where(moves, width[np.asarray(c.panel, dtype=np.int64)][:, None], np.inf).min(axis=0)  # (Nk,) [m]
    scale = np.minimum(1.0, np.where(np.isfinite(w), w, panel_width) / panel_width)
    return torch.as_tensor(scale, dtype=torch.float64).reshape(nk, 1)


def _moves(params) -> np.ndarray:
    """(Nc, Nk) bool: whether effective point k moves control point c (a non-zero block of L_c)."""
    nc, nk = len(params.controls), params.n_k
    return np.abs(params.L_c.detach().cpu().numpy()).reshape(nc, 2, nk, 2).sum(axis=(1, 3)) > 1e-12


def band_projectors(params, bands: tuple[str, ...] | list[str], mode: str) -> torch.Tensor | None:
    """(Nk, 2, 2) float64 maps applied to each effective control point's step, or None when
    nothing is held: the identity for points that move no panel named in ``bands``; for those
    that do, 0 (``mode`` "held") or, for "height", the projection that leaves every band control
    point it moves still at its placed height: its step loses the component along B^T up, B the
    (2, 2) block of L_c from the point to the band's control point, up the band's upright 2D
    direction (:func:`unsew.grading.grade.upright`). A band then changes its girth, as grading
    changes it, never its height (docs/decisions/013)."""
    if mode == "free" or not bands:
        return None
    c, nk = params.controls, params.n_k
    L = params.L_c.detach().cpu().numpy().reshape(len(c), 2, nk, 2)
    moves = _moves(params)
    P = np.tile(np.eye(2), (nk, 1, 1))
    for name in bands:
        p = c.panel_names.index(name)
        up = upright(params.pattern.panels[name])
        for g in c.of_panel(p):
            for k in np.flatnonzero(moves[g]):
                if mode == "held" or up is None:
                    P[k] = 0.0
                    continue
                v = P[k].T @ (L[g, :, k, :].T @ up)  # the part of k's step that still lifts point g
                n2 = float(v @ v)
                if n2 > 1e-24:
                    P[k] = P[k] - np.outer(P[k] @ v, v) / n2
    return torch.as_tensor(P, dtype=torch.float64)


class AreaHold:
    """Ends each of phase two's steps on the start's total rest area (``area: target``): K is
    replaced by K_c + s (K - K_c), where K_c puts every control point at its panel's centroid of
    control points and s = sqrt(A_0 / A(uv(K))). uv is affine in K and each panel's vertices are
    affine combinations of its own control points (:mod:`unsew.pattern.params`), so this scales
    every panel about that centroid by s: a similarity, seams scaled alike, no triangle inverted.
    Read through the symmetric parameters (K_c = pinv(L_c) (M C(K) - b_c), M averaging within a
    panel), which holds exactly because a centroid of mirrored points is the mirror of theirs.

    params: the PatternParams; faces_uv: (F, 3) int64 tensor; K0: (Nk, 2) [m], whose area A_0 [m^2]
    is held; kept: names of panels left unscaled (waistbands whose height ``optimizer.bands``
    holds): their control points are their own centre, so the others take the whole change (the
    factor is then found in a few rounds instead of one).
    """

    def __init__(self, params, faces_uv: torch.Tensor, K0: torch.Tensor, kept: tuple[str, ...] = ()):
        c = params.controls
        nc = len(c)
        M = np.zeros((nc, nc))
        for p, name in enumerate(c.panel_names):
            idx = c.of_panel(p)
            M[np.ix_(idx, idx)] = np.eye(len(idx)) if name in kept else 1.0 / len(idx)
        M2 = np.kron(M, np.eye(2))  # on xy-flattened control points
        L, b = params.L_c.detach().cpu().numpy(), params.b_c.detach().cpu().numpy()
        P = np.linalg.pinv(L)
        dev = K0.device
        self.A = torch.as_tensor(P @ M2 @ L, dtype=torch.float64, device=dev)  # (2 Nk, 2 Nk)
        self.c = torch.as_tensor(P @ (M2 @ b - b), dtype=torch.float64, device=dev)  # (2 Nk,) [m]
        self.params, self.faces_uv, self.kept = params, faces_uv, tuple(kept)
        with torch.no_grad():
            self.area0 = float(rest_area(params.uv(K0), faces_uv))

    def __call__(self, K: torch.Tensor) -> torch.Tensor:
        """K (Nk, 2) [m] scaled onto the held area (no gradient)."""
        with torch.no_grad():
            for _ in range(8):  # one round when every panel scales; kept panels converge geometrically
                a = float(rest_area(self.params.uv(K), self.faces_uv))
                s = math.sqrt(self.area0 / a)
                if abs(s - 1.0) < 1e-12:
                    break
                Kc = (self.A @ K.reshape(-1) + self.c).reshape(-1, 2)
                K = Kc + s * (K - Kc)
        return K


class PhaseTwo:
    """The optimisation of phase two from a :class:`~unsew.fit.material.MaterialChoice`.

    ``loss()`` drapes the current pattern and returns its :class:`LossTerms`; ``step()`` makes
    one iteration (loss, backward, Adam, inversion backtracking, warm start, convergence);
    ``run(callback)`` iterates until the budget is spent or the loss has converged;
    ``state_dict()`` / ``load_state_dict()`` checkpoint and resume it. ``best`` is the
    lowest-loss :class:`Iterate` so far.

    Device: phase one hands over numpy/CPU data; everything phase two computes with (the pattern
    maps, the SimModel, K, Gamma, the drapes, the targets, the seam pairs) is moved once here to
    ``cfg.device``, and the drapes' sparse factorizations run on the CPU (:mod:`unsew.sim.solve`).
    ``best_fit()`` and ``gamma_last()`` hand back CPU data.
    """

    def __init__(self, choice: MaterialChoice, target: Target, sdf, cfg: FitConfig):
        s = choice.start
        self.cfg, self.sdf, self.mesh, self.material0 = cfg, sdf, s.mesh, s.material
        self.anchors = s.anchors  # held as the start's drape holds them (unsew.dress.held_anchors)
        dev = torch.device(cfg.device)
        self.params = PatternParams.build(s.graded, s.mesh).to(dev)
        self.model = SimModel.build(s.mesh.faces, s.mesh.faces_uv).to(dev)
        self.settings = cfg.drape.replace(friction_eps=cfg.optimizer.friction_eps)
        self._targets(target, dev)
        self.contours_x = open_contours(np.asarray(s.x), s.mesh.faces)
        self.seam_pairs = torch.as_tensor(
            seam_segment_pairs(s.mesh, s.graded.stitches), dtype=torch.int64, device=dev
        )
        self.edges, self.edges_uv = (e.to(dev) for e in triangle_edges(s.mesh.faces, s.mesh.faces_uv))
        self.gamma0 = s.material.gamma().to(dev)
        self.K = self.params.K0.detach().clone().to(dev).requires_grad_(True)
        self.theta, self.gamma_of = material_params(self.gamma0)
        self.free_mat = torch.tensor(material_mask(cfg.material.fit), dtype=self.theta.dtype, device=dev)
        o = cfg.optimizer
        self.opt_k = torch.optim.Adam([self.K], lr=o.lr, betas=o.betas)
        self.k_scale = step_scales(self.params, o.panel_width).to(dev)
        self.bands = tuple(waistbands(s.graded))
        P = band_projectors(self.params, self.bands, o.bands)
        self.k_project = None if P is None else P.to(dev)
        self._scaled = bool((self.k_scale < 1).any())  # any narrow panel: checked once, not every step
        self.area_hold = (
            None
            if cfg.area != "target"
            else AreaHold(
                self.params, self.faces_uv, self.K.detach(), kept=self.bands if o.bands != "free" else ()
            )
        )
        self.seam_hold = (
            None if o.seams != "held" else SeamHold(self.params, self.K.detach(), project=self.k_project)
        )
        self.opt_m = torch.optim.Adam([self.theta], lr=cfg.material.lr, betas=o.betas)
        self.x_prev = torch.as_tensor(np.asarray(s.x), dtype=torch.float64, device=dev)
        self.rest = self._start_at_rest()
        with torch.no_grad():
            self.uv_start = self.params.uv(self.K).detach()
            self.panel_areas0 = panel_areas(
                self.uv_start, self.faces_uv, self.face_panel, len(self.mesh.panel_names)
            )
        self.history: dict[str, list[float]] = {k: [] for k in LOSS_TERMS}
        self.best = Iterate(
            math.inf, self.K.detach().clone(), self.gamma0.detach().clone(), self.x_prev.clone()
        )
        self._settle_start()  # after the start iterate: with no iteration made, its drape is the start's
        self.iteration, self.converged = 0, False
        self._pending: tuple | None = None  # the kept trial's (terms, gamma, x): the next iteration's loss
        self._momentum: torch.Tensor | None = None  # (Nk, 2): the running sum of dL/dK (_step_k)
        self._length = 1.0  # the next step's length, in learning rates (_line_search)
        self.trials: list[int] = []  # per iteration, the trial drapes its step took (0: no line search)

    def _start_at_rest(self) -> dict:
        """Settle the graded drape ``x_prev`` until it is at rest, when it is not.

        Every iteration drapes from rest where the last one ended, so a start still moving (a wide
        skirt's hem) goes on settling through the iterations and the loss climbs whatever the
        steps do, and the start, measured before the settling, stays the best iterate. Off by
        default (docs/decisions/013).

        A drape of REST_CHUNK steps probes the start: when the 99th percentile of its vertex
        speeds ends above ``optimizer.rest_speed`` [m/s] it is draped on (velocities kept) by such
        chunks until the speed falls below or ``optimizer.rest_steps`` have run, and phase two
        starts there. The largest speed cannot tell: a few vertices in contact keep near the
        friction's slip speed on drapes whose shape no longer changes. A start at rest is left
        exactly as it was.

        Returns {"steps": steps draped before phase two (0: at rest), "speed_p99_m_s": the
        probe's speed, "speed_p99_end_m_s": the speed where phase two starts}."""
        o = self.cfg.optimizer
        if o.rest_speed <= 0 or o.rest_steps <= 0:
            return {"steps": 0, "speed_p99_m_s": None, "speed_p99_end_m_s": None}
        cloth = Cloth(
            self.params.uv(self.K.detach()),
            self.gamma0,
            self.material0.density,
            friction=self.material0.friction,
            anchors=self.anchors,
        )

        def p99(st):
            return float(torch.quantile(st.v.norm(dim=1), 0.99))

        with torch.no_grad():
            st = drape(
                self.model,
                SimState.at_rest(self.x_prev),
                self.sdf,
                cloth,
                steps=REST_CHUNK,
                settings=self.settings,
            )
            first = speed = p99(st)
            if speed <= o.rest_speed:
                return {"steps": 0, "speed_p99_m_s": first, "speed_p99_end_m_s": first}
            steps = REST_CHUNK
            while speed > o.rest_speed and steps < o.rest_steps:
                n = min(REST_CHUNK, o.rest_steps - steps)
                st = drape(self.model, st, self.sdf, cloth, steps=n, settings=self.settings)
                steps, speed = steps + n, p99(st)
        self.x_prev = st.x.detach().clone()
        return {"steps": steps, "speed_p99_m_s": first, "speed_p99_end_m_s": speed}

    def _targets(self, target: Target, dev) -> None:
        """The target points the Chamfer sees (a seeded subset) and their curvature weights."""
        tv, n = target.verts, self.cfg.loss.target_points
        rng = np.random.default_rng(self.cfg.seed)
        sub = np.sort(rng.choice(len(tv), n, replace=False)) if len(tv) > n else np.arange(len(tv))
        w = curvature_weights(tv, target.faces) if self.cfg.loss.curvature_weighted else np.ones(len(tv))
        self.T = torch.as_tensor(tv, dtype=torch.float64, device=dev)  # (M, 3) [m]: the open contours' target
        self.T_sub = self.T[torch.as_tensor(sub, device=dev)]
        self.w_sub = torch.as_tensor(np.asarray(w, dtype=np.float64)[sub], dtype=torch.float64, device=dev)
        self.area_target = target.area  # A_T [m^2]
        self.faces_uv = torch.as_tensor(np.asarray(self.mesh.faces_uv), dtype=torch.int64, device=dev)
        self.face_panel = torch.as_tensor(
            np.asarray(self.mesh.uv_panel)[np.asarray(self.mesh.faces_uv)[:, 0]],
            dtype=torch.int64,
            device=dev,
        )  # (F,) panel of each triangle
        self.contours_t = target.contours

    def material_on(self, it: int | None = None) -> bool:
        """Whether Gamma is a variable at iteration ``it`` (default: the current one)."""
        it = self.iteration if it is None else it
        return self.cfg.fits_material and it >= self.cfg.material.start_iteration

    def loss(
        self, *, K: torch.Tensor | None = None, theta: torch.Tensor | None = None
    ) -> tuple[LossTerms, torch.Tensor, torch.Tensor]:
        """Drape the current K (and Gamma, when it is a variable) from the previous drape, or the
        ``K`` (Nk, 2) [m] and ``theta`` (5,) given. Returns (terms, gamma (5,), drape x (Nx, 3)
        [m]), differentiable in K and theta."""
        w = self.cfg.loss
        uv = self.params.uv(self.K if K is None else K)
        theta = self.theta if theta is None else theta
        gamma = self.gamma_of(theta) if self.material_on() else self.gamma0
        x = drape(
            self.model,
            SimState.at_rest(self.x_prev),
            self.sdf,
            Cloth(uv, gamma, self.material0.density, friction=self.material0.friction, anchors=self.anchors),
            settings=self.settings,
        ).x
        zero_x, zero_uv = x.sum() * 0, uv.sum() * 0
        l_cf = loss_chamfer(x, self.T_sub, weights_t=self.w_sub)
        l_open = (
            loss_open_contours(x, self.contours_x, self.T, self.contours_t) if self.contours_t else zero_x
        )
        l_seam = loss_seam(uv, pairs=self.seam_pairs) if w.seam > 0 else zero_uv
        l_mat = loss_material(gamma)
        l_prior = loss_prior(uv, self.uv_start) if w.prior > 0 else zero_uv
        l_area = loss_area(uv, self.faces_uv, self.area_target) if w.area > 0 else zero_uv
        l_panel = (
            loss_panel_area(uv, self.faces_uv, self.face_panel, self.panel_areas0)
            if w.panel_area > 0
            else zero_uv
        )
        l_stretch = (
            loss_stretch(x, uv, self.edges, self.edges_uv, bound=w.stretch_bound) if w.stretch > 0 else zero_x
        )
        total = (
            l_cf
            + w.open * l_open
            + w.seam * l_seam
            + w.material * l_mat
            + w.prior * l_prior
            + w.area * l_area
            + w.panel_area * l_panel
            + w.stretch * l_stretch
        )
        return LossTerms(total, l_cf, l_open, l_seam, l_mat, l_prior, l_area, l_panel, l_stretch), gamma, x

    def _set_learning_rates(self) -> None:
        o = self.cfg.optimizer
        decay = o.lr_decay ** (self.iteration / o.iterations)
        for opt, lr in ((self.opt_k, o.lr), (self.opt_m, self.cfg.material.lr)):
            for group in opt.param_groups:
                group["lr"] = lr * decay

    def step(self) -> Iteration:
        """One iteration: the loss at K (the drape the last step's line search kept, or a fresh
        one), its gradient, a step, and, with ``OptimizerSettings.retries`` > 0, the line search that
        shortens a step raising the loss (:meth:`_line_search`); returns what it draped and
        measured."""
        it, mat_on = self.iteration, self.material_on()
        self._set_learning_rates()
        self.opt_k.zero_grad()
        self.opt_m.zero_grad()
        terms, gamma, x = self._pending if self._pending is not None else self.loss()
        self._pending = None
        if not torch.isfinite(terms.total):
            raise InputError(
                f"the loss became non-finite at iteration {it}; try a smaller --lr or a coarser mesh"
            )
        terms.total.backward()
        values = terms.floats()
        for key, val in values.items():
            self.history[key].append(val)
        if values["total"] < self.best.loss:
            self.best = Iterate(
                values["total"],
                self.K.detach().clone(),
                gamma.detach().clone(),
                x.detach().clone(),
                it,
                mat_on,
            )
        K_before, theta_before = self.K.detach().clone(), self.theta.detach().clone()
        moved = it >= self.cfg.optimizer.pattern_start
        if moved:
            self._step_k(K_before)
        if mat_on:
            if self.theta.grad is not None:
                self.theta.grad.mul_(self.free_mat)  # entries left out of material.fit stay put
            self.opt_m.step()
        self._hold(K_before)
        if self.cfg.optimizer.warm_start:
            self.x_prev = x.detach()
        self.iteration += 1
        trials = 0
        o = self.cfg.optimizer
        if o.retries > 0 and (moved or mat_on) and self.iteration < o.iterations:
            trials = self._line_search(values["total"], K_before, theta_before)
        self.trials.append(trials)
        self.converged = self._has_converged()
        last = self.converged or self.iteration >= self.cfg.optimizer.iterations
        return Iteration(it, values, K_before, gamma.detach(), x.detach(), self.mesh.faces, last)

    def _step_k(self, K_before: torch.Tensor) -> None:
        """The control points' step, shortened for narrow panels (step_scales) and projected for
        held bands (band_projectors). With ``OptimizerSettings.retries`` > 0 it follows the gradient's
        running sum m = MOMENTUM m + dL/dK, scaled so that the point moving most moves the
        learning rate [m] times the line search's step length: each point's step is in proportion
        to its gradient, where Adam's first step moves every coordinate by the learning rate
        whatever its gradient's size (sign-like, and on a noisy gradient a rise of the loss);
        with 0, Adam's step (the paper)."""
        if self.cfg.optimizer.retries <= 0:
            self.opt_k.step()
        else:
            g = self.K.grad.detach()  # (Nk, 2) [1/m]
            m = g if self._momentum is None else MOMENTUM * self._momentum + g
            self._momentum = m
            n = float(m.norm(dim=1).max())
            if n > 0:
                with torch.no_grad():
                    self.K.sub_(self._length * self.opt_k.param_groups[0]["lr"] / n * m)
        if self._scaled:
            with torch.no_grad():  # narrow panels' points take shorter steps (step_scales)
                short = K_before + self.k_scale * (self.K - K_before)
                self.K.copy_(torch.where(self.k_scale < 1, short, self.K))
        if self.k_project is not None:
            with torch.no_grad():  # waistbands keep their height (band_projectors)
                self.K.copy_(K_before + torch.einsum("kij,kj->ki", self.k_project, self.K - K_before))

    def _line_search(self, loss0: float, K_before: torch.Tensor, theta_before: torch.Tensor) -> int:
        """Keep the step just taken (K, theta) only where its drape, from the drape at K_before, has
        a loss no higher than ``loss0`` (K_before's), or, when it has not, than K_before draped
        from that same drape (a drape still settling lowers or raises both alike; one drape more,
        without tape); else retry it at half its length, up to ``OptimizerSettings.retries`` times (the
        holds applied again), and when none is lower keep the shortest. A step kept whole makes
        the next one GROW times longer (at most GROW_CAP learning rates); one kept shorter makes
        the next as short. The kept trial's drape, tape and all, is the next iteration's loss
        (``_pending``): a step kept whole costs no drape more than Adam's. Returns the number of
        drapes it made."""
        K_full, theta_full = self.K.detach().clone(), self.theta.detach().clone()
        t, ref = 1.0, 0
        for r in range(self.cfg.optimizer.retries + 1):
            if r > 0:
                t *= 0.5
                with torch.no_grad():
                    self.K.copy_(K_before + t * (K_full - K_before))
                    self.theta.copy_(theta_before + t * (theta_full - theta_before))
                self._hold(K_before)
            trial = self.loss()
            total = float(trial[0].total.detach())
            if r == 0 and not total <= loss0:  # the step, or the drape still moving? K_before from here
                with torch.no_grad():
                    loss0, ref = float(self.loss(K=K_before, theta=theta_before)[0].total), 1
            if math.isfinite(total) and total <= loss0:
                self._length = min(GROW_CAP, self._length * (GROW if r == 0 else 0.5**r))
                self._pending = trial
                return r + 1 + ref
        self._length *= 0.5**self.cfg.optimizer.retries
        self._pending = trial  # none lower: the shortest is kept (undone, K would draw the same step)
        return self.cfg.optimizer.retries + 1 + ref

    def _settle_start(self) -> None:
        """Drape the start once (one iteration's steps, no tape) before phase two's first gradient,
        when steps are line searched (``OptimizerSettings.retries`` > 0): the start drape, settled in phase
        one's settings, still moves in phase two's, and a gradient taken on a drape still moving
        points anywhere (docs/decisions/018)."""
        if self.cfg.optimizer.retries <= 0:
            return
        with torch.no_grad():
            self.x_prev = (
                drape(
                    self.model,
                    SimState.at_rest(self.x_prev),
                    self.sdf,
                    Cloth(
                        self.params.uv(self.K.detach()),
                        self.gamma0,
                        self.material0.density,
                        friction=self.material0.friction,
                        anchors=self.anchors,
                    ),
                    settings=self.settings,
                )
                .x.detach()
                .clone()
            )

    def _hold(self, K_before: torch.Tensor) -> None:
        """End the step on a pattern that sews (``optimizer.seams: held``: every stitch's length
        ratio as the start has it, :class:`~unsew.pattern.seams.SeamHold`), has no flipped
        triangle (:meth:`_backtrack_inversions`) and, with ``area: target``, the start's total rest
        area (:class:`AreaHold`; :meth:`_seams_and_area`)."""
        with torch.no_grad():
            if self.seam_hold is not None:
                self.K.copy_(self.seam_hold(self.K.detach()))
            self._backtrack_inversions(K_before)
            self.K.copy_(self._seams_and_area(self.K.detach(), self.seam_hold))

    def _seams_and_area(self, K: torch.Tensor, seam_hold: SeamHold | None) -> torch.Tensor:
        """K (Nk, 2) [m] put through ``seam_hold`` (when given) and the area hold (with ``area:
        target``). The area hold scales each panel by one factor, which keeps the seam ratios;
        panels it leaves unscaled (held bands) take a few alternating rounds."""
        for _ in range(4):
            if seam_hold is not None:
                K = seam_hold(K)
            if self.area_hold is not None:
                K = self.area_hold(K)
            if (
                seam_hold is None
                or self.area_hold is None
                or not self.area_hold.kept
                or abs(seam_hold.residuals(K)).max() < 1e-6
            ):
                return K
        return K

    def _backtrack_inversions(self, K_before: torch.Tensor) -> None:
        """A step that inverts pattern triangles, or flattens one below MIN_TRIANGLE_QUALITY, is
        shortened (halved towards the previous K) until none does."""
        with torch.no_grad():
            for _ in range(10):
                uv = self.params.uv(self.K).cpu().numpy()
                if len(check_inverted(uv, self.mesh.faces_uv, min_quality=MIN_TRIANGLE_QUALITY)) == 0:
                    return
                self.K.copy_(0.5 * (self.K + K_before))
            self.K.copy_(K_before)

    def _has_converged(self) -> bool:
        """The best loss of the last ``patience`` iterations improved on the earlier best by less
        than ``tol`` of it (judged once both variables have had ``patience`` iterations)."""
        o, h = self.cfg.optimizer, self.history["total"]
        it = self.iteration - 1
        if len(h) > o.patience and it >= max(self.cfg.material.start_iteration, o.pattern_start) + o.patience:
            old = min(h[: -o.patience])
            return (old - min(h[-o.patience :])) < o.tol * abs(old)
        return False

    def run(
        self, callback: Callable[[Iteration], None] | None = None, *, stop: Callable[[], bool] | None = None
    ) -> None:
        """Iterate until the budget is spent or the loss has converged; ``callback(Iteration)``
        after every iteration (progress, checkpoints, traces); ``stop() -> True`` ends the loop
        before the next iteration (the fit's time limit)."""
        while self.iteration < self.cfg.optimizer.iterations and not self.converged:
            if stop is not None and stop():
                return
            info = self.step()
            if callback is not None:
                callback(info)

    def state_dict(self) -> dict:
        """Everything :meth:`load_state_dict` needs to continue from here (copies: stepping on
        does not change it)."""
        return {
            "iteration": self.iteration,
            "K": self.K.detach().clone(),
            "theta": self.theta.detach().clone(),
            "opt_k": copy.deepcopy(self.opt_k.state_dict()),
            "opt_m": copy.deepcopy(self.opt_m.state_dict()),
            "x_prev": self.x_prev.clone(),
            "history": {k: list(v) for k, v in self.history.items()},
            "best": dataclasses.asdict(self.best),
            "trials": list(self.trials),
            "momentum": None if self._momentum is None else self._momentum.clone(),
            "length": self._length,
        }

    def load_state_dict(self, state: dict) -> None:
        """Continue from a :meth:`state_dict` of a PhaseTwo built from the same start."""
        dev = self.K.device
        with torch.no_grad():
            self.K.copy_(state["K"])
            self.theta.copy_(state["theta"])
        self.opt_k.load_state_dict(state["opt_k"])
        self.opt_m.load_state_dict(state["opt_m"])
        self.x_prev = state["x_prev"].to(dev)
        h = state["history"]  # a checkpoint written before a term existed lacks it: zeros
        self.history = {k: list(h.get(k, [0.0] * len(h["total"]))) for k in LOSS_TERMS}
        best = dict(state["best"])  # a checkpoint is read onto the CPU (checkpoint.py): tensors back to dev
        self.best = Iterate(**{k: v.to(dev) if torch.is_tensor(v) else v for k, v in best.items()})
        self.iteration = int(state["iteration"])
        self.trials = list(state.get("trials", []))  # absent from checkpoints written before line search
        self._pending = None  # the next iteration drapes K afresh from x_prev, as the kept trial did
        m = state.get("momentum")
        self._momentum = None if m is None else m.to(dev)
        self._length = float(state.get("length", 1.0))

    def best_fit(self):
        """The best iterate as (pattern, uv (Nu, 2) [m] numpy, drape x (Nx, 3) [m] numpy, Material),
        all on the CPU whatever ``cfg.device``. With ``optimizer.seams: trued`` its seams are put
        back in the graded pattern's length ratios first (:meth:`_trued`)."""
        b = self.best
        K, x = (b.K, b.x) if self.cfg.optimizer.seams != "trued" else self._trued(b)
        with torch.no_grad():
            uv = self.params.uv(K)
        g = b.gamma.cpu().numpy()
        m0 = self.material0
        material = Material(
            float(g[0]), float(g[1]), float(g[2]), float(g[3]), float(g[4]), m0.density, m0.friction
        )
        return self.params.to_pattern(K), uv.cpu().numpy(), x.cpu().numpy(), material

    def _trued(self, b: Iterate) -> tuple[torch.Tensor, torch.Tensor]:
        """(K (Nk, 2) [m], x (Nx, 3) [m]) of iterate ``b`` with every stitch put back in the start's
        length ratio (the seam hold once, at the end, with the area hold) and its drape draped on
        from ``b.x`` for one iteration's steps in its own material; ``b`` unchanged when its seams
        already are (the start) or when the truing would flip a triangle."""
        hold = SeamHold(self.params, self.params.K0, project=self.k_project)
        with torch.no_grad():
            if abs(hold.residuals(b.K)).max() < 1e-9:
                return b.K, b.x
            K = self._seams_and_area(b.K, hold)
            uv = self.params.uv(K)
            if len(check_inverted(uv.cpu().numpy(), self.mesh.faces_uv, min_quality=MIN_TRIANGLE_QUALITY)):
                return b.K, b.x
            x = drape(
                self.model,
                SimState.at_rest(b.x),
                self.sdf,
                Cloth(
                    uv,
                    b.gamma,
                    self.material0.density,
                    friction=self.material0.friction,
                    anchors=self.anchors,
                ),
                settings=self.settings,
            ).x
        return K, x

    def gamma_last(self) -> list[float]:
        """Gamma at the current theta (the last iterate's material, as floats)."""
        return [float(v) for v in self.gamma_of(self.theta.detach()).cpu()]
