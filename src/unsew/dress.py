"""Dress a body with a sewing pattern: mesh the panels, place them around the body, sew the
seams shut (no gradients), and let the garment settle. The result is the first draped state
X of the paper (3.4.1) from which differentiable drapes are warm-started.

This is the one place the stages meet for a forward drape; the CLI's ``drape``, grading,
the fit and the benchmarks all call :func:`dress`.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import torch

from unsew.body.placement import hint_shift, meets_seams, place_as_given, place_garment
from unsew.body.sdf import BodySDF
from unsew.errors import SimulationError
from unsew.meshing import mesh_pattern
from unsew.sim.checks import check_dressed, placed_top, sleeve_vertices
from unsew.sim.drape import Cloth, DrapeSettings, drape, merge_sewn, sew
from unsew.sim.material import Material, get_material
from unsew.sim.model import SimModel
from unsew.sim.seam_guide import through_pairs
from unsew.sim.state import SimState

__all__ = [
    "Dressed",
    "dress",
    "settle",
    "DRESS_SETTINGS",
    "resolve_material",
    "hold_vertices",
    "dress_stats",
    "hanging_edges",
]

#: A lower garment's waistline: its vertices within this height of its top [m].
HOLD_BAND = 0.02


@dataclass
class Dressed:
    """A pattern sewn and draped on a body.

    pattern: the Pattern; mesh: its GarmentMesh (uv (Nu,2) [m], faces (F,3) into X, ...);
    model: SimModel on the sewn topology; x: draped sewn vertices (Nx, 3) float64 torch [m];
    uv: rest positions (Nu, 2) float64 torch [m]; material: the Material used; sdf: the body SDF;
    x_start: the placed panels' positions merged on the sewn vertices (n_x, 3) float64 numpy [m]
    (the rise check of :func:`unsew.sim.checks.check_dressed`), or None.
    """

    pattern: object
    mesh: object
    model: object
    x: object
    uv: object
    material: object
    sdf: object
    stats: dict = field(default_factory=dict)  #: timings [s] and seam gap [m] (see :func:`dress`)
    x_start: object = None


def resolve_material(material):
    """A Material from a library name or a Material instance."""
    if isinstance(material, Material):
        return material
    return get_material(str(material))


def hold_vertices(pattern, mesh, body, x_unsewn) -> np.ndarray:
    """Vertices held still at the start of the sewing phase: the waistline of a lower garment
    (every panel below the body's chest: skirts, trousers), none for tops and dresses.

    x_unsewn: (Nu, 3) [m] placed panels. Returns (P,) int64 uv indices (possibly empty).
    """
    x = np.asarray(x_unsewn)
    chest_y = float(body.skeleton.position("chest")[1])
    top = float(x[:, 1].max())
    if top > chest_y:
        return np.zeros(0, dtype=np.int64)
    bnd = np.concatenate([mesh.boundary_loop(p) for p in range(len(mesh.panel_names))])
    return bnd[x[bnd, 1] > top - HOLD_BAND].astype(np.int64)


#: Edge labels of the edges a garment hangs from, as GarmentCode's programs write them: a lower
#: garment's or a waistband's top (``lower_interface``) and a strapless bodice's top
#: (``strapless_top``). GarmentCodeData's simulation holds them at the body by attachment
#: constraints; :func:`dress` holds such an edge at the height the pattern's own placement gives
#: when it is an opening (not sewn to another panel: a dress's waist seam hangs from its bodice).
ATTACH_LABELS = ("lower_interface", "strapless_top")


def hanging_edges(pattern) -> set:
    """The (panel name, edge index) pairs of ``pattern``'s open edges (sewn to nothing) labelled
    one of :data:`ATTACH_LABELS`: the edges the garment hangs from."""
    sewn = {(side.panel, side.edge) for st in pattern.stitches for side in (st.a, st.b)}
    return {
        (name, e)
        for name, pa in pattern.panels.items()
        for e, edge in enumerate(pa.edges)
        if edge.label in ATTACH_LABELS and (name, e) not in sewn
    }


def attached_vertices(pattern, mesh, body, sdf):
    """The rest vertices on unsewn edges labelled ATTACH_LABELS and their heights, as
    ``Cloth.anchors`` (uv indices (A,) int64 torch, heights (A,) float64 torch [m]), or None when
    there is none. A height is the mean over a sewn vertex's copies of the pattern's own placement
    (:func:`unsew.body.placement.place_as_given`: each panel's translation and rotation)."""
    hung = hanging_edges(pattern)
    if not hung:
        return None
    idx = [np.asarray(v, np.int64) for key, v in mesh.edge_verts.items() if key in hung]
    idx = np.unique(np.concatenate(idx))
    y = np.asarray(place_as_given(pattern, mesh, body, sdf=sdf))[:, 1]
    xu = np.asarray(mesh.x_of_u)
    ysum = np.bincount(xu, weights=y, minlength=mesh.n_x)
    cnt = np.bincount(xu, minlength=mesh.n_x)
    height = (ysum / np.maximum(cnt, 1))[xu[idx]]
    return torch.as_tensor(idx), torch.as_tensor(height, dtype=torch.float64)


#: A drape holds its labelled hanging edges when their vertices lie this close to their heights,
#: at the median [m] (a held drape's lie within 1 mm, a free one's slide centimetres).
HELD_WITHIN = 5e-3


def held_anchors(pattern, mesh, body, sdf, x):
    """:func:`attached_vertices` when the drape x (n_x, 3) [m] on ``mesh`` holds them (their
    median height error under HELD_WITHIN: :func:`dress` kept the held drape), else None: what
    later drapes from x (the fit's) hold so as not to let go what the dressing held."""
    anchors = attached_vertices(pattern, mesh, body, sdf)
    if anchors is None:
        return None
    idx, height = anchors
    y = np.asarray(x)[np.asarray(mesh.x_of_u)[idx.numpy()], 1]
    return anchors if float(np.median(np.abs(y - height.numpy()))) < HELD_WITHIN else None


def dress_stats(d, *, x_unsewn_sewn=None) -> dict:
    """Figures of a dressed garment (for tests and benchmarks).

    d: :class:`Dressed`. Returns a dict: ``depth_mm`` deepest vertex inside the body [mm]
    (0 if none), ``inside_pct`` share of vertices inside [%], ``stretch`` largest edge length
    over its rest length [-], ``inverted`` triangles whose 3D normal opposes its neighbours'
    average by more than 150 deg, ``bbox`` (2, 3) [m], plus ``d.stats``.
    """
    x = d.x.detach()
    with torch.no_grad():
        sd, _ = d.sdf.query(x)
    m = d.mesh
    e = m.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    eu = m.faces_uv[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    xn = x.numpy()
    L = np.linalg.norm(xn[e[:, 0]] - xn[e[:, 1]], axis=1)
    L0 = np.linalg.norm(m.uv[eu[:, 0]] - m.uv[eu[:, 1]], axis=1)
    out = dict(d.stats)
    out.update(
        n_x=int(m.n_x),
        depth_mm=float(max(0.0, -float(sd.min())) * 1000.0),
        inside_pct=float((sd < 0).double().mean()) * 100.0,
        stretch=float((L / L0).max()),
        inverted=_folded_triangles(xn, m.faces),
        bbox=np.stack([xn.min(0), xn.max(0)]),
    )
    return out


def _folded_triangles(x, faces) -> int:
    """Triangles folded through their neighbours: the normal opposes the mean normal of the
    triangles sharing its vertices by more than 150 degrees."""
    n = np.cross(x[faces[:, 1]] - x[faces[:, 0]], x[faces[:, 2]] - x[faces[:, 0]])
    nv = np.zeros_like(x)
    for k in range(3):
        np.add.at(nv, faces[:, k], n)
    nb = nv[faces].sum(axis=1) - n  # (F, 3)
    c = np.einsum("ij,ij->i", n, nb) / np.maximum(
        np.linalg.norm(n, axis=1) * np.linalg.norm(nb, axis=1), 1e-30
    )
    return int((c < np.cos(np.radians(150))).sum())


#: dress()'s settings when none are given: the fit's, with a shorter sewing and settling phase
#: (60 + 20 steps against the fit's 80 + 40), as dress() has always defaulted to.
DRESS_SETTINGS = DrapeSettings(sew_steps=60, settle_steps=20)


def dress(
    pattern,
    body,
    *,
    sdf=None,
    mesh=None,
    material="cotton",
    gamma=None,
    settings: DrapeSettings = DRESS_SETTINGS,
    progress: Callable[[str, int, int], None] | None = None,
) -> Dressed:
    """Mesh, place, sew and settle ``pattern`` on ``body``; a pattern file sized to another body
    is first moved onto this one's shoulders (:func:`_on_this_body`; the returned ``pattern`` and
    ``mesh`` are then the moved ones).

    Args:
        pattern: unsew.pattern.model.Pattern. body: unsew.body.body.Body.
        sdf: the body's SDF (built and disk-cached from ``body`` when None).
        mesh: a GarmentMesh of ``pattern`` to reuse (meshed at ``settings.edge_length`` when None).
        material: library name or Material; gamma: optional (5,) torch overriding its stiffness.
        settings: :class:`~unsew.sim.drape.DrapeSettings`: the mesh's edge length, the sewing
            phase (``sew_steps`` of ``sew_dt``, seam springs, the waistline held ``hold_steps``,
            gravity ramped over ``ramp_steps``) and ``settle_steps`` of plain draping at ``dt``.
            Default :data:`DRESS_SETTINGS`.
        progress: optional callback ``progress(phase, k, n)`` (phases "place", "sew", "settle").

    Returns:
        :class:`Dressed`; its ``stats`` hold ``place_s``, ``sew_s``, ``settle_s`` [s],
        ``settle_more`` (steps settled beyond ``settle_steps`` because an edge was still stretched
        over SETTLED_STRETCH: up to SETTLE_MORE rounds of ``settle_steps`` while each helps),
        ``seam_gap`` [m] (largest distance between two unsewn copies of a seam vertex after
        sewing, before they are merged), ``max_speed`` [m/s] at the end of settling and
        ``start_height`` [m] the mean height of the placed garment's vertices (the drop check
        of :func:`unsew.sim.checks.check_dressed`), ``guided_seams`` (seam pairs sewn round the
        body, :mod:`unsew.sim.seam_guide`) and, where that drape was unsound and sewing them
        straight gave a sounder one, ``guide_dropped`` (that count; the straight drape returned);
        ``start_given`` (True) where the drape from the wrapped start stayed unsound and one from
        the pattern's own placement (:func:`unsew.body.placement.place_as_given`) was sounder;
        ``held`` the number of rest vertices held at their height (:func:`attached_vertices`),
        0 where none is labelled or where the drape so held was unsound and the free one sounder;
        ``edge_contact`` (True) where the drape was still unsound and one with the body repelling
        the mesh edges' midpoints too (``DrapeSettings.edge_contact``) was sounder.
    """
    mat = resolve_material(material)
    if mesh is None:
        mesh = mesh_pattern(pattern, edge_length=settings.edge_length)
    pattern, mesh = _on_this_body(pattern, mesh, body)
    if sdf is None:
        sdf = BodySDF.build(body)
    g = mat.gamma() if gamma is None else torch.as_tensor(gamma, dtype=torch.float64).detach()
    uv = torch.as_tensor(np.asarray(mesh.uv), dtype=torch.float64)

    anchors = attached_vertices(pattern, mesh, body, sdf)
    cloth = Cloth(uv, g, mat.density, friction=mat.friction, anchors=anchors)
    top, sleeves = None, None
    if settings.judge_placement:
        top, sleeves = placed_top(pattern, mesh, body, sdf=sdf), sleeve_vertices(pattern, mesh, body)
    job = _Job(pattern, body, sdf, mesh, mat, cloth, settings, progress, top, sleeves)
    return _fall_back(job)


def _on_this_body(pattern, mesh, body):
    """(pattern, mesh), their own placement moved onto ``body``'s shoulders where the file was
    sized to another body (:func:`unsew.body.placement.hint_shift`, docs/decisions/070)."""
    shift = hint_shift(pattern, mesh, body)
    if not shift:
        return pattern, mesh
    from unsew.grading.placement import lifted, lifted_mesh

    return lifted(pattern, shift), lifted_mesh(mesh, shift)


def _fall_back(job: _Job) -> Dressed:
    """The drape, and a sounder one where it is unsound: free instead of held at its labelled
    edges, sewn straight instead of round the body, from the pattern's own placement, then with
    the body repelling the mesh edges too."""
    d, job = _fall_back_held(job)
    if _unsound(d, job) and job.settings.edge_fallback and not job.settings.edge_contact:
        # cloth caught across a limb or the armpit, its vertices either side of the body: dress
        # again with the edges' midpoints repelled too and keep the sounder (docs/decisions/042)
        edged = dataclasses.replace(job, settings=job.settings.replace(edge_contact=True))
        try:
            e = _fall_back_unheld(edged, _dress_retried(edged))
        except SimulationError:
            return d
        if _sounder(e, d, job):
            e.stats["edge_contact"] = True
            e.stats["held"] = d.stats["held"]
            return e
    return d


def _fall_back_held(job: _Job) -> tuple[Dressed, _Job]:
    """:func:`_fall_back` but the last step, with the job whose drape it returns (held or free)."""
    if job.cloth.anchors is None:
        d = _fall_back_unheld(job, _dress_retried(job))
        d.stats["held"] = 0
        return d, job
    free_job = dataclasses.replace(job, cloth=dataclasses.replace(job.cloth, anchors=None))
    try:
        d = _dress_retried(job)
    except SimulationError:
        job, d = free_job, _dress_retried(free_job)
    if job is not free_job and _unsound(d, job):
        # held where the pattern puts its hanging edges, the cloth can be pulled too far for a
        # sound drape (a strap off the shoulder): dress it free and keep the sounder of the two
        free = _unless_diverged(d, "the drape with nothing held", _dress_retried, free_job)
        if free is not None and _sounder(free, d, job):
            job, d = free_job, free
    held = 0 if job.cloth.anchors is None else len(job.cloth.anchors[0])
    d = _fall_back_unheld(job, d)
    d.stats["held"] = held
    return d, job


def _fall_back_unheld(job: _Job, d: Dressed) -> Dressed:
    """:func:`_fall_back` after the choice of holding the labelled edges: sewn straight, then from
    the pattern's own placement."""
    if d.stats["guided_seams"] and _unsound(d, job):
        # a seam led round the body can also drag cloth where it should not go: dress again
        # sewing straight and keep the sounder of the two (docs/decisions/033)
        straight = dataclasses.replace(job, settings=dataclasses.replace(job.settings, seam_guide=False))
        plain = _unless_diverged(d, "the drape sewn straight", _dress_retried, straight)
        if plain is not None and _sounder(plain, d, job):
            plain.stats["guide_dropped"] = d.stats["guided_seams"]
            d = plain
    if _unsound(d, job):
        # the wrapped start's reading of the panels can be wrong for a design (a long sleeve
        # taken for a leg, a collar wrapped on the torso): dress again from the pattern's own
        # placement and keep the sounder of the two
        try:
            given = _dress_once(job, force_meet=False, given=True)
        except SimulationError:
            return d  # that drape diverged: the first one's verdict stands
        if _sounder(given, d, job):
            given.stats["start_given"] = True
            return given
    return d


def _dress_retried(job: _Job) -> Dressed:
    """:func:`_dress_once`, and once more with the seam copies started at their midpoint when the
    first drape is unsound and the placement had left them apart."""
    d = _dress_once(job, force_meet=False)
    if not d.stats["met_seams"]:
        fault = _sewing_fault(d, job)
        if fault:
            # Seam copies started apart can tear an edge (a loose tee's sleeve on an A-pose body)
            # or leave a band's seams open and triangles folded: dress again with the copies
            # started at their midpoint, and keep that when it is sound.
            met = "the retry with the seam copies met"
            retry = _unless_diverged(d, met, _dress_once, job, force_meet=True)
            if retry is not None and (
                not _sewing_fault(retry, job) or (not _verdict(d, job).ok and _verdict(retry, job).ok)
            ):
                retry.stats["placement_retry"] = fault
                return retry
    return d


def _unless_diverged(d: Dressed, what: str, dress_fn, *args, **kwargs) -> Dressed | None:
    """``dress_fn(*args, **kwargs)``, a second try at a sounder drape than ``d``; None where it
    diverged, which is noted in ``d.stats["diverged"]``: the drape in hand stands."""
    try:
        return dress_fn(*args, **kwargs)
    except SimulationError:
        d.stats.setdefault("diverged", []).append(what)
        return None


def _verdict(d: Dressed, job: _Job):
    """The checks of drape ``d`` (:func:`unsew.sim.checks.check_dressed`); where the job judges
    the placement (``job.placed_top``), also against the pattern's own placement of its top and
    of its sleeves (round the arms, docs/decisions/062). A seam left open is not judged here
    (docs/decisions/060); ``unsew drape`` refuses the unsewn one it is left with."""
    if job.placed_top is None:
        return check_dressed(d, body=job.body)
    return check_dressed(d, body=job.body, placed_top_m=job.placed_top, sleeves=job.sleeves)


def _unsound(d: Dressed, job: _Job) -> bool:
    """A drape that fails its checks or keeps an edge over SETTLED_STRETCH."""
    return not _verdict(d, job).ok or _stretch_max(d.x, d.mesh) > SETTLED_STRETCH


def _sounder(a: Dressed, b: Dressed, job: _Job) -> bool:
    """Whether drape ``a`` is sounder than ``b``: it passes its checks where ``b`` fails, or both
    alike and its largest edge stretch is lower."""
    ok_a, ok_b = _verdict(a, job).ok, _verdict(b, job).ok
    if ok_a != ok_b:
        return ok_a
    return _stretch_max(a.x, a.mesh) < _stretch_max(b.x, b.mesh)


def settle(
    mesh,
    x_from,
    sdf,
    material="cotton",
    *,
    settings: DrapeSettings = DRESS_SETTINGS,
    model: SimModel | None = None,
    progress: Callable[[str, int, int], None] | None = None,
    anchors=None,
) -> np.ndarray:
    """A sewn garment let settle from another drape: ``settings.settle_steps`` steps of plain
    draping at ``settings.dt`` in ``material``, starting at rest from ``x_from``.

    What :func:`dress` does after sewing, without the placement and the sewing: the cheap way to
    drape a pattern already dressed once in another fabric or stiffness (the fit's material
    choice, :mod:`unsew.fit.material`). mesh: the GarmentMesh ``x_from`` lies on; x_from: (n_x, 3)
    [m]; sdf: the body's SDF; model: the sewn mesh's SimModel (``SimModel.build(mesh.faces,
    mesh.faces_uv)``), to reuse across calls on one mesh (built here when None; its sparse
    pattern is cached on it); progress: ``progress("settle", k, n)``; anchors: the vertices held at
    their height (``Cloth.anchors``, :func:`held_anchors` of the drape x_from), or None. Returns
    (n_x, 3) float64 [m].
    """
    mat = resolve_material(material)
    steps = settings.settle_steps
    x0 = torch.as_tensor(np.asarray(x_from), dtype=torch.float64)
    if x0.shape != (mesh.n_x, 3):
        raise ValueError(f"x_from must be ({mesh.n_x}, 3) positions on the mesh, got {tuple(x0.shape)}")
    uv = torch.as_tensor(np.asarray(mesh.uv), dtype=torch.float64)
    model = SimModel.build(mesh.faces, mesh.faces_uv) if model is None else model
    cb = (lambda k, s: progress("settle", k + 1, steps)) if progress else None
    with torch.no_grad():
        st = drape(
            model,
            SimState.at_rest(x0.clone()),
            sdf,
            Cloth(uv, mat.gamma(), mat.density, friction=mat.friction, anchors=anchors),
            settings=settings,
            steps=steps,
            callback=cb,
        )
    return st.x.detach().numpy()


#: Widest seam [m] left open by the sewing phase that :func:`dress` accepts without a retry.
SEAM_GAP_MAX = 2e-3

#: Largest edge stretch [-] (3D length over pattern length) of a settled garment (a good drape
#: stays below 1.5, :mod:`unsew.sim.checks`): above it :func:`dress` settles on, ``settle_steps``
#: at a time, at most SETTLE_MORE times, while each round lowers it by SETTLE_GAIN or more.
SETTLED_STRETCH = 1.5
SETTLE_MORE = 2
SETTLE_GAIN = 0.01


def _stretch_max(x, mesh) -> float:
    """Largest edge length over its pattern length [-] of sewn positions x (n_x, 3) [m]."""
    e = mesh.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    eu = mesh.faces_uv[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    xn = x.detach().cpu().numpy()
    L = np.linalg.norm(xn[e[:, 0]] - xn[e[:, 1]], axis=1)
    return float((L / np.linalg.norm(mesh.uv[eu[:, 0]] - mesh.uv[eu[:, 1]], axis=1)).max())


def _sewing_fault(d, job) -> str:
    """Why a dressed garment is unsound ("" when it is): a failed verdict (:func:`_verdict`), a
    seam left open wider than SEAM_GAP_MAX, or triangles folded through their neighbours."""
    v = _verdict(d, job)
    if not v.ok:
        return v.reason
    if d.stats["seam_gap"] > SEAM_GAP_MAX:
        return f"seams {d.stats['seam_gap'] * 1000:.1f} mm open after sewing"
    folded = _folded_triangles(d.x.detach().numpy(), d.mesh.faces)
    return f"{folded} triangles folded" if folded else ""


@dataclass(frozen=True)
class _Job:
    """The resolved arguments of :func:`dress`: the cloth holds the mesh's uv (Nu, 2) [m], the
    material's (or the given) Gamma, its density and friction."""

    pattern: object
    body: object
    sdf: object
    mesh: object
    material: Material
    cloth: Cloth
    settings: DrapeSettings
    progress: Callable[[str, int, int], None] | None
    #: the height [m] of the garment's top in the pattern's own placement, where each drape is
    #: judged against it (``DrapeSettings.judge_placement``), else None
    placed_top: float | None = None
    #: :func:`unsew.sim.checks.sleeve_vertices` where the job judges the placement, else None
    sleeves: dict | None = None


def _guided_seams(job: _Job, x_unsewn) -> int:
    """How many seam pairs the sewing leads round the body (0 without ``settings.seam_guide``)."""
    if not job.settings.seam_guide or not len(job.mesh.seam_pairs):
        return 0
    x = x_unsewn if torch.is_tensor(x_unsewn) else torch.as_tensor(np.asarray(x_unsewn))
    x = x.to(torch.float64)
    pairs = torch.as_tensor(np.asarray(job.mesh.seam_pairs), dtype=torch.int64, device=x.device)
    return int(through_pairs(x, pairs, job.sdf).sum())


def _sew_placed(job: _Job, x_unsewn, hold) -> tuple[torch.Tensor, float]:
    """Sew the placed panels x_unsewn (Nu, 3) [m] shut: (sewn positions (n_x, 3) [m], the widest
    seam gap left [m])."""
    mesh, settings, progress = job.mesh, job.settings, job.progress
    model_unsewn = SimModel.build(mesh.faces_uv, mesh.faces_uv, springs=mesh.seam_pairs)
    cb = (lambda k, s: progress("sew", k + 1, settings.sew_steps)) if progress else None
    xs = sew(
        model_unsewn,
        x_unsewn,
        job.sdf,
        job.cloth,
        settings=settings,
        hold=hold if len(hold) else None,
        callback=cb,
    )
    sp = torch.as_tensor(np.asarray(mesh.seam_pairs), dtype=torch.int64)
    gap = float((xs[sp[:, 0]] - xs[sp[:, 1]]).norm(dim=1).max()) if len(sp) else 0.0
    return merge_sewn(xs, mesh.x_of_u, mesh.n_x), gap


def _settle_sewn(job: _Job, model, x) -> tuple[torch.Tensor, float, int]:
    """Settle the sewn garment x (n_x, 3) [m]: ``settle_steps``, then more while an edge stays
    stretched (module constants). Returns (positions [m], largest speed [m/s], steps beyond
    ``settle_steps``)."""
    settings, progress, sdf, mesh = job.settings, job.progress, job.sdf, job.mesh
    more = 0
    cb = (lambda k, s: progress("settle", k + 1, settings.settle_steps)) if progress else None
    with torch.no_grad():
        st = drape(
            model,
            SimState.at_rest(x),
            sdf,
            job.cloth,
            settings=settings,
            steps=settings.settle_steps,
            callback=cb,
        )
        # still pulled somewhere (a seam just closed, cloth caught under an arm): settle on
        worst = _stretch_max(st.x, mesh)
        while worst > SETTLED_STRETCH and more < SETTLE_MORE * settings.settle_steps:
            st = drape(model, st, sdf, job.cloth, settings=settings, steps=settings.settle_steps)
            more += settings.settle_steps
            now = _stretch_max(st.x, mesh)
            if worst - now < SETTLE_GAIN:
                break
            worst = now
    return st.x, float(st.v.norm(dim=1).max()), more


def _dress_once(job: _Job, *, force_meet: bool, given: bool = False) -> Dressed:
    """One placement, sewing and settling of :func:`dress` (its arguments resolved); ``given``:
    from the pattern's own placement (:func:`unsew.body.placement.place_as_given`)."""
    pattern, body, mesh = job.pattern, job.body, job.mesh
    t0 = time.perf_counter()
    if given:
        x_unsewn = place_as_given(pattern, mesh, body, sdf=job.sdf)
    else:
        x_unsewn = place_garment(pattern, mesh, body, sdf=job.sdf, force_meet=force_meet)
    hold = hold_vertices(pattern, mesh, body, x_unsewn)
    t1 = time.perf_counter()
    if job.progress:
        job.progress("place", 1, 1)
    guided = _guided_seams(job, x_unsewn)
    x, gap = _sew_placed(job, x_unsewn, hold)
    model = SimModel.build(mesh.faces, mesh.faces_uv)
    t2 = time.perf_counter()
    speed = 0.0
    more = 0
    if job.settings.settle_steps > 0:
        x, speed, more = _settle_sewn(job, model, x)
    t3 = time.perf_counter()
    x_start = np.asarray(merge_sewn(x_unsewn, mesh.x_of_u, mesh.n_x), dtype=np.float64)
    stats = dict(
        place_s=t1 - t0,
        sew_s=t2 - t1,
        settle_s=t3 - t2,
        seam_gap=gap,
        max_speed=speed,
        start_height=float(x_start[:, 1].mean()),
        met_seams=not given and (force_meet or meets_seams(body)),
        settle_more=more,
        guided_seams=guided,
    )
    return Dressed(pattern, mesh, model, x.detach(), job.cloth.uv, job.material, job.sdf, stats, x_start)
