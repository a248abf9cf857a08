"""Checks at the pattern boundary: closed counter-clockwise panels, sane stitches.

:func:`validate_pattern` raises :class:`~unsew.errors.PatternError` (one line naming the panel
and edge) for what cannot be sewn, mirrors clockwise panels in place, and returns warnings
for what can be sewn but looks wrong (stitched edges of different lengths).

A clockwise panel is one seen from inside the garment: GarmentCode draws the back and the right
half of a garment that way, so that with their placement every panel's outward normal is
``sign(area) * R @ z``. Such a panel is mirrored (x -> -x in its own frame, curvature mirrored)
and its placement turned half a turn about its own y axis: the same cloth in the same 3D place,
now counter-clockwise seen from outside, its edges numbered and directed as before, so the
file's stitches keep their meaning (side ``a``'s start still meets side ``b``'s end). Reversing
the loop instead would flip the direction of every stitched edge of the panel and sew its seams
twisted.
"""

from __future__ import annotations

import numpy as np

from unsew.errors import PatternError
from unsew.pattern.model import Panel, Pattern, StitchSide
from unsew.tolerances import GEOM_EPS, STITCH_LENGTH_WARN_REL

__all__ = ["validate_pattern", "mirror_panel", "reorient_panel", "signed_area", "find_self_intersection"]

#: Segments per curved edge when testing outlines for self-intersection.
_SEGMENTS_PER_CURVE = 24


def signed_area(panel: Panel) -> float:
    """Signed area [m^2] of the panel's sampled outline (positive when counter-clockwise)."""
    from unsew.pattern.curves import panel_outline

    p = panel_outline(panel, points_per_edge=_SEGMENTS_PER_CURVE)
    q = np.roll(p, -1, axis=0)
    return 0.5 * float(np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]))


def reorient_panel(panel: Panel) -> dict[int, int]:
    """Reverse the panel's loop in place (edge order and each edge's direction, curvature
    re-expressed), turning clockwise into counter-clockwise. Returns the map old edge index ->
    new edge index (``n - 1 - i``)."""
    n = len(panel.edges)
    panel.edges = [e.reversed() for e in reversed(panel.edges)]
    return {i: n - 1 - i for i in range(n)}


def mirror_panel(panel: Panel) -> None:
    """Mirror the panel in place about its own y axis, keeping it where it is in 3D.

    Vertices (x, y) -> (-x, y) [m]; each edge keeps its endpoints (so its index, its direction
    and the stitches on it), its curvature is mirrored (:func:`~unsew.pattern.model.mirror_curvature`);
    the rotation becomes ``R @ diag(-1, 1, -1)`` (half a turn about the panel's y axis), so
    ``R' @ (-x, y, 0) + t == R @ (x, y, 0) + t``: every point stays put in 3D and the panel's
    normal ``R' @ z`` flips. A clockwise panel becomes counter-clockwise."""
    from unsew.pattern.model import matrix_to_euler_xyz, mirror_curvature

    panel.vertices = panel.vertices * np.array([-1.0, 1.0])
    for e in panel.edges:
        if e.curvature is not None:
            e.curvature = mirror_curvature(e.curvature)
    panel.rotation = matrix_to_euler_xyz(panel.rotation_matrix() @ np.diag([-1.0, 1.0, -1.0]))


def _segments(panel: Panel):
    """Outline segments (M, 2, 2) [m] and the edge index (M,) of each."""
    from unsew.pattern.curves import sample_edge

    segs, owner = [], []
    for i, e in enumerate(panel.edges):
        n = _SEGMENTS_PER_CURVE if e.curvature is not None else 1
        pts = sample_edge(panel, i, n)
        segs.append(np.stack([pts[:-1], pts[1:]], axis=1))
        owner.append(np.full(n, i))
    return np.concatenate(segs), np.concatenate(owner)


def find_self_intersection(panel: Panel) -> tuple[int, int] | None:
    """The indices of two edges whose (sampled) curves cross, or None.

    Segments that share an outline vertex (neighbours in the loop) are not tested against
    each other; touching at a shared corner is not a crossing.
    """
    segs, owner = _segments(panel)
    m = len(segs)
    a, b = segs[:, 0], segs[:, 1]  # (M, 2)
    d = b - a

    def cross(u, v):
        return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]

    # For every pair (i, j): orientation of j's ends w.r.t. segment i, and of i's ends w.r.t. j.
    o1 = cross(d[:, None], a[None, :] - a[:, None])  # (M, M)
    o2 = cross(d[:, None], b[None, :] - a[:, None])
    o3 = cross(d[None, :], a[:, None] - a[None, :])
    o4 = cross(d[None, :], b[:, None] - a[None, :])
    scale = float(np.abs(d).max()) ** 2 + GEOM_EPS
    eps = 1e-12 * scale
    hit = (o1 * o2 < 0) & (o3 * o4 < 0)
    hit &= (np.abs(o1) > eps) & (np.abs(o2) > eps) & (np.abs(o3) > eps) & (np.abs(o4) > eps)
    idx = np.arange(m)
    near = (np.abs(idx[:, None] - idx[None, :]) <= 1) | (np.abs(idx[:, None] - idx[None, :]) == m - 1)
    hit &= ~near
    hit &= idx[:, None] < idx[None, :]
    if not hit.any():
        return None
    i, j = np.argwhere(hit)[0]
    return int(owner[i]), int(owner[j])


def _finite(x) -> bool:
    try:
        return bool(np.all(np.isfinite(np.asarray(x, dtype=np.float64))))
    except (TypeError, ValueError):
        return False


def _check_curvature(p: Panel, i: int, w: str) -> None:
    """PatternError (prefixed ``w``) when edge i's curvature is of an unknown kind, holds NaN, or
    is a circle shorter than half its chord."""
    e = p.edges[i]
    c = e.curvature
    if c.kind not in ("quadratic", "cubic", "circle"):
        raise PatternError(f"{w}: unknown curvature type {c.kind!r}")
    vals = c.params[:1] if c.kind == "circle" else c.params
    if not _finite(vals):
        raise PatternError(f"{w} has NaN curvature parameters; fix them")
    if c.kind == "circle":
        chord = float(np.linalg.norm(p.vertices[e.end] - p.vertices[e.start]))
        if float(c.params[0]) < chord / 2 * (1 - 1e-6):
            raise PatternError(
                f"{w}: circle radius {float(c.params[0]):.4g} m is shorter than half the "
                f"chord {chord / 2:.4g} m; enlarge the radius"
            )


def _check_panel(p: Panel) -> None:
    w = f"panel {p.name!r}"
    nv = len(p.vertices)
    if nv < 3:
        raise PatternError(f"{w} has {nv} vertices; a panel needs at least 3")
    if len(p.edges) < 2:
        raise PatternError(f"{w} has {len(p.edges)} edge(s); a panel outline needs a closed loop of edges")
    for name, arr in (("vertices", p.vertices), ("translation", p.translation), ("rotation", p.rotation)):
        if not _finite(arr):
            raise PatternError(f"{w} has NaN or infinite {name}; fix the coordinates")
    for i, e in enumerate(p.edges):
        if not (0 <= e.start < nv and 0 <= e.end < nv):
            raise PatternError(f"{w} edge {i}: endpoint out of range (panel has {nv} vertices)")
        if e.start == e.end or np.linalg.norm(p.vertices[e.end] - p.vertices[e.start]) <= GEOM_EPS:
            raise PatternError(f"{w} edge {i} has zero length (vertices {e.start} and {e.end} coincide)")
        if e.curvature is not None:
            _check_curvature(p, i, f"{w} edge {i}")
    for i, e in enumerate(p.edges):
        nxt = p.edges[(i + 1) % len(p.edges)]
        if e.end != nxt.start:
            j = (i + 1) % len(p.edges)
            raise PatternError(
                f"{w} is not a closed loop: edge {i} ends at vertex {e.end} but edge {j} starts at vertex "
                f"{nxt.start}; order the edges so each starts where the previous one ends"
            )
    hit = find_self_intersection(p)
    if hit is not None:
        raise PatternError(
            f"{w} outline intersects itself: edge {hit[0]} crosses edge {hit[1]}; fix the vertices or "
            "curvature"
        )


def validate_pattern(pattern: Pattern) -> list[str]:
    """Check ``pattern``, normalize it in place, and return warnings (one line each).

    Raises :class:`~unsew.errors.PatternError` for: no panels; a panel with fewer than 3
    vertices; NaN coordinates; an open loop (edge i's end is not edge i+1's start); a zero-length
    edge; a self-intersecting outline; a stitch to a missing panel or edge; an edge stitched
    twice. Clockwise panels are mirrored in place (:func:`mirror_panel`: same 3D placement,
    same edge numbers and stitches) with a warning; stitched edges whose arc lengths differ by more than
    :data:`unsew.tolerances.STITCH_LENGTH_WARN_REL` get a warning.
    """
    from unsew.pattern.curves import edge_length

    if not pattern.panels:
        raise PatternError("the pattern has no panels; add at least one panel")
    warnings: list[str] = []
    for name in pattern.panel_order:
        if name not in pattern.panels:
            raise PatternError(f"panel_order names a missing panel {name!r}")
    for p in pattern.panels.values():
        _check_panel(p)

    _check_stitch_targets(pattern)
    for name, p in pattern.panels.items():
        if signed_area(p) < 0:
            mirror_panel(p)
            warnings.append(
                f"panel {name!r} was clockwise (drawn from inside the garment); mirrored it to make it "
                "counter-clockwise, same place in 3D, same edges and stitches"
            )

    for k, s in enumerate(pattern.stitches):
        la = edge_length(pattern.panels[s.a.panel], s.a.edge)
        lb = edge_length(pattern.panels[s.b.panel], s.b.edge)
        if abs(la - lb) > STITCH_LENGTH_WARN_REL * max(la, lb):
            warnings.append(
                f"stitch {k}: edge {s.a.edge} of panel {s.a.panel!r} is {la * 100:.1f} cm long but edge "
                f"{s.b.edge} of panel {s.b.panel!r} is {lb * 100:.1f} cm "
                f"({abs(la - lb) / max(la, lb) * 100:.0f} % apart)"
            )
    return warnings


def _check_stitch_targets(pattern: Pattern) -> None:
    """PatternError for a stitch to a missing panel or edge, or an edge stitched twice (checked
    before any renumbering)."""
    seen: dict[StitchSide, int] = {}
    for k, s in enumerate(pattern.stitches):
        for side in (s.a, s.b):
            if side.panel not in pattern.panels:
                raise PatternError(
                    f"stitch {k} refers to a missing panel {side.panel!r}; fix the stitch or add the panel"
                )
            ne = len(pattern.panels[side.panel].edges)
            if not (0 <= side.edge < ne):
                raise PatternError(
                    f"stitch {k} refers to edge {side.edge} of panel {side.panel!r}, which has {ne} edges "
                    f"(0-{ne - 1})"
                )
            if side in seen:
                raise PatternError(
                    f"edge {side.edge} of panel {side.panel!r} is stitched twice (stitches {seen[side]} and "
                    f"{k}); split the edge or remove one stitch"
                )
            seen[side] = k
