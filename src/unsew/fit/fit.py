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
from dataclasses import dataclass, replace
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
from unsew.fit.scene import Scene
from unsew.fit.start import Start, choose_base, start_chosen, with_garment_read
from unsew.fit.target import Target
from unsew.sim.checks import DrapeVerdict, check_drape

__all__ = ["FitResult", "fit"]


@dataclass(frozen=True)
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
    scene, contact = _scene(case, cfg, bar, log)
    clock.lap("body_sdf_s")
    saved = load_checkpoint(checkpoint) if resume and checkpoint and Path(checkpoint).is_file() else None
    if saved is not None:  # phase one and the material choice are in the checkpoint
        choice, state = saved
        log(f"resuming from iteration {state['iteration']} ({checkpoint})")
    else:
        choice = _phase_one(case, scene, clock, budget)
    two = PhaseTwo(choice, scene.target, scene.sdf, scene.cfg)
    if two.rest["steps"]:
        log(
            f"phase two starts from the graded drape let settle {two.rest['steps']} more steps: it was still "
            f"moving (99th percentile speed {two.rest['speed_p99_m_s']:.4f} m/s, then "
            f"{two.rest['speed_p99_end_m_s']:.4f} m/s)"
        )
    if saved is not None:
        two.load_state_dict(state)
    _run_phase_two(two, choice, scene, budget, checkpoint=checkpoint, callback=callback)
    clock.lap("optimization_s")
    return replace(_checked_result(case, choice, two, scene, clock, budget), contact=contact)


def _scene(case, cfg: FitConfig, bar: Progress, log) -> tuple[Scene, dict]:
    """(the fit's Scene, its body contact for metrics.json): the body's SDF and the target read,
    the contact set from the target where :data:`unsew.fit.contact.CONTACT` says so (logged)."""
    sdf, target = BodySDF.build(case.body), Target.of_case(case, seed=cfg.seed)
    cfg, contact = contact_for_target(cfg, target.verts, case.body, sdf)
    if contact["mode"] == "target":
        log(
            f"contact: the target's cloth rests {contact['gap_mm']:.1f} mm from the body; every drape rests "
            f"it {contact['threshold_mm']:.1f} mm off (contact stiffness {contact['stiffness']:.0e} N/m^4)"
        )
    return Scene(case.body, target, sdf, cfg, bar, log), contact


def _phase_one(case, scene: Scene, clock, budget: TimeBudget) -> MaterialChoice:
    """Phase two's start: the base chosen, graded (:func:`start_chosen`) and its fabric chosen
    (:func:`choose_start`), each stage timed on ``clock``."""
    cfg = scene.cfg
    material0 = resolve_material(AUTO_START_MATERIAL if cfg.material.start == "auto" else cfg.material.start)
    base = choose_base(case, scene.target, scene.sdf, cfg, material0, progress=scene.progress, log=scene.log)
    clock.lap("base_choice_s", keep=bool(base.table))
    first = start_chosen(base, scene, material0, budget=budget)
    clock.lap("grading_s")
    choice = choose_start(first, scene, garment=first.base_name, budget=budget)
    clock.lap("material_choice_s", keep=cfg.material.start == "auto")
    return choice


def _run_phase_two(
    two: PhaseTwo, choice: MaterialChoice, scene: Scene, budget: TimeBudget, *, checkpoint, callback
):
    """Run phase two, a bar or line per iteration, a checkpoint written after each; it stops
    while one more iteration and the re-dress check (a drape from scratch) fit ``budget``."""
    cfg, target = scene.cfg, scene.target
    shown = scene.progress.iterations(
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


@dataclass
class _Returned:
    """What the checks decide is returned: pattern, rest positions uv (Nu, 2) [m], drape x (Nx, 3)
    [m], material; the graded drape, phase two's warm drape of a kept pattern, where the drapes
    come from (FitResult.drapes), the checks' figures, and a drape from scratch's duration [s]."""

    pattern: object
    uv: np.ndarray
    x: np.ndarray
    material: object
    x_graded: np.ndarray
    drapes: dict
    drape_s: float
    x_warm: np.ndarray | None = None
    redress: RedressCheck | None = None
    spread: MeshSpread | None = None


def _checked_result(
    case, choice: MaterialChoice, two: PhaseTwo, scene: Scene, clock, budget: TimeBudget
) -> FitResult:
    """Phase two's best iterate, put through the re-dress check (which may return the graded
    pattern instead) and the mesh spread (skipped when its two drapes would overrun ``budget``),
    as a FitResult."""
    s, cfg = choice.start, scene.cfg
    pattern, uv, x, material = two.best_fit()
    r = _Returned(
        pattern,
        uv,
        x,
        material,
        np.asarray(s.x),
        {"result": "phase two" if two.best.iteration >= 0 else "graded start", "graded": "graded start"},
        s.dress_s,  # a drape from scratch [s], the base's in phase one
    )
    if cfg.checks.redress and two.best.iteration >= 0:
        _redress(r, s, scene, budget)
        clock.lap("redress_s")
    # the three-mesh check has dressed the returned pattern on the spread's meshes already
    if r.spread is None and cfg.checks.mesh_spread > 0 and not budget.fits(2 * r.drape_s):
        budget.cut("mesh spread skipped")
    elif r.spread is None and cfg.checks.mesh_spread > 0:
        kept = r.redress and r.redress.phase_two_kept
        result_mm = r.redress.fit_redressed_mm if kept else scene.target.distance_mm(r.x, s.mesh.faces)
        r.spread = mesh_spread(r.pattern, r.material, scene, result_mm)
        clock.lap("mesh_spread_s")
    return _fit_result(r, choice, two, scene, clock, budget)


def _redress(r: _Returned, s: Start, scene: Scene, budget: TimeBudget) -> None:
    """The re-dress check on ``r`` (phase two's best iterate): on the fit's mesh, then on three
    when five more drapes fit ``budget``; ``r`` becomes what it decides is returned, its drapes
    the patterns dressed from scratch where the check dressed them."""
    t0 = time.perf_counter()
    r.redress = redress_check(r.pattern, r.uv, r.material, s, scene)
    # the re-dress is a drape of the result from scratch, timed now: a closer estimate of the
    # mesh spread's two drapes than the base's
    r.drape_s = max(r.drape_s, time.perf_counter() - t0)
    if REDRESS_MESHES == 3 and scene.cfg.checks.mesh_spread > 0 and r.redress.fit_redressed_mm is not None:
        if budget.fits(5 * r.drape_s):  # the graded pattern on three meshes, phase two's on two more
            r.redress, r.spread = redress_on_three(r.redress, r.pattern, r.material, s, scene)
        else:
            budget.cut("re-dress check judged on one mesh (three would overrun)")
    redress = r.redress
    if not redress.phase_two_kept and redress.x_graded is None:  # judged on one mesh, refused or failed
        if budget.fits(r.drape_s):
            redress.x_graded, _ = graded_afresh(s, scene)
        else:
            budget.cut(
                "the graded pattern's drape is the one the material choice let settle (no time to dress "
                "it afresh)"
            )
    # the returned drape is the returned pattern dressed from scratch where the check dressed
    # it: a kept phase two's warm drape can lie nearer the target than its pattern dresses
    if redress.x_graded is not None:
        r.x_graded = redress.x_graded
    if redress.phase_two_kept:
        r.x_warm, r.x = r.x, redress.x_fit
    else:  # the graded pattern's rest mesh (= uv(K0)), drape and material
        r.pattern, r.uv, r.x, r.material = (
            s.graded,
            np.asarray(s.mesh.uv, dtype=np.float64),
            r.x_graded,
            s.material,
        )
    r.drapes = _fresh_drapes(redress)


def _fit_result(
    r: _Returned, choice: MaterialChoice, two: PhaseTwo, scene: Scene, clock, budget
) -> FitResult:
    """The FitResult of what the checks returned, ``r``, from phase two ``two`` started at ``choice``."""
    s, cfg = choice.start, scene.cfg
    return FitResult(
        pattern=r.pattern,
        base_pattern=s.base,
        graded_pattern=s.graded,
        mesh=s.mesh,
        x=r.x,
        uv=r.uv,
        material=r.material,
        history=two.history,
        grade_table=s.grade_table,
        timings=clock.total(),
        iterations=len(two.history["total"]),
        converged=two.converged,
        x_graded=r.x_graded,
        x_base=s.x_base,
        x_warm=r.x_warm,
        drapes=r.drapes,
        params=two.params.to("cpu"),
        base_mesh=s.mesh_base,
        start_material=s.material,
        material_choice=choice.table,
        base_name=s.base_name,
        base_choice=list(s.base_choice) or None,
        best_iteration=two.best.iteration,
        material_fitted=two.best.material_on and (r.redress is None or r.redress.phase_two_kept),
        material_start_iteration=cfg.material.start_iteration if cfg.fits_material else None,
        gamma_last=two.gamma_last(),
        redress=r.redress,
        mesh_spread=r.spread,
        drape_check=check_drape(
            r.x, faces=s.mesh.faces, uv=r.uv, faces_uv=s.mesh.faces_uv, body=scene.body, sdf=scene.sdf
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
