"""Checks after phase two (not in the paper).

The re-dress check: the optimizer's drapes are warm-started, so a lower loss can come from
steering the cloth along its path rather than from a better pattern. Phase two's best pattern, in
its material, is dressed from scratch on the same mesh; unless it lies closer to the target than
the graded pattern's drape, the graded pattern, its drape and the start material are the result
(docs/history.md, "Re-dressing a fit's result").

The mesh spread: the returned pattern dressed on two other triangulations; how far the folds move
with the mesh alone is the floor under the result's distance to the target (docs/history.md,
"The mesh floor").
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from unsew.dress import dress
from unsew.errors import PatternError, SimulationError
from unsew.fit.config import FitConfig
from unsew.fit.progress import Progress
from unsew.fit.start import Start
from unsew.fit.target import Target
from unsew.grading.grade import moved_mesh
from unsew.meshing import mesh_pattern

__all__ = ["RedressCheck", "MeshSpread", "redress_check", "mesh_spread", "REDRESS_MARGIN_MM"]

#: Phase two's pattern is kept only if, dressed from scratch, it lies at least this much closer
#: to the target than the graded pattern's drape [mm]. An unmoved pattern re-dresses to its
#: graded drape up to round-off, so a tie returns the graded pattern.
REDRESS_MARGIN_MM = 0.01


@dataclass
class RedressCheck:
    """fit_redressed_mm: phase two's pattern dressed from scratch, its distance to the target
    [mm] (None when it was refused); graded_mm: the graded drape's [mm]; phase_two_kept: whether
    phase two's pattern is the result; refused: why phase two's pattern was not dressed ("" when
    it was): it cannot be meshed afresh (a panel squeezed to a sliver, an outline crossing itself),
    so it is no pattern to return."""

    fit_redressed_mm: float | None
    graded_mm: float
    phase_two_kept: bool
    refused: str = ""

    def as_dict(self) -> dict:
        return asdict(self)


@dataclass
class MeshSpread:
    """edge_lengths_m: the two meshes' edge lengths [m]; chamfer_mm: the returned pattern's
    drape on each, its distance to the target [mm] (None: the drape failed); result_mm: the
    result's own distance [mm]."""

    edge_lengths_m: list
    chamfer_mm: list
    result_mm: float

    def as_dict(self) -> dict:
        return asdict(self)


def redress_check(pattern, uv, material, start: Start, body, target: Target, sdf, cfg: FitConfig, *,
                  progress: Progress, log=print) -> RedressCheck:
    """Dress ``pattern`` (rest positions ``uv`` (Nu, 2) [m] on ``start.mesh``'s topology) in
    ``material`` from scratch and compare it with the graded drape ``start.x``. A pattern that
    cannot be meshed afresh (phase two moved the rest mesh's vertices, which can squeeze a panel
    flat while the moved mesh still drapes) is refused and the graded pattern returned."""
    cf_graded = target.distance_mm(start.x, start.mesh.faces)
    try:
        mesh_pattern(pattern, edge_length=cfg.drape.edge_length)
    except PatternError as exc:
        log(f"re-dress check: phase two's pattern cannot be meshed afresh ({exc}): the graded pattern is returned")
        return RedressCheck(None, cf_graded, False, refused=str(exc))
    with progress.phase("re-dress the fit") as bar:
        x = dress(pattern, body, sdf=sdf, mesh=moved_mesh(start.mesh, pattern, uv), material=material,
                  settings=cfg.drape, progress=bar).x.numpy()
    cf_re = target.distance_mm(x, start.mesh.faces)
    kept = bool(cf_re < cf_graded - REDRESS_MARGIN_MM)
    log(f"re-dress check: the fitted pattern dressed from scratch lies {cf_re:.2f} mm from the target, "
        f"the graded one {cf_graded:.2f} mm: " + ("fit kept" if kept else "the graded pattern is returned"))
    return RedressCheck(cf_re, cf_graded, kept)


def mesh_spread(pattern, material, body, target: Target, sdf, cfg: FitConfig, result_mm: float, *,
                progress: Progress, log=print) -> MeshSpread:
    """``pattern`` in ``material`` dressed from scratch (the fit's settings) on meshes of edge
    length x (1 - s) and x (1 + s), s = ``cfg.checks.mesh_spread``. A drape that fails
    (SimulationError, or PatternError: the pattern cannot be meshed at that length) is None: the
    figure is a diagnostic, not the result."""
    h0, s = cfg.drape.edge_length, cfg.checks.mesh_spread
    lengths = [h0 * (1 - s), h0 * (1 + s)]
    out = []
    for h in lengths:
        with progress.phase(f"dress on a {100 * h:.2f} cm mesh") as bar:
            try:
                d = dress(pattern, body, sdf=sdf, material=material, settings=cfg.drape.replace(edge_length=h),
                          progress=bar)
                out.append(target.distance_mm(d.x.numpy(), d.mesh.faces))
            except (SimulationError, PatternError):
                out.append(None)
    spread = MeshSpread(lengths, out, result_mm)
    log(f"mesh spread: the returned pattern dressed on meshes {100 * s:.0f} % finer / coarser lies "
        f"{' / '.join('failed' if v is None else f'{v:.2f} mm' for v in out)} from the target "
        f"(the result {result_mm:.2f} mm)")
    return spread
