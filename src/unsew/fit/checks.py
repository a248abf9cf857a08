"""Checks after phase two (not in the paper).

The re-dress check: the optimizer's drapes are warm-started, so a lower loss can come from
steering the cloth along its path rather than from a better pattern. Phase two's best pattern, in
its material, is dressed from scratch on the same mesh; unless it lies closer to the target than
the graded pattern's drape, the graded pattern, its drape and the start material are the result.

With :data:`REDRESS_MESHES` 3 the check judges on three meshes instead of one (docs/decisions/005: one
drape of a wide garment moves by more than phase two changes it, and the graded drape it is
compared with was chosen among the material candidates' drapes for being close): both patterns are
dressed from scratch on the fit's mesh and on the mesh spread's two, and phase two is kept if its
mean distance lies below the graded pattern's (:func:`redress_on_three`).

The mesh spread: the returned pattern dressed on two other triangulations; how far the folds move
with the mesh alone is the floor under the result's distance to the target.

Every drape from scratch these checks make is judged as the result is
(:func:`unsew.sim.checks.check_dressed`): one that ends exploded, fallen, off the body or inside
it is a failed drape, whatever its distance to the target. A drape torn at a shrunk neckline can
lie close to the target; kept for that, it would become the result and fail the fit's last check
(docs/decisions/006).
"""

from __future__ import annotations

import math
from dataclasses import asdict, astuple, dataclass, field, fields

import numpy as np

from unsew.dress import dress
from unsew.errors import PatternError, SimulationError
from unsew.fit.config import FitConfig
from unsew.fit.scene import Scene
from unsew.fit.start import Start
from unsew.grading.grade import moved_mesh
from unsew.meshing import mesh_pattern
from unsew.pattern.curves import panel_outline
from unsew.pattern.validate import validate_pattern
from unsew.sim.checks import check_dressed

__all__ = [
    "RedressCheck",
    "MeshSpread",
    "redress_check",
    "redress_on_three",
    "graded_afresh",
    "mesh_spread",
    "spread_lengths",
    "mm_list",
    "unmoved",
    "kept_on_meshes",
    "REDRESS_MARGIN_MM",
    "REDRESS_MESHES",
    "UNMOVED_TOL",
]

#: meshes the re-dress check judges on: 3, both patterns dressed from scratch on the fit's mesh and
#: the mesh spread's two, means compared; 1, the fit's mesh alone (docs/decisions/005) [-]
REDRESS_MESHES = 3

#: Phase two's pattern is kept only if, dressed from scratch, it lies at least this much closer
#: to the target than the graded pattern's drape [mm]. An unmoved pattern re-dresses to its
#: graded drape up to round-off, so a tie returns the graded pattern.
REDRESS_MARGIN_MM = 0.01
#: Phase two's pattern and material within this of the graded ones (panel outlines [m], material
#: figures relative [-]) are the graded ones: phase two moved nothing, and drapes of the two on other
#: meshes would differ by round-off grown through the steps alone (:func:`unmoved`).
UNMOVED_TOL = 1e-9


@dataclass(frozen=True)
class RedressCheck:
    """fit_redressed_mm: phase two's pattern dressed from scratch, its distance to the target
    [mm] (None when it was refused or its drape failed); graded_mm: the graded drape's [mm];
    phase_two_kept: whether phase two's pattern is the result; refused: why phase two's pattern
    was not dressed ("" when it was): it cannot be meshed afresh (a panel squeezed to a sliver, an
    outline crossing itself), so it is no pattern to return; failed: why its drape from scratch
    on the fit's mesh failed its check (exploded, fallen, ...; "" when it did not), which returns
    the graded pattern too.

    Judged on three meshes (:func:`redress_on_three`): edge_lengths_m, the fit's mesh and the
    spread's two [m]; fit_mm and graded_fresh_mm, each pattern dressed from scratch on each of
    them, its distance to the target [mm] (None: that drape failed); fit_mean_mm and
    graded_mean_mm, their means over the meshes where the graded drape did not fail [mm]. On one
    mesh these are None and meshes is 1.

    x_fit, x_graded: the drapes from scratch on the fit's mesh (Nx, 3) [m] of phase two's
    pattern and of the graded pattern (None: not dressed, or the drape failed); the fit returns
    the kept pattern's, so the result's drape is one that dressing its pattern reproduces. Not
    in :meth:`as_dict`."""

    fit_redressed_mm: float | None
    graded_mm: float
    phase_two_kept: bool
    refused: str = ""
    failed: str = ""
    meshes: int = 1
    edge_lengths_m: list | None = None
    fit_mm: list | None = None
    graded_fresh_mm: list | None = None
    fit_mean_mm: float | None = None
    graded_mean_mm: float | None = None
    x_fit: np.ndarray | None = field(default=None, repr=False)
    x_graded: np.ndarray | None = field(default=None, repr=False)

    def as_dict(self) -> dict:
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name not in ("x_fit", "x_graded")}


@dataclass(frozen=True)
class MeshSpread:
    """edge_lengths_m: the two meshes' edge lengths [m]; chamfer_mm: the returned pattern's
    drape on each, its distance to the target [mm] (None: the drape failed); result_mm: the
    result's own distance [mm]."""

    edge_lengths_m: list
    chamfer_mm: list
    result_mm: float

    def as_dict(self) -> dict:
        return asdict(self)


def redress_check(pattern, uv, material, start: Start, scene: Scene) -> RedressCheck:
    """Dress ``pattern`` (rest positions ``uv`` (Nu, 2) [m] on ``start.mesh``'s topology) in
    ``material`` from scratch on ``scene.body`` and compare it with the graded drape ``start.x``.
    A pattern that cannot be meshed afresh (phase two moved the rest mesh's vertices, which can
    squeeze a panel flat while the moved mesh still drapes) or that its own reader would refuse
    (:func:`unsew.pattern.validate.validate_pattern`: an outline crossing itself at a corner,
    which meshing can survive) is refused and the graded pattern returned: written, it could not
    be loaded back."""
    body, target, cfg, log = scene.body, scene.target, scene.cfg, scene.log
    cf_graded = target.distance_mm(start.x, start.mesh.faces)
    try:
        # an outline crossing itself, which a mesh can survive, is refused too
        validate_pattern(pattern.copy())
        mesh_pattern(pattern, edge_length=cfg.drape.edge_length)
    except PatternError as exc:
        log(
            f"re-dress check: phase two's pattern cannot be meshed afresh or read back ({exc}): "
            "the graded pattern is returned"
        )
        return RedressCheck(None, cf_graded, False, refused=str(exc))
    with scene.progress.phase("re-dress the fit") as bar:
        try:
            x, failed = _judged(
                dress(
                    pattern,
                    body,
                    sdf=scene.sdf,
                    mesh=moved_mesh(start.mesh, pattern, uv),
                    material=material,
                    settings=cfg.drape,
                    progress=bar,
                ),
                body,
            )
        except SimulationError as exc:  # phase two's pattern cannot be dressed: the graded one stands
            x, failed = None, str(exc)
    if failed:
        log(
            f"re-dress check: the fitted pattern dressed from scratch failed ({failed}): the graded pattern "
            "is returned"
        )
        return RedressCheck(None, cf_graded, False, failed=failed)
    cf_re = target.distance_mm(x, start.mesh.faces)
    kept = bool(cf_re < cf_graded - REDRESS_MARGIN_MM)
    log(
        f"re-dress check: the fitted pattern dressed from scratch lies {cf_re:.2f} mm from the target, "
        f"the graded one {cf_graded:.2f} mm: " + ("fit kept" if kept else "the graded pattern is returned")
    )
    return RedressCheck(cf_re, cf_graded, kept, x_fit=x)


def kept_on_meshes(fit_mm: list, graded: list) -> tuple[bool, float | None, float | None, str]:
    """Whether phase two's pattern is kept over its drapes from scratch on several meshes.

    fit_mm, graded: each pattern's distance to the target [mm] on each mesh, None where its drape
    failed its check. Phase two's pattern is kept when its drapes fail on fewer meshes than the
    graded pattern's (it is the one that can be dressed); otherwise when it failed on none of the
    meshes where the graded drape succeeded and its mean distance over those lies
    REDRESS_MARGIN_MM below the graded one's. Returns (kept, phase two's mean or None, the graded
    mean or None, a note for the log: "" unless failures decided)."""
    pairs = [(a, b) for a, b in zip(fit_mm, graded) if b is not None]
    failed = any(a is None for a, _ in pairs)
    fit_mean = None if failed or not pairs else sum(a for a, _ in pairs) / len(pairs)
    graded_mean = sum(b for _, b in pairs) / len(pairs) if pairs else None
    n_fit, n_graded = sum(a is None for a in fit_mm), sum(b is None for b in graded)
    if n_fit < n_graded:
        return (
            True,
            fit_mean,
            graded_mean,
            (
                f" (the graded pattern's drapes failed on {n_graded} of {len(graded)} "
                f"meshes, phase two's on {n_fit})"
            ),
        )
    kept = fit_mean is not None and graded_mean is not None and fit_mean < graded_mean - REDRESS_MARGIN_MM
    return kept, fit_mean, graded_mean, ""


def redress_on_three(
    first: RedressCheck, pattern, material, start: Start, scene: Scene
) -> tuple[RedressCheck, MeshSpread]:
    """The re-dress check judged on three meshes. ``first`` is :func:`redress_check`'s verdict on
    the fit's mesh (phase two's ``pattern`` in ``material`` dressed from scratch; not refused).
    The graded pattern is dressed from scratch in its material on the fit's mesh (``start.x`` was
    let settle from another material's drape, so it is not one), and both patterns on the mesh
    spread's two meshes (:func:`spread_lengths`). Phase two is kept if its mean distance over the
    meshes where the graded drape succeeded lies REDRESS_MARGIN_MM below the graded pattern's
    mean, and it failed on none of them, or if its drapes failed on fewer meshes than the graded
    one's (:func:`kept_on_meshes`). Also returns the mesh spread of the returned pattern,
    from these drapes (no further drape is needed)."""
    lengths = spread_lengths(scene.cfg)
    x_graded, g0 = graded_afresh(start, scene)
    graded = [g0] + [
        _dressed_mm(start.graded, start.material, scene, h, "the graded pattern") for h in lengths
    ]
    if unmoved(pattern, material, start):  # the same pattern: its drapes are the graded ones
        scene.log("re-dress check: phase two moved neither the pattern nor the material")
        fit_mm = [first.fit_redressed_mm] + graded[1:]
    else:
        fit_mm = [first.fit_redressed_mm] + [
            _dressed_mm(pattern, material, scene, h, "phase two's pattern") for h in lengths
        ]
    kept, fit_mean, graded_mean, why = kept_on_meshes(fit_mm, graded)
    scene.log(
        f"re-dress check on three meshes: the fitted pattern dressed from scratch lies {mm_list(fit_mm)} mm "
        f"from the target, the graded one {mm_list(graded)} mm: "
        + ("fit kept" if kept else "the graded pattern is returned")
        + why
    )
    check = RedressCheck(
        first.fit_redressed_mm,
        first.graded_mm,
        kept,
        meshes=3,
        edge_lengths_m=[scene.cfg.drape.edge_length, *lengths],
        fit_mm=fit_mm,
        graded_fresh_mm=graded,
        fit_mean_mm=fit_mean,
        graded_mean_mm=graded_mean,
        x_fit=first.x_fit,
        x_graded=x_graded,
    )
    spread = MeshSpread(
        lengths,
        fit_mm[1:] if kept else graded[1:],
        fit_mm[0] if kept else (first.graded_mm if g0 is None else g0),
    )
    return check, spread


def unmoved(pattern, material, start: Start) -> bool:
    """Whether phase two's ``pattern`` and ``material`` are the graded ones (``start.graded``,
    ``start.material``) up to :data:`UNMOVED_TOL`: the same panels, their outlines (curves
    sampled) that far apart at most [m], and every material figure that close relatively. Phase
    two rebuilds the pattern from its parameters, so an unmoved pattern differs from the graded
    one by round-off, which a drape from scratch on a freshly meshed panel can grow to tenths of
    a millimetre."""
    a, b = pattern.panels, start.graded.panels
    if a.keys() != b.keys() or any(len(a[n].edges) != len(b[n].edges) for n in a):
        return False
    for n in a:  # outlines sampled along their curves, so a moved control point of a curve counts
        oa, ob = panel_outline(a[n]), panel_outline(b[n])
        if oa.shape != ob.shape or np.abs(oa - ob).max(initial=0.0) > UNMOVED_TOL:
            return False
    return all(
        math.isclose(u, v, rel_tol=UNMOVED_TOL, abs_tol=1e-12)
        for u, v in zip(astuple(material), astuple(start.material))
    )


def graded_afresh(start: Start, scene: Scene) -> tuple[np.ndarray | None, float | None]:
    """The graded pattern in its material dressed from scratch on the fit's mesh (``start.x`` was
    let settle from another material's drape): the drape (Nx, 3) [m] and its distance to the
    target [mm], or (None, None) when the drape fails (raises, or fails its check)."""
    with scene.progress.phase("dress the graded pattern afresh") as bar:
        try:
            x, failed = _judged(
                dress(
                    start.graded,
                    scene.body,
                    sdf=scene.sdf,
                    mesh=start.mesh,
                    material=start.material,
                    settings=scene.cfg.drape,
                    progress=bar,
                ),
                scene.body,
            )
        except SimulationError:
            return None, None
    return (None, None) if failed else (x, scene.target.distance_mm(x, start.mesh.faces))


def _judged(d, body) -> tuple[np.ndarray, str]:
    """A :class:`unsew.dress.Dressed` as its drape (Nx, 3) [m] and why it fails its check
    (:func:`unsew.sim.checks.check_dressed`; "" when it passes)."""
    verdict = check_dressed(d, body=body)
    return d.x.numpy(), verdict.reason


def mm_list(values, digits: int = 2) -> str:
    """Distances [mm] (None: a drape that failed) as "a / b / failed"."""
    return " / ".join("failed" if v is None else f"{v:.{digits}f}" for v in values)


def spread_lengths(cfg: FitConfig) -> list[float]:
    """The mesh spread's two edge lengths, x (1 - s) and x (1 + s) the fit's, s =
    ``cfg.checks.mesh_spread`` [m]."""
    h0, s = cfg.drape.edge_length, cfg.checks.mesh_spread
    return [h0 * (1 - s), h0 * (1 + s)]


def _dressed_mm(pattern, material, scene: Scene, h: float, what: str) -> float | None:
    """``pattern`` in ``material`` meshed at edge length ``h`` [m] and dressed from scratch (the
    fit's settings): its distance to the target [mm], or None when the drape fails
    (SimulationError, its check, or PatternError: the pattern cannot be meshed at that length)."""
    with scene.progress.phase(f"dress {what} on a {100 * h:.2f} cm mesh") as bar:
        try:
            d = dress(
                pattern,
                scene.body,
                sdf=scene.sdf,
                material=material,
                settings=scene.cfg.drape.replace(edge_length=h),
                progress=bar,
            )
        except (SimulationError, PatternError):
            return None
    x, failed = _judged(d, scene.body)
    return None if failed else scene.target.distance_mm(x, d.mesh.faces)


def mesh_spread(pattern, material, scene: Scene, result_mm: float) -> MeshSpread:
    """``pattern`` in ``material`` dressed from scratch (the fit's settings) on the meshes of
    :func:`spread_lengths`. A drape that fails is None: the figure is a diagnostic, not the
    result."""
    lengths = spread_lengths(scene.cfg)
    out = [_dressed_mm(pattern, material, scene, h, "the result") for h in lengths]
    spread = MeshSpread(lengths, out, result_mm)
    scene.log(
        f"mesh spread: the returned pattern dressed on meshes {100 * scene.cfg.checks.mesh_spread:.0f} % "
        "finer / "
        f"coarser lies {mm_list(out)} mm from the target "
        f"(the result {result_mm:.2f} mm)"
    )
    return spread
