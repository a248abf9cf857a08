"""Phase one of the fit: linear grading of a base pattern to a target garment (paper 3.3,
supplementary Algorithm 2).

``grade`` drapes the base pattern on the wearer (X_init), places the open contours of X_init and
of the target on the skeleton and pairs them (:mod:`unsew.grading.contours`), maps every paired
source contour to its 2D open curves (:mod:`unsew.grading.curves`), moves and widens those curves'
control points by the measured length and girth differences (:mod:`unsew.grading.edit`; the
length is the change of cloth length to the garment's top opening, :mod:`unsew.grading.cloth`,
or Algorithm 2's axial distance along the bone with ``GradingSettings.length`` "axial"),
projects the edit onto the symmetric parameters K, moves every other pattern vertex with
``params.uv(K)``, scales the edit back if it would invert triangles, re-meshes when panel edges
got stretched beyond 1.5x the target edge length (or always: ``remesh``), and re-drapes: U_LG
and X_LG.

Contours that match nothing (an extra hole in the target, a torn hem) are listed in the table
and left alone.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np
import torch

from unsew.dress import DRESS_SETTINGS, dress
from unsew.errors import InputError, PatternError, SimulationError, UnsewError
from unsew.grading.area import clip_note, scale_to_area
from unsew.grading.band_gap import BAND_GAP_MODES, hangs_from_band, pressed_loop_excess
from unsew.grading.cloth import cloth_lengths, rest_cloth_lengths, top_contour
from unsew.grading.contours import ContourMatch, PlacedContour, match_contours, place_contours
from unsew.grading.curves import curves_of_contour, rest_length, stitched_edges
from unsew.grading.edit import curve_edit, edit_directions, project_edit, safe_fraction
from unsew.grading.guards import (
    WaistBound,
    bounded_band,
    bounded_extensions,
    bounded_girth,
    bounded_waist,
    waist_bound,
)
from unsew.grading.placement import choose_lift, is_lower
from unsew.grading.profile import SideSeams, side_seam_moves, side_seams_for
from unsew.meshing.sew import mesh_pattern
from unsew.pattern.params import PatternParams
from unsew.sim.drape import DrapeSettings

__all__ = [
    "GradeResult",
    "GradingSettings",
    "grade",
    "moved_mesh",
    "dress_drape",
    "flat_drape",
    "format_table",
    "TABLE_COLUMNS",
    "REMESH_STRETCH",
    "REMESH_MODES",
    "LENGTH_MODES",
    "waistbands",
    "upright",
    "source_girth",
    "CRUMPLE_TOL",
    "STRETCH_TOL",
    "GRADE_SETTINGS",
    "GradePass",
    "GradingError",
    "MESH_RETRIES",
    "armhole_down",
    "ARM_HANGS",
    "SIDE_SEAM_MODES",
]


class GradingError(UnsewError):
    """Grading made a pattern it cannot mesh even with its edit undone: a failure of unsew's
    grading after the input was accepted, never reported as a fault of the input."""


#: Halvings of an edit's fraction tried when its graded pattern cannot be meshed (a panel folded
#: or crossed); after them the edit is undone (fraction 0).
MESH_RETRIES = 4

#: grade()'s drape settings when none are given: dress()'s on a 3 cm mesh (grade's default edge
#: length has been 3 cm, the fit's 2.5 cm; a fit passes its own settings).
GRADE_SETTINGS = DRESS_SETTINGS.replace(edge_length=0.03)

#: Re-mesh after grading when a rest edge grew beyond this factor times the target edge length
#: (``GradingSettings.remesh`` "stretched"; the default "always" meshes every graded pattern afresh).
REMESH_STRETCH = 1.5
#: The choices of ``GradingSettings.remesh``.
REMESH_MODES = ("always", "stretched")
#: The choices of ``GradingSettings.length``: cloth length to the top opening, or Algorithm 2's axial
#: distance.
LENGTH_MODES = ("cloth", "axial")
#: The choices of ``GradingSettings.side_seams``: left alone, or graded by the torso's girth.
SIDE_SEAM_MODES = ("none", "girth")
#: A further grading pass is made only when some contour's cloth length (or, without one, its
#: position along the bone) is still further than this from the target's [m], or its girth
#: differs by more than PASS_GIRTH_TOL [m].
PASS_LENGTH_TOL = 0.005
PASS_GIRTH_TOL = 0.01


@dataclass
class GradeResult:
    """The outcome of linear grading.

    pattern: the graded pattern U_LG (:class:`~unsew.pattern.model.Pattern`).
    mesh: its :class:`~unsew.meshing.sew.GarmentMesh` (re-meshed or the base mesh moved).
    x_draped: X_LG, the graded pattern draped on the wearer, (n_x, 3) float64 [m] (None when
        ``redrape=False``).
    table: one dict per contour row (:data:`TABLE_COLUMNS`), JSON-serialisable.
    K: the graded effective control points (Nk, 2) float64 [m] of the *base* parameters.
    fraction: the part of the wanted edit applied (1.0 unless scaled back to avoid inversions).
    remeshed: whether the graded pattern was meshed again.
    x_init: the drape of the base pattern, (n_x0, 3) float64 [m], on ``mesh_init``.
    mesh_init: the base pattern's GarmentMesh.
    matches: the contour pairs (:class:`~unsew.grading.contours.ContourMatch`).
    area_scales: the length factor of each pass's area scaling (``GradingSettings.area``, in pass
        order; empty without it). ``K`` is then the last contour edit's, before its scaling.
    placement: what the placement choice tried (:func:`unsew.grading.placement.choose_lift`'s row:
        ``lift_m``, ``wanted_m``, ``tried_m``, ``chamfer_mm``); None when it did not run.
    note: a one-line warning when the last pass's area scaling was clipped (None: none).
    """

    pattern: object
    mesh: object
    x_draped: np.ndarray | None
    table: list
    K: np.ndarray
    fraction: float = 1.0
    remeshed: bool = False
    x_init: np.ndarray | None = None
    mesh_init: object = None
    matches: list = field(default_factory=list)
    area_scales: list = field(default_factory=list)
    placement: dict | None = None
    note: str | None = None


#: Keys of every row of ``GradeResult.table``.
TABLE_COLUMNS = (
    "source_contour", "target_contour", "part", "bone", "source_length_m", "target_length_m",
    "axial_distance_m", "extension_m", "girth_difference_m", "cloth_difference_m", "edits", "warnings",
)  # fmt: skip


def flat_drape(pattern, mesh, body=None) -> np.ndarray:
    """The panels laid flat at their 3D placement, seams merged: (n_x, 3) float64 [m], the mean of
    ``mesh.uv_placed3d`` over the copies of each sewn vertex. A stand-in for a drape in tests and
    when no simulator is wanted."""
    out = np.zeros((mesh.n_x, 3))
    cnt = np.zeros(mesh.n_x)
    np.add.at(out, mesh.x_of_u, mesh.uv_placed3d)
    np.add.at(cnt, mesh.x_of_u, 1.0)
    return out / cnt[:, None]


def dress_drape(
    pattern, mesh, body, *, material="cotton", sdf=None, settings: DrapeSettings = DRESS_SETTINGS
) -> np.ndarray:
    """The grading drape: :func:`unsew.dress.dress` (place, sew, merge, settle) on ``mesh``.

    pattern, mesh: the pattern and its GarmentMesh. body: the wearer (:class:`Body`).
    material: a :class:`~unsew.sim.material.Material` or a name from ``MATERIALS``.
    sdf: the body's SDF (default: ``BodySDF.build(body)``, cached on disk).
    settings: :class:`~unsew.sim.drape.DrapeSettings` of the drape (default dress()'s).

    Returns the draped sewn vertices, (n_x, 3) float64 [m].
    Raises SimulationError when the drape diverged.
    """
    d = dress(pattern, body, sdf=sdf, mesh=mesh, material=material, settings=settings)
    x = d.x.detach().cpu().numpy().astype(np.float64)
    if not np.isfinite(x).all():
        raise SimulationError(
            "the drape diverged (non-finite positions); try a smaller edge length or another material"
        )
    return x


def _rest_edge_stretch(uv: np.ndarray, faces_uv: np.ndarray, edge_length: float) -> float:
    """Longest rest edge divided by the target edge length."""
    f = np.asarray(faces_uv)
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    return float(np.linalg.norm(uv[e[:, 0]] - uv[e[:, 1]], axis=1).max() / edge_length)


def moved_mesh(mesh, pattern, uv: np.ndarray):
    """The GarmentMesh ``mesh`` with its rest positions moved to ``uv`` (Nu, 2) float64 [m] (same
    topology and vertex order); the flat panels' 3D placement (``uv_placed3d``, (Nu, 3) [m]) is
    recomputed from ``pattern``'s panel translations and rotations."""
    placed = np.zeros((len(uv), 3))
    for p, name in enumerate(mesh.panel_names):
        idx = np.flatnonzero(mesh.uv_panel == p)
        placed[idx] = pattern.panels[name].to_world(uv[idx])
    return replace(mesh, uv=uv.copy(), uv_placed3d=placed)


@dataclass(frozen=True)
class GradingSettings:
    """How :func:`grade` grades: its drapes and the rules of each pass. Units in brackets."""

    #: the drapes; ``drape.edge_length`` is the rest edge length [m] the patterns are meshed at
    drape: DrapeSettings = GRADE_SETTINGS
    #: the drapes' fabric: a :class:`~unsew.sim.material.Material` or a name from ``MATERIALS``
    material: object = "cotton"
    redrape: bool = True  #: drape the graded pattern (X_LG); False leaves ``x_draped`` None
    #: contour pairing gate [m] (None: :data:`~unsew.grading.contours.MAX_CENTRE_DISTANCE`)
    max_centre_distance: float | None = None
    #: grading passes; a further pass grades the graded pattern again from its own drape while a
    #: contour is off by more than PASS_LENGTH_TOL or PASS_GIRTH_TOL (one edit cannot know how the
    #: drape answers; the next measures it). One drape each [-]
    passes: int = 2
    #: keep each panel's top where it was placed when its top is an edited open curve (a waist):
    #: the change of length goes to the other end (:func:`_hold_tops`)
    hold_top: bool = True
    #: "always": every graded pattern is meshed afresh before it is draped, so X_LG is reproducible
    #: from U_LG alone; "stretched": only when a rest edge grew beyond REMESH_STRETCH times the edge
    #: length, else the base mesh is moved with the pattern (:func:`moved_mesh`)
    remesh: str = "always"
    #: how far a contour's open curve moves: "cloth", by the change of cloth length to the garment's
    #: top opening, target minus drape, read on the pattern's rest mesh (:mod:`unsew.grading.cloth`;
    #: contours without such a path move axially); "axial", by the axial extension along the bone
    #: (Algorithm 2)
    length: str = "cloth"
    #: "none": the side seams stay where the base has them (Algorithm 2); "girth": for a garment
    #: hanging from the shoulders, each pass also moves the side-seam points between the hips and
    #: the armpits by the target's torso girth at their height minus the drape's
    #: (:mod:`unsew.grading.profile`)
    side_seams: str = "none"
    #: "none": a waistband is graded to the target's top loop as measured; "target": for a garment
    #: that hangs from its band (:func:`~unsew.grading.band_gap.hangs_from_band`), to that loop less
    #: the length the target's own contact gap adds, its bottom and the waist seam below with it
    #: (:mod:`unsew.grading.band_gap`)
    band_gap: str = "none"
    #: the target's surface area [m^2]: each pass's pattern is scaled to it (every panel but the
    #: waistbands by one factor about its centroid: :func:`unsew.grading.area.scale_to_area`) and
    #: meshed afresh before it is draped (None: no scaling, Algorithm 2)
    area: float | None = None
    #: for a garment that hangs from the waist, dress the last pass's pattern again lifted towards
    #: the target's top opening and keep the placement whose drape lies closest
    #: (:mod:`unsew.grading.placement`; two more drapes; needs ``redrape``)
    lift: bool = True
    #: ``room(seconds, what)``, asked before each drape grading can do without (the passes after
    #: the first, the lift choice's) with the last graded drape's duration [s] as its estimate;
    #: False leaves it and what follows out, ``what`` saying it in words (a fit's time limit,
    #: :mod:`unsew.fit.budget`). None: every drape runs.
    room: Callable[[float, str], bool] | None = None

    def replace(self, **changes) -> "GradingSettings":
        """A copy with ``changes`` applied."""
        return replace(self, **changes)


def grade(
    pattern,
    body,
    target_verts,
    target_faces,
    settings: GradingSettings = GradingSettings(),
    *,
    mesh=None,
    x_init=None,
    drape_fn: Callable | None = None,
) -> GradeResult:
    """Grade ``pattern`` so that its draped open contours land where the target's are (phase one).

    pattern: the base pattern (:class:`~unsew.pattern.model.Pattern`, panels placed around the body).
    body: the wearer (:class:`~unsew.body.body.Body`; its skeleton is used).
    target_verts: (V, 3) float64 [m]; target_faces: (F, 3) int: the target garment T.
    settings: :class:`GradingSettings`.
    mesh: the base pattern's GarmentMesh (default: meshed at ``settings.drape.edge_length``).
    x_init: the base pattern already draped, (n_x, 3) [m] on ``mesh`` (default: draped here).
    drape_fn: ``drape_fn(pattern, mesh, body) -> (n_x, 3) [m]`` used for every drape (default:
        :func:`dress_drape` in ``settings.material`` with ``settings.drape``, the body's SDF built
        or read from its cache; :func:`flat_drape` for a quick look).

    Returns a :class:`GradeResult`; its ``note`` says when the last pass's area scaling was clipped.
    """
    tv, tf = _check_grade_args(target_verts, target_faces, settings)
    if drape_fn is None:

        def drape_fn(p, m, b):  # noqa: E306
            return dress_drape(p, m, b, material=settings.material, settings=settings.drape)

    mesh = mesh if mesh is not None else mesh_pattern(pattern, edge_length=settings.drape.edge_length)
    x_init = _base_drape(pattern, mesh, body, x_init, drape_fn)
    ctx = _pass_context(tv, tf, body, settings)
    first = _grade_pass(pattern, mesh, x_init, ctx)
    cur, rows, x_lg, scales, drape_s = _graded_passes(first, body, ctx, settings, drape_fn)
    tried = None
    if settings.lift and x_lg is not None and is_lower(ctx.tgt):
        room = None if settings.room is None else lambda what: settings.room(drape_s, what)
        p_l, mesh_l, x_lg, tried = choose_lift(cur.pattern, cur.mesh, x_lg, body, drape_fn, tv, tf, room)
        if tried is not None:
            cur = replace(cur, pattern=p_l, mesh=mesh_l)
            rows.append(_lift_row(tried))
    return GradeResult(
        pattern=cur.pattern,
        mesh=cur.mesh,
        x_draped=x_lg,
        table=rows,
        K=cur.K,
        fraction=first.fraction,
        remeshed=first.remeshed or cur.remeshed,
        x_init=x_init,
        mesh_init=mesh,
        matches=first.matches,
        area_scales=scales,
        placement=tried,
        # the last pass decides the graded pattern's area
        note=clip_note(scales[-1], settings.area, cur.pattern) if scales else None,
    )


def _pass_context(tv: np.ndarray, tf: np.ndarray, body, settings: GradingSettings) -> "_PassContext":
    """What every pass shares: the target's contours placed on ``body``'s skeleton, its cloth
    lengths, and the side seams' and band's readings of the target when ``settings`` ask for them."""
    skel = body.skeleton
    tgt = place_contours(tv, tf, skel)
    ctx = _PassContext(
        tgt,
        skel,
        {} if settings.max_centre_distance is None else {"max_centre_distance": settings.max_centre_distance},
        cloth_lengths(tv, tf, tgt) if settings.length == "cloth" else (None, {}),
        settings.hold_top,
        settings.remesh,
        waist_bound(body),
    )
    if settings.side_seams == "girth":
        ctx.side_seams = side_seams_for(body, tv, tf, tgt)
    if settings.band_gap == "target" and hangs_from_band(tgt):
        ctx.band_excess = pressed_loop_excess(tv, tgt, body)
        ctx.band_whole = True
    return ctx


def _graded_passes(first: "GradePass", body, ctx: "_PassContext", settings: GradingSettings, drape_fn):
    """(last pass, table rows, its drape X_LG (None without ``redrape``), area scale per pass, the
    last drape's seconds): the first pass, then further ones from each pass's drape while they are
    worth it (:func:`_further_pass`) and ``settings.room`` lets them, each scaled to
    ``settings.area`` and draped."""
    cur, rows = first, list(first.rows)
    x_lg, scales, drape_s = None, [], 0.0
    n = max(int(settings.passes), 1)
    for k in range(n):
        if k > 0:
            what = f"grading: passes {k + 1}-{n} not draped"
            if settings.room is not None and not settings.room(drape_s, what):
                break
            nxt = _further_pass(cur, x_lg, ctx)
            if nxt is None:
                break
            rows += [
                {**r, "edits": [f"pass {k + 1}: {e}" for e in r["edits"]]} for r in nxt.rows if r["edits"]
            ]
            cur = nxt
        if settings.area is not None:
            scaled, s = scale_to_area(cur.pattern, settings.area, bands=waistbands(cur.pattern))
            cur = replace(
                cur,
                pattern=scaled,
                mesh=mesh_pattern(scaled, edge_length=cur.mesh.edge_length),
                remeshed=True,
            )
            scales.append(s)
        if not settings.redrape:
            break
        t0 = time.perf_counter()
        x_lg = np.asarray(drape_fn(cur.pattern, cur.mesh, body), dtype=np.float64)
        drape_s = time.perf_counter() - t0
    return cur, rows, x_lg, scales, drape_s


def _lift_row(tried: dict) -> dict:
    """The contour table's row of the placement choice (:func:`unsew.grading.placement.choose_lift`)."""
    cands = ", ".join(
        f"{dy * 100:+.1f} cm {cf:.2f} mm" for dy, cf in zip(tried["tried_m"], tried["chamfer_mm"])
    )
    what = (
        f"placement: every panel moved {tried['lift_m'] * 100:+.1f} cm in height"
        if tried["lift_m"]
        else "placement kept"
    )
    return {
        **{k: None for k in TABLE_COLUMNS},
        "part": "torso",
        "extension_m": tried["wanted_m"],
        "edits": [
            f"{what} (the target's waist minus the drape's: {tried['wanted_m'] * 100:+.1f} cm; drapes "
            f"{cands})"
        ],
        "warnings": [],
    }


def _base_drape(pattern, mesh, body, x_init, drape_fn) -> np.ndarray:
    """The base pattern's drape (n_x, 3) float64 [m] on ``mesh``: ``x_init``, checked, or draped."""
    x_init = np.asarray(drape_fn(pattern, mesh, body) if x_init is None else x_init, dtype=np.float64)
    if x_init.shape != (mesh.n_x, 3):
        raise InputError(f"x_init must be ({mesh.n_x}, 3) positions on the base mesh, got {x_init.shape}")
    return x_init


def _check_grade_args(target_verts, target_faces, settings: GradingSettings):
    """The target as (V, 3) float64 and (F, 3) int64 arrays; InputError on a bad mode or mesh."""
    for name, modes in (
        ("side_seams", SIDE_SEAM_MODES),
        ("band_gap", BAND_GAP_MODES),
        ("remesh", REMESH_MODES),
        ("length", LENGTH_MODES),
    ):
        if getattr(settings, name) not in modes:
            raise InputError(f"{name} must be one of {', '.join(modes)}, got {getattr(settings, name)!r}")
    tv = np.asarray(target_verts, dtype=np.float64)
    tf = np.asarray(target_faces, dtype=np.int64)
    if tv.ndim != 2 or tv.shape[1] != 3 or len(tv) == 0 or tf.ndim != 2 or tf.shape[1] != 3 or len(tf) == 0:
        raise InputError(
            f"target mesh must be (V, 3) vertices and (F, 3) faces, got {tv.shape} and {tf.shape}"
        )
    return tv, tf


@dataclass
class _PassContext:
    """What every grading pass shares: the target's placed contours ``tgt``, the skeleton, the
    pairing options, the target's cloth lengths (``(None, {})`` for the axial rule), and the
    ``hold_top`` and ``remesh`` choices."""

    tgt: list
    skel: object
    match_kw: dict
    tcloth: tuple
    hold_top: bool = True
    remesh: str = "always"
    waist: WaistBound | None = None
    side_seams: SideSeams | None = None  # the side seams graded by girth (None: left alone)
    # target index -> its loop's contact excess [m] (band_gap)
    band_excess: dict = field(default_factory=dict)
    band_whole: bool = False  # a band's girth edit carried down its sides into the panels below (band_gap)


def _further_pass(cur: "GradePass", x_lg: np.ndarray, ctx: _PassContext) -> "GradePass | None":
    """Another pass from the graded drape ``x_lg``: the contours' remaining offsets, edited again,
    each scaled by how far the drape answered the previous pass's edit. None when every contour
    is already close enough (:func:`_worth_a_pass`)."""
    src = place_contours(x_lg, cur.mesh.faces, ctx.skel)
    now = match_contours(src, ctx.tgt, ctx.skel, garment_centre=x_lg.mean(axis=0), **ctx.match_kw)
    cloth = _cloth_wants(src, now, x_lg, cur.mesh.faces, ctx.tcloth)
    if not _worth_a_pass(now, cloth):
        return None
    gains = response_gains(cur.matches, cur.applied, now)
    return _grade_pass(cur.pattern, cur.mesh, x_lg, ctx, gains=gains, placed=(src, now, cloth))


#: Bounds of the gain a later grading pass applies to a contour's remaining offset (see
#: :func:`response_gains`).
MAX_PASS_GAIN = 3.0
#: A response below this fraction of the edit is taken as noise, not as a slow answer.
MIN_RESPONSE = 0.2


def response_gains(prev_matches, applied: dict, now_matches) -> dict:
    """Per target contour, the factor by which the next pass scales its remaining extension.

    prev_matches: the previous pass's matches (extension measured before its edit [m]);
    applied: target index -> the extension that pass applied to the pattern [m] (after any
    scale-back); now_matches: the matches measured on the drape after the edit.

    The drape answers a pattern edit only in part: a flared skirt's hem lengthened by 7 cm along
    the panel came down 4 cm (measured on bench_grading's skirt), because the cloth hangs at an
    angle and the waist rides. The response r = (extension before - extension after) / applied is
    measured per contour; the next edit is divided by it (gain 1/r, clamped to
    [1, MAX_PASS_GAIN]). A response below MIN_RESPONSE or of the wrong sign is drape noise: gain 1.
    Returns only the contours whose gain is not 1.
    """
    before = {m.target: m.extension for m in prev_matches}
    gains = {}
    for m in now_matches:
        a = applied.get(m.target, 0.0)
        if m.target not in before or abs(a) < PASS_LENGTH_TOL:
            continue
        r = (before[m.target] - m.extension) / a
        if r >= MIN_RESPONSE:
            g = float(min(max(1.0 / r, 1.0), MAX_PASS_GAIN))
            if g > 1.0:
                gains[m.target] = g
    return gains


#: A source loop is read as pleated by the drape, not by its pattern, when its crumple (loop
#: length / hull perimeter) exceeds the target's by more than CRUMPLE_TOL and its 3D length
#: exceeds the rest length of the pattern edges that form it by more than STRETCH_TOL (relative).
CRUMPLE_TOL = 0.05
STRETCH_TOL = 0.05


def source_girth(s: PlacedContour, t: PlacedContour, rest: float | None) -> tuple[float, str]:
    """The source contour's girth [m] to grade against the target loop's length, and why it is not
    the loop's own length ("" when it is).

    s, t: the paired source and target contours (:class:`PlacedContour`, with their hulls).
    rest: the rest length [m] of the pattern edges that form ``s``
        (:func:`~unsew.grading.curves.rest_length`; None or 0: unknown, the loop's length is used).

    A loop longer than its own cloth edge is stretched, and one longer than its convex hull is
    pleated. When the source loop is both, beyond the target's pleats (:data:`CRUMPLE_TOL`) and
    its rest length (:data:`STRETCH_TOL`), the drape has caught the opening, not sized it: read
    by its length, the next pass would narrow it further and crumple it more; its girth is then
    the hull times the target's crumple. A loop pleated by
    its own extra cloth is not stretched, and its length is its girth: the base skirt's flared
    hem, 1.722 m around a 1.520 m hull from 1.722 m of edge, graded to a narrower target.
    """
    if rest is None or not rest > 0:
        return s.length, ""
    if s.crumple > t.crumple + CRUMPLE_TOL and s.length > rest * (1.0 + STRETCH_TOL):
        g = s.hull * t.crumple
        if g < s.length:
            return float(g), (
                f"source loop caught by the drape ({s.length:.3f} m from {rest:.3f} m of edge, "
                f"loop/hull {s.crumple:.2f} against the target's {t.crumple:.2f}): girth read from its hull"
            )
    return s.length, ""


def _worth_a_pass(matches, cloth: dict | None = None) -> bool:
    """Whether any contour is still off by more than PASS_LENGTH_TOL in cloth length (``cloth``:
    target index -> difference [m]) or else along its bone, or by PASS_GIRTH_TOL in girth."""
    cloth = cloth or {}
    return any(
        abs(cloth.get(m.target, m.extension)) > PASS_LENGTH_TOL or abs(m.girth_difference) > PASS_GIRTH_TOL
        for m in matches
    )


#: Control points within this height [m] of a panel's highest one (as placed) form its top.
TOP_BAND = 0.01


# Why the tops are held: the panel's 2D position also sets where it is placed around the body
# before sewing. A waist found 3.5 cm higher on the target than on the base drape (bench_grading's
# skirt, whose narrower, longer target hangs higher on the hips) is the drape's answer to the
# pattern, not a waist placed higher; moving the waist curve up both lengthened the panel and
# placed it 2 cm higher, and that placement alone put the drape 4 to 7 mm (Chamfer) from where the
# same shape placed at the base's height lands.
def _hold_tops(
    pattern, controls, C0: np.ndarray, delta: np.ndarray, edited: dict, band_whole: bool = False
) -> tuple[np.ndarray, dict]:
    """The edit with each panel's top held at its height: where a panel's highest control points
    (as placed around the body, within :data:`TOP_BAND`) all lie on one edited open curve (a
    skirt's or trousers' waist), the panel is translated in 2D, along the direction placed
    upright, by minus that curve's upward move, so the length change goes to the other end.

    ``edited``: panel index -> (control points, target contour index, that contour's girth
    difference [m]) of each edited open curve on the panel.

    A waistband (:func:`_is_band`: open only along its top) keeps its height: its edit loses its
    upright component, and its waist's upward move lengthens the panels sewn to its bottom instead
    (:func:`_carry_down`); held like the others, the band took the whole change and grew taller.
    Not when the band's girth explains the move (:func:`_band_read_as_fit`).

    ``band_whole``: a band's top widened or narrowed takes its bottom and the panels sewn below
    with it (:func:`_band_girth_down`), so the band stays a strip and the waist seam under it
    changes by as much.

    Returns (a new (Nc, 2) array [m], target index -> a warning for each band top whose move was
    not carried down).
    """
    out = delta.copy()
    held: dict[int, str] = {}
    stitched = stitched_edges(pattern)
    open_edges = {
        (n, k) for n, pan in pattern.panels.items() for k in range(len(pan.edges)) if (n, k) not in stitched
    }
    carried: dict[str, list[float]] = {}  # panel name -> upward moves of the bands sewn above it [m]
    for p, curves in edited.items():
        panel = pattern.panels[controls.panel_names[p]]
        cidx = controls.of_panel(p)
        height = panel.to_world(C0[cidx])[:, 1]
        top = {int(g) for g, h in zip(cidx, height) if h >= height.max() - TOP_BAND}
        tops = [(t, dg) for c, t, dg in curves if top <= c]
        up = upright(panel) if tops else None
        if up is None:  # no edited top, or a panel placed lying down: no top to hold
            continue
        rise = float(np.mean([out[g] @ up for g in top]))
        if not _is_band(panel, height, open_edges):
            out[cidx] -= rise * up
            continue
        out[cidx] -= np.outer(out[cidx] @ up, up)
        if band_whole:
            _band_girth_down(pattern, controls, C0, out, panel)
        warning = _band_read_as_fit(rise, tops[0][1])
        if warning:
            held[tops[0][0]] = warning
        else:
            for below in _sewn_below(pattern, panel):
                carried.setdefault(below, []).append(rise)
    for name, rises in carried.items():
        _carry_down(pattern, controls, C0, out, name, float(np.mean(rises)))
    return out, held


def _band_read_as_fit(rise: float, dg: float) -> str | None:
    """The warning when a band top's upward move ``rise`` [m] is its girth's (change ``dg`` [m]) doing
    (:func:`_girth_explains`: a band tighter than the target's and lower, or looser and higher,
    sits where its girth meets the body, and the girth edit moves it; carried down, a too-loose
    band's low seat lengthens the panels under it and puts their hips too low), else None."""
    if not _girth_explains(rise, dg):
        return None
    return (
        f"band top {rise * 100:+.1f} cm on the target with its girth {dg * 100:+.1f} cm: read as "
        "the band's fit, not carried down to the panels below"
    )


#: An arm hangs when its bone points down at least this much (the y of its unit direction below
#: minus this: 30 degrees under the horizontal). A T-pose arm does not: there the contour further
#: along the arm is an armhole further out, the paper's move.
ARM_HANGS = 0.5


def armhole_down(pattern, positions: np.ndarray, curve, controls, bone) -> np.ndarray | None:
    """The unit (2,) float64 direction its placement points down in the frame of ``curve``'s
    panel when the curve is an armhole moved by the contour of a hanging arm, else None.

    pattern, positions (Nc, 2) float64 [m], curve (:class:`~unsew.grading.curves.OpenCurve`),
    controls: as :func:`unsew.grading.edit.edit_directions`. bone: the source contour's
    :class:`~unsew.body.skeleton.Bone` (None: on no bone); it must be an arm's pointing down by
    :data:`ARM_HANGS`, and the curve's outward direction must point up on the body.

    Why: a sleeveless bodice's armhole lies above and beside the panel's middle, so its outward
    direction points out and up, while an arm contour found further down the arm on the target
    is a deeper armhole; moved out and up, the armhole's lower end flared out from the side seam
    A sleeve's hem points down
    the arm already and is left to the paper's edit.
    """
    if bone is None or not bone.part.endswith("arm") or float(bone.direction[1]) > -ARM_HANGS:
        return None
    panel = pattern.panels[curve.panel]
    up = upright(panel)
    if up is None:
        return None
    d, _, _ = edit_directions(pattern, positions, curve, controls)
    if float(d @ up) <= 0.0:
        return None
    return -up


def _girth_explains(rise: float, girth_difference: float) -> bool:
    """Whether a band top's wanted upward move ``rise`` [m] is the answer to its girth: the target's
    top is tighter and higher, or looser and lower (``girth_difference`` [m]: target minus source,
    beyond :data:`PASS_GIRTH_TOL`)."""
    return abs(girth_difference) > PASS_GIRTH_TOL and rise * girth_difference < 0


def upright(panel) -> np.ndarray | None:
    """The unit 2D direction of ``panel`` (a (2,) float64 vector in its own frame) that its
    placement points up (world +y); None when the panel is placed lying down."""
    up = panel.rotation_matrix()[1, :2]
    n = float(np.linalg.norm(up))
    return up / n if n >= 0.5 else None


#: A waistband is a strip: at least this many times as wide (across its upright direction) as
#: it is high. A bodice half (GarmentCode's pencil dress, jumpsuit) is also open only above
#: (neck, armholes) and sewn below at the waist, but taller than wide: not a band.
BAND_ASPECT = 2.0


def _is_band(panel, height: np.ndarray, open_edges: set) -> bool:
    """Whether ``panel`` is a waistband: a strip (:data:`BAND_ASPECT`) placed upright whose open
    (unstitched) edges all lie in the upper half of its placed height range, sewn along its
    bottom, open only at its top. ``height``: its control points' placed heights [m];
    ``open_edges``: (panel name, edge index) of unstitched edges."""
    lo, hi = float(height.min()), float(height.max())
    up = upright(panel)
    if hi - lo < 1e-6 or up is None:
        return False
    v = np.asarray(panel.vertices, dtype=np.float64)
    if np.ptp(v @ np.array([up[1], -up[0]])) < BAND_ASPECT * np.ptp(v @ up):
        return False
    ys = panel.to_world(panel.vertices)[:, 1]
    mid = 0.5 * (lo + hi)
    opened = [e for k, e in enumerate(panel.edges) if (panel.name, k) in open_edges]
    return bool(opened) and all(ys[e.start] > mid and ys[e.end] > mid for e in opened)


def waistbands(pattern) -> list[str]:
    """Names of the panels of ``pattern`` that are waistbands (:func:`_is_band`, judged on the
    panel's vertices as placed): the panels phase two can be told to leave the height of, or
    leave alone (``optimizer.bands``)."""
    stitched = stitched_edges(pattern)
    open_edges = {
        (n, k) for n, pan in pattern.panels.items() for k in range(len(pan.edges)) if (n, k) not in stitched
    }
    return [
        n for n, pan in pattern.panels.items() if _is_band(pan, pan.to_world(pan.vertices)[:, 1], open_edges)
    ]


def _world_x_dir(panel) -> np.ndarray:
    """The 2D direction (2,) in ``panel``'s frame scaled so that a move along it of 1 moves the
    placed point by 1 m in world x (zero when the panel's plane is edge-on to x)."""
    ex = panel.rotation_matrix()[0, :2]
    n2 = float(ex @ ex)
    return ex / n2 if n2 > 0.25 else np.zeros(2)


def _band_girth_down(pattern, controls, C0: np.ndarray, out: np.ndarray, band) -> None:
    """The sideways move of ``band``'s two outermost top corners (world x, their edit in ``out``)
    given, in place, to its two outermost bottom corners and to the vertex each of those is sewn
    to on the panels below (the end, nearer across the body, of the edge stitched to the band's
    bottom edge there): the band widens or narrows as a whole and the waist seam under it with it.

    Why: a band graded by its top loop alone became a trapezoid whose bottom, and the skirt's top
    sewn to it, kept the base's girth, and the skirt hung below the target's (docs/decisions/009)."""
    p = controls.panel_names.index(band.name)
    cidx = controls.of_panel(p)
    world = band.to_world(C0[cidx])
    ex = _world_x_dir(band)
    if not ex.any():
        return
    dx = (out[cidx] @ band.rotation_matrix()[:, :2].T)[:, 0]  # world-x move of each control point [m]
    top = np.flatnonzero(world[:, 1] >= world[:, 1].max() - TOP_BAND)
    low = np.flatnonzero(world[:, 1] <= world[:, 1].min() + TOP_BAND)
    if len(top) < 2 or len(low) < 2:
        return
    where = {(int(controls.panel[g]), int(controls.vertex[g])): int(g) for g in range(len(controls))}
    for pick in (np.argmin, np.argmax):
        t, b = top[pick(world[top, 0])], low[pick(world[low, 0])]
        out[cidx[b]] += (dx[t] - dx[b]) * ex
        corner = int(controls.vertex[cidx[b]])
        for name, k in _sewn_to_corner(pattern, band, corner, float(world[b, 0])):
            g = where.get((controls.panel_names.index(name), k))
            if g is not None:
                out[g] += dx[t] * _world_x_dir(pattern.panels[name])


def _sewn_to_corner(pattern, band, corner: int, x: float) -> list[tuple[str, int]]:
    """(panel name, vertex index) sewn to vertex ``corner`` of ``band`` on the panels below it:
    for each stitch of a bottom edge of the band (both ends in the lower half of its placed
    height) that ends at the corner, the end of the other edge nearer in world x to ``x`` [m]
    (the corner's). The band's side edges, sewn to the band's other pieces, are not followed."""
    ys = band.to_world(band.vertices)[:, 1]
    mid = 0.5 * (float(ys.min()) + float(ys.max()))
    out = []
    for st in pattern.stitches:
        for a, b in ((st.a, st.b), (st.b, st.a)):
            if a.panel != band.name or b.panel == band.name:
                continue
            e = band.edges[a.edge]
            if corner not in (e.start, e.end) or not (ys[e.start] < mid and ys[e.end] < mid):
                continue
            other = pattern.panels[b.panel]
            f = other.edges[b.edge]
            ends = other.to_world(other.vertices[[f.start, f.end]])[:, 0]
            k = f.start if abs(ends[0] - x) <= abs(ends[1] - x) else f.end
            if (b.panel, int(k)) not in out:
                out.append((b.panel, int(k)))
    return out


def _sewn_below(pattern, band) -> list[str]:
    """Names of the panels stitched to an edge of ``band`` that lies wholly in the lower half of
    its placed height: the panels hanging from a waistband (not the band's other pieces)."""
    ys = band.to_world(band.vertices)[:, 1]
    mid = 0.5 * (float(ys.min()) + float(ys.max()))
    low = {k for k, e in enumerate(band.edges) if ys[e.start] < mid and ys[e.end] < mid}
    out = []
    for st in pattern.stitches:
        for a, b in ((st.a, st.b), (st.b, st.a)):
            if a.panel == band.name and a.edge in low and b.panel != band.name and b.panel not in out:
                out.append(b.panel)
    return out


def _carry_down(pattern, controls, C0: np.ndarray, out: np.ndarray, name: str, rise: float) -> None:
    """Lengthen panel ``name`` by ``rise`` [m] below its top, in place in ``out``: every control
    point lower than its top (:data:`TOP_BAND`) moves down by ``rise`` along the upright direction,
    so its top stays sewn to the band and its placement is unchanged. A dart's tip
    (:func:`_dart_tips`) whose dart opens at the top stays with the top: the dart keeps its
    length. Carried down with the rest, a tip dragged the rest mesh beside its narrow wedge across
    the dart's legs, and the edit was scaled back to avoid inverted triangles."""
    if name not in controls.panel_names:
        return
    p = controls.panel_names.index(name)
    panel = pattern.panels[name]
    up = upright(panel)
    if up is None:
        return
    cidx = controls.of_panel(p)
    height = panel.to_world(C0[cidx])[:, 1]
    tips = _dart_tips(pattern, name, panel.to_world(panel.vertices)[:, 1], height.max() - TOP_BAND)
    below = [
        int(g)
        for g, h in zip(cidx, height)
        if h < height.max() - TOP_BAND and int(controls.vertex[g]) not in tips
    ]
    out[below] -= rise * up


def _dart_tips(pattern, name: str, ys: np.ndarray, top: float) -> set:
    """Vertex indices of panel ``name``'s dart tips that open at its top: the vertex where an
    edge ends and the next begins, the two stitched to each other, their other ends at or above
    ``top`` [m] (``ys``: the panel's vertices' placed heights [m])."""
    panel = pattern.panels[name]
    n = len(panel.edges)
    pairs = {frozenset(((s.a.panel, s.a.edge), (s.b.panel, s.b.edge))) for s in pattern.stitches}
    tips = set()
    for k, e in enumerate(panel.edges):
        f = panel.edges[(k + 1) % n]
        if frozenset(((name, k), (name, (k + 1) % n))) in pairs and ys[e.start] >= top and ys[f.end] >= top:
            tips.add(int(e.end))
    return tips


def _cloth_wants(src, matches, x, faces, tcloth) -> dict:
    """Target index -> target cloth length - source cloth length [m] (:mod:`unsew.grading.cloth`)
    of every matched contour but the top one; {} when the target's cloth lengths were not
    measured or the two top contours are not a pair."""
    ttop, tl = tcloth
    if ttop is None:
        return {}
    stop, sl = cloth_lengths(x, faces, src)
    if stop is None or {m.source: m.target for m in matches}.get(stop.index) != ttop.index:
        return {}
    return {m.target: tl[m.target] - sl[m.source] for m in matches if m.source in sl and m.target in tl}


#: Corrections of a cloth-length edit measured on the edited pattern's own rest mesh.
CLOTH_STEPS = 2
#: ... stopped when every contour's rest cloth length is within this of its goal [m].
CLOTH_TOL = 0.001


@dataclass
class GradePass:
    """One pass of Algorithm 2.

    pattern, mesh: the graded pattern and its GarmentMesh; rows: its contour table rows;
    matches: the contour pairs it edited; applied: target index -> extension applied [m];
    K: (Nk, 2) float64 [m]; fraction: the part of the edit applied; remeshed: whether ``mesh``
    was meshed afresh.
    """

    pattern: object
    mesh: object
    rows: list
    matches: list
    applied: dict
    K: np.ndarray
    fraction: float
    remeshed: bool


@dataclass
class _Item:
    """A matched contour to edit: its match, its open curves, the girth difference [m] (target
    minus source), each curve's share of it [m] (by 3D length), its warnings, the source girth
    [m] graded from, and each curve's weight in the shares (its part of the loop's 3D length)."""

    match: ContourMatch
    curves: list
    girth_difference: float
    shares: list
    warnings: list
    girth: float = 0.0
    weights: list = field(default_factory=list)
    bone: object = None  # the source contour's Bone (None: on no bone)


@dataclass
class _Edit:
    """An edit of the control points: K (Nk, 2) [m], the fraction applied, the pattern and mesh."""

    K: torch.Tensor
    fraction: float
    pattern: object
    mesh: object
    remeshed: bool
    exts: dict = field(default_factory=dict)  # target index -> extension applied before ``fraction`` [m]
    notes: dict = field(default_factory=dict)  # target index -> warnings of the bounds (grading.guards)
    held: set = field(default_factory=set)  # targets whose band top move was not carried down (_hold_tops)


def _grade_pass(
    pattern, mesh, x_init, ctx: _PassContext, *, gains: dict | None = None, placed=None
) -> GradePass:
    """One pass of Algorithm 2: contours of the drape ``x_init`` (on ``mesh``) paired with the
    target's, the open curves moved and widened, projected on K, scaled back if needed, and the
    mesh moved or re-meshed.

    A contour with a cloth length on both sides (``ctx.tcloth``) is moved so that the pattern's
    cloth length at rest changes by the target's minus the drape's: the move starts at that
    difference and is corrected :data:`CLOTH_STEPS` times on the edited pattern's mesh. The
    others move by their axial extension times ``gains[target index]`` (default 1). ``placed``:
    the drape's placed contours, their matches and cloth differences when already computed."""
    if placed is None:
        src = place_contours(x_init, mesh.faces, ctx.skel)
        matches = match_contours(src, ctx.tgt, ctx.skel, garment_centre=x_init.mean(axis=0), **ctx.match_kw)
        cloth = _cloth_wants(src, matches, x_init, mesh.faces, ctx.tcloth)
    else:
        src, matches, cloth = placed
    gains = gains or {}
    params = PatternParams.build(pattern, mesh)
    items = [_item(m, src, ctx.tgt, x_init, params, mesh, ctx.band_excess) for m in matches]
    exts = {
        m.target: cloth[m.target] if m.target in cloth else m.extension * gains.get(m.target, 1.0)
        for m in matches
    }
    _bound_waist(src, items, exts, ctx.waist)
    seams, seam_notes = None, []
    if ctx.side_seams is not None:
        control_x = mesh.x_of_u[params.control_uv]
        seams, seam_notes = side_seam_moves(
            params.pattern, params.controls, control_x, x_init, mesh.faces, ctx.side_seams
        )
    edit = _edit_with_cloth_goals(params, mesh, src, items, exts, cloth, ctx, seams)
    for it in items:
        it.warnings.extend(edit.notes.get(it.match.target, []))
    rows, wanted = _pass_rows(params.pattern, src, ctx.tgt, matches, items, edit.exts, cloth, gains)
    rows += [
        {**{k: None for k in TABLE_COLUMNS}, "part": "torso", "edits": [n], "warnings": []}
        for n in seam_notes
    ]
    if edit.fraction < 1.0:
        note = f"edit scaled back to {edit.fraction:.0%} to avoid inverted triangles or an invalid panel"
        for r in rows:
            if r["edits"]:
                r["warnings"].append(note)
    # a held move moved nothing
    applied = {t: edit.fraction * e for t, e in wanted.items() if t not in edit.held}
    return GradePass(
        edit.pattern,
        edit.mesh,
        rows,
        matches,
        applied,
        edit.K.detach().cpu().numpy(),
        edit.fraction,
        edit.remeshed,
    )


def _bound_waist(src, items, exts: dict, waist: WaistBound | None) -> None:
    """Bound the top opening's move and widening by the body when it is a waist
    (:func:`unsew.grading.guards.bounded_waist`); ``exts`` and the top item change in place."""
    top = top_contour(src)
    it = next((it for it in items if top is not None and it.match.source == top.index), None)
    if it is None or waist is None:
        return
    t = it.match.target
    ext, dg, notes = bounded_waist(waist, float(top.centre[1]), exts[t], it.girth, it.girth_difference)
    if not notes:
        return
    exts[t] = ext
    it.shares = [dg * w for w in it.weights]
    it.girth_difference = dg
    it.warnings.extend(notes)


def _item(m: ContourMatch, src, tgt, x_init, params, mesh, band_excess: dict | None = None) -> _Item:
    """The open curves of a matched source contour and its girth to grade. ``band_excess``:
    target index -> the length [m] its loop owes to the target's contact gap, read off when the
    curves are a waistband's (:mod:`unsew.grading.band_gap`)."""
    s, t = src[m.source], tgt[m.target]
    curves = curves_of_contour(s.contour.indices, x_init, params.pattern, mesh, params.controls)
    warnings = [] if curves else ["no open pattern curve forms this contour; left alone"]
    rest = rest_length(params.pattern, curves)
    girth, why = source_girth(s, t, rest)
    if why:
        warnings.append(why)
    t_len = t.length
    band = bool(curves) and set(c.panel for c in curves) <= set(waistbands(params.pattern))
    excess = (band_excess or {}).get(m.target, 0.0) if band else 0.0
    if excess:
        t_len -= excess
        warnings.append(
            f"band sized to the target's loop less {excess * 100:.1f} cm, what its contact gap adds"
        )
    dg = t_len - girth
    if band:
        dg, cut = bounded_band(rest, t_len, dg)
        if cut:
            warnings.append(cut)
    total = max(s.length, 1e-12)  # each curve's share of the contour's 3D length
    weights = [c.length3d / total for c in curves]
    return _Item(m, curves, dg, [dg * w for w in weights], warnings, girth, weights, s.bone)


def _whole_panel(pattern, c) -> bool:
    """Whether the open curve ``c`` is every edge of its panel (such a panel is not edited)."""
    return len(c.edges) == len(pattern.panels[c.panel].edges)


def _edit_with_cloth_goals(
    params, mesh, src, items, exts: dict, cloth: dict, ctx: _PassContext, seams: np.ndarray | None = None
) -> _Edit:
    """The edit of the pass, with each cloth-length move corrected on the edited pattern's own
    rest mesh until its rest cloth length is within CLOTH_TOL of its goal (``exts`` is updated).
    ``seams``: the side-seam points' moves (Nc, 2) [m] (:mod:`unsew.grading.profile`), or None."""
    top = top_contour(src) if cloth else None
    keys = {it.match.target: [(c.panel, e) for c in it.curves for e in c.edges] for it in items}
    top_edges = next(
        (keys[it.match.target] for it in items if top is not None and it.match.source == top.index), []
    )
    keyed = {t: k for t, k in keys.items() if t in cloth and k}
    goal = {}
    if keyed and top_edges:
        rest0 = rest_cloth_lengths(mesh, keyed, top_edges)
        goal = {t: rest0[t] + cloth[t] for t in keyed if t in rest0}
    for step in range(CLOTH_STEPS + 1):
        edit = _edit(params, mesh, items, exts, ctx, seams)
        if not goal or step == CLOTH_STEPS:
            break
        now = rest_cloth_lengths(edit.mesh, {t: keyed[t] for t in goal}, top_edges)
        err = {t: goal[t] - now[t] for t in goal if t in now}
        if all(abs(e) < CLOTH_TOL for e in err.values()):
            break
        for t, e in err.items():
            exts[t] += e
    return edit


def _edit(params, mesh, items, exts: dict, ctx: _PassContext, seams: np.ndarray | None = None) -> _Edit:
    """Move and widen every item's open curves within the bounds of :mod:`unsew.grading.guards`,
    hold the tops, project on K, scale back to avoid inversions, and mesh the graded pattern
    (afresh or the base mesh moved; scaled back further if a panel cannot be meshed)."""
    C0 = params.control_points(params.K0).detach().cpu().numpy()
    exts, cut = bounded_extensions(params.pattern, C0, items, exts, params.controls)
    notes = {t: [n] for t, n in cut.items()}
    delta = np.zeros_like(C0)
    # panel index -> (control points, target, girth difference) per edited curve
    edited: dict[int, list[tuple]] = {}
    for it in items:
        for c, dg in zip(it.curves, it.shares):
            if _whole_panel(params.pattern, c):
                continue
            dg, note = bounded_girth(params.pattern, c, dg)
            if note:
                notes.setdefault(it.match.target, []).append(note)
            delta += curve_edit(
                params.pattern,
                C0,
                c,
                params.controls,
                extension=exts[it.match.target],
                girth_change=dg,
                deepen=armhole_down(params.pattern, C0, c, params.controls, it.bone),
            )
            edited.setdefault(c.panel_index, []).append(
                (set(int(g) for g in c.controls), it.match.target, it.girth_difference)
            )
    if seams is not None:
        delta = delta + seams
    held: dict[int, str] = {}
    if ctx.hold_top:
        delta, held = _hold_tops(params.pattern, params.controls, C0, delta, edited, ctx.band_whole)
        for t, note in held.items():
            notes.setdefault(t, []).append(note)
    K0 = params.K0
    K1 = project_edit(params, C0 + delta)
    frac = safe_fraction(params, K0, K1)
    K, frac, graded, new_mesh, remeshed = _meshed(params, mesh, K0, K1, frac, ctx.remesh)
    return _Edit(K, float(frac), graded, new_mesh, bool(remeshed), exts, notes, set(held))


def _meshed(params, mesh, K0, K1, frac: float, remesh: str):
    """(K, fraction, graded pattern, its mesh, remeshed) of the edit ``K0 + frac (K1 - K0)``; when
    the graded pattern cannot be meshed (a panel folded back or crossed), the fraction is halved
    up to :data:`MESH_RETRIES` times and then set to 0 (the base's shape, already meshed). A
    pattern that still fails raises :class:`GradingError`, not the input's PatternError."""
    tries = [frac * 0.5**k for k in range(MESH_RETRIES + 1)] + [0.0]
    for f in tries:
        K = K0 + f * (K1 - K0)
        try:
            graded = params.to_pattern(K)
            with torch.no_grad():
                uv = params.uv(K).cpu().numpy()
            remeshed = (
                remesh == "always" or _rest_edge_stretch(uv, mesh.faces_uv, mesh.edge_length) > REMESH_STRETCH
            )
            new_mesh = (
                mesh_pattern(graded, edge_length=mesh.edge_length)
                if remeshed
                else moved_mesh(mesh, graded, uv)
            )
            return K, f, graded, new_mesh, remeshed
        except PatternError as exc:
            last = exc
    raise GradingError(
        f"grading made a pattern it cannot mesh, even with its edit undone ({last}); this is a "
        "failure of unsew's grading, not of the input: rerun with --no-grading or another --base"
    )


def _pass_rows(pattern, src, tgt, matches, items, exts, cloth, gains) -> tuple[list, dict]:
    """The contour table rows of a pass, and target index -> extension wanted [m] of every
    contour that got an edit."""
    rows, wanted = [], {}
    for it in items:
        m = it.match
        s, t = src[m.source], tgt[m.target]
        ext, edits = exts[m.target], []
        gain = gains.get(m.target, 1.0) if m.target not in cloth else 1.0
        for c, dg in zip(it.curves, it.shares):
            if _whole_panel(pattern, c):
                it.warnings.append(f"panel {c.panel} is all open edges; not edited")
                continue
            names = "+".join(pattern.panels[c.panel].edges[e].label or f"edge{e}" for e in c.edges)
            if m.target in cloth:
                how = f" (cloth length {cloth[m.target] * 100:+.1f} cm)"
            else:
                how = f" (x{gain:.2f}: the drape answered the last pass in part)" if gain != 1.0 else ""
            edits.append(f"{c.panel}:{names} move {ext * 100:+.1f} cm{how}, widen {dg * 100:+.1f} cm")
        if edits:
            wanted[m.target] = ext
        rows.append(_row(s, t, m, edits, it.warnings, it.girth_difference, cloth.get(m.target)))
    matched_s, matched_t = {m.source for m in matches}, {m.target for m in matches}
    rows += [
        _row(s, None, None, [], ["source contour matches no target contour; left alone"])
        for s in src
        if s.index not in matched_s
    ]
    rows += [
        _row(None, t, None, [], ["target contour matches no source contour; left alone"])
        for t in tgt
        if t.index not in matched_t
    ]
    return rows, wanted


def _name(c: PlacedContour | None) -> str | None:
    if c is None:
        return None
    return f"#{c.index} {c.part or 'no bone'}{' ' + c.bone.name if c.bone is not None else ''}"


def _row(
    s: PlacedContour | None,
    t: PlacedContour | None,
    m: ContourMatch | None,
    edits,
    warnings,
    girth_difference: float | None = None,
    cloth_difference: float | None = None,
) -> dict:
    if girth_difference is None and m is not None:
        girth_difference = m.girth_difference
    return {
        "source_contour": _name(s),
        "target_contour": _name(t),
        "part": m.part if m else (s or t).part,
        "bone": m.bone if m else ((s or t).bone.name if (s or t).bone is not None else None),
        "source_length_m": None if s is None else round(s.length, 5),
        "target_length_m": None if t is None else round(t.length, 5),
        "axial_distance_m": None if m is None else round(m.axial_distance, 5),
        "extension_m": None if m is None else round(m.extension, 5),
        "girth_difference_m": None if girth_difference is None else round(float(girth_difference), 5),
        "cloth_difference_m": None if cloth_difference is None else round(float(cloth_difference), 5),
        "edits": list(edits),
        "warnings": list(warnings),
    }


def format_table(table: list) -> str:
    """The contour table as aligned text (lengths in cm)."""
    head = (
        f"{'source':<24} {'target':<24} {'part':<10} {'axial cm':>9} {'ext cm':>8} {'cloth cm':>9} "
        f"{'girth cm':>9}  edits / warnings"
    )
    lines = [head, "-" * len(head)]
    cm = lambda v: "" if v is None else f"{v * 100:+.1f}"  # noqa: E731
    for r in table:
        notes = "; ".join(r["edits"] + r["warnings"])
        lines.append(
            f"{r['source_contour'] or '-':<24} {r['target_contour'] or '-':<24} {r['part'] or '-':<10} "
            f"{cm(r['axial_distance_m']):>9} {cm(r['extension_m']):>8} {cm(r.get('cloth_difference_m')):>9} "
            f"{cm(r['girth_difference_m']):>9}  {notes}"
        )
    return "\n".join(lines)
