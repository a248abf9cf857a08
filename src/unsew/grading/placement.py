"""Where a lower garment is placed on the body before it is dressed (a step of phase one that the
paper does not have).

A skirt or trousers is held at the waist by friction and by its band's tension. Our dressing
(:func:`unsew.dress.dress`: placement, sewing, settling) often leaves such a garment near the
height it was placed at; on 13 of 36 banded foreign targets (draped by another simulator) the
graded drape's waist sat 1.1-5.1 cm below the target's. Grading cannot lift it: a waist found higher
on the target is read as the band's fit or held at its height (:func:`unsew.grading.grade._hold_tops`),
because moving the waist curve would also lengthen the panels. The placement is not the pattern's
shape, so it is chosen as the fabric is, by draping: the graded pattern is dressed again with every
panel lifted by half and by all of the height between the target's top opening and its drape's,
and the closest of the three drapes (mean surface distance) is kept.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Callable

import numpy as np

from unsew.errors import UnsewError
from unsew.losses.contours import open_contours
from unsew.metrics.surface import surface_metrics

__all__ = [
    "LIFT_TOL",
    "LIFT_FRACTIONS",
    "LIFT_SAMPLES",
    "top_height",
    "lifted",
    "lifted_mesh",
    "is_lower",
    "choose_lift",
]

#: Heights [m] between the target's top opening and the drape's below which nothing is tried.
LIFT_TOL = 0.01
#: Parts of that height the candidate placements lift the garment by [-].
LIFT_FRACTIONS = (0.5, 1.0)
#: Surface samples of the distance that decides (the fit's objective's count, unsew.fit.target).
LIFT_SAMPLES = 20_000


def top_height(verts, faces) -> float | None:
    """Mean height [m] (+y) of the vertices of a mesh's highest open contour (by its mean
    height): the waist of a skirt or trousers. verts: (V, 3) float [m]; faces: (F, 3) int.
    None for a closed mesh."""
    v = np.asarray(verts, dtype=np.float64)
    loops = open_contours(v, faces)
    if not loops:
        return None
    return max(float(v[c.indices, 1].mean()) for c in loops)


def lifted(pattern, dy: float):
    """A copy of ``pattern`` (:class:`~unsew.pattern.model.Pattern`) with every panel's placement moved ``dy``
    [m] up (+y); the panels' shapes are unchanged."""
    out = pattern.copy()
    for panel in out.panels.values():
        panel.translation = panel.translation + np.array([0.0, float(dy), 0.0])
    return out


def lifted_mesh(mesh, dy: float):
    """A copy of the GarmentMesh ``mesh`` whose flat panels are placed ``dy`` [m] higher
    (``uv_placed3d``, where :func:`unsew.dress.dress` places a mesh it is given)."""
    return replace(
        mesh, uv_placed3d=np.asarray(mesh.uv_placed3d, dtype=np.float64) + np.array([0.0, float(dy), 0.0])
    )


def is_lower(placed) -> bool:
    """Whether a garment whose open contours are ``placed`` (:class:`~unsew.grading.contours.PlacedContour`
    list) hangs from the waist: it has contours, and none of them lies on an arm."""
    return bool(placed) and all(c.part != "arm" for c in placed)


def choose_lift(
    pattern,
    mesh,
    x,
    body,
    drape_fn: Callable,
    target_verts,
    target_faces,
    may_drape: Callable[[str], bool] | None = None,
) -> tuple[object, object, np.ndarray, dict | None]:
    """The placement of ``pattern`` whose drape lies closest to the target.

    pattern: the graded Pattern, dressed as ``x`` (n_x, 3) [m] on ``mesh``; drape_fn(pattern,
    mesh, body) -> (n_x, 3) [m] dresses a pattern from scratch; target_verts (V, 3) [m],
    target_faces (F, 3): the target. Returns (pattern, mesh, drape, row): the input unchanged and
    row None when the two top openings lie within :data:`LIFT_TOL` of each other; otherwise the
    closest of the input and its :data:`LIFT_FRACTIONS` lifts, and a row saying what was tried
    (``lift_m``, ``tried_m``, ``chamfer_mm`` of each, in the order tried). A candidate whose
    drape fails is left out, and so are the candidates from the first one ``may_drape(what)``
    refuses (a fit's time limit; None: all are draped).
    """
    tv = np.asarray(target_verts, dtype=np.float64)
    t_top, s_top = top_height(tv, target_faces), top_height(x, mesh.faces)
    if t_top is None or s_top is None or abs(t_top - s_top) < LIFT_TOL:
        return pattern, mesh, x, None

    def distance(xx) -> float:
        return surface_metrics(np.asarray(xx), mesh.faces, tv, target_faces, n_samples=LIFT_SAMPLES, seed=0)[
            "chamfer_mm"
        ]

    dy = t_top - s_top
    best = (distance(x), 0.0, pattern, mesh, x)
    tried, chamfers = [0.0], [round(best[0], 3)]
    for frac in LIFT_FRACTIONS:
        what = f"placement: a lift of {frac * dy * 100:+.1f} cm not draped"
        if may_drape is not None and not may_drape(what):
            break
        p, m = lifted(pattern, frac * dy), lifted_mesh(mesh, frac * dy)
        try:
            xl = np.asarray(drape_fn(p, m, body), dtype=np.float64)
        except UnsewError:
            continue
        cf = distance(xl)
        tried.append(round(frac * dy, 5))
        chamfers.append(round(cf, 3))
        if cf < best[0]:
            best = (cf, frac * dy, p, m, xl)
    row = {"lift_m": round(best[1], 5), "wanted_m": round(dy, 5), "tried_m": tried, "chamfer_mm": chamfers}
    return best[2], best[3], best[4], row
