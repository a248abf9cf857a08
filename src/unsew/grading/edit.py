"""The control-point edit of linear grading (paper 3.3, Fig. 4).

For each open curve of a matched contour:

- *length*: all the curve's control points move by the contour's extension along
  ``normalise(midpoint(curve ends) - mean(the panel's other control points))``: away from the
  panel's middle when the target contour lies further out (a longer hem), towards it otherwise;
  an armhole moved by the contour of a hanging arm deepens instead (``deepen``, not in the paper:
  :func:`unsew.grading.grade.armhole_down`);
- *width*: the curve's share of the girth difference (its share of the contour's 3D length)
  widens it along the unit chord ``(end - start) / |end - start|``: the start moves back by half,
  the end forward by half, control points in between in proportion to their place along the chord.
  On a curved edge the chord change is scaled by chord / curve length, so the curve's *length*
  changes by the wanted amount.

The wanted positions of all control points are then projected onto the effective control points
K (:meth:`PatternParams.k_from_control_points`, least squares), which keeps the pattern's symmetry:
edits of mirrored or paired panels that disagree are averaged. The mesh follows through
``params.uv(K)`` (per-curve frames and mean value coordinates); an edit that would invert
triangles is scaled back by bisection on its fraction (:func:`safe_fraction`).
"""

from __future__ import annotations

import numpy as np

from unsew.grading.curves import OpenCurve
from unsew.pattern.curves import edge_length
from unsew.pattern.model import Pattern
from unsew.pattern.params import check_inverted
from unsew.tolerances import MIN_TRIANGLE_QUALITY

__all__ = ["curve_edit", "edit_directions", "safe_fraction", "project_edit"]


def edit_directions(
    pattern: Pattern, positions: np.ndarray, curve: OpenCurve, controls
) -> tuple[np.ndarray, np.ndarray, float]:
    """The length direction, the unit chord and the chord length of an open curve.

    pattern: the pattern (for the curve's end vertices when they are not control points).
    positions: (Nc, 2) float64 [m] current control-point positions.
    curve: the open curve. controls: the pattern's :class:`ControlPoints`.

    Returns (d (2,) unit length direction, w (2,) unit chord start -> end, chord [m]).
    """
    panel = pattern.panels[curve.panel]
    cidx = controls.of_panel(curve.panel_index)
    vpos = {int(controls.vertex[g]): positions[g] for g in cidx}
    a = np.asarray(vpos.get(curve.start, panel.vertices[curve.start]), dtype=np.float64)
    b = np.asarray(vpos.get(curve.end, panel.vertices[curve.end]), dtype=np.float64)
    others = [g for g in cidx if g not in set(curve.controls.tolist())]
    ref = positions[others].mean(axis=0) if others else panel.vertices.mean(axis=0)
    d = 0.5 * (a + b) - ref
    nd = float(np.linalg.norm(d))
    d = d / nd if nd > 0 else np.zeros(2)
    w = b - a
    chord = float(np.linalg.norm(w))
    w = w / chord if chord > 0 else np.zeros(2)
    return d, w, chord


def curve_edit(
    pattern: Pattern,
    positions: np.ndarray,
    curve: OpenCurve,
    controls,
    *,
    extension: float,
    girth_change: float,
    deepen: np.ndarray | None = None,
) -> np.ndarray:
    """Displacements (Nc, 2) float64 [m] of all control points for one open curve's edit.

    pattern, positions (Nc, 2) [m], curve, controls: as :func:`edit_directions`.
    extension: how far the curve moves outward [m] (negative: inward).
    girth_change: change of the curve's length [m] (its share of the contour's girth difference).
    deepen: None, or the unit (2,) direction in the panel's frame that its placement points down,
        for an armhole moved by an arm contour (:func:`unsew.grading.grade.armhole_down`): the
        move then deepens the armhole, the curve's lowest control point moving the whole
        ``extension`` along ``deepen``, its highest (the shoulder) not at all, those between in
        proportion to their height.
    Only the curve's own control points move.
    """
    delta = np.zeros_like(positions, dtype=np.float64)
    if len(curve.controls) == 0:
        return delta
    d, w, chord = edit_directions(pattern, positions, curve, controls)
    panel = pattern.panels[curve.panel]
    length2d = sum(edge_length(panel, e) for e in curve.edges)
    dw = girth_change * (chord / length2d if length2d > 0 else 1.0)
    a = (
        positions[curve.controls[0]]
        if int(controls.vertex[curve.controls[0]]) == curve.start
        else panel.vertices[curve.start]
    )
    move = {int(g): extension * d for g in curve.controls}
    if deepen is not None:
        depth = np.array([float(positions[g] @ deepen) for g in curve.controls])
        span = float(depth.max() - depth.min())
        for g, h in zip(curve.controls, depth):
            move[int(g)] = extension * ((h - depth.min()) / span if span > 0 else 1.0) * deepen
    for g in curve.controls:
        t = float((positions[g] - a) @ w) / chord if chord > 0 else 0.5
        delta[g] += move[int(g)] + (t - 0.5) * dw * w
    return delta


def project_edit(params, wanted) -> "torch.Tensor":  # noqa: F821
    """Effective control points K (Nk, 2) torch float64 [m] closest to the wanted control-point
    positions (Nc, 2) [m] (symmetric edits averaged)."""
    return params.k_from_control_points(np.asarray(wanted, dtype=np.float64))


def safe_fraction(params, K0, K1, *, iterations: int = 12) -> float:
    """The largest fraction t in [0, 1] (by bisection) such that ``K0 + t (K1 - K0)`` inverts no
    triangle of the rest mesh; 1.0 when the whole edit is safe, 0.0 when even a tiny one is not.

    params: :class:`~unsew.pattern.params.PatternParams`. K0, K1: (Nk, 2) torch float64 [m].
    """
    import torch

    faces = params.mesh.faces_uv

    def ok(t: float) -> bool:
        with torch.no_grad():
            return (
                len(check_inverted(params.uv(K0 + t * (K1 - K0)), faces, min_quality=MIN_TRIANGLE_QUALITY))
                == 0
            )

    if ok(1.0):
        return 1.0
    lo, hi = 0.0, 1.0
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        if ok(mid):
            lo = mid
        else:
            hi = mid
    return lo
