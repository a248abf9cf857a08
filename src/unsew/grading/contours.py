"""Open contours placed on the skeleton, and matched between a source and a target garment
(paper 3.3 and supplementary Algorithm 2).

Every open contour (boundary loop, :func:`unsew.losses.contours.open_contours`) is located on the
wearer's skeleton:

- its *encircled bones* are Algorithm 2's EncircledBones: the bones onto which the contour centre
  projects inside the segment (0 < u < 1). The torso's root bone (pelvis -> its child on the
  torso chain) is also tried below the pelvis (u <= 0): a t-shirt hem or a skirt hem hangs below
  the pelvis joint, on the continuation of the spine, not around a thigh; likewise the last bone
  of a limb chain past its end (u >= 1: a leg opening below the ankle joint);
- among them, the bones whose line passes *through* the loop (distance h of the centre to the
  bone below the loop's mean radius) are preferred, then those that cross the loop's plane at
  more than 30 degrees (not a sideways hip or collar bone); the nearest (smallest h) is the
  contour's bone, and its part (``torso``, ``head``, ``left_arm``, ...) the contour's part;
- its axial position is ``distToRoot(P)``: the distance along the chain of bones from the
  skeleton's root to the projection P of the centre (:meth:`Skeleton.distance_to_root`, with the
  unclamped axial coordinate, so a hem below the pelvis has a negative position).

Matching (Algorithm 2's MAP): a source and a target contour may pair when they share a body part
(``head`` and ``torso`` count as one: a neckline sits on the neck bone or just above it). Among
allowed pairs the assignment minimising a cost on centre distance, relative perimeter difference
and normal angle is taken (Hungarian); pairs beyond the gates (:data:`MAX_CENTRE_DISTANCE`,
:data:`MAX_PERIMETER_RATIO`) are never made, so a hole that matches nothing stays unmatched.

The girth difference of a pair is the difference of the loops' lengths (grading reads a
crumpled and stretched loop differently: :func:`unsew.grading.grade.source_girth`). A slit or
vent (a skirt's side slit: the hem loop climbs up the side seam and comes back) is no girth: its
climb and return are cut from the loop's length, centre, plane and cloth length (:func:`slits`).

The axial distance of a pair is ``distToRoot(P_t) - distToRoot(P_s)`` along the source
contour's bone chain (the target's own bone when it lies on the same part, else the target
centre projected on the source's bone). The *extension* is that distance signed so that positive
means the target contour lies further out from the garment (a longer hem, sleeve or leg, a
higher neckline or waist).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from unsew.body.skeleton import Bone, Skeleton, axial_coordinate, encircled_bones
from unsew.geometry.topology import vertex_adjacency
from unsew.losses.contours import Contour, open_contours

__all__ = [
    "PlacedContour",
    "ContourMatch",
    "place_contours",
    "match_contours",
    "lone_parts",
    "part_group",
    "MAX_CENTRE_DISTANCE",
    "MAX_PERIMETER_RATIO",
    "FAR_CENTRE_FACTOR",
    "FAR_PARTS",
    "hull_perimeter",
    "slits",
]

#: Source and target contours whose centres are further apart than this are never paired [m].
MAX_CENTRE_DISTANCE = 0.45
#: ... nor those whose perimeters differ by more than this factor (either way).
MAX_PERIMETER_RATIO = 2.0
#: A pair farther apart than MAX_CENTRE_DISTANCE but within this factor of it still matches when
#: each contour is the only one of its body part on its mesh and the part is one of FAR_PARTS
#: (:func:`match_contours`): a hem. Not the arms: a long sleeve's cuff would pair with a tank
#: top's armhole, each the only contour of its arm, half a metre up.
FAR_CENTRE_FACTOR = 2.0
FAR_PARTS = ("torso",)
#: Contours flatter than this (second/first singular value) have no plane to compare.
MIN_ROUNDNESS = 0.2
#: Edge rings around a contour whose vertices tell on which side of it the cloth lies.
INWARD_RINGS = 3
#: A slit: the loop climbs along its bone into the cloth by at least SLIT_RISE [m] in segments
#: steeper than SLIT_STEEP (|axial step| / step length) and comes back down the same way. A hem's
#: folds wave across the bone, a sloped hem climbs gently: neither is cut.
SLIT_RISE = 0.04
SLIT_STEEP = 0.7
#: Segments at a slit's top that may lie flat between its climb and its return.
SLIT_APEX = 2


def lone_parts(contours: list[PlacedContour]) -> set[str]:
    """The body parts on which exactly one of ``contours`` (placed on a bone) lies."""
    parts = [c.part for c in contours if c.bone is not None]
    return {p for p in parts if parts.count(p) == 1}


def part_group(part: str) -> str:
    """The matching group of a body part: ``head`` and ``torso`` are one group (``torso``)."""
    return "torso" if part in ("torso", "head") else part


@dataclass
class PlacedContour:
    """One open contour located on the skeleton.

    index: position in the list of contours of its mesh.
    contour: the :class:`~unsew.losses.contours.Contour` (indices into the mesh's vertices,
        length [m], centre (3,) [m], unit normal (3,)).
    radius: mean distance of the contour's vertices to its centre [m].
    bone: the bone it is located on (None when no bone qualifies).
    u: axial coordinate of the centre on ``bone`` (unclamped) [dimensionless].
    h: distance of the centre to the bone's line [m].
    part: body part of ``bone`` (``""`` when none).
    position: distToRoot of the centre's projection on ``bone`` [m].
    candidates: all qualifying bones, nearest first: (bone, u, h) tuples.
    roundness: second over first singular value of the centred contour points, outside its
        slits (0 for a loop collapsed onto a line, whose normal means nothing; about 1 for a
        round loop).
    inward: (3,) [m] from the centre to the mean of the garment vertices within
        :data:`INWARD_RINGS` edge rings of the contour (the side the cloth lies on); None when
        the mesh gives no such vertices.
    hull: perimeter of the convex hull of the loop (outside its slits) in its least-squares
        plane [m] (:func:`hull_perimeter`; NaN when not measured).
    slit_cut: length cut from the perimeter for slits [m] (:func:`slits`; 0 without).
    kept: (k,) bool over ``contour.indices``, False on a slit's climb and return; None: no slit.
    rim_centre, rim_normal: (3,) [m] mean and (3,) unit least-squares plane normal of the
        vertices outside the slits; None without slits (``centre`` and ``normal`` then read
        the contour's own).
    """

    index: int
    contour: Contour
    radius: float
    bone: Bone | None
    u: float
    h: float
    part: str
    position: float
    candidates: list = field(default_factory=list)
    roundness: float = 1.0
    inward: np.ndarray | None = None
    hull: float = float("nan")
    slit_cut: float = 0.0
    kept: np.ndarray | None = None
    rim_centre: np.ndarray | None = None
    rim_normal: np.ndarray | None = None

    @property
    def crumple(self) -> float:
        """Loop length over hull perimeter (dimensionless): about 1 for a smooth loop, more for
        a pleated or crumpled one; 1.0 when the hull was not measured."""
        if not np.isfinite(self.hull) or self.hull <= 0:
            return 1.0
        return float(self.length / self.hull)

    @property
    def length(self) -> float:
        """Perimeter [m], less the climb and return of its slits (``slit_cut``)."""
        return float(self.contour.length) - self.slit_cut

    @property
    def centre(self) -> np.ndarray:
        """Centre (3,) [m]: the contour's, or with slits the mean of the vertices outside them."""
        return self.contour.centre if self.rim_centre is None else self.rim_centre

    @property
    def normal(self) -> np.ndarray:
        """Unit normal (3,) of the loop's least-squares plane (outside its slits, when it has some)."""
        return self.contour.normal if self.rim_normal is None else self.rim_normal

    @property
    def rim(self) -> np.ndarray:
        """(k',) int64 mesh vertex indices of the loop outside its slits (all of it without)."""
        idx = np.asarray(self.contour.indices, dtype=np.int64)
        return idx if self.kept is None else idx[self.kept]


@dataclass
class ContourMatch:
    """A source contour paired with a target contour.

    source, target: indices into the source and target contour lists.
    part: body part of the source contour's bone.
    bone: name of the bone the distance is measured along (the source's).
    axial_distance: distToRoot(P_t) - distToRoot(P_s) [m] (Algorithm 2).
    extension: the axial distance signed outward from the garment [m]: > 0 when the target
        contour lies further from the garment's middle than the source's (a longer sleeve).
    girth_difference: target perimeter - source perimeter [m].
    cost: matching cost (dimensionless; smaller is a closer pair).
    """

    source: int
    target: int
    part: str
    bone: str
    axial_distance: float
    extension: float
    girth_difference: float
    cost: float


def _torso_root_bone(skeleton: Skeleton) -> Bone | None:
    """The bone from the root joint to its child on the torso axis (pelvis -> spine): the child
    of the root whose bone is torso and points most upward."""
    root = int(np.flatnonzero(skeleton.parents == -1)[0])
    best, best_up = None, -np.inf
    for b in skeleton.bones():
        if skeleton.index(b.parent) == root and b.part == "torso":
            up = float(b.direction[1])
            if up > best_up:
                best, best_up = b, up
    return best if best_up > 0.5 else None


def _chain_end_bones(skeleton: Skeleton) -> list[Bone]:
    """Bones of a limb (not torso/head) that end a chain: no child bone of the same part
    continues in their direction (cosine > 0.7). A leg opening below the ankle joint or a long
    cuff past the wrist lies on their continuation (u >= 1)."""
    bones = skeleton.bones()
    out = []
    for b in bones:
        if b.part in ("torso", "head"):
            continue
        kids = [c for c in bones if c.parent == b.child and c.part == b.part]
        if not any(float(c.direction @ b.direction) > 0.7 for c in kids):
            out.append(b)
    return out


def place_contours(
    verts, faces, skeleton: Skeleton, *, contours: list[Contour] | None = None
) -> list[PlacedContour]:
    """Open contours of a mesh located on the skeleton (module docstring).

    verts: (V, 3) float64 [m] (numpy or torch). faces: (F, 3) int.
    skeleton: the wearer's skeleton, same frame.
    contours: precomputed ``open_contours(verts, faces)`` (default: computed here).

    Returns one :class:`PlacedContour` per contour, in the order of ``contours``.
    """
    try:
        import torch

        if isinstance(verts, torch.Tensor):
            verts = verts.detach().cpu().numpy()
    except ImportError:  # pragma: no cover
        pass
    v = np.asarray(verts, dtype=np.float64)
    if contours is None:
        contours = open_contours(v, faces)
    bones = skeleton.bones()
    root_bone = _torso_root_bone(skeleton)
    adj = vertex_adjacency(faces, len(v))
    ends = _chain_end_bones(skeleton)
    return [_placed(i, c, v, adj, skeleton, bones, root_bone, ends) for i, c in enumerate(contours)]


def _bone_candidates(c: Contour, pts: np.ndarray, bones, root_bone, ends) -> list:
    """(bone, u, h) candidates for contour ``c`` (its points ``pts`` (k, 3) [m]): the bones it
    encircles, the torso's root bone when it lies below its start, the chain-end bones when it lies
    beyond their ends (u: axial coordinate [-], h: distance from the bone's line [m])."""
    cands = [(e.bone, e.u, e.h) for e in encircled_bones(pts, bones)]
    if root_bone is not None:
        u = float(axial_coordinate(c.centre, root_bone))
        if u <= 0.0:
            P = root_bone.a + u * (root_bone.b - root_bone.a)
            cands.append((root_bone, u, float(np.linalg.norm(c.centre - P))))
    for b in ends:
        u = float(axial_coordinate(c.centre, b))
        if u >= 1.0:
            P = b.a + u * (b.b - b.a)
            cands.append((b, u, float(np.linalg.norm(c.centre - P))))
    return cands


def _placed(
    i: int, c: Contour, v: np.ndarray, adj, skeleton: Skeleton, bones, root_bone, ends
) -> PlacedContour:
    """Contour ``c`` (index ``i``) of the mesh with vertices ``v`` (V, 3) [m] placed on its bone:
    the best candidate of :func:`_bone_candidates`, the loop read without its slits."""
    pts = v[c.indices]
    radius = float(np.linalg.norm(pts - c.centre, axis=1).mean())
    sv = np.linalg.svd(pts - pts.mean(axis=0), compute_uv=False)
    roundness = float(sv[1] / sv[0]) if len(sv) > 1 and sv[0] > 0 else 0.0
    cands = _bone_candidates(c, pts, bones, root_bone, ends)
    # bones through the loop first, then bones across the loop's plane (a contour encircles a
    # bone roughly along its normal; a sideways hip or collar bone is not it), then the nearest
    across = lambda b: roundness < MIN_ROUNDNESS or abs(float(c.normal @ b.direction)) >= 0.5  # noqa: E731
    cands.sort(key=lambda t: (t[2] >= radius, not across(t[0]), t[2]))
    inward = _inward(adj, v, c)
    if not cands:
        nan = float("nan")
        return PlacedContour(
            i, c, radius, None, nan, nan, "", nan, [], roundness, inward, hull_perimeter(pts)
        )
    bone, u, h = cands[0]
    kept, cut = slits(pts, _into_cloth(bone.direction, inward))
    hull = hull_perimeter(pts if kept is None else pts[kept])
    pc = PlacedContour(
        i,
        c,
        radius,
        bone,
        float(u),
        float(h),
        bone.part,
        0.0,
        cands,
        roundness,
        inward,
        hull,
        slit_cut=cut,
        kept=kept,
    )
    if kept is not None:  # the loop's place and plane without its slits
        rim = pts[kept]
        pc.rim_centre = rim.mean(axis=0)
        _, sv, vt = np.linalg.svd(rim - pc.rim_centre, full_matrices=False)
        pc.rim_normal = vt[2] if float(vt[2] @ c.normal) >= 0 else -vt[2]
        pc.roundness = float(sv[1] / sv[0]) if sv[0] > 0 else 0.0
        u = float(axial_coordinate(pc.rim_centre, bone))
        pc.u = u
    pc.position = float(skeleton.distance_to_root(bone, u))
    return pc


def hull_perimeter(points) -> float:
    """Perimeter [m] of the convex hull of ``points`` (k, 3) [m] projected on their
    least-squares plane; NaN for fewer than three points or points on a line."""
    from scipy.spatial import ConvexHull, QhullError

    p = np.asarray(points, dtype=np.float64)
    if len(p) < 3:
        return float("nan")
    c = p - p.mean(axis=0)
    _, _, vt = np.linalg.svd(c, full_matrices=False)
    q = c @ vt[:2].T
    try:
        ring = q[ConvexHull(q).vertices]
    except QhullError:
        return float("nan")
    return float(np.linalg.norm(np.roll(ring, -1, axis=0) - ring, axis=1).sum())


def _into_cloth(direction, inward) -> np.ndarray:
    """The unit bone direction (3,) signed to point into the cloth (along ``inward`` when known)."""
    a = np.asarray(direction, dtype=np.float64)
    a = a / max(float(np.linalg.norm(a)), 1e-12)
    return -a if inward is not None and float(a @ inward) < 0 else a


def slits(points, axis) -> tuple[np.ndarray | None, float]:
    """Slits and vents of one loop: (kept, cut).

    points: (k, 3) float64 [m], the loop in walking order; axis: (3,) unit, along the bone into
    the cloth (up from a hem, down from a neckline). A slit is a run of segments climbing along
    ``axis`` by at least :data:`SLIT_RISE`, each steeper than :data:`SLIT_STEEP`, then (after at
    most :data:`SLIT_APEX` flat segments at its top) a run coming down by as much.
    kept: (k,) bool, False on the vertices strictly inside a slit's climb and return; None when
    the loop has no slit, or when its climbs and returns would leave fewer than three of its
    vertices (a tall narrow loop along ``axis``: no rim to place, and the rim's plane was
    undefined). cut: the slits' length less the chords that close them [m].
    """
    p = np.asarray(points, dtype=np.float64)
    k = len(p)
    d = np.roll(p, -1, axis=0) - p  # segment t: p[t] -> p[t + 1]
    seg = np.linalg.norm(d, axis=1)
    dh = d @ np.asarray(axis, dtype=np.float64)
    sgn = np.where(np.abs(dh) > SLIT_STEEP * np.maximum(seg, 1e-12), np.sign(dh), 0.0).astype(np.int64)
    flat = np.flatnonzero(sgn == 0)
    if k < 4 or len(flat) == 0:
        return None, 0.0
    h = p @ np.asarray(axis, dtype=np.float64)
    start = flat[np.argmin(h[flat])]  # the lowest flat segment: on the hem, not a slit's top
    order = (start + np.arange(k)) % k  # walked from there, no slit wraps round the end
    s_, h_, l_ = sgn[order], dh[order], seg[order]
    kept, cut, t = np.ones(k, dtype=bool), 0.0, 0
    while t < k:
        if s_[t] != 1:
            t += 1
            continue
        a = t
        while t < k and s_[t] == 1:
            t += 1
        top = t
        while t < k and t - top < SLIT_APEX and s_[t] == 0:
            t += 1
        b = t
        while t < k and s_[t] == -1:
            t += 1
        if t > b and h_[a:top].sum() >= SLIT_RISE and -h_[b:t].sum() >= SLIT_RISE:
            i, j = order[a], order[t % k]  # the slit runs from vertex i to vertex j
            kept[order[a + 1 : t]] = False
            cut += float(l_[a:t].sum() - np.linalg.norm(p[j] - p[i]))
    return (None, 0.0) if kept.all() or np.count_nonzero(kept) < 3 else (kept, cut)


def _inward(adj, v, c: Contour) -> np.ndarray | None:
    """From the contour's centre to the mean of the vertices within INWARD_RINGS edge rings of
    it (the contour's own vertices excluded): (3,) [m], or None when there are none."""
    on = np.zeros(adj.shape[0], dtype=bool)
    on[np.asarray(c.indices, dtype=np.int64)] = True
    seen = on.copy()
    for _ in range(INWARD_RINGS):
        seen |= (adj @ seen.astype(np.int8)) > 0
    near = seen & ~on
    if not near.any():
        return None
    return v[near].mean(axis=0) - c.centre


def _target_position(skeleton: Skeleton, s: PlacedContour, t: PlacedContour) -> float:
    """distToRoot of the target centre along the source's chain: the target's own bone when it
    is of the same part group, else the target centre projected on the source's bone."""
    if t.bone is not None and part_group(t.part) == part_group(s.part):
        return t.position
    u = float(axial_coordinate(t.centre, s.bone))
    return float(skeleton.distance_to_root(s.bone, u))


def match_contours(
    source: list[PlacedContour],
    target: list[PlacedContour],
    skeleton: Skeleton,
    *,
    garment_centre: np.ndarray,
    max_centre_distance: float = MAX_CENTRE_DISTANCE,
    max_perimeter_ratio: float = MAX_PERIMETER_RATIO,
) -> list[ContourMatch]:
    """Pair source and target contours on the same body part (Algorithm 2) and measure them.

    source, target: from :func:`place_contours` on the source (draped base pattern) and target
        meshes. skeleton: the wearer's.
    garment_centre: (3,) [m] a point in the middle of the source garment (its vertex mean), used
        to sign the extension outward for a contour without neighbouring vertices (else its
        ``inward`` side tells).
    max_centre_distance [m], max_perimeter_ratio: gates beyond which no pair is made, but for
        a pair farther apart than max_centre_distance (up to :data:`FAR_CENTRE_FACTOR` times it)
        whose contours are each the only torso contour of their mesh (a long base's hem half a
        metre below a short target's: left alone, its cloth went into the area scaling).

    Returns the matches (each source and target contour at most once), by source index.
    """
    from scipy.optimize import linear_sum_assignment

    ns, nt = len(source), len(target)
    big = 1e6
    cost = np.full((max(ns, 1), max(nt, 1)), big)
    far = {}  # (i, j) -> the cost of a pair that failed the centre-distance gate alone
    for i, s in enumerate(source):
        for j, t in enumerate(target):
            c = _pair_cost(s, t, max_centre_distance, max_perimeter_ratio)
            if c is None:
                continue
            if float(np.linalg.norm(s.centre - t.centre)) > max_centre_distance:
                far[i, j] = c
                continue
            cost[i, j] = c
    # A pair kept apart by the centre distance alone still matches when each is the only torso
    # contour of its mesh: a long base's hem half a metre below a short target's.
    alone = lone_parts(source) & lone_parts(target) & set(FAR_PARTS)
    for (i, j), c in far.items():
        if source[i].part == target[j].part in alone:
            cost[i, j] = c
    if ns == 0 or nt == 0:
        return []
    rows, cols = linear_sum_assignment(cost)
    out = [
        _measured(int(i), int(j), source[i], target[j], skeleton, garment_centre, float(cost[i, j]))
        for i, j in zip(rows, cols)
        if cost[i, j] < big
    ]
    out.sort(key=lambda m: m.source)
    return out


def _pair_cost(s: PlacedContour, t: PlacedContour, max_centre_distance: float, max_perimeter_ratio: float):
    """The cost of pairing source contour ``s`` with target contour ``t`` (centre distance over the
    source's radius + perimeter ratio - 1 + 1 - |cos| of the planes' angle), or None when they
    cannot pair: unplaced, on other body parts, perimeters too different, centres farther apart
    than FAR_CENTRE_FACTOR x ``max_centre_distance`` [m], planes more than 60 degrees apart."""
    if s.bone is None or t.bone is None:
        return None
    s_parts = {part_group(b.part) for b, _, _ in s.candidates}
    t_parts = {part_group(b.part) for b, _, _ in t.candidates}
    if part_group(s.part) not in t_parts and part_group(t.part) not in s_parts:
        return None
    dc = float(np.linalg.norm(s.centre - t.centre))
    ratio = max(s.length, t.length) / max(min(s.length, t.length), 1e-9)
    if ratio > max_perimeter_ratio or dc > FAR_CENTRE_FACTOR * max_centre_distance:
        return None
    cosn = abs(float(s.normal @ t.normal))
    if min(s.roundness, t.roundness) < MIN_ROUNDNESS:
        cosn = 1.0  # a loop collapsed onto a line has no meaningful plane
    elif cosn < 0.5:  # planes more than 60 degrees apart
        return None
    ref = max(s.radius, 0.05)
    return dc / ref + (ratio - 1.0) + (1.0 - cosn)


def _measured(i: int, j: int, s: PlacedContour, t: PlacedContour, skeleton, garment_centre, cost: float):
    """The :class:`ContourMatch` of source contour ``s`` (index ``i``) and target ``t`` (``j``):
    the axial distance along the source's bone, signed outward, and the girth difference [m]."""
    axial = _target_position(skeleton, s, t) - s.position
    # Outward: away from the cloth next to the contour (a cuff's sleeve, a hem's body); the
    # garment's centre only when the mesh gave no neighbours. (The vertex mean of a long
    # dress lies so low that it read a sleeve's outward direction backwards.)
    if s.inward is not None:
        outward = -float(s.inward @ s.bone.direction)
    else:
        outward = float((s.centre - np.asarray(garment_centre, dtype=np.float64)) @ s.bone.direction)
    sign = 1.0 if outward >= 0 else -1.0
    return ContourMatch(
        source=i,
        target=j,
        part=s.part,
        bone=s.bone.name,
        axial_distance=float(axial),
        extension=float(sign * axial),
        girth_difference=float(t.length - s.length),
        cost=cost,
    )
