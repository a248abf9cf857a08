"""Judge a drape: is the garment on the body, whole, and outside it?

A simulation that ran to the end is not yet a success: a garment can slide off the body, fall
to the floor, tear its triangles to many times their length or end up inside the body, and
still come back without an error. :func:`check_drape` looks at the final positions and returns
a :class:`DrapeVerdict`; a bad verdict names the first failed check in one line, so ``unsew
drape`` (and the fit) can stop with that line instead of writing a result that looks finished.

Checks, in order (the first that fails is the reason):

1. ``exploded``: a position is NaN or infinite.
2. ``exploded``: an edge is stretched beyond :data:`STRETCH_MAX` times its pattern length, or
   the 99th percentile beyond :data:`STRETCH_P99_MAX`.
3. ``fallen``: the garment's lowest point is below the body's lowest point (the floor) by more
   than :data:`FLOOR_TOL`; or its highest point is below the body's crotch (nothing holds a
   garment up there); or, when the start of the drape is given, it has dropped by more than
   :data:`DROP_MAX` from where it was placed (a waistband slid down the hips, a top slid off
   the shoulders): the median of its vertices' drops when their start heights are given (a
   hood placed above the head and falling onto it is a minority of them), else the drop of
   its mean height; or its top (the :data:`TOP_QUANTILE` quantile of its vertex heights) has
   dropped by more than :data:`TOP_DROP_MAX` from the start's and ends below the shoulder
   joints (a top whose sleeves and bodice slid off the shoulders into a heap at the hips drops
   its median less than its top; a hood falling onto the head ends above the shoulders); or,
   in :func:`check_dressed` given the top of the pattern's own placement (its panels'
   translation and rotation), its top ends more than :data:`TOP_DROP_MAX` below that and below
   the shoulder joints (a start that already lay low, a bodice placed at the hips, drops
   nothing from itself).
   ``rose``: when the start's vertex heights are given, more than :data:`RISE_MAX_PCT` % of the
   vertices ended above the body's chest joint and more than :data:`RISE_DIST` above where
   they were placed (a top gathered up round the neck, a skirt bunched on the shoulders; a
   circle skirt's hem flaring out rises as much, but below the chest).
4. ``off the body``: more than :data:`FAR_MAX_PCT` % of the vertices lie above the body's
   crotch and further than :data:`FAR_DIST` from the body (below the crotch a wide skirt hangs
   free of the legs; a garment fallen there fails the height checks).
5. ``inside the body``: more than :data:`INSIDE_MAX_PCT` % of the vertices are inside it.
6. ``crumpled``: the draped surface's area is below :data:`AREA_MIN` times the pattern's (cloth
   does not shrink: a garment gathered into a strip or a ball loses area, a folded one does not).
7. ``unsewn``: in :func:`check_dressed` asked for it (``seam_gap_max``, as ``unsew drape`` asks
   for :data:`SEAM_GAP_MAX`), a seam still open wider than that when the sewing phase ended (the
   two copies of a seam vertex apart before they are merged): the panels never met where the
   seam is, and the garment merged from them is not the one sewn (a sleeve left hanging beside
   the torso, docs/decisions/053).
8. ``off the arm``: in :func:`check_dressed` given the sleeves' vertices (:func:`sleeve_vertices`:
   the panels the pattern's own placement puts round an arm), a sleeve whose cloth along the
   upper arm covers less than :data:`SLEEVE_COVER_MIN` of the directions round the arm's bone:
   the arm is not in it (a top worn off its shoulders, its sleeves bunched beside the arms or
   the torso, docs/decisions/062); or one with too little cloth along the upper arm to judge
   that lies farther than :data:`SLEEVE_ROOT_NEAR` from its shoulder joint (a top slid down
   the arms to the hips, its sleeves with it).

The thresholds are failure bounds, far from a good drape's figures (a good drape has < 0.5 %
inside, stretch below 1.5).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, replace

import numpy as np

from unsew.errors import SimulationError

__all__ = [
    "DrapeVerdict",
    "check_drape",
    "check_dressed",
    "placed_top",
    "sleeve_vertices",
    "sleeves_judged",
    "SLEEVE_COVER_MIN",
    "STRETCH_MAX",
    "STRETCH_P99_MAX",
    "AREA_MIN",
    "FLOOR_TOL",
    "DROP_MAX",
    "TOP_DROP_MAX",
    "RISE_DIST",
    "RISE_MAX_PCT",
    "FAR_DIST",
    "FAR_MAX_PCT",
    "INSIDE_MAX_PCT",
]

#: Largest edge length over its pattern length [-] before a drape counts as exploded.
STRETCH_MAX = 3.0
#: Largest 99th percentile of edge stretch [-] (a garment torn all over, not one bad seam vertex).
STRETCH_P99_MAX = 1.6
#: Smallest draped area over pattern area [-] (docs/decisions/046).
AREA_MIN = 0.85
#: How far below the body's lowest point the garment may reach [m] (cloth lying on the floor).
FLOOR_TOL = 0.02
#: How far the garment's mean height may drop from where the drape started [m].
DROP_MAX = 0.10
#: How far the garment's top may drop from where the drape started [m] (docs/decisions/034).
TOP_DROP_MAX = 0.20
#: The quantile of the vertex heights that stands for the garment's top [-].
TOP_QUANTILE = 0.98
#: A vertex that ends above the body's chest joint and more than this above where it was
#: placed has risen [m].
RISE_DIST = 0.20
#: Largest share of risen vertices [%].
RISE_MAX_PCT = 5.0
#: A vertex further than this from every body vertex is off the body [m].
FAR_DIST = 0.15
#: Largest share of vertices off the body [%].
FAR_MAX_PCT = 30.0
#: Largest share of vertices inside the body [%].
INSIDE_MAX_PCT = 5.0
#: Widest seam left open when the sewing phase ends [m] (the ``unsewn`` check, docs/decisions/053).
SEAM_GAP_MAX = 0.02
#: Least share of the directions round an upper arm that its sleeve's cloth covers [-] (the
#: ``off the arm`` check, docs/decisions/062).
SLEEVE_COVER_MIN = 0.5
#: The stretch of the bone from shoulder to elbow (fractions of it) where a sleeve is judged:
#: below a short sleeve's hem, clear of the armpit.
SLEEVE_BAND = (0.2, 0.7)
#: Farthest from the bone a sleeve vertex counts [m] (a skirt's side gore read as a sleeve hangs
#: 0.2-0.3 m from it at the waist; a sleeve bunched beside the arm lies 0.08-0.15 m off).
SLEEVE_NEAR = 0.18
#: Fewest sleeve vertices in that band for a judgment (a cap sleeve ends above it) [-].
SLEEVE_MIN_POINTS = 8
#: A sleeve with too few vertices along the upper arm to judge passes only with one within this
#: distance of its shoulder joint [m] (a cap sleeve's armhole goes round it; decision 069).
SLEEVE_ROOT_NEAR = 0.15
#: Directions round the bone counted [-].
SLEEVE_SECTORS = 24


@dataclass(frozen=True)
class DrapeVerdict:
    """What :func:`check_drape` found.

    ok: every check passed. reason: one line naming the failed check ("" when ok).
    inside_pct: vertices inside the body [%]. depth_mm: deepest vertex inside [mm] (0 if none).
    far_pct: vertices above the body's crotch and further than FAR_DIST from the body [%] (of
    all the vertices).
    stretch_max, stretch_p99: largest and 99th-percentile edge length over pattern length [-].
    y_min, y_max: the garment's height range [m]. drop: how far it fell from the start [m]: the
    median of its vertices' drops (start_y given), else of its mean height (start_height given),
    else NaN. finite: no NaN or inf. rise_pct: vertices above the body's chest joint and more
    than RISE_DIST above where they were placed [%] (NaN when start_y was not given).
    top_drop: how far the garment's top (TOP_QUANTILE of the heights) fell from the start's [m]
    (NaN when start_y was not given). area_ratio: the draped surface's area over the pattern's [-].
    """

    ok: bool
    reason: str
    inside_pct: float
    depth_mm: float
    far_pct: float
    stretch_max: float
    stretch_p99: float
    y_min: float
    y_max: float
    drop: float
    finite: bool
    rise_pct: float = float("nan")
    top_drop: float = float("nan")
    area_ratio: float = float("nan")

    def as_dict(self) -> dict:
        """The verdict as a JSON-able dict (a figure that was not measured, NaN, is None)."""
        return {
            k: None if isinstance(v, float) and not np.isfinite(v) else v for k, v in asdict(self).items()
        }

    def raise_if_bad(self, what: str = "drape") -> None:
        """Raise :class:`~unsew.errors.SimulationError` with ``"<what> failed: <reason>"``
        when the verdict is bad."""
        if not self.ok:
            raise SimulationError(f"{what} failed: {self.reason}")


def _edges(faces: np.ndarray, faces_uv: np.ndarray):
    e = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    eu = faces_uv[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    return e, eu


def check_drape(
    x,
    *,
    faces,
    uv,
    faces_uv,
    body,
    sdf=None,
    start_height=None,
    start_y=None,
) -> DrapeVerdict:
    """Judge a draped garment (see the module docstring for the checks).

    Args:
        x: draped sewn vertices [m], (N, 3), float (numpy or torch).
        faces: (F, 3) int triangles into ``x``. uv: pattern (rest) positions [m], (Nu, 2).
        faces_uv: (F, 3) int the same triangles into ``uv`` (edge rest lengths come from it).
        body: unsew.body.body.Body (verts [m] and skeleton: the floor, the crotch).
        sdf: the body's BodySDF for the inside test (built, disk-cached, when None).
        start_height: optional mean vertex height [m] of the garment where the drape started
            (the placed panels): the drop check.
        start_y: optional (N,) height [m] of each vertex of ``x`` where the drape started: the
            rise check, and the drop check in place of ``start_height``.

    Returns:
        :class:`DrapeVerdict`.
    """
    x, uv = _float64(x), _float64(uv)
    faces, faces_uv = np.asarray(faces, dtype=np.int64), np.asarray(faces_uv, dtype=np.int64)
    broken = _broken(x)
    if broken is not None:
        return broken
    s_max, s_99 = _stretch(x, faces, uv, faces_uv)
    area_ratio = _area_ratio(x, faces, uv, faces_uv)
    crotch = _crotch_height(body)
    inside_pct, depth_mm, far_pct = _body_gaps(x, body, sdf, crotch=crotch)
    y_min, y_max = float(x[:, 1].min()), float(x[:, 1].max())
    drop, rise_pct, top_drop = _moved(
        x, start_height, start_y, chest=float(body.skeleton.position("chest")[1])
    )
    floor = float(np.asarray(body.verts, dtype=np.float64)[:, 1].min())
    drops = (drop, top_drop, float(np.quantile(x[:, 1], TOP_QUANTILE)))
    heights = _height_failure(y_min, y_max, drops, floor=floor, crotch=crotch, shoulder=_shoulder(body))
    reason = _stretch_failure(s_max, s_99) or heights or _rise_failure(rise_pct)
    reason = reason or _body_failure(far_pct, inside_pct) or _area_failure(area_ratio)
    figures = (inside_pct, depth_mm, far_pct, s_max, s_99, y_min, y_max, drop, True, rise_pct, top_drop)
    return DrapeVerdict(reason == "", reason, *figures, area_ratio=area_ratio)


def _broken(x: np.ndarray) -> DrapeVerdict | None:
    """The verdict on positions x (N, 3) [m] with no vertex or with a NaN or infinite one, else None."""
    nan = float("nan")
    if len(x) == 0:
        return DrapeVerdict(
            False, "the garment has no vertices", nan, nan, nan, nan, nan, nan, nan, nan, True
        )
    bad_rows = ~np.isfinite(x).all(axis=1)
    if bad_rows.any():
        bad, n_bad = int(np.flatnonzero(bad_rows)[0]), int(bad_rows.sum())
        reason = f"exploded: {n_bad} vertices are NaN or infinite (first: vertex {bad})"
        return DrapeVerdict(False, reason, *([nan] * 8), False)
    return None


def _moved(x, start_height, start_y, *, chest) -> tuple[float, float, float]:
    """(drop [m], rise_pct [%], top_drop [m]) of the vertices x (N, 3) [m] from the start (see
    :class:`DrapeVerdict`; chest: the body's chest joint height [m]): from the heights start_y
    (N,) [m] when given, else the drop of the mean height from start_height [m] (NaN when
    neither is given), no rise and no top drop (NaN)."""
    nan = float("nan")
    if start_y is None:
        return (nan if start_height is None else float(start_height) - float(x[:, 1].mean())), nan, nan
    y0 = _float64(start_y).reshape(-1)
    if y0.shape != (len(x),):
        raise ValueError(f"start_y must hold one height per vertex ({len(x)}), got shape {y0.shape}")
    rose = (x[:, 1] - y0 > RISE_DIST) & (x[:, 1] > chest)
    top_drop = float(np.quantile(y0, TOP_QUANTILE) - np.quantile(x[:, 1], TOP_QUANTILE))
    return float(np.median(y0 - x[:, 1])), float(rose.mean() * 100.0), top_drop


def _rise_failure(rise_pct) -> str:
    """The reason of a failed rise check ("" when it passes or was not made); share [%]."""
    if np.isfinite(rise_pct) and rise_pct > RISE_MAX_PCT:
        return (
            f"rose: {rise_pct:.0f} % of the vertices ended above the chest, more than {RISE_DIST:g} m "
            f"above where they were put on (bound {RISE_MAX_PCT:g} %)"
        )
    return ""


def _float64(a) -> np.ndarray:
    """A numpy or torch array as a float64 numpy array."""
    import torch

    return np.asarray(a.detach().cpu().numpy() if torch.is_tensor(a) else a, dtype=np.float64)


def _stretch(x, faces, uv, faces_uv) -> tuple[float, float]:
    """Largest and 99th-percentile edge length over pattern length [-] of the triangles
    ``faces`` (F, 3) into ``x`` (N, 3) [m], rest lengths from ``faces_uv`` into ``uv`` (Nu, 2) [m]."""
    e, eu = _edges(faces, faces_uv)
    L = np.linalg.norm(x[e[:, 0]] - x[e[:, 1]], axis=1)
    L0 = np.maximum(np.linalg.norm(uv[eu[:, 0]] - uv[eu[:, 1]], axis=1), 1e-12)
    ratio = L / L0
    return float(ratio.max()), float(np.percentile(ratio, 99))


def _area_ratio(x, faces, uv, faces_uv) -> float:
    """The triangles' total area in ``x`` (N, 3) [m] over their total in ``uv`` (Nu, 2) [m] [-]."""
    from unsew.geometry.repair import triangle_areas
    from unsew.meshing.triangulate import signed_areas

    a3 = triangle_areas(x, faces).sum()
    return float(a3 / max(np.abs(signed_areas(uv, faces_uv)).sum(), 1e-15))


def _area_failure(area_ratio) -> str:
    """The reason of a failed area check ("" when it passes); ratio [-]."""
    if area_ratio < AREA_MIN:
        return (
            f"crumpled: the draped surface is {area_ratio * 100:.0f} % of the pattern's area "
            f"(bound {AREA_MIN * 100:.0f} %)"
        )
    return ""


def _body_gaps(x, body, sdf, *, crotch=-np.inf) -> tuple[float, float, float]:
    """(inside_pct, depth_mm, far_pct) of the vertices ``x`` (N, 3) [m]: share inside the body
    [%] by its SDF (built when None), deepest of them [mm] (0 if none), share above ``crotch``
    [m] and further than FAR_DIST from every body vertex [%]."""
    import torch
    from scipy.spatial import cKDTree

    if sdf is None:
        from unsew.body.sdf import BodySDF

        sdf = BodySDF.build(body)
    with torch.no_grad():
        d, _ = sdf.query(torch.as_tensor(x, dtype=torch.float64))
    d = d.numpy()
    inside_pct = float((d < 0).mean() * 100.0)
    depth_mm = float(max(0.0, -float(d.min())) * 1000.0)
    bv = np.asarray(body.verts, dtype=np.float64)
    far = cKDTree(bv).query(x, distance_upper_bound=FAR_DIST)[0]
    far_pct = float((np.isinf(far) & (x[:, 1] > crotch)).mean() * 100.0)
    return inside_pct, depth_mm, far_pct


def _stretch_failure(s_max, s_99) -> str:
    """The reason of the first failed stretch check ("" when both pass); stretches [-]."""
    if s_max > STRETCH_MAX:
        return (
            f"exploded: an edge is stretched to {s_max:.1f} times its pattern length (bound {STRETCH_MAX:g})"
        )
    if s_99 > STRETCH_P99_MAX:
        return (
            f"exploded: 1 % of the edges are stretched beyond {s_99:.2f} times their pattern length "
            f"(bound {STRETCH_P99_MAX:g})"
        )
    return ""


def _shoulder(body) -> float:
    """Height of the lower shoulder joint [m]."""
    sk = body.skeleton
    return float(min(sk.position("left_shoulder")[1], sk.position("right_shoulder")[1]))


def _height_failure(y_min, y_max, drops, *, floor, crotch, shoulder) -> str:
    """The reason of the first failed height check, in the module docstring's order ("" when
    all pass). Heights, drops (drop, top_drop, the top's height y_top), floor (the body's lowest
    point), crotch and shoulder (the lower shoulder joint) [m]."""
    drop, top_drop, y_top = drops
    if y_min < floor - FLOOR_TOL:
        return f"fallen: the garment reaches {floor - y_min:.2f} m below the body's feet"
    if y_max < crotch:
        return f"fallen: the garment's top is at y = {y_max:.2f} m, below the body's crotch ({crotch:.2f} m)"
    if np.isfinite(drop) and drop > DROP_MAX:
        return f"fallen: the garment slid {drop:.2f} m down from where it was put on (bound {DROP_MAX:g} m)"
    if np.isfinite(top_drop) and top_drop > TOP_DROP_MAX and y_top < shoulder:
        return (
            f"fallen: the garment's top slid {top_drop:.2f} m down from where it was put on "
            f"(off the shoulders or the hips; bound {TOP_DROP_MAX:g} m)"
        )
    return ""


def _placed_failure(below: float, y_top: float, *, shoulder: float) -> str:
    """The reason of a failed drop check against the pattern's own placement ("" when it passes):
    the top ``below`` [m] under that placement's top, ending at ``y_top`` [m]; the lower shoulder
    joint's height ``shoulder`` [m]."""
    if below > TOP_DROP_MAX and y_top < shoulder:
        return (
            f"fallen: the garment's top is {below:.2f} m below where the pattern places it "
            f"(off the shoulders or the hips; bound {TOP_DROP_MAX:g} m)"
        )
    return ""


def placed_top(pattern, mesh, body, sdf=None) -> float:
    """The height [m] of the garment's top (TOP_QUANTILE of its vertex heights) in the pattern's
    own placement of its panels on ``body`` (:func:`unsew.body.placement.place_as_given`).

    pattern: unsew.pattern.model.Pattern whose panels carry their translation and rotation;
    mesh: its GarmentMesh; body: unsew.body.body.Body with a skeleton; sdf: the body's BodySDF
    (built when None). Returns a float [m]; a pattern placed low (no translation) gives a low
    top, which no drape falls from."""
    from unsew.body.placement import place_as_given

    x = np.asarray(place_as_given(pattern, mesh, body, sdf=sdf), dtype=np.float64)
    return float(np.quantile(x[:, 1], TOP_QUANTILE))


def sleeve_vertices(pattern, mesh, body) -> dict:
    """{side ("left"/"right"): (k,) int64 sewn vertices of the panels the pattern's own placement
    puts round that arm} (:func:`unsew.body.placement.panel_roles`); sides without one left out.

    pattern: Pattern whose panels carry their translation and rotation; mesh: its GarmentMesh;
    body: Body with a skeleton."""
    from unsew.body.placement import panel_roles

    roles = panel_roles(pattern, body)
    names = list(mesh.panel_names)
    out = {}
    for side in ("left", "right"):
        ids = [names.index(n) for n, r in roles.items() if r == f"{side}_sleeve" and n in names]
        if ids:
            uv_of = np.isin(np.asarray(mesh.uv_panel), ids)
            out[side] = np.unique(np.asarray(mesh.x_of_u)[uv_of]).astype(np.int64)
    return out


def sleeve_cover(x, idx, body, side: str) -> float:
    """The share [-] of SLEEVE_SECTORS directions round the ``side`` upper arm's bone (shoulder
    to elbow joint) in which some of the vertices ``x[idx]`` ((N, 3) [m], (k,) int) lie, counting
    those whose projection on the bone falls in SLEEVE_BAND, within SLEEVE_NEAR of it; NaN with
    fewer than SLEEVE_MIN_POINTS there."""
    sk = body.skeleton
    a = np.asarray(sk.position(f"{side}_shoulder"), dtype=np.float64)
    b = np.asarray(sk.position(f"{side}_elbow"), dtype=np.float64)
    length = float(np.linalg.norm(b - a))
    if length <= 0.0:
        return float("nan")
    ax = (b - a) / length
    p = _float64(x)[np.asarray(idx, dtype=np.int64)] - a
    t = p @ ax / length
    p = p - np.outer(p @ ax, ax)  # off the bone
    p = p[(t > SLEEVE_BAND[0]) & (t < SLEEVE_BAND[1]) & (np.linalg.norm(p, axis=1) < SLEEVE_NEAR)]
    if len(p) < SLEEVE_MIN_POINTS:
        return float("nan")
    helper = np.array([0.0, 0.0, 1.0]) if abs(ax[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    u = np.cross(ax, helper)
    u /= np.linalg.norm(u)
    w = np.cross(ax, u)
    ang = np.arctan2(p @ w, p @ u)
    sector = np.floor((ang + np.pi) / (2 * np.pi) * SLEEVE_SECTORS).astype(np.int64) % SLEEVE_SECTORS
    return len(np.unique(sector)) / SLEEVE_SECTORS


def _sleeve_failure(x, sleeves: dict, body) -> str:
    """The reason of a failed ``off the arm`` check ("" when every judged sleeve passes)."""
    for side, idx in sleeves.items():
        cover = sleeve_cover(x, idx, body, side)
        if cover < SLEEVE_COVER_MIN:
            return (
                f"off the arm: the {side} sleeve covers {cover * 100:.0f} % of the directions round "
                f"the upper arm (bound {SLEEVE_COVER_MIN * 100:g} %)"
            )
        if np.isnan(cover):  # nothing along the upper arm: a cap sleeve, or one fallen off it
            root = np.asarray(body.skeleton.position(f"{side}_shoulder"), dtype=np.float64)
            gap = float(np.linalg.norm(_float64(x)[np.asarray(idx, dtype=np.int64)] - root, axis=1).min())
            if gap > SLEEVE_ROOT_NEAR:
                return (
                    f"off the arm: the {side} sleeve lies {gap:.2f} m from the shoulder joint at its "
                    f"nearest (bound {SLEEVE_ROOT_NEAR:g} m)"
                )
    return ""


def sleeves_judged(verdict: DrapeVerdict, x, sleeves: dict, body) -> DrapeVerdict:
    """``verdict`` on the drape ``x`` (N, 3) [m], failed ``off the arm`` where it passed and one
    of the ``sleeves`` (:func:`sleeve_vertices`) does not go round its arm."""
    reason = _sleeve_failure(x, sleeves, body) if verdict.ok and sleeves else ""
    return replace(verdict, ok=False, reason=reason) if reason else verdict


def _body_failure(far_pct, inside_pct) -> str:
    """The reason of the first failed check against the body ("" when both pass); shares [%]."""
    if far_pct > FAR_MAX_PCT:
        return (
            f"off the body: {far_pct:.0f} % of the vertices are above the crotch and more than "
            f"{FAR_DIST:g} m from the body "
            f"(bound {FAR_MAX_PCT:g} %)"
        )
    if inside_pct > INSIDE_MAX_PCT:
        return f"inside the body: {inside_pct:.1f} % of the vertices (bound {INSIDE_MAX_PCT:g} %)"
    return ""


def _crotch_height(body) -> float:
    """Height of the crotch [m]: the lowest body point on the centre line between the knees
    and the pelvis (the hips' joint height when the body has no such point)."""
    sk = body.skeleton
    v = np.asarray(body.verts, dtype=np.float64)
    pel = sk.position("pelvis")
    knee = max(sk.position("left_knee")[1], sk.position("right_knee")[1])
    m = (np.abs(v[:, 0] - pel[0]) < 0.012) & (v[:, 1] > knee) & (v[:, 1] < pel[1])
    return float(v[m, 1].min()) if m.any() else float(0.5 * (pel[1] + knee))


def check_dressed(
    d, *, body=None, start_height=None, start_y=None, placed_top_m=None, seam_gap_max=None, sleeves=None
) -> DrapeVerdict:
    """:func:`check_drape` of a :class:`unsew.dress.Dressed` (its sewn mesh, rest shape and SDF).

    body: the body it was dressed on (needed: a Dressed does not keep it). start_height: see
    :func:`check_drape`; when None, the mean height of the placed panels that
    :func:`unsew.dress.dress` records as ``d.stats["start_height"]`` [m] is used. start_y: see
    :func:`check_drape`; when None, the heights of the placed vertices ``d.x_start`` (n_x, 3) [m]
    (None when the Dressed has none). placed_top_m: optional height [m] of the garment's top
    (TOP_QUANTILE of its heights) in the pattern's own placement (:func:`placed_top`): a drape
    that passes :func:`check_drape` is judged against it too (the module docstring's ``fallen``).
    seam_gap_max: optional bound [m] on ``d.stats["seam_gap"]``, the widest seam left open by the
    sewing phase (the module docstring's ``unsewn``). sleeves: optional :func:`sleeve_vertices`
    of the garment, each judged against its arm (``off the arm``), checked last.
    """
    if body is None:
        raise ValueError("check_dressed needs the body the garment was dressed on")
    if start_height is None:
        start_height = d.stats.get("start_height")
    x_start = getattr(d, "x_start", None)
    if start_y is None and x_start is not None:
        start_y = _float64(x_start)[:, 1]
    m = d.mesh
    v = check_drape(
        d.x,
        faces=m.faces,
        uv=m.uv,
        faces_uv=m.faces_uv,
        body=body,
        sdf=d.sdf,
        start_height=start_height,
        start_y=start_y,
    )
    if not v.ok:
        return v
    reason = ""
    if placed_top_m is not None:
        y_top = float(np.quantile(_float64(d.x)[:, 1], TOP_QUANTILE))
        reason = _placed_failure(float(placed_top_m) - y_top, y_top, shoulder=_shoulder(body))
    gap = float(d.stats.get("seam_gap", 0.0))
    if not reason and seam_gap_max is not None and gap > seam_gap_max:
        reason = (
            f"unsewn: a seam was still {gap * 1000:.0f} mm open when the sewing ended "
            f"(bound {seam_gap_max * 1000:g} mm)"
        )
    v = replace(v, ok=False, reason=reason) if reason else v
    return sleeves_judged(v, d.x, sleeves, body)
