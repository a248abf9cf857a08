"""The two-phase fit (paper 3.3-3.5) as a pipeline of stages with typed hand-offs:

1. start (:mod:`unsew.fit.start`): the base pattern dressed on the wearer and graded -> :class:`Start`;
2. material (:mod:`unsew.fit.material`): the starting fabric, given or chosen by draping ->
   :class:`MaterialChoice`;
3. optimize (:mod:`unsew.fit.optimize`): :class:`PhaseTwo`, Adam on the control points and the
   material through differentiable drapes, one callback per iteration;
4. checks (:mod:`unsew.fit.checks`): the re-dress check and the mesh spread;
5. checkpoint (:mod:`unsew.fit.checkpoint`): written after every iteration, read by ``--resume``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np
import torch

from unsew._memory import bound_heap, peak_rss_mb, release_free_memory
from unsew.body.sdf import BodySDF
from unsew.dress import resolve_material
from unsew.errors import InputError
from unsew.fit.budget import TimeBudget
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
from unsew.fit.start import choose_base, start_chosen, with_garment_read
from unsew.fit.target import Target
from unsew.sim.checks import DrapeVerdict, check_drape

__all__ = ["FitResult", "fit"]


@dataclass
class FitResult:
    """What a fit produces (:func:`unsew.fit.outputs.write_result` writes it as the result folder).

    pattern: final Pattern; base_pattern, graded_pattern: the starting points; mesh: GarmentMesh
    of the result; x: final drape (Nx, 3) float64 numpy [m]; uv: final rest positions (Nu, 2) [m];
    material: final Material; history: per-iteration loss terms (:data:`~unsew.fit.optimize.LOSS_TERMS`);
    grade_table: rows of phase one; timings: seconds per stage; iterations: phase two's count;
    converged: whether it stopped on its tolerance; x_graded, x_base: the graded and base drapes
    (Nx, 3) [m] (the base on ``base_mesh``); params: the PatternParams of the graded pattern;
    start_material: phase two's start; material_choice: the auto choice's table, best first;
    base_name, base_choice: the base pattern's name and the automatic base choice's table (best first);
    best_iteration: the iterate returned (-1: the start); material_fitted: whether the returned
    material was optimised; material_start_iteration: when the material joined (None: never);
    gamma_last: the last iterate's Gamma (5,); redress, mesh_spread: the checks' figures (None: off);
    drape_check: the returned drape judged on its body (:func:`unsew.sim.checks.check_drape`: fallen,
    off the body, exploded, inside it); :func:`unsew.fit.run.run_fit` refuses a bad one.
    rest: how phase two's start was let settle (:meth:`unsew.fit.optimize.PhaseTwo._start_at_rest`).
    memory_mb: the process's peak resident memory [MB] at the end of each stage (keys as
    ``timings``, "loaded" at the fit's start), so the stage that set the peak is the first one
    reaching the last value. time_limit: the fit's time limit and what gave way to it
    (:meth:`unsew.fit.budget.TimeBudget.as_dict`).
    x_warm: phase two's own drape of a kept pattern (Nx, 3) [m], warm-started along the
    optimizer's path (None: phase two not kept); ``x`` is then the pattern dressed from scratch.
    drapes: where ``x`` and ``x_graded`` come from ({"result": ..., "graded": ...}: "fresh",
    dressed from scratch on the fit's mesh; "graded start", the material choice's settled drape;
    "phase two", the optimizer's warm drape, when no re-dress check ran).
    """

    pattern: object
    base_pattern: object
    graded_pattern: object
    mesh: object
    x: np.ndarray
    uv: np.ndarray
    material: object
    history: dict
    grade_table: list
    timings: dict
    iterations: int
    converged: bool
    x_graded: np.ndarray | None = None
    x_base: np.ndarray | None = None
    params: object = None
    base_mesh: object = None
    start_material: object = None
    material_choice: list | None = None
    base_name: str = ""
    base_choice: list | None = None
    best_iteration: int = -1
    material_fitted: bool = False
    material_start_iteration: int | None = None
    gamma_last: list | None = None
    redress: RedressCheck | None = None
    mesh_spread: MeshSpread | None = None
    drape_check: DrapeVerdict | None = None
    memory_mb: dict | None = None
    time_limit: dict | None = None
    rest: dict | None = None
    x_warm: np.ndarray | None = None
    drapes: dict | None = None
    contact: dict | None = None


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
    material0 = resolve_material(AUTO_START_MATERIAL if cfg.material.start == "auto" else cfg.material.start)
    sdf, target = BodySDF.build(case.body), Target.of_case(case, seed=cfg.seed)
    cfg, contact = contact_for_target(cfg, target.verts, case.body, sdf)
    if contact["mode"] == "target":
        log(
            f"contact: the target's cloth rests {contact['gap_mm']:.1f} mm from the body; every drape rests "
            f"it {contact['threshold_mm']:.1f} mm off (contact stiffness {contact['stiffness']:.0e} N/m^4)"
        )
    clock.lap("body_sdf_s")
    saved = load_checkpoint(checkpoint) if resume and checkpoint and Path(checkpoint).is_file() else None
    if saved is not None:  # phase one and the material choice are in the checkpoint
        choice, state = saved
        log(f"resuming from iteration {state['iteration']} ({checkpoint})")
    else:
        base = choose_base(case, target, sdf, cfg, material0, progress=bar, log=log)
        clock.lap("base_choice_s", keep=bool(base.table))
        first = start_chosen(
            base, case.body, target, sdf, cfg, material0, progress=bar, log=log, budget=budget
        )
        garment = first.base_name
        clock.lap("grading_s")
        choice = choose_start(
            first, case.body, target, sdf, cfg, progress=bar, log=log, garment=garment, budget=budget
        )
        clock.lap("material_choice_s", keep=cfg.material.start == "auto")
    two = PhaseTwo(choice, target, sdf, cfg)
    if two.rest["steps"]:
        log(
            f"phase two starts from the graded drape let settle {two.rest['steps']} more steps: it was still "
            f"moving (99th percentile speed {two.rest['speed_p99_m_s']:.4f} m/s, then "
            f"{two.rest['speed_p99_end_m_s']:.4f} m/s)"
        )
    if saved is not None:
        two.load_state_dict(state)
    shown = bar.iterations(
        cfg.optimizer.iterations,
        two.iteration,
        lambda info: target.distance_mm(info.x.cpu().numpy(), info.faces, n_samples=BAR_SAMPLES),
    )

    ticks = [time.perf_counter()]  # when each iteration ended (the first: when phase two began)

    def on_iteration(info: Iteration) -> None:
        ticks.append(time.perf_counter())
        release_free_memory()  # an iteration's tape, freed in pieces all over the heap
        shown(info)
        if checkpoint is not None:
            save_checkpoint(checkpoint, choice, two.state_dict())
        if callback is not None:
            callback(info)

    # phase two stops while one more iteration and the re-dress check (a drape from scratch) fit
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
    clock.lap("optimization_s")
    result = _checked_result(case, cfg, choice, two, target, sdf, clock, bar, log, budget)
    result.contact = contact
    return result


def _checked_result(
    case,
    cfg: FitConfig,
    choice: MaterialChoice,
    two: PhaseTwo,
    target: Target,
    sdf,
    clock,
    bar: Progress,
    log,
    budget: TimeBudget,
) -> FitResult:
    """Phase two's best iterate, put through the re-dress check (which may return the graded
    pattern instead) and the mesh spread (skipped when its two drapes would overrun ``budget``),
    as a FitResult."""
    s = choice.start
    pattern, uv, x, material = two.best_fit()
    # drape_s: a drape from scratch [s], the base's in phase one
    redress, drape_s, spread = None, s.dress_s, None
    x_graded, x_warm = np.asarray(s.x), None
    drapes = {"result": "phase two" if two.best.iteration >= 0 else "graded start", "graded": "graded start"}
    if cfg.checks.redress and two.best.iteration >= 0:
        t0 = time.perf_counter()
        redress = redress_check(pattern, uv, material, s, case.body, target, sdf, cfg, progress=bar, log=log)
        # the re-dress is a drape of the result from scratch, timed now: a closer estimate of the
        # mesh spread's two drapes than the base's
        drape_s = max(drape_s, time.perf_counter() - t0)
        if REDRESS_MESHES == 3 and cfg.checks.mesh_spread > 0 and redress.fit_redressed_mm is not None:
            if budget.fits(5 * drape_s):  # the graded pattern on three meshes, phase two's on two more
                redress, spread = redress_on_three(
                    redress, pattern, material, s, case.body, target, sdf, cfg, progress=bar, log=log
                )
            else:
                budget.cut("re-dress check judged on one mesh (three would overrun)")
        if not redress.phase_two_kept and redress.x_graded is None:  # judged on one mesh, refused or failed
            if budget.fits(drape_s):
                redress.x_graded, _ = graded_afresh(s, case.body, target, sdf, cfg, progress=bar)
            else:
                budget.cut(
                    "the graded pattern's drape is the one the material choice let settle (no time to dress "
                    "it afresh)"
                )
        # the returned drape is the returned pattern dressed from scratch where the check dressed
        # it: a kept phase two's warm drape can lie nearer the target than its pattern dresses
        if redress.x_graded is not None:
            x_graded = redress.x_graded
        if redress.phase_two_kept:
            x_warm, x = x, redress.x_fit
        else:  # the graded pattern's rest mesh (= uv(K0)), drape and material
            pattern, uv, x, material = s.graded, np.asarray(s.mesh.uv, dtype=np.float64), x_graded, s.material
        drapes = _fresh_drapes(redress)
        clock.lap("redress_s")
    # the three-mesh check has dressed the returned pattern on the spread's meshes already
    if spread is None and cfg.checks.mesh_spread > 0 and not budget.fits(2 * drape_s):
        budget.cut("mesh spread skipped")
    elif spread is None and cfg.checks.mesh_spread > 0:
        result_mm = (
            redress.fit_redressed_mm
            if redress and redress.phase_two_kept
            else target.distance_mm(x, s.mesh.faces)
        )
        spread = mesh_spread(pattern, material, case.body, target, sdf, cfg, result_mm, progress=bar, log=log)
        clock.lap("mesh_spread_s")
    return FitResult(
        pattern=pattern,
        base_pattern=s.base,
        graded_pattern=s.graded,
        mesh=s.mesh,
        x=x,
        uv=uv,
        material=material,
        history=two.history,
        grade_table=s.grade_table,
        timings=clock.total(),
        iterations=len(two.history["total"]),
        converged=two.converged,
        x_graded=x_graded,
        x_base=s.x_base,
        x_warm=x_warm,
        drapes=drapes,
        params=two.params.to("cpu"),
        base_mesh=s.mesh_base,
        start_material=s.material,
        material_choice=choice.table,
        base_name=s.base_name,
        base_choice=list(s.base_choice) or None,
        best_iteration=two.best.iteration,
        material_fitted=two.best.material_on and (redress is None or redress.phase_two_kept),
        material_start_iteration=cfg.material.start_iteration if cfg.fits_material else None,
        gamma_last=two.gamma_last(),
        redress=redress,
        mesh_spread=spread,
        drape_check=check_drape(
            x, faces=s.mesh.faces, uv=uv, faces_uv=s.mesh.faces_uv, body=case.body, sdf=sdf
        ),
        memory_mb=clock.peaks,
        time_limit=budget.as_dict(),
        rest=two.rest,
    )


def _fresh_drapes(redress: RedressCheck) -> dict:
    """Where the result's and the graded drapes come from once the re-dress check has run: "fresh"
    (the pattern dressed from scratch on the fit's mesh, as ``unsew drape`` of it would) or "graded
    start" (the graded drape the material choice let settle from another fabric's drape)."""
    graded = "fresh" if redress.x_graded is not None else "graded start"
    return {"result": "fresh" if redress.phase_two_kept else graded, "graded": graded}


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
