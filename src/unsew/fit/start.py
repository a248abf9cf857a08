"""Phase one of the fit (paper 3.3): the base pattern sized to the wearer, dressed on the body and
graded to the target's open contours. Its hand-off is a :class:`Start`."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from unsew.body.measure import measure_body
from unsew.dress import dress
from unsew.errors import InputError
from unsew.fit.config import FitConfig
from unsew.fit.progress import Progress
from unsew.fit.target import Target
from unsew.grading.grade import grade
from unsew.io.garmentcode import load_pattern
from unsew.losses.contours import open_contours
from unsew.pattern.base import make_base_pattern

__all__ = ["Start", "start", "base_pattern_for"]

#: garment types a base pattern may stand in for (same panel topology)
_COMPATIBLE = {
    "tshirt": {"tshirt", "dress"},
    "dress": {"dress", "tshirt"},
    "pants": {"pants", "shorts"},
    "shorts": {"shorts", "pants"},
    "skirt": {"skirt"},
}


@dataclass
class Start:
    """Where phase two starts from.

    base: the base Pattern; graded: the graded pattern U_LG (the base itself without grading);
    mesh: its GarmentMesh; x: its drape X_LG (n_x, 3) float64 [m] on ``mesh``; grade_table: the
    contour rows of grading; x_base, mesh_base: the base pattern's drape and mesh; material: the
    Material all of these were dressed in.
    """

    base: object
    graded: object
    mesh: object
    x: np.ndarray
    grade_table: list
    x_base: np.ndarray
    mesh_base: object
    material: object

    def replace(self, **changes) -> "Start":
        return dataclasses.replace(self, **changes)


def base_pattern_for(case, cfg: FitConfig):
    """The base pattern: cfg.base (garment name or GarmentCode JSON path) or meta.json's garment,
    sized to the wearer's measurements. Refuses a base of the wrong garment type."""
    base = cfg.base or case.garment
    if not base:
        raise InputError("no base pattern: meta.json names no garment; pass --base tshirt|dress|pants|shorts|skirt|P.json")
    if base in _COMPATIBLE:
        if case.garment and case.garment not in _COMPATIBLE[base]:
            raise InputError(
                f"base pattern {base!r} cannot make a {case.garment} target (meta.json); "
                f"use --base {case.garment}"
            )
        return make_base_pattern(base, measure_body(case.body))
    p = Path(base)
    if p.suffix.lower() != ".json":
        raise InputError(f"--base {base!r} is neither a garment type ({', '.join(_COMPATIBLE)}) nor a .json pattern")
    return load_pattern(p)


def _check_contours_compatible(n_src: int, n_tgt: int, garment: str) -> None:
    if n_tgt == 0:
        raise InputError("the target has no open contours (hem, cuff, neckline): it does not look like a garment")
    if n_src and abs(n_src - n_tgt) > max(2, n_src // 2):
        raise InputError(
            f"the base pattern's garment has {n_src} openings but the target has {n_tgt}: "
            f"the base ({garment or 'custom'}) does not match this target's garment type"
        )


def start(base, body, target: Target, sdf, cfg: FitConfig, material, *, progress: Progress,
          label: str = "drape base", garment: str = "") -> Start:
    """Dress ``base`` on ``body`` in ``material`` and, unless ``cfg.grading`` is off, grade it to
    ``target`` in the same material (:func:`unsew.grading.grade.grade`). Raises InputError when
    the base's openings do not match the target's (``garment`` names the base in the message)."""
    with progress.phase(label) as bar:
        dressed = dress(base, body, sdf=sdf, material=material, settings=cfg.drape, progress=bar)
    x_b = dressed.x.numpy().copy()
    _check_contours_compatible(len(open_contours(x_b, dressed.mesh.faces)), len(target.contours), garment)
    if not cfg.grading:
        return Start(base, base, dressed.mesh, x_b, [], x_b, dressed.mesh, material)

    def drape_fn(p, m, b):
        return dress(p, b, sdf=sdf, mesh=m, material=material, settings=cfg.drape).x.numpy()

    g = grade(base, body, target.verts, target.faces, settings=cfg.drape, material=material, sdf=sdf,
              mesh=dressed.mesh, x_init=x_b, drape_fn=drape_fn)
    return Start(base, g.pattern, g.mesh, np.asarray(g.x_draped), g.table, x_b, dressed.mesh, material)
