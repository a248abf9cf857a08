"""Measure a body from its mesh and skeleton: girths, lengths and heights (``Measurements``).

Girths are convex-hull perimeters of cross-sections, as a tape measure reads them:

- bust: horizontal section of torso (arms cut away) at its fullest level between the spine and
  shoulder joints, with the arms down. With an upper arm raised to less than
  ``RAISED_ARM_DEG`` below horizontal (T-pose) that level is at the armpits, which the raised arm
  pulls up and out; the bust is then read at the bust points instead (the level of the trunk's
  greatest depth, below the armpits) and scaled by ``RAISED_ARM_BUST``, the ratio of the
  arms-down bust to that girth with the arms raised, read on anny bodies measured in both poses
  (``python -m benchmarks rig`` at 81f6fbb);
- waist: the narrowest torso section between the hip level and the chest joint (the natural
  waist); its height is ``waist_height``;
- hip: the fullest horizontal section of torso and legs (arms cut away) between the crotch and
  the pelvis joint;
- neck: section a quarter of the way from the neck joint to the head joint, of the points within
  8 cm of the neck axis;
- upper arm: the left arm cut perpendicular to the upper-arm bone at 30 % from the shoulder;
  where that cut reaches the armpit (its girth more than ``ARM_CUT_JUMP`` times the cut's at
  40 %, on a body whose arms hang close to the chest), the girth carried back to 30 % on the
  line through the cuts at 40 % and 50 %;
- thigh: the left leg cut horizontally 3 cm below the crotch.

Arms and legs are told apart by the skinning weights when the body has them, else by the nearest
bone (``Body.vertex_parts``). Lengths follow the skeleton: arm = shoulder->elbow->wrist, leg =
hip->knee->ankle, torso = neck base to the waist level, shoulder width = between the outermost
surface points 3 cm above the shoulder joints (acromion level); with an arm raised, whose top
then continues the shoulder's, the distance between the shoulder joints plus
``RAISED_ARM_SHOULDER_OUT`` on each side (read on anny bodies in both poses). All in metres.

A reading no person has (a waist under ``HUMAN_WAIST``, a waist level not below the bust's, trunk
joints out of order) is refused in one line naming the skeleton joint behind it; ``cross_check_rig``
also compares bust, waist and hip with the reading on the skeleton rigged from the mesh alone.
"""

from __future__ import annotations

import itertools

import numpy as np

from unsew.pattern.measurements import Measurements
from unsew.body.skeleton import Bone, distance_to_bone
from unsew.errors import InputError
from unsew.geometry.topology import unique_edges

__all__ = [
    "measure_body",
    "check_human",
    "cross_check_rig",
    "HUMAN_WAIST",
    "RIG_CROSS_TOL",
    "section_points",
    "hull_perimeter",
    "arms_raised",
    "bust_point_girth",
    "bust_reading",
    "upper_arm_cut",
    "RAISED_ARM_DEG",
    "RAISED_ARM_BUST",
    "RAISED_ARM_SHOULDER_OUT",
    "ARM_CUT_JUMP",
]

#: An upper arm (shoulder -> elbow) less than this far below horizontal is raised [degrees]
#: (A-pose arms hang 44-51 degrees below it on anny and GarmentCode bodies, T-pose ones -3-4).
RAISED_ARM_DEG = 25.0
#: Arms-down bust / trunk girth at the bust points with both arms raised: the median over eight
#: anny shapes built in A- and T-pose (0.985-1.007; ``python -m benchmarks rig`` at 81f6fbb).
RAISED_ARM_BUST = 0.993
#: With an arm raised, the acromion sits this far [m] outside the shoulder joint: the median of
#: (arms-down shoulder width - raised-arms joint distance) / 2 over the same anny shapes (0.017-0.047).
RAISED_ARM_SHOULDER_OUT = 0.029
#: The upper arm's cut at 30 % reaches the armpit when its girth is more than this many times the
#: cut's at 40 % (anny bodies: 1.03-1.06; GarmentCode's A-pose bodies: 1.27-1.35;
#: ``python -m benchmarks measure_arm`` at 81f6fbb).
ARM_CUT_JUMP = 1.15
#: The narrowest and widest waist girth of a person [m] (adults' waists lie at 0.55-1.5 m; the
#: range is wide so that only a wrong reading, never a body, is refused).
HUMAN_WAIST = (0.40, 2.5)
#: Bust, waist or hip read with a given skeleton farther than this [m] from the reading with the
#: skeleton rigged from the mesh alone is refused (:func:`cross_check_rig`). Waist and hip read
#: the same (within 0.002) with anny's own joints and with the rig's on anny's default, T-pose,
#: stepping, small and tall heavy bodies, and with the rig's, limb-labelled or SMPL-style joints on
#: GarmentCode's four bodies; the bust moves with the arms' joints (which faces are cut away as
#: arms): up to 0.029 on GarmentCode's bodies, 0.071 on the tall heavy anny body
#: (``python -m benchmarks body_measure``; ``python -m benchmarks body_measure --anny``).
RIG_CROSS_TOL = {"bust": 0.10, "waist": 0.05, "hip": 0.05}
#: The joints each girth's reading depends on (its levels and the parts cut away).
_GIRTH_JOINTS = {
    "bust": ("spine", "chest", "left_shoulder", "right_shoulder", "left_elbow", "right_elbow"),
    "waist": ("pelvis", "chest", "left_hip", "right_hip", "left_shoulder", "right_shoulder"),
    "hip": ("pelvis", "left_hip", "right_hip", "left_knee", "right_knee"),
}


def section_points(
    verts: np.ndarray, faces: np.ndarray, origin: np.ndarray, normal: np.ndarray
) -> np.ndarray:
    """Points where mesh edges cross the plane through ``origin`` with ``normal``.

    verts: (V, 3) float64 [m]; faces: (F, 3) int; origin, normal: (3,) [m] / unit.
    Returns (K, 3) float64 [m], one point per crossing edge.
    """
    s = (verts - origin) @ normal  # (V,) signed height above the plane
    e = unique_edges(faces)[0]  # (E, 2)
    sa, sb = s[e[:, 0]], s[e[:, 1]]
    cross = (sa < 0) != (sb < 0)
    e, sa, sb = e[cross], sa[cross], sb[cross]
    t = sa / (sa - sb)
    return verts[e[:, 0]] + (verts[e[:, 1]] - verts[e[:, 0]]) * t[:, None]


def hull_perimeter(points2d: np.ndarray) -> float:
    """Perimeter of the convex hull of 2D points, (K, 2) float64 [m] -> [m]; 0 for < 3 points."""
    from scipy.spatial import ConvexHull, QhullError

    if len(points2d) < 3:
        return 0.0
    try:
        return float(ConvexHull(points2d).area)  # in 2D, "area" is the perimeter
    except QhullError:
        return 0.0


def _horizontal_girth(verts, faces, keep_face, y):
    p = section_points(verts, faces[keep_face], np.array([0.0, y, 0.0]), np.array([0.0, 1.0, 0.0]))
    return hull_perimeter(p[:, [0, 2]])


def _scan(verts, faces, keep_face, y0, y1, *, step=0.005):
    ys = np.arange(min(y0, y1), max(y0, y1) + 1e-9, step)
    return ys, np.array([_horizontal_girth(verts, faces, keep_face, y) for y in ys])


def _bust(body, torso_face, sh_y: float) -> tuple[float, float]:
    """(bust girth [m], its height [m]): the fullest torso level (faces ``torso_face``, arms cut
    away) between spine and shoulders (height sh_y [m]), arms down; with the arms raised,
    RAISED_ARM_BUST times the girth at the bust points."""
    V, F, sk = body.verts, body.faces, body.skeleton
    if arms_raised(sk):
        g_b, bust_y = bust_point_girth(body)
        return RAISED_ARM_BUST * g_b, bust_y
    spine, chest = sk.position("spine"), sk.position("chest")
    ys, g = _scan(V, F, torso_face, spine[1] + 0.3 * (chest[1] - spine[1]), sh_y - 0.03)
    return float(g.max()), float(ys[int(np.argmax(g))])


def _cut_faces(F: np.ndarray, parts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(no_arm_face, torso_face): (F,) bool masks of the faces with no arm vertex, and with no
    arm, leg or head vertex. F: (F, 3) int faces; parts: (V,) str (``Body.vertex_parts``)."""
    no_arm_face = ~np.isin(parts, ["left_arm", "right_arm"])[F].any(axis=1)
    torso_face = no_arm_face & ~np.isin(parts, ["left_leg", "right_leg", "head"])[F].any(axis=1)
    return no_arm_face, torso_face


def bust_reading(body, *, at: float | None = None) -> tuple[float, float]:
    """(bust girth [m], its height [m, world y]) as ``measure_body`` reads them; with ``at``
    [m], the girth of the torso's section at that height instead (arms cut away by the same
    parts; also with raised arms, whose bust ``measure_body`` reads otherwise), to tell a bust
    read at another level from one whose section is cut otherwise."""
    _, torso_face = _cut_faces(body.faces, body.vertex_parts())
    if at is not None:
        return _horizontal_girth(body.verts, body.faces, torso_face, float(at)), float(at)
    sk = body.skeleton
    return _bust(body, torso_face, 0.5 * (sk.position("left_shoulder")[1] + sk.position("right_shoulder")[1]))


def _crotch_y(V, sk) -> float:
    """Crotch height [m]: the lowest midline surface point of V (n, 3) [m] above the knees
    (halfway between knees and pelvis when there is none)."""
    pelvis = sk.position("pelvis")
    knee_y = 0.5 * (sk.position("left_knee")[1] + sk.position("right_knee")[1])
    mid = (np.abs(V[:, 0] - pelvis[0]) < 0.015) & (V[:, 1] > knee_y) & (V[:, 1] < pelvis[1])
    return float(V[mid, 1].min()) if mid.any() else float(0.5 * (knee_y + pelvis[1]))


def _shoulder_width(V, sk) -> float:
    """Shoulder width [m]: between the shoulders' outer edges on V (n, 3) [m]; with the arms
    raised, between the shoulder joints plus RAISED_ARM_SHOULDER_OUT on each side."""
    l_sh, r_sh = sk.position("left_shoulder"), sk.position("right_shoulder")
    if arms_raised(sk):  # the raised arm's top continues the shoulder's: no outer edge to find
        return float(abs(l_sh[0] - r_sh[0])) + 2 * RAISED_ARM_SHOULDER_OUT
    return _outer_x(V, l_sh, 1.0) + _outer_x(V, r_sh, -1.0)


def _limb_lengths(sk) -> tuple[float, float]:
    """(arm length, leg length) [m]: each the mean of the left and right joint chains."""
    arm = 0.5 * (
        _length(sk, "left_shoulder", "left_elbow", "left_wrist")
        + _length(sk, "right_shoulder", "right_elbow", "right_wrist")
    )
    leg = 0.5 * (
        _length(sk, "left_hip", "left_knee", "left_ankle")
        + _length(sk, "right_hip", "right_knee", "right_ankle")
    )
    return arm, leg


def measure_body(body) -> Measurements:
    """Measurements of a body (see the module docstring for each definition).

    body: a ``Body`` (verts (V,3) float64 [m], faces, skeleton with the required joints).
    Returns ``Measurements`` in metres.
    """
    V, F, sk = body.verts, body.faces, body.skeleton
    P = sk.position
    _check_trunk_order(sk)
    floor = float(V[:, 1].min())
    height = float(V[:, 1].max() - floor)
    parts = body.vertex_parts()
    no_arm_face, torso_face = _cut_faces(F, parts)

    pelvis, spine, chest, neck, head = (P(n) for n in ("pelvis", "spine", "chest", "neck", "head"))
    l_sh, r_sh = P("left_shoulder"), P("right_shoulder")
    sh_y = 0.5 * (l_sh[1] + r_sh[1])

    crotch_y = _crotch_y(V, sk)

    bust, bust_y = _bust(body, torso_face, sh_y)
    # waist: narrowest torso level between hip level and chest
    ys_w, g_w = _scan(V, F, torso_face, pelvis[1] + 0.04, chest[1])
    k = int(np.argmin(np.where(g_w > 0, g_w, np.inf)))
    waist, waist_y = float(g_w[k]), float(ys_w[k])
    # hip: fullest torso + legs level between the crotch and the pelvis joint
    ys_h, g_h = _scan(V, F, no_arm_face, crotch_y + 0.02, pelvis[1] + 0.02)
    hip = float(g_h.max())

    check_human(body, parts, bust=bust, waist=waist, waist_y=waist_y, bust_y=bust_y, hip=hip)

    neck_g = _neck_girth(V, F, neck, head)
    upper_arm = _upper_arm_girth(V, F, parts, l_sh, P("left_elbow"))
    # thigh: left leg 3 cm below the crotch
    leg_v = (parts == "left_leg") | ((parts == "torso") & (V[:, 0] > pelvis[0]))
    leg_f = leg_v[F].all(axis=1) & (V[F][:, :, 0].min(axis=1) > pelvis[0])
    thigh = _horizontal_girth(V, F, leg_f, crotch_y - 0.03)
    arm, leg = _limb_lengths(sk)
    return Measurements(
        height=height,
        bust=bust,
        waist=waist,
        hip=hip,
        neck=neck_g,
        upper_arm=upper_arm,
        thigh=thigh,
        shoulder_width=_shoulder_width(V, sk),
        arm_length=arm,
        leg_length=leg,
        torso_length=float(neck[1] - waist_y),
        waist_height=waist_y - floor,
        crotch_height=crotch_y - floor,
        neck_height=float(neck[1] - floor),
    )


def cross_check_rig(body, *, tol: dict | None = None):
    """Measure a body with its given skeleton and check bust, waist and hip against the readings
    with the skeleton rigged from the mesh alone (``unsew.body.rig``); returns the given
    skeleton's ``Measurements``. A girth farther than ``tol`` [m] from the rig's is refused in
    one line naming it and the joint, of those it depends on, farthest from the rig's (``tol``:
    girth name -> [m], default :data:`RIG_CROSS_TOL`). Bodies
    rigged already or made by a body model (with skinning weights) are only measured; so is a
    body the rig cannot read (a pose it does not know: the given skeleton is all there is)."""
    m = measure_body(body)
    if body.rigged or body.weights is not None:
        return m
    try:
        rig, mr = _rigged_reading(body.verts, body.faces)
    except (InputError, IndexError, ValueError):
        return m
    sk = body.skeleton
    tol = {**RIG_CROSS_TOL, **(tol or {})}
    for k, joints in _GIRTH_JOINTS.items():
        a, b = getattr(m, k), getattr(mr, k)
        if abs(a - b) > tol[k]:
            off = {n: float(np.linalg.norm(sk.position(n) - rig.position(n))) for n in joints}
            j = max(off, key=off.get)
            raise InputError(
                f"{k} {a * 100:.1f} cm with the given skeleton but {b * 100:.1f} cm from the mesh alone: "
                f"skeleton joint {j!r} lies {off[j] * 100:.0f} cm from where the mesh puts it; check it in "
                "skeleton.json, or remove the file to rig the body from its mesh"
            )
    return m


_LAST_RIG: dict = {}


def _rigged_reading(verts: np.ndarray, faces: np.ndarray):
    """(skeleton rigged from the mesh, its Measurements); the last mesh's are kept."""
    import hashlib

    from unsew.body.body import Body
    from unsew.body.rig import rig_skeleton

    key = hashlib.sha1(
        np.ascontiguousarray(verts).tobytes() + np.ascontiguousarray(faces).tobytes()
    ).hexdigest()
    if key not in _LAST_RIG:
        rig = rig_skeleton(verts, faces)
        _LAST_RIG.clear()
        _LAST_RIG[key] = (rig, measure_body(Body(verts, faces, rig, None, rigged=True)))
    return _LAST_RIG[key]


def check_human(body, parts, *, bust: float, waist: float, waist_y: float, bust_y: float, hip: float) -> None:
    """Refuse girths no person has, in one line naming the reading and the skeleton joint behind it.

    A waist under ``HUMAN_WAIST[0]`` means the trunk at the waist level was taken for another part:
    the joint named ends the bone nearest the cut-away points there (a hip or shoulder joint
    placed too high). A waist at or above the bust's level means the waist scan reached past the
    bust: it is bounded by the ``chest`` joint. body: the measured ``Body``; parts: (V,) str
    (``Body.vertex_parts``); girths [m], heights [m, world y]."""
    if waist < HUMAN_WAIST[0]:
        part, joint = _trunk_taken(body, parts, waist_y)
        raise InputError(
            f"waist {waist * 100:.1f} cm at {waist_y:.2f} m is under {HUMAN_WAIST[0] * 100:.0f} cm: the "
            f"trunk there is read as {part} from skeleton joint {joint!r}; check its "
            "position and parent in skeleton.json"
        )
    if waist > HUMAN_WAIST[1]:
        raise InputError(f"waist {waist * 100:.0f} cm is more than any person's; check the body's units")
    if waist_y >= bust_y:
        raise InputError(
            f"waist level {waist_y:.2f} m is not below the bust's {bust_y:.2f} m: the waist is sought up to "
            f"skeleton joint 'chest' at {body.skeleton.position('chest')[1]:.2f} m; check its position in "
            "skeleton.json"
        )


def _check_trunk_order(sk) -> None:
    """Refuse a trunk whose joints do not rise from the pelvis to the head (the levels every girth
    is sought between), naming the first joint out of order."""
    chain = ("pelvis", "spine", "chest", "neck", "head")
    for a, b in itertools.pairwise(chain):
        ya, yb = sk.position(a)[1], sk.position(b)[1]
        if not ya < yb:
            bad = b if b in ("spine", "chest") or a in ("neck", "head") else a
            raise InputError(
                f"skeleton joint {bad!r} is out of the trunk's order: {a!r} at {ya:.2f} m is not below {b!r} "
                f"at {yb:.2f} m (pelvis, spine, chest, neck and head rise in that order on a standing body); "
                "check it in skeleton.json"
            )


def _trunk_taken(body, parts, y: float) -> tuple[str, str]:
    """At height y [m]: the part most of the trunk's non-torso points are read as, and the joint
    ending that part's bone nearest them (the trunk: the section's loop around the pelvis'
    vertical axis). ("torso", "pelvis") when nothing there is read as another part."""
    from scipy.spatial import cKDTree

    from unsew.body.rig import level_loops, surrounds

    V = body.verts
    axis = body.skeleton.position("pelvis")[[0, 2]]
    loops = level_loops(V, body.faces, V[:, 1], y)
    trunk = [lp for lp in loops if surrounds(axis, lp[2][:, [0, 2]])] or loops
    if not trunk:
        return "torso", "pelvis"
    pts = max(trunk, key=lambda lp: lp[1])[2]
    p = parts[cKDTree(V).query(pts)[1]]
    if (p == "torso").all():
        return "torso", "pelvis"
    part = _common(p[p != "torso"])
    pts = pts[p == part]
    bones = [b for b in body.skeleton.bones() if b.part == part]
    d = np.stack([distance_to_bone(pts, b) for b in bones], axis=1)  # (k, nbones)
    return part, _common(np.array([b.name for b in bones])[np.argmin(d, axis=1)])


def _common(values: np.ndarray) -> str:
    u, c = np.unique(values, return_counts=True)
    return str(u[np.argmax(c)])


def arms_raised(skeleton) -> bool:
    """Whether either upper arm (shoulder -> elbow) is less than ``RAISED_ARM_DEG`` below horizontal."""
    for side in ("left", "right"):
        d = skeleton.position(f"{side}_elbow") - skeleton.position(f"{side}_shoulder")
        if np.degrees(np.arcsin(-d[1] / max(float(np.linalg.norm(d)), 1e-12))) < RAISED_ARM_DEG:
            return True
    return False


def bust_point_girth(body, *, step: float = 0.005) -> tuple[float, float]:
    """Girth [m] and height [m, world y] of the trunk at its bust points: of the horizontal loops
    around the chest joint's vertical axis, from 30 % of the way spine -> chest up to 3 cm under
    the shoulders, the one of greatest front-to-back depth, read below the armpits (where the
    loop's girth first jumps by over 15 %, the arms have joined it). The girth is the loop's
    convex-hull perimeter (a tape over the bust points). Does not depend on which faces are
    taken for arms, so it reads the same on a rigged body as with the body model's own joints.
    """
    from unsew.body.rig import level_loops, surrounds

    V, F, P = body.verts, body.faces, body.skeleton.position
    axis = P("chest")[[0, 2]]
    spine, chest = P("spine"), P("chest")
    sh_y = 0.5 * (P("left_shoulder")[1] + P("right_shoulder")[1])
    rows = []  # (y, girth, depth)
    for y in np.arange(spine[1] + 0.3 * (chest[1] - spine[1]), sh_y - 0.03, step):
        loops = [lp for lp in level_loops(V, F, V[:, 1], y) if surrounds(axis, lp[2][:, [0, 2]])]
        if not loops:
            continue
        pts = max(loops, key=lambda lp: lp[1])[2]
        g = hull_perimeter(pts[:, [0, 2]])
        if rows and g > 1.15 * rows[-1][1]:
            break
        rows.append((float(y), g, float(np.ptp(pts[:, 2]))))
    if not rows:
        raise InputError("cannot measure the bust: no horizontal section surrounds the chest")
    y, g, _ = max(rows, key=lambda r: r[2])
    return g, y


def _neck_girth(V, F, neck, head) -> float:
    """Girth [m] a quarter of the way from the neck joint to the head joint, of the faces within
    8 cm of the neck's vertical axis."""
    y_n = neck[1] + 0.25 * (head[1] - neck[1])
    near_neck = np.linalg.norm((V - neck)[:, [0, 2]], axis=1) < 0.08
    p = section_points(V, F[near_neck[F].all(axis=1)], np.array([0.0, y_n, 0.0]), np.array([0.0, 1.0, 0.0]))
    return hull_perimeter(p[:, [0, 2]])


def _upper_arm_girth(V, F, parts, shoulder, elbow) -> float:
    """Girth [m] of the left upper arm near the armpit (see the module docstring)."""
    g30, g40 = (upper_arm_cut(V, F, parts, shoulder, elbow, t) for t in (0.3, 0.4))
    if g30 <= ARM_CUT_JUMP * g40:
        return g30
    return 2.0 * g40 - upper_arm_cut(V, F, parts, shoulder, elbow, 0.5)


def upper_arm_cut(V, F, parts, shoulder, elbow, t: float) -> float:
    """Girth [m] of the left arm cut perpendicular to the upper-arm bone at the fraction ``t`` of
    its length from the shoulder (convex-hull perimeter of the cut).

    Args:
        V: (V, 3) float64 body vertices [m]. F: (F, 3) int faces. parts: (V,) str part of each
            vertex (``Body.vertex_parts``); only ``left_arm`` vertices within 10 cm of the bone
            are cut. shoulder, elbow: (3,) joint positions [m]. t: fraction in [0, 1].
    """
    ub = Bone("left_elbow", "left_shoulder", "left_elbow", shoulder, elbow, "left_arm")
    o = ub.a + t * (ub.b - ub.a)
    near_arm = (parts == "left_arm") & (distance_to_bone(V, ub) < 0.1)
    p = section_points(V, F[near_arm[F].all(axis=1)], o, ub.direction)
    p = p[np.linalg.norm(p - o, axis=1) < 0.1]
    e1 = np.cross(ub.direction, [0.0, 0.0, 1.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(ub.direction, e1)
    return hull_perimeter(np.stack([(p - o) @ e1, (p - o) @ e2], axis=1))


def _outer_x(V, sh, sign: float) -> float:
    """Outermost surface x [m] (times ``sign``) 3 cm above a shoulder joint (the acromion; lower,
    the deltoid's bulge would count)."""
    m = (V[:, 1] >= sh[1] + 0.03) & (np.linalg.norm(V - sh, axis=1) < 0.09)
    return float((sign * V[m, 0]).max()) if m.any() else float(sign * sh[0])


def _length(sk, *names) -> float:
    """Length [m] of the polyline through the named joints."""
    pts = [sk.position(n) for n in names]
    return float(sum(np.linalg.norm(b - a) for a, b in zip(pts[:-1], pts[1:])))
