"""The two-phase fit (paper 3.3-3.5): :func:`fit` builds the fit's context once
(:func:`unsew.fit.stages.build_context`: the body's SDF, the target, the config, the time limit,
progress, log) and runs the stages of :mod:`unsew.fit.stages` on it in turn, each
``stage(ctx, previous) -> its result``: base choice, grading, material (or the checkpoint read by
``--resume``), phase two (a checkpoint written after every iteration), the re-dress check, the mesh
spread. The :class:`FitResult` holds their results.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import torch

from unsew._memory import bound_heap, peak_rss_mb, release_free_memory
from unsew.errors import InputError
from unsew.fit.budget import TimeBudget
from unsew.fit.config import FitConfig
from unsew.fit.optimize import Iteration
from unsew.fit.progress import Progress
from unsew.fit.scene import FitContext
from unsew.fit.stages import (
    ChecksResult,
    PhaseOneResult,
    PhaseTwoResult,
    base_stage,
    build_context,
    grading_stage,
    material_stage,
    phase_two_stage,
    redress_stage,
    resume_stage,
    spread_stage,
)
from unsew.fit.start import with_garment_read
from unsew.sim.checks import DrapeVerdict, check_drape, sleeve_vertices, sleeves_judged

__all__ = ["FitResult", "fit"]


class _Of:
    """A read-only attribute of :class:`FitResult` read off one of its stage results: ``path``
    dotted from the FitResult ("checks.x"), or a function of the FitResult."""

    def __init__(self, path, doc: str = ""):
        self.path, self.__doc__ = path, doc

    def __get__(self, result, owner=None):
        if result is None:
            return self
        if callable(self.path):
            return self.path(result)
        value = result
        for name in self.path.split("."):
            value = getattr(value, name)
        return value


@dataclass(frozen=True)
class FitResult:
    """What a fit produces (:func:`unsew.fit.outputs.write_result` writes it as the result folder):
    its stages' results, made once at the fit's end and never changed.

    phase_one: where phase two started (:class:`~unsew.fit.stages.PhaseOneResult`: the base and
    graded patterns, the material choice); phase_two: its best iterate, history and convergence
    (:class:`~unsew.fit.stages.PhaseTwoResult`); checks: what the re-dress check and the mesh
    spread decided is returned (:class:`~unsew.fit.stages.ChecksResult`). Computed at the end:
    drape_check, the returned drape judged on its body (:func:`unsew.sim.checks.check_drape`:
    fallen, off the body, exploded, inside it; a sleeve off its arm; :func:`unsew.fit.run.run_fit`
    refuses a bad one);
    timings: seconds per stage; memory_mb: the process's peak resident memory [MB] at the end of
    each stage (keys as ``timings``, "loaded" at the fit's start), so the stage that set the peak
    is the first one reaching the last value; time_limit: the fit's time limit and what gave way
    to it (:meth:`unsew.fit.budget.TimeBudget.as_dict`); contact: the body contact every drape
    used (:func:`unsew.fit.contact.contact_for_target`).

    Read-only attributes read off the stage results (each documented below): pattern, uv, x,
    material, mesh, x_graded, x_warm, drapes, redress, mesh_spread (checks); base_pattern,
    graded_pattern, grade_table, x_base, base_mesh, start_material, base_name, base_choice,
    material_choice (phase one); history, iterations, converged, params, best_iteration,
    gamma_last, rest, material_start_iteration (phase two); material_fitted.
    """

    phase_one: PhaseOneResult
    phase_two: PhaseTwoResult
    checks: ChecksResult
    drape_check: DrapeVerdict | None = None
    timings: dict = field(default_factory=dict)
    memory_mb: dict | None = None
    time_limit: dict | None = None
    contact: dict | None = None

    pattern = _Of("checks.pattern", "the final Pattern")
    uv = _Of("checks.uv", "the final rest positions (Nu, 2) [m]")
    x = _Of("checks.x", "the final drape (Nx, 3) float64 numpy [m] on ``mesh``")
    material = _Of("checks.material", "the final Material")
    mesh = _Of("checks.mesh", "the GarmentMesh of the result (the graded pattern's)")
    x_graded = _Of("checks.x_graded", "the graded drape (Nx, 3) [m] on ``mesh``")
    x_warm = _Of(
        "checks.x_warm",
        "phase two's own drape of a kept pattern (Nx, 3) [m], warm-started along the optimizer's "
        "path (None: phase two not kept); ``x`` is then the pattern dressed from scratch",
    )
    drapes = _Of(
        "checks.drapes",
        'where ``x`` and ``x_graded`` come from ({"result": ..., "graded": ...}: "fresh", dressed '
        "from scratch on the fit's mesh; \"graded start\", the material choice's settled drape; "
        '"phase two", the optimizer\'s warm drape, when no re-dress check ran)',
    )
    redress = _Of("checks.redress", "the re-dress check's figures (RedressCheck; None: off)")
    mesh_spread = _Of("checks.spread", "the mesh spread's figures (MeshSpread; None: off)")
    base_pattern = _Of("phase_one.start.base", "the base pattern, before grading")
    graded_pattern = _Of("phase_one.start.graded", "the graded pattern, phase two's start")
    grade_table = _Of("phase_one.start.grade_table", "rows of phase one's grading")
    x_base = _Of("phase_one.start.x_base", "the base drape (Nx, 3) [m] on ``base_mesh``")
    base_mesh = _Of("phase_one.start.mesh_base", "the base pattern's GarmentMesh")
    start_material = _Of("phase_one.start.material", "phase two's start material")
    base_name = _Of("phase_one.start.base_name", "the base pattern's name (library base or JSON path)")
    base_choice = _Of(
        lambda r: list(r.phase_one.start.base_choice) or None,
        "the automatic base choice's table, best first (None: the base was given)",
    )
    material_choice = _Of("phase_one.choice.table", "the auto material choice's table, best first")
    history = _Of("phase_two.history", "per-iteration loss terms (unsew.fit.optimize.LOSS_TERMS)")
    iterations = _Of("phase_two.iterations", "phase two's iteration count")
    converged = _Of("phase_two.converged", "whether phase two stopped on its tolerance")
    params = _Of("phase_two.params", "the PatternParams of the graded pattern")
    best_iteration = _Of("phase_two.best_iteration", "the iterate returned by phase two (-1: the start)")
    gamma_last = _Of("phase_two.gamma_last", "the last iterate's Gamma (5,)")
    rest = _Of("phase_two.rest", "how phase two's start was let settle (PhaseTwo._start_at_rest)")
    material_start_iteration = _Of(
        "phase_two.material_start_iteration", "when the material joined phase two (None: never)"
    )
    material_fitted = _Of(
        lambda r: r.phase_two.best_material_on and (r.redress is None or r.redress.phase_two_kept),
        "whether the returned material was optimised",
    )


def fit(
    case,
    cfg: FitConfig,
    *,
    progress: bool | Progress = True,
    checkpoint: Path | None = None,
    resume: bool = False,
    log: Callable[[str], None] = print,
    callback: Callable[[Iteration], None] | None = None,
    started: float | None = None,
) -> FitResult:
    """Run both phases on a loaded case (from unsew.body.case.load_case) and return the FitResult.

    progress: True/False or a :class:`Progress` (its stream decides bars or plain lines).
    checkpoint: file written after every iteration (and read with ``resume=True``).
    callback: called with every phase-two :class:`~unsew.fit.optimize.Iteration` (traces).
    started: when the command began (a ``time.perf_counter()`` reading, before the case was
    loaded): the time limit counts from it, so a slow load (an anny body's first build on a
    machine: minutes) leaves less for the optional work, not an overrun; metrics.json's
    ``timings_s.load_s`` is that time. Default: now.
    """
    bound_heap()  # freed memory goes back to the system (unsew._memory); peak memory: metrics.json
    clock, bar = _Clock(), progress if isinstance(progress, Progress) else Progress(progress)
    budget = TimeBudget(cfg.time_limit, log=log, started=started)
    if started is not None:
        clock.timings["load_s"] = clock.t0 - started
    torch.manual_seed(cfg.seed)
    _check_device(cfg.device)
    case = with_garment_read(case, cfg, log=log)
    ctx = build_context(
        case, cfg, progress=bar, log=log, budget=budget, checkpoint=checkpoint, callback=callback
    )
    clock.lap("body_sdf_s")
    one = resume_stage(ctx) if resume else None  # phase one and the material choice are in the checkpoint
    if one is None:
        base = base_stage(ctx)
        clock.lap("base_choice_s", keep=bool(base.choice.table))
        graded = grading_stage(ctx, base)
        clock.lap("grading_s")
        one = material_stage(ctx, graded)
        clock.lap("material_choice_s", keep=ctx.cfg.material.start == "auto")
    two = phase_two_stage(ctx, one)
    clock.lap("optimization_s")
    redressed = redress_stage(ctx, two)
    if redressed.redress is not None:
        clock.lap("redress_s")
    checked = spread_stage(ctx, redressed)
    if checked.spread is not redressed.spread:
        clock.lap("mesh_spread_s")
    return _fit_result(ctx, one, two, checked, clock)


def _fit_result(
    ctx: FitContext, one: PhaseOneResult, two: PhaseTwoResult, checked: ChecksResult, clock: "_Clock"
) -> FitResult:
    """The FitResult of the stages' results, the returned drape judged on its body."""
    timings = clock.total()
    return FitResult(
        one,
        two,
        checked,
        drape_check=_result_verdict(ctx, checked),
        timings=timings,
        memory_mb=clock.peaks,
        time_limit=ctx.budget.as_dict(),
        contact=ctx.contact,
    )


def _result_verdict(ctx: FitContext, checked: ChecksResult):
    """The returned drape judged on its body (:func:`unsew.sim.checks.check_drape`), its sleeves
    round the arms the pattern's placement puts them on (docs/decisions/062)."""
    mesh = checked.mesh
    v = check_drape(
        checked.x, faces=mesh.faces, uv=checked.uv, faces_uv=mesh.faces_uv, body=ctx.body, sdf=ctx.sdf
    )
    return sleeves_judged(v, checked.x, sleeve_vertices(checked.pattern, mesh, ctx.body), ctx.body)


def _check_device(device: str) -> None:
    if device == "cpu":
        return
    try:
        ok = torch.device(device).type == "cuda" and torch.cuda.is_available()
    except RuntimeError:
        ok = False
    if not ok:
        raise InputError(f"--device {device}: no such device is visible to torch here; use --device cpu")


class _Clock:
    """Seconds per stage: ``lap(name)`` records the time since the previous lap, and the process's
    peak resident memory so far [MB] (``peaks``)."""

    def __init__(self):
        self.t0 = self.last = time.perf_counter()
        self.timings: dict[str, float] = {}
        self.peaks: dict[str, float | None] = {"loaded": peak_rss_mb()}

    def lap(self, name: str, *, keep: bool = True) -> None:
        now = time.perf_counter()
        if keep:
            self.timings[name] = self.timings.get(name, 0.0) + now - self.last
            self.peaks[name] = peak_rss_mb()
        release_free_memory()  # a stage's scratch memory, before the next stage
        self.last = time.perf_counter()

    def total(self) -> dict[str, float]:
        return {**self.timings, "total_s": time.perf_counter() - self.t0}
