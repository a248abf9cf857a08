"""The structural choices of a draped garment read off its shape: sleeves, necklines, a hood or a
standing collar, the skirt's flare and the hem's length.

Only the target's openings, its cross-sections and the skeleton's joint positions are used
(FORMATS.md's required names), as in :mod:`unsew.grading.garment_type`, which reads the type:

- sleeves: where each arm opening's centre lies along the shoulder-elbow-wrist line, as a share
  of the arm (an armhole stays at the shoulder);
- necklines: the neck opening's front and back halves, seen from the front: a V has one corner at
  its bottom, a square a flat bottom between two corners, any other shape is round; no neck
  opening on a bodice is a strapless top; not read under a hood or a standing collar;
- a hood rises over the head joint; a standing (turtle) collar's opening sits above the neck joint;
- the skirt's flare: the hem's length over the garment's girth at the hip joints (a cross-section
  of the mesh, :func:`trimesh.intersections.mesh_plane`);
- the length: the hem's (or the leg openings') depth below the hip joints as a share of the leg
  (hip joints to the floor under the ankles);
- waist darts, which no mesh shows: decided from how close the cut follows the body
  (:func:`_darts`): a bodice's girth at the chest line, a straight skirt's or trousers' at the
  hip joints, over the body's there.

Waistbands and cuffs are not read: no girth profile or rim measure tells them apart on the
GarmentCode targets (docs/decisions/030-separate-pieces-and-darts.md).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from unsew.grading.garment_type import (
    GarmentReading,
    _chest_y,
    _encloses,
    _limb_chains,
    _mid_y,
    _neck_opening,
    _openings_by_part,
    _half_is_v,
    _half_run,
    _radius,
    read_garment_type,
    read_necklines,
)
from unsew.losses.contours import open_contours

__all__ = [
    "DesignReading",
    "read_design",
    "SLEEVE_CLASSES",
    "NECK_CLASSES",
    "COLLAR_CLASSES",
    "SKIRT_CLASSES",
    "LENGTH_CLASSES",
]

SLEEVE_CLASSES = ("none", "short", "long")
NECK_CLASSES = ("round", "v", "square", "none")
COLLAR_CLASSES = ("none", "hood", "turtle")
SKIRT_CLASSES = ("pencil", "a-line", "flared")
LENGTH_CLASSES = ("above knee", "knee", "below knee")

#: An arm opening crossed by the arm line (or, when the arm line misses it, whose centre lies)
#: within this share of the arm (shoulder to wrist) from the shoulder joint is an armhole (no
#: sleeve): an armhole's seam runs round the shoulder's rim, about a fifth of the arm out from the
#: joint at most ...
ARMHOLE_SHARE = 0.2
#: ... one past it and up to this share ends a short sleeve (above the elbow), beyond it a long one.
SHORT_SLEEVE_SHARE = 0.5
#: A loop round no limb, beside the torso and narrower than this [m] (mean radius) is a sleeve's
#: end hanging off the arm line (a wide armhole's radius is about 0.07 m) ...
SLEEVE_END_RADIUS = 0.05
#: ... and so is a wider one (a bell sleeve's cuff) whose centre lies farther than this many of
#: its radii from the shoulder joint: an armhole goes round the shoulder, its centre within about
#: its diameter of the joint.
SLEEVE_END_REACH = 4.0
#: A square neckline half: its bottom stays within this share of the half's depth over at least
#: :data:`SQUARE_FLAT` of the neckline's width (a round bottom: about half of it; a V: a point)
#: and ends in a corner (a shallow round back is as flat, without corners).
SQUARE_BAND = 0.15
SQUARE_FLAT = 0.6
#: A hood: the garment rises this far [m] or more above the head joint.
HOOD_ABOVE_HEAD = 0.05
#: A standing collar: the neck opening's centre sits this far [m] or more above the neck joint.
TURTLE_ABOVE_NECK = 0.04
#: The skirt's flare (the hem's length seen from above, a slit's rise left out, over the hip
#: girth: the body's at the hip joints, arms left out, or the garment's without a body): below
#: the first value a pencil skirt, below the second an A-line, beyond a flared (circle, godet,
#: tiered) one; GarmentCode's designs are classed by the same ratio (benchmarks/gcd/truth.py).
FLARE_EDGES = (1.2, 1.7)
#: A bodice reaches over the shoulders when cloth lies higher than the shoulder joints beside the
#: neck (between these shares of the half shoulder width out from the centre line): a strap or a
#: shoulder seam lies on the shoulder, a few cm over the joint; a strapless top's edge stays under
#: the armpits, well below it.
STRAP_BAND = (0.4, 1.2)
#: The hem's depth below the hip joints as a share of the leg: up to the first value above the
#: knee, up to the second at the knee, beyond below it.
LENGTH_EDGES = (0.33, 0.55)
#: The floor lies under the ankle joints by this share of the hip-to-ankle height.
ANKLE_HEIGHT = 0.09
#: Waist darts: a bodice whose girth at the chest line, or a straight skirt's or trousers' at the
#: hip joints, is at most this times the body's there is cut to the body and takes darts.
FITTED_EASE = 1.06


@dataclass(frozen=True)
class DesignReading:
    """A garment's structural choices read off its shape; each None where the garment has no such
    part (no sleeves' reading on a skirt, no skirt on trousers).

    garment: the type (:data:`unsew.grading.garment_type.READ_TYPES`); sleeves: one of
    :data:`SLEEVE_CLASSES`; neck_front, neck_back: :data:`NECK_CLASSES`; collar:
    :data:`COLLAR_CLASSES`; skirt: :data:`SKIRT_CLASSES`; length: :data:`LENGTH_CLASSES`;
    darts: whether the cut needs waist darts (decided, not seen: :func:`_darts`);
    evidence: {choice: the measure it was read from, in words}; numbers: {"sleeve_share",
    "hem_share", "flare", "front_deg", ...} the measures themselves (shares [-], angles [deg]);
    "sleeve_through" 1.0 where the sleeve share is where the arm line passes through the opening
    or where the garment has no arm opening (no share to doubt), 0.0 where it is an opening's
    centre off the arm line.
    """

    garment: str
    sleeves: str | None = None
    neck_front: str | None = None
    neck_back: str | None = None
    collar: str | None = None
    skirt: str | None = None
    length: str | None = None
    darts: bool | None = None
    evidence: dict = field(default_factory=dict)
    numbers: dict = field(default_factory=dict)

    def choices(self) -> dict:
        """{choice: class or None} for sleeves, neck_front, neck_back, collar, skirt, length, darts."""
        keys = ("sleeves", "neck_front", "neck_back", "collar", "skirt", "length", "darts")
        return {k: getattr(self, k) for k in keys}

    def summary(self) -> str:
        """One line: the type and each choice read, with its evidence."""
        parts = [self.garment]
        for k, v in self.choices().items():
            if v is not None:
                ev = self.evidence.get(k)
                parts.append(_WORDS[k](v) + (f" ({ev})" if ev else ""))
        return "read: " + ", ".join(parts)


#: How each choice reads in :meth:`DesignReading.summary`.
_WORDS = {
    "sleeves": lambda v: "sleeveless" if v == "none" else f"{v} sleeves",
    "neck_front": lambda v: "strapless" if v == "none" else f"{'V' if v == 'v' else v}-neck front",
    "neck_back": lambda v: "no back neckline" if v == "none" else f"{'V' if v == 'v' else v}-neck back",
    "collar": lambda v: "no collar" if v == "none" else ("a hood" if v == "hood" else "a standing collar"),
    "skirt": lambda v: f"{v} skirt",
    "length": lambda v: "hem at the knee" if v == "knee" else f"hem {v.replace(' ', ' the ')}",
    "darts": lambda v: "waist darts" if v else "no darts",
}


def _arm_share(p: np.ndarray, joints: list[np.ndarray]) -> float:
    """Where point p (3,) [m] lies along the polyline ``joints`` (shoulder, elbow, wrist, ...): the
    arc length to its nearest point over the shoulder-to-wrist length [-]."""
    seg = [(a, b) for a, b in zip(joints[:-1], joints[1:])]
    lengths = np.array([np.linalg.norm(b - a) for a, b in seg])
    best, share = np.inf, 0.0
    for k, (a, b) in enumerate(seg):
        t = float(np.clip((p - a) @ (b - a) / max(lengths[k] ** 2, 1e-12), 0.0, 1.0))
        d = float(np.linalg.norm(a + t * (b - a) - p))
        if d < best:
            best, share = d, float(lengths[:k].sum() + t * lengths[k])
    return share / max(float(lengths[:2].sum()), 1e-9)


def _hanging_ends(v: np.ndarray, loops, centres: np.ndarray, skeleton, free: np.ndarray) -> list[float]:
    """Shares of the arm of the sleeve ends that hang off the arm line (a tight cuff of a sleeve
    that did not follow the arm): ``free`` (C,) bool loops round no limb, narrower than
    :data:`SLEEVE_END_RADIUS` or farther than :data:`SLEEVE_END_REACH` radii from the shoulder
    joint, beside the torso (out past the shoulder joints' half-way line) and between the hips
    and the shoulders. The share: the farther of the end's projection on the arm line and its
    straight distance from the shoulder joint, over the arm's length."""
    chains = _limb_chains(skeleton)
    mid_x = 0.5 * (skeleton.position("left_shoulder")[0] + skeleton.position("right_shoulder")[0])
    half = 0.5 * abs(skeleton.position("left_shoulder")[0] - skeleton.position("right_shoulder")[0])
    hip_y, sh_y = _mid_y(skeleton, "hip"), _mid_y(skeleton, "shoulder")
    out = []
    for i in np.flatnonzero(free):
        c = centres[i]
        if abs(c[0] - mid_x) < 0.5 * half or not hip_y < c[1] < sh_y:
            continue
        side = "left" if (c[0] - mid_x) * (skeleton.position("left_shoulder")[0] - mid_x) > 0 else "right"
        arm = chains[f"{side}_arm"]
        radius, from_shoulder = _radius(v, loops[i]), float(np.linalg.norm(c - arm[0]))
        if radius > SLEEVE_END_RADIUS and from_shoulder <= SLEEVE_END_REACH * radius:
            continue
        reach = float(np.linalg.norm(arm[1] - arm[0]) + np.linalg.norm(arm[2] - arm[1]))
        out.append(max(_arm_share(c, arm), from_shoulder / reach))
    return out


def _arm_crossing(pts: np.ndarray, arm: list[np.ndarray], centre: np.ndarray) -> np.ndarray | None:
    """Where the arm line ``arm`` (shoulder, elbow, wrist, ...), run on inwards to the torso's
    centre ``centre`` (3,) [m], passes through the opening ``pts`` (k, 3) [m]: its crossing with
    the opening's plane (the points' least-squares plane) when that lies inside the opening, else
    None. An armhole is crossed at the shoulder however low it hangs; a sleeve's end where it ends."""
    c = pts.mean(axis=0)
    _, _, vt = np.linalg.svd(pts - c)
    n, basis = vt[2], vt[:2]
    line = [centre, *arm]
    for a, b in zip(line[:-1], line[1:]):
        da, db = float((a - c) @ n), float((b - c) @ n)
        if da * db > 0 or da == db:
            continue
        p = a + da / (da - db) * (b - a)
        if _encloses((pts - c) @ basis.T, basis @ (p - c)):
            return p
    return None


def _sleeves(v: np.ndarray, loops, skeleton) -> tuple[str, float, str, bool]:
    """(class, share, evidence, through): the longer side's arm opening's share of the arm: where
    the arm line passes through it (``through``), or, where it misses it, where its centre lies
    along the arm."""
    centres = np.stack([np.asarray(c.centre, dtype=np.float64) for c in loops])
    leg, _, on = _openings_by_part(v, loops, centres, skeleton)
    neck = _neck_opening(v, loops, skeleton)
    chains = _limb_chains(skeleton)
    mid = 0.5 * (skeleton.position("left_shoulder") + skeleton.position("right_shoulder"))
    shares, hows, through = [], [], []
    for s in ("left", "right"):
        arm = chains[f"{s}_arm"]
        for i in np.flatnonzero(on[f"{s}_arm"] & ~leg):
            if loops[i] is neck:
                continue
            p = _arm_crossing(v[np.asarray(loops[i].indices)], arm, mid)
            shares.append(_arm_share(centres[i] if p is None else p, arm))
            hows.append(" (the arm line through it)" if p is not None else " (its centre)")
            through.append(p is not None)
    free = ~(leg | on["left_arm"] | on["right_arm"])
    hanging = _hanging_ends(v, loops, centres, skeleton, free)
    shares += hanging
    hows += [" (a sleeve end off the arm line)"] * len(hanging)
    through += [False] * len(hanging)
    if not shares:
        return "none", 0.0, "no arm opening", True
    k = int(np.argmax(shares))
    share = shares[k]
    if share <= ARMHOLE_SHARE:
        cls = "none"
    else:
        cls = "short" if share <= SHORT_SLEEVE_SHARE else "long"
    return cls, round(share, 2), f"arm opening {share:.2f} of the arm from the shoulder{hows[k]}", through[k]


def _is_square(pts: np.ndarray, width: float) -> tuple[bool, float]:
    """(is square, flat share) of one neckline half ``pts`` (k, 2) [m] (x across, y up): a flat
    bottom (the share of the neckline's ``width`` over which the half stays within
    :data:`SQUARE_BAND` of its depth of its lowest point, at least :data:`SQUARE_FLAT`) that ends
    in a corner (:func:`unsew.grading.garment_type._half_is_v` at its lowest point); a flat
    bottom without a corner is a shallow round one."""
    if len(pts) < 5 or width <= 0:
        return False, 0.0
    depth = float(pts[:, 1].max() - pts[:, 1].min())
    low = pts[pts[:, 1] <= pts[:, 1].min() + SQUARE_BAND * max(depth, 1e-9)]
    flat = float(np.ptp(low[:, 0])) / width
    return flat >= SQUARE_FLAT and _half_is_v(pts, width)[0], flat


def _necklines(v: np.ndarray, faces, loops, skeleton) -> tuple[tuple, dict, str]:
    """((front, back) classes, numbers, evidence) of a bodice's neck opening."""
    neck = _neck_opening(v, loops, skeleton)
    if neck is None:
        return ("none", "none"), {}, "no neck opening (a strapless top)"
    (front, back), deg = read_necklines(v, faces, skeleton, contours=loops)
    p = v[np.asarray(neck.indices)]
    cz, width = float(p[:, 2].mean()), float(np.ptp(p[:, 0]))
    out, nums = [], dict(deg)
    for name, kind, side in (("front", front, p[:, 2] >= cz), ("back", back, p[:, 2] < cz)):
        # a flat bottom's end is a corner too: square first
        sq, flat = _is_square(p[_half_run(side)][:, :2], width) if side.sum() >= 5 else (False, 0.0)
        nums[f"{name}_flat"] = round(flat, 2)
        out.append("square" if sq else kind)
    ev = (
        f"front corner {nums.get('front_deg', 180):.0f} deg, flat {nums['front_flat']:.2f}; "
        f"back corner {nums.get('back_deg', 180):.0f} deg, flat {nums['back_flat']:.2f}"
    )
    return (out[0], out[1]), nums, ev


def _over_shoulders(v: np.ndarray, skeleton) -> float:
    """How far [m] the cloth beside the neck (:data:`STRAP_BAND` of the half shoulder width out
    from the centre line, either side) reaches above the shoulder joints; -inf where none lies
    there. Negative: no cloth over the shoulders (a strapless top)."""
    ls, rs = skeleton.position("left_shoulder"), skeleton.position("right_shoulder")
    mid_x, half = 0.5 * (ls[0] + rs[0]), 0.5 * abs(ls[0] - rs[0])
    out = np.abs(v[:, 0] - mid_x) / max(half, 1e-9)
    band = (out >= STRAP_BAND[0]) & (out <= STRAP_BAND[1])
    return float(v[band, 1].max() - 0.5 * (ls[1] + rs[1])) if band.any() else -np.inf


def _collar(v: np.ndarray, loops, skeleton) -> tuple[str, str]:
    """(class, evidence): a hood over the head joint, a standing collar above the neck joint."""
    above_head = float(v[:, 1].max() - skeleton.position("head")[1])
    if above_head >= HOOD_ABOVE_HEAD:
        return "hood", f"the garment rises {100 * above_head:.0f} cm over the head joint"
    neck = _neck_opening(v, loops, skeleton)
    if neck is not None:
        dy = float(neck.centre[1] - skeleton.position("neck")[1])
        if dy >= TURTLE_ABOVE_NECK:
            return "turtle", f"the neck opening {100 * dy:.0f} cm over the neck joint"
        return "none", f"the neck opening {100 * dy:+.0f} cm from the neck joint"
    return "none", "no neck opening"


def _girth_at(mesh_v: np.ndarray, faces: np.ndarray, y: float) -> float:
    """The garment's girth [m] at height y: the length of its cross-section with the plane Y = y
    (:func:`trimesh.intersections.mesh_plane`); 0 where it does not reach that height."""
    import trimesh

    m = trimesh.Trimesh(mesh_v, faces, process=False)
    seg = trimesh.intersections.mesh_plane(m, plane_normal=[0.0, 1.0, 0.0], plane_origin=[0.0, y, 0.0])
    return float(np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1).sum()) if len(seg) else 0.0


def _hem_loop(v: np.ndarray, loops, skeleton):
    """The hem: the torso opening (round neither a leg nor an arm) whose vertices reach lowest."""
    centres = np.stack([np.asarray(c.centre, dtype=np.float64) for c in loops])
    leg, arm, _ = _openings_by_part(v, loops, centres, skeleton)
    torso = [c for c, off in zip(loops, leg | arm) if not off]
    return min(torso, key=lambda c: float(np.percentile(v[np.asarray(c.indices), 1], 10.0)), default=None)


def _hip_girth(skeleton, body) -> float:
    """The body's girth [m] at the hip joints' height, the arms (and hands) left out: the
    cross-section's pieces within 2.5 times the hip joints' half spacing of the centre line."""
    import trimesh

    lh, rh = skeleton.position("left_hip"), skeleton.position("right_hip")
    m = trimesh.Trimesh(np.asarray(body.verts), np.asarray(body.faces), process=False)
    seg = trimesh.intersections.mesh_plane(m, plane_normal=[0.0, 1.0, 0.0], plane_origin=[0.0, lh[1], 0.0])
    if not len(seg):
        return 0.0
    keep = np.abs(seg.mean(axis=1)[:, 0] - 0.5 * (lh[0] + rh[0])) < 1.25 * abs(lh[0] - rh[0])
    return float(np.linalg.norm(seg[keep, 1] - seg[keep, 0], axis=1).sum())


def _skirt_and_length(v: np.ndarray, faces, loops, skeleton, reading: GarmentReading, *, body=None):
    """({"skirt", "length"}, numbers, evidence) of a skirt, dress, trousers or shorts."""
    hip_y = _mid_y(skeleton, "hip")
    ankle_y = _mid_y(skeleton, "ankle")
    leg = (hip_y - ankle_y) * (1.0 + ANKLE_HEIGHT)  # hip joints to the floor [m]
    out, nums, ev = {}, {}, {}
    if reading.garment in ("pants", "shorts", "jumpsuit"):
        low_y = reading.details.get("leg_y", float("nan"))
        what = "leg openings"
    else:
        low_y = reading.hem_y
        what = "hem"
        hem = _hem_loop(v, loops, skeleton)
        idx = np.r_[hem.indices, hem.indices[0]] if hem is not None else np.zeros(0, dtype=np.int64)
        # seen from above: a slit's rise adds nothing to the hem's girth
        hem_len = float(np.linalg.norm(np.diff(v[idx][:, [0, 2]], axis=0), axis=1).sum())
        girth = _hip_girth(skeleton, body) if body is not None else 0.0
        whose = "the body's" if girth > 0 else "the garment's"
        girth = girth if girth > 0 else _girth_at(v, faces, hip_y)
        if girth > 0 and hem_len > 0:
            flare = hem_len / girth
            out["skirt"] = SKIRT_CLASSES[int(flare >= FLARE_EDGES[0]) + int(flare >= FLARE_EDGES[1])]
            nums["flare"] = round(flare, 2)
            ev["skirt"] = f"hem {hem_len:.2f} m round, {flare:.2f} x {whose} girth at the hips"
    if np.isfinite(low_y):
        share = (hip_y - low_y) / leg
        out["length"] = LENGTH_CLASSES[int(share > LENGTH_EDGES[0]) + int(share > LENGTH_EDGES[1])]
        nums["hem_share"] = round(share, 2)
        knee = _mid_y(skeleton, "knee")
        ev["length"] = (
            f"{what} {100 * abs(low_y - knee):.0f} cm {'below' if low_y < knee else 'above'} the knees"
        )
    return out, nums, ev


def _darts(v: np.ndarray, faces, skeleton, garment: str, skirt: str | None, body):
    """(darts, the garment's girth over the body's, evidence) of a garment's cut: a bodice whose
    girth at the chest line, or a straight (pencil) skirt's or trousers' at the hip joints, lies
    within :data:`FITTED_EASE` of the body's there is cut to follow the body, and a flat panel
    follows the body's narrowing to the waist only with darts; a looser cut hangs past it, and a
    cone skirt takes the waist in by its flare. (None, nan, reason) without a body or a girth."""
    if body is None:
        return None, np.nan, "no body to measure the fit against"
    if garment == "skirt" and skirt != "pencil":
        return False, np.nan, f"a {skirt} skirt's cone takes in the waist"
    if garment in ("tshirt", "dress", "jumpsuit"):
        y, axis, where = _chest_y(skeleton), skeleton.position("spine"), "chest line"
        ls, rs = skeleton.position("left_shoulder"), skeleton.position("right_shoulder")
        reach = 0.5 * abs(ls[0] - rs[0])  # the sleeves and arms hang beyond the shoulder joints
    else:
        lh, rh = skeleton.position("left_hip"), skeleton.position("right_hip")
        y, axis, where, reach = (
            0.5 * (lh[1] + rh[1]),
            0.5 * (lh + rh),
            "hip joints",
            1.25 * abs(lh[0] - rh[0]),
        )
    g = _torso_girth_at(v, faces, y, axis, reach)
    b = _torso_girth_at(np.asarray(body.verts), np.asarray(body.faces), y, axis, reach)
    if not (g > 0 and b > 0):
        return None, np.nan, f"no girth at the {where}"
    ease = g / b
    ev = f"girth {g:.2f} m at the {where}, {ease:.2f} x the body's"
    return bool(ease <= FITTED_EASE), ease, ev


def _hull_perimeter(pts: np.ndarray) -> float:
    """The perimeter [m] of the convex hull of points ``pts`` (k, 3) [m] seen from above (x, z):
    a girth that folds and a jagged mesh edge do not lengthen; 0 for fewer than 3 points."""
    from scipy.spatial import ConvexHull, QhullError

    if len(pts) < 3:
        return 0.0
    try:
        return float(ConvexHull(pts[:, [0, 2]]).area)  # a 2D hull's "area" is its perimeter
    except QhullError:  # points on a line
        return 0.0


def _torso_girth_at(v: np.ndarray, faces, y: float, axis: np.ndarray, reach: float) -> float:
    """The garment's girth [m] round the torso at height y: the hull perimeter
    (:func:`_hull_perimeter`) of its cross-section with the plane Y = y, the points within
    ``reach`` [m] across (x) of the body's axis point ``axis`` (3,) [m] (sleeves and legs
    beyond it left out); 0 where it does not reach that height."""
    import trimesh

    m = trimesh.Trimesh(v, faces, process=False)
    seg = trimesh.intersections.mesh_plane(m, plane_normal=[0.0, 1.0, 0.0], plane_origin=[0.0, y, 0.0])
    if not len(seg):
        return 0.0
    p = seg.reshape(-1, 3)
    return _hull_perimeter(p[np.abs(p[:, 0] - axis[0]) < reach])


def read_design(
    verts, faces, skeleton, *, contours=None, reading: GarmentReading | None = None, body=None
) -> DesignReading:
    """Read the garment type (:func:`unsew.grading.garment_type.read_garment_type`) and its
    structural choices (:class:`DesignReading`) off a draped garment.

    verts: (V, 3) float64 [m], world frame (Y up, the body facing +Z); faces: (F, 3) int;
    skeleton: the wearer's :class:`~unsew.body.skeleton.Skeleton`; contours: the mesh's open
    contours when already found; reading: the type's reading when already made; body: the
    wearer (:class:`~unsew.body.body.Body`, its ``verts`` and ``faces``), whose hip girth the
    skirt's flare is measured against (without it, the garment's own girth at the hips).
    Raises InputError as :func:`read_garment_type` does (no opening, missing joints).
    """
    v = np.asarray(verts, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64)
    loops = open_contours(v, f) if contours is None else contours
    r = read_garment_type(v, f, skeleton, contours=loops) if reading is None else reading
    got, nums, ev = {}, {}, {}
    if r.garment in ("tshirt", "dress", "jumpsuit"):
        got["sleeves"], nums["sleeve_share"], ev["sleeves"], through = _sleeves(v, loops, skeleton)
        nums["sleeve_through"] = 1.0 if through else 0.0
        nums["over_shoulders"] = round(_over_shoulders(v, skeleton), 3)
        if nums["over_shoulders"] < 0.0:
            got["collar"], got["neck_front"], got["neck_back"] = "none", "none", "none"
            ev["neck_front"] = ev["collar"] = (
                f"no cloth over the shoulders (a strapless top: its edge beside the neck "
                f"{-100 * nums['over_shoulders']:.0f} cm under the shoulder joints)"
            )
        else:
            got["collar"], ev["collar"] = _collar(v, loops, skeleton)
        if got["collar"] == "none" and "neck_front" not in got:
            # under a hood or a standing collar no opening shows the neckline
            (got["neck_front"], got["neck_back"]), n, ev["neck_front"] = _necklines(v, f, loops, skeleton)
            nums.update(n)
    if r.garment != "tshirt":
        o, n, e = _skirt_and_length(v, f, loops, skeleton, r, body=body)
        got.update(o)
        nums.update(n)
        ev.update(e)
    got["darts"], ease, ev["darts"] = _darts(v, f, skeleton, r.garment, got.get("skirt"), body)
    if np.isfinite(ease):
        nums["fit_ease"] = round(float(ease), 3)
    return DesignReading(r.garment, **got, evidence=ev, numbers=nums)
