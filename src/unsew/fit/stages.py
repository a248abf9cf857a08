"""The stages of a fit, each ``stage(ctx, previous) -> its result``: ``ctx`` the fit's
:class:`~unsew.fit.scene.FitContext` (built once by :func:`build_context`), ``previous`` the
result of the stage before it, every result a frozen dataclass.

1. :func:`base_stage` (None) -> :class:`BaseResult`: the base pattern, the user's or chosen by
   draping (:func:`unsew.fit.start.choose_base`), and the start fabric it was dressed in;
2. :func:`grading_stage` (BaseResult) -> :class:`~unsew.fit.start.Start`: the base dressed and
   graded (:func:`unsew.fit.start.start_chosen`);
3. :func:`material_stage` (Start) -> :class:`PhaseOneResult`: the starting fabric, given or chosen
   by draping (:func:`unsew.fit.material.choose_start`); or :func:`resume_stage`, the same read
   from a checkpoint with phase two's state;
4. :func:`phase_two_stage` (PhaseOneResult) -> :class:`PhaseTwoResult`: Adam on the control points
   and the material (:class:`unsew.fit.optimize.PhaseTwo`), a checkpoint after every iteration;
5. :func:`redress_stage` (PhaseTwoResult) -> :class:`ChecksResult`: the re-dress check, which
   decides what is returned (:mod:`unsew.fit.checks`);
6. :func:`spread_stage` (ChecksResult) -> ChecksResult: the mesh spread, when the re-dress check
   on three meshes has not measured it.

:func:`unsew.fit.fit.fit` runs them in turn and makes the :class:`~unsew.fit.fit.FitResult` of
their results.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from unsew._memory import release_free_memory
from unsew.body.sdf import BodySDF
from unsew.dress import resolve_material
from unsew.fit.checkpoint import load_checkpoint, save_checkpoint
from unsew.fit.checks import (
    REDRESS_MESHES,
    MeshSpread,
    RedressCheck,
    graded_afresh,
    mesh_spread,
    redress_check,
    redress_on_three,
)
from unsew.fit.config import FitConfig
from unsew.fit.contact import contact_for_target
from unsew.fit.material import AUTO_START_MATERIAL, MaterialChoice, choose_start
from unsew.fit.optimize import Iteration, PhaseTwo
from unsew.fit.progress import BAR_SAMPLES, Progress
from unsew.fit.scene import FitContext
from unsew.fit.start import BaseChoice, Start, choose_base, start_chosen
from unsew.fit.target import Target

__all__ = [
    "BaseResult",
    "PhaseOneResult",
    "PhaseTwoResult",
    "ChecksResult",
    "build_context",
    "base_stage",
    "grading_stage",
    "material_stage",
    "resume_stage",
    "phase_two_stage",
    "redress_stage",
    "spread_stage",
]


def build_context(case, cfg: FitConfig, *, progress: Progress, log, **fixed) -> FitContext:
    """The fit's context: the body's SDF and the target read off ``case``, the contact set from
    the target where :data:`unsew.fit.contact.CONTACT` says so (logged; ``ctx.cfg`` holds it).
    fixed: the rest of :class:`FitContext` (budget, checkpoint, callback)."""
    sdf, target = BodySDF.build(case.body), Target.of_case(case, seed=cfg.seed)
    cfg, contact = contact_for_target(cfg, target.verts, case.body, sdf)
    if contact["mode"] == "target":
        log(
            f"contact: the target's cloth rests {contact['gap_mm']:.1f} mm from the body; every drape rests "
            f"it {contact['threshold_mm']:.1f} mm off (contact stiffness {contact['stiffness']:.0e} N/m^4)"
        )
    return FitContext(case.body, target, sdf, cfg, progress, log, case=case, contact=contact, **fixed)


@dataclass(frozen=True)
class BaseResult:
    """The base stage's result: ``choice`` (:class:`~unsew.fit.start.BaseChoice`: the pattern, its
    name, the choice's table) and ``material``, the start fabric (Material) it was dressed in."""

    choice: BaseChoice
    material: object


def base_stage(ctx: FitContext, previous: None = None) -> BaseResult:
    """The base pattern: the user's (``cfg.base``) or chosen by draping, in the start fabric
    (``cfg.material.start``, or :data:`~unsew.fit.material.AUTO_START_MATERIAL` when "auto")."""
    start = ctx.cfg.material.start
    material = resolve_material(AUTO_START_MATERIAL if start == "auto" else start)
    choice = choose_base(ctx.case, ctx.target, ctx.sdf, ctx.cfg, material, progress=ctx.progress, log=ctx.log)
    return BaseResult(choice, material)


def grading_stage(ctx: FitContext, base: BaseResult) -> Start:
    """The base dressed and graded to the target (both bases of a tie; the closer kept)."""
    return start_chosen(base.choice, ctx, base.material, budget=ctx.budget)


@dataclass(frozen=True)
class PhaseOneResult:
    """Where phase two starts: ``choice`` (:class:`~unsew.fit.material.MaterialChoice`: the graded
    pattern, its drape and fabric, the material choice's table) and ``state``, phase two's state
    to continue from (:meth:`~unsew.fit.optimize.PhaseTwo.state_dict`; None: from the start)."""

    choice: MaterialChoice
    state: dict | None = None

    @property
    def start(self) -> Start:
        """The graded start phase two begins at."""
        return self.choice.start


def material_stage(ctx: FitContext, graded: Start) -> PhaseOneResult:
    """Phase two's starting fabric: the given one, or the auto choice from ``graded``."""
    return PhaseOneResult(choose_start(graded, ctx, garment=graded.base_name, budget=ctx.budget))


def resume_stage(ctx: FitContext, previous: None = None) -> PhaseOneResult | None:
    """Phase one and phase two's state read from ``ctx.checkpoint`` (logged), or None when there
    is no checkpoint file."""
    if ctx.checkpoint is None or not Path(ctx.checkpoint).is_file():
        return None
    choice, state = load_checkpoint(ctx.checkpoint)
    ctx.log(f"resuming from iteration {state['iteration']} ({ctx.checkpoint})")
    return PhaseOneResult(choice, state)


@dataclass(frozen=True)
class PhaseTwoResult:
    """Phase two's result, on the CPU.

    start: the :class:`~unsew.fit.start.Start` it began at; pattern, uv (Nu, 2) [m], x (Nx, 3)
    [m], material: its best iterate (:meth:`~unsew.fit.optimize.PhaseTwo.best_fit`, phase two's
    warm drape); best_iteration: that iterate's (-1: the start); best_material_on: whether its
    material was a variable then; history: per-iteration loss terms; converged: whether it stopped
    on its tolerance; params: the graded pattern's PatternParams; gamma_last: the last iterate's
    Gamma (5,); rest: how the start was let settle; material_start_iteration: when the material
    joined (None: never)."""

    start: Start
    pattern: object
    uv: np.ndarray
    x: np.ndarray
    material: object
    best_iteration: int
    best_material_on: bool
    history: dict
    converged: bool
    params: object
    gamma_last: list
    rest: dict
    material_start_iteration: int | None

    @property
    def iterations(self) -> int:
        """Iterations made."""
        return len(self.history["total"])


def phase_two_stage(ctx: FitContext, one: PhaseOneResult) -> PhaseTwoResult:
    """Phase two from ``one`` (continued from its state when resumed), until its iterations are
    made, it converges, or one more iteration and the re-dress check would overrun the budget."""
    cfg = ctx.cfg
    two = PhaseTwo(one.choice, ctx.target, ctx.sdf, cfg)
    if two.rest["steps"]:
        ctx.log(
            f"phase two starts from the graded drape let settle {two.rest['steps']} more steps: it was still "
            f"moving (99th percentile speed {two.rest['speed_p99_m_s']:.4f} m/s, then "
            f"{two.rest['speed_p99_end_m_s']:.4f} m/s)"
        )
    if one.state is not None:
        two.load_state_dict(one.state)
    _run_phase_two(two, one.choice, ctx)
    pattern, uv, x, material = two.best_fit()
    return PhaseTwoResult(
        start=one.start,
        pattern=pattern,
        uv=uv,
        x=x,
        material=material,
        best_iteration=two.best.iteration,
        best_material_on=two.best.material_on,
        history=two.history,
        converged=two.converged,
        params=two.params.to("cpu"),
        gamma_last=two.gamma_last(),
        rest=two.rest,
        material_start_iteration=cfg.material.start_iteration if cfg.fits_material else None,
    )


def _run_phase_two(two: PhaseTwo, choice: MaterialChoice, ctx: FitContext) -> None:
    """Run phase two, a bar or line per iteration, a checkpoint written after each; it stops
    while one more iteration and the re-dress check (a drape from scratch) fit ``ctx.budget``."""
    cfg, target, budget = ctx.cfg, ctx.target, ctx.budget
    shown = ctx.progress.iterations(
        cfg.optimizer.iterations,
        two.iteration,
        lambda info: target.distance_mm(info.x.cpu().numpy(), info.faces, n_samples=BAR_SAMPLES),
    )
    ticks = [time.perf_counter()]  # when each iteration ended (the first: when phase two began)

    def on_iteration(info: Iteration) -> None:
        ticks.append(time.perf_counter())
        release_free_memory()  # an iteration's tape, freed in pieces all over the heap
        shown(info)
        if ctx.checkpoint is not None:
            save_checkpoint(ctx.checkpoint, choice, two.state_dict())
        if ctx.callback is not None:
            ctx.callback(info)

    redress_s = choice.start.dress_s if cfg.checks.redress else 0.0

    def out_of_time() -> bool:
        recent = np.diff(ticks[-6:])  # the last iterations' durations [s]
        iteration_s = float(recent.max()) if len(recent) else 0.5 * choice.start.dress_s
        if budget.fits(iteration_s + redress_s):
            return False
        budget.cut(f"phase two stopped after {two.iteration} of {cfg.optimizer.iterations} iterations")
        return True

    try:
        two.run(on_iteration, stop=out_of_time)
    finally:
        shown.close()


@dataclass(frozen=True)
class ChecksResult:
    """What the checks decide is returned: pattern, rest positions uv (Nu, 2) [m], drape x (Nx, 3)
    [m] on ``mesh`` (the fit's GarmentMesh), material; the graded drape x_graded (Nx, 3) [m], where
    the drapes come from (``drapes``, :attr:`unsew.fit.fit.FitResult.drapes`), a drape from
    scratch's duration [s] (``drape_s``), phase two's warm drape of a kept pattern (``x_warm``),
    and the checks' figures (``redress``, ``spread``; None: not run)."""

    pattern: object
    uv: np.ndarray
    x: np.ndarray
    material: object
    mesh: object
    x_graded: np.ndarray
    drapes: dict
    drape_s: float
    x_warm: np.ndarray | None = None
    redress: RedressCheck | None = None
    spread: MeshSpread | None = None


def redress_stage(ctx: FitContext, two: PhaseTwoResult) -> ChecksResult:
    """Phase two's best iterate put through the re-dress check (when ``cfg.checks.redress`` and
    phase two moved off its start), which may return the graded pattern instead; without the
    check, phase two's best iterate and warm drape."""
    s = two.start
    r = ChecksResult(
        two.pattern,
        two.uv,
        two.x,
        two.material,
        s.mesh,
        np.asarray(s.x),
        {"result": "phase two" if two.best_iteration >= 0 else "graded start", "graded": "graded start"},
        s.dress_s,  # a drape from scratch [s], the base's in phase one
    )
    if not (ctx.cfg.checks.redress and two.best_iteration >= 0):
        return r
    return _redressed(r, s, ctx)


def _redressed(r: ChecksResult, s: Start, ctx: FitContext) -> ChecksResult:
    """The re-dress check on ``r`` (phase two's best iterate): on the fit's mesh, then on three
    when five more drapes fit the budget; returns what it decides is returned, its drapes the
    patterns dressed from scratch where the check dressed them."""
    budget, t0 = ctx.budget, time.perf_counter()
    redress, spread = redress_check(r.pattern, r.uv, r.material, s, ctx), None
    # the re-dress is a drape of the result from scratch, timed now: a closer estimate of the
    # mesh spread's two drapes than the base's
    drape_s = max(r.drape_s, time.perf_counter() - t0)
    if REDRESS_MESHES == 3 and ctx.cfg.checks.mesh_spread > 0 and redress.fit_redressed_mm is not None:
        if budget.fits(5 * drape_s):  # the graded pattern on three meshes, phase two's on two more
            redress, spread = redress_on_three(redress, r.pattern, r.material, s, ctx)
        else:
            budget.cut("re-dress check judged on one mesh (three would overrun)")
    if not redress.phase_two_kept and redress.x_graded is None:  # judged on one mesh, refused or failed
        if budget.fits(drape_s):
            redress = replace(redress, x_graded=graded_afresh(s, ctx)[0])
        else:
            budget.cut(
                "the graded pattern's drape is the one the material choice let settle (no time to dress "
                "it afresh)"
            )
    # the returned drape is the returned pattern dressed from scratch where the check dressed
    # it: a kept phase two's warm drape can lie nearer the target than its pattern dresses
    x_graded = r.x_graded if redress.x_graded is None else redress.x_graded
    checked = replace(
        r, x_graded=x_graded, drape_s=drape_s, redress=redress, spread=spread, drapes=_fresh_drapes(redress)
    )
    if redress.phase_two_kept:
        return replace(checked, x_warm=r.x, x=redress.x_fit)
    # the graded pattern's rest mesh (= uv(K0)), drape and material
    return replace(
        checked, pattern=s.graded, uv=np.asarray(s.mesh.uv, dtype=np.float64), x=x_graded, material=s.material
    )


def _fresh_drapes(redress: RedressCheck) -> dict:
    """Where the result's and the graded drapes come from once the re-dress check has run: "fresh"
    (the pattern dressed from scratch on the fit's mesh, as ``unsew drape`` of it would) or "graded
    start" (the graded drape the material choice let settle from another fabric's drape)."""
    graded = "fresh" if redress.x_graded is not None else "graded start"
    return {"result": "fresh" if redress.phase_two_kept else graded, "graded": graded}


def spread_stage(ctx: FitContext, checked: ChecksResult) -> ChecksResult:
    """``checked`` with the mesh spread of its pattern (``cfg.checks.mesh_spread`` > 0), unless the
    three-mesh re-dress check measured it already or its two drapes would overrun the budget."""
    if checked.spread is not None or ctx.cfg.checks.mesh_spread <= 0:
        return checked
    if not ctx.budget.fits(2 * checked.drape_s):
        ctx.budget.cut("mesh spread skipped")
        return checked
    r = checked.redress
    kept = r and r.phase_two_kept
    result_mm = r.fit_redressed_mm if kept else ctx.target.distance_mm(checked.x, checked.mesh.faces)
    return replace(checked, spread=mesh_spread(checked.pattern, checked.material, ctx, result_mm))
