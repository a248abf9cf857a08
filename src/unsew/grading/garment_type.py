"""The garment type read off a draped garment: which of its openings go round a leg, an arm or the
torso, how high the garment reaches and how low its hem hangs.

Only the skeleton's joint positions are used (FORMATS.md's required names), never a part label a
file may set otherwise: a leg opening is a loop round one leg's hip-knee-ankle line that leaves the
other leg outside it, an arm opening one round the shoulder-elbow-wrist line, and everything else
goes round the torso (a waist, a hem, a neckline).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from unsew.errors import InputError
from unsew.losses.contours import open_contours

__all__ = ["GarmentReading", "read_garment_type", "read_necklines", "READ_TYPES", "V_ANGLE_DEG"]

#: Types the reading can return: the library's five and a one-piece suit (legs and arms or a bodice).
READ_TYPES = ("tshirt", "dress", "pants", "shorts", "skirt", "jumpsuit")
#: A loop goes round a limb when the limb's line passes within its radius of its centre, or within
#: this distance [m] of it, whichever is larger (a tight cuff's radius is small, and it hangs
#: off-centre on a bent arm) ...
LIMB_NEAR = 0.05
#: ... the line running on past the wrist and the ankle by this much [m] (a hand, a foot).
LIMB_END = 0.08
#: A loop round one leg alone has the other leg's opening for a twin when another loop lies at its
#: mirror image across the hip joints' centre plane (height and distance across) and has its
#: radius, each within this share of its radius [-].
TWIN_TOL = 0.5
#: Fraction of the way from the hip joints up to the shoulder joints above which a garment covers
#: the chest: a skirt's or trousers' waistband stays below it, a bodice reaches above it.
CHEST_LEVEL = 0.7
#: An upper garment whose hem hangs further below the shoulder joints than this many times the
#: shoulders' height above the hip joints is a dress rather than a top (docs/decisions/019).
DRESS_DROP = 1.25
#: The hem's height: this percentile of its vertices' heights (a flared hem folds up and down).
HEM_PERCENTILE = 10.0
#: Leg openings further below the waist opening than this many times the hip joints' height above
#: the knees are trousers', nearer ones shorts' (measured from the garment's own waist, so a waist
#: that slid down leaves the reading as it was; docs/decisions/019).
TROUSER_DROP = 1.8
#: A neckline half (front or back) is a V when, seen from the front, its lowest point turns by
#: less than this angle [deg] between the loop's points a third of the neckline's width along it
#: either way (a round neckline's bottom: about 140 degrees; a V's point: 2 atan(half width / depth)).
V_ANGLE_DEG = 115.0
#: ... the arm of that angle, as a fraction of the neckline's width [-].
V_ARM = 0.35


@dataclass
class GarmentReading:
    """What a garment's shape says of its type.

    garment: one of :data:`READ_TYPES`; reason: one line saying why.
    legs, arms: openings found round the left and right leg / arm, (left, right).
    torso: number of openings round the torso (waist, hem, neckline).
    top_y, hem_y: the garment's highest point and its lowest torso opening's height [m]
    (:data:`HEM_PERCENTILE` of its vertices; NaN without a torso opening).
    """

    garment: str
    reason: str
    legs: tuple = (0, 0)
    arms: tuple = (0, 0)
    torso: int = 0
    top_y: float = float("nan")
    hem_y: float = float("nan")
    details: dict = field(default_factory=dict)


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance [m] of points p (N, 3) to the segment a-b ((3,), (3,))."""
    ab = b - a
    t = np.clip(((p - a) @ ab) / max(float(ab @ ab), 1e-12), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


def _chain_distance(p: np.ndarray, joints: list[np.ndarray]) -> np.ndarray:
    """Distance [m] of points p (N, 3) to the polyline through ``joints``."""
    return np.min([_segment_distance(p, a, b) for a, b in zip(joints[:-1], joints[1:])], axis=0)


def _limb_chains(skeleton) -> dict[str, list[np.ndarray]]:
    """The four limbs' joint chains [m] from the skeleton's joint names (FORMATS.md)."""
    need = [
        f"{s}_{j}" for s in ("left", "right") for j in ("shoulder", "elbow", "wrist", "hip", "knee", "ankle")
    ]
    missing = [n for n in need if n not in skeleton]
    if missing:
        raise InputError(
            f"the skeleton lacks joint(s) {missing}: the garment type cannot be read; "
            "name it in meta.json or pass --base"
        )
    out = {}
    for s in ("left", "right"):
        for limb, joints in (("arm", ("shoulder", "elbow", "wrist")), ("leg", ("hip", "knee", "ankle"))):
            p = [skeleton.position(f"{s}_{j}") for j in joints]
            d = p[-1] - p[-2]
            out[f"{s}_{limb}"] = [*p, p[-1] + LIMB_END * d / max(float(np.linalg.norm(d)), 1e-9)]
    return out


def _mid_y(skeleton, joint: str) -> float:
    """Mean height [m] of the left and right ``joint`` (``"hip"``, ``"shoulder"``, ``"knee"``)."""
    return 0.5 * float(skeleton.position(f"left_{joint}")[1] + skeleton.position(f"right_{joint}")[1])


def _chest_y(skeleton) -> float:
    """Height [m] of the chest line: :data:`CHEST_LEVEL` of the way from the hips up to the shoulders."""
    hip_y = _mid_y(skeleton, "hip")
    return hip_y + CHEST_LEVEL * (_mid_y(skeleton, "shoulder") - hip_y)


def _radius(v: np.ndarray, c) -> float:
    """Mean distance [m] of contour ``c``'s vertices (of ``v`` (V, 3) [m]) to its centre."""
    return float(np.linalg.norm(v[np.asarray(c.indices)] - c.centre, axis=1).mean())


def read_garment_type(verts, faces, skeleton, *, contours=None) -> GarmentReading:
    """Read the garment type of a draped garment.

    verts: (V, 3) float64 [m], world frame (Y up); faces: (F, 3) int; skeleton: the wearer's
    :class:`~unsew.body.skeleton.Skeleton` (joint positions by name); contours: the mesh's open
    contours when already found (:func:`unsew.losses.contours.open_contours`).
    Raises InputError when the garment has no opening (a closed shape is no garment).
    """
    v = np.asarray(verts, dtype=np.float64)
    loops = open_contours(v, faces) if contours is None else contours
    if not loops:
        raise InputError(
            "the target has no opening (no hem, waist or neckline): the garment type cannot be read"
        )
    centres = np.stack([np.asarray(c.centre, dtype=np.float64) for c in loops])  # (C, 3) [m]
    leg, arm, on = _openings_by_part(v, loops, centres, skeleton)
    torso = ~(leg | arm)
    legs = (int(on["left_leg"].sum()), int(on["right_leg"].sum()))
    arms = (int((on["left_arm"] & arm).sum()), int((on["right_arm"] & arm).sum()))
    hip_y, knee_y = _mid_y(skeleton, "hip"), _mid_y(skeleton, "knee")
    top_y = float(v[:, 1].max())
    hem_y, waist_y = float("nan"), float("nan")
    if torso.any():
        t = np.flatnonzero(torso)
        low = int(t[np.argmin(centres[t, 1])])
        hem_y = float(np.percentile(v[np.asarray(loops[low].indices), 1], HEM_PERCENTILE))
        waist_y = float(centres[t, 1].max())
    chest = _chest_y(skeleton)
    upper = bool(any(arms)) or top_y > chest
    said = (
        f"{sum(legs)} leg, {sum(arms)} arm and {int(torso.sum())} torso opening(s), "
        f"top {100 * (top_y - chest):+.0f} cm from the chest line"
    )
    leg_y = float(centres[leg, 1].mean()) if leg.any() else float("nan")
    heights = {
        "hip_y": hip_y,
        "knee_y": knee_y,
        "chest_y": chest,
        "shoulder_y": _mid_y(skeleton, "shoulder"),
        "waist_y": waist_y,
        "leg_y": leg_y,
    }
    garment, why = _type_of(min(legs) >= 1, upper, hem_y, heights, said)
    return GarmentReading(garment, why, legs, arms, int(torso.sum()), top_y, hem_y, heights)


def _openings_by_part(v: np.ndarray, loops, centres: np.ndarray, skeleton):
    """(leg, arm, on): which loops (C,) bool go round a leg, round an arm (and no leg), and
    ``on``: "left_arm", ... -> (C,) bool, a loop round that limb with the other side's outside it."""
    chains = _limb_chains(skeleton)
    radii = np.array([_radius(v, c) for c in loops])
    dist = {k: _chain_distance(centres, j) for k, j in chains.items()}  # limb -> (C,) [m]
    near = np.maximum(radii, LIMB_NEAR)
    on = {}
    for side, other in (("left", "right"), ("right", "left")):
        for limb in ("arm", "leg"):
            # round this limb, with the other side's limb outside the loop
            on[f"{side}_{limb}"] = (dist[f"{side}_{limb}"] < near) & (dist[f"{other}_{limb}"] > radii)
    for side, other in (("left", "right"), ("right", "left")):
        if on[f"{side}_leg"].any() and not on[f"{other}_leg"].any():
            on[f"{other}_leg"] = _mirror_twin(on[f"{side}_leg"], centres, radii, skeleton)
    if not (on["left_leg"].any() and on["right_leg"].any()):
        # a loop round one leg alone is a hem hanging to one side (legs' openings come in pairs)
        on["left_leg"] = on["right_leg"] = np.zeros(len(loops), dtype=bool)
    leg = on["left_leg"] | on["right_leg"]
    arm = (on["left_arm"] | on["right_arm"]) & ~leg
    return leg, arm, on


def _mirror_twin(round_leg: np.ndarray, centres: np.ndarray, radii: np.ndarray, skeleton) -> np.ndarray:
    """(C,) bool: the loops that mirror a loop of ``round_leg`` (C,) bool across the hip joints'
    centre plane, at its height and of its size (within :data:`TWIN_TOL` of its radius, centres
    and radii [m]): the other leg's opening, where that leg's line misses it by a little (a hem
    lying on the floor round a foot, the foot forward of the ankle's line)."""
    lh, rh = skeleton.position("left_hip"), skeleton.position("right_hip")
    mid, across = 0.5 * (lh + rh), (lh - rh) / max(float(np.linalg.norm(lh - rh)), 1e-9)
    out = np.zeros(len(centres), dtype=bool)
    for i in np.flatnonzero(round_leg):
        mirrored = centres[i] - 2.0 * float((centres[i] - mid) @ across) * across
        tol = TWIN_TOL * radii[i]
        # the mirrored point's height and distance across, not its depth: one foot may stand forward
        dy = np.abs(centres[:, 1] - mirrored[1])
        dx = np.abs((centres - mid) @ across - (mirrored - mid) @ across)
        out |= (dy < tol) & (dx < tol) & (np.abs(radii - radii[i]) < tol) & ~round_leg
    return out


def _type_of(split: bool, upper: bool, hem_y: float, h: dict, said: str):
    """(garment type, why in words) from the openings: round both legs (``split``), a bodice
    (``upper``), the lowest torso opening's height ``hem_y`` and the heights ``h`` [m] (joints:
    "hip_y", "knee_y", "shoulder_y"; openings: "waist_y" the highest torso one, "leg_y" the legs'
    mean); ``said``: the openings counted, for the reason."""
    if split and upper:
        return "jumpsuit", f"openings round both legs and a bodice ({said})"
    thigh = h["hip_y"] - h["knee_y"]  # [m]
    if split:
        if np.isfinite(h["waist_y"]):
            drop = (h["waist_y"] - h["leg_y"]) / thigh
            garment = "pants" if drop > TROUSER_DROP else "shorts"
            return garment, (
                f"openings round both legs {drop:.2f} x hip-to-knee below the waist opening "
                f"(trousers past {TROUSER_DROP}; {said})"
            )
        garment = "pants" if h["leg_y"] < h["knee_y"] else "shorts"
        return (
            garment,
            f"openings round both legs {100 * (h['leg_y'] - h['knee_y']):+.0f} cm from the knees ({said})",
        )
    if upper:
        if not np.isfinite(hem_y):
            return "tshirt", f"a bodice ({said})"
        drop = (h["shoulder_y"] - hem_y) / (h["shoulder_y"] - h["hip_y"])
        garment = "dress" if drop >= DRESS_DROP else "tshirt"
        return garment, (
            f"a bodice with its hem {drop:.2f} x shoulder-to-hip below the shoulders "
            f"(a dress from {DRESS_DROP}; {said})"
        )
    return "skirt", f"one tube round the hips and legs ({said})"


def _encloses(poly: np.ndarray, p: np.ndarray) -> bool:
    """Whether point p (2,) lies inside the closed polygon ``poly`` (k, 2) (even-odd rule)."""
    x, y = poly[:, 0], poly[:, 1]
    x2, y2 = np.roll(x, -1), np.roll(y, -1)
    dy = np.where(y2 == y, 1e-12, y2 - y)
    cross = ((y > p[1]) != (y2 > p[1])) & (p[0] < (x2 - x) * (p[1] - y) / dy + x)
    return bool(cross.sum() % 2)


def _neck_opening(v: np.ndarray, loops, skeleton):
    """The neck opening: the highest loop whose centre lies above the chest line and that goes
    round the neck (seen from above, the neck joint lies inside it: a neckline run into an
    armhole still does), or, failing that, lies near the torso's centre line and round no arm;
    None without one."""
    chains = _limb_chains(skeleton)
    chest = _chest_y(skeleton)
    neck_xz = skeleton.position("neck")[[0, 2]]
    mid_x = 0.5 * (skeleton.position("left_shoulder")[0] + skeleton.position("right_shoulder")[0])
    half_shoulders = 0.5 * abs(skeleton.position("left_shoulder")[0] - skeleton.position("right_shoulder")[0])
    best = None
    for c in loops:
        cen = np.asarray(c.centre, dtype=np.float64)
        r = _radius(v, c)
        on_arm = any(
            float(_chain_distance(cen[None], chains[f"{s}_arm"])[0]) < max(r, LIMB_NEAR)
            for s in ("left", "right")
        )
        central = abs(cen[0] - mid_x) < 0.5 * half_shoulders and not on_arm
        if cen[1] > chest and (central or _encloses(v[np.asarray(c.indices)][:, [0, 2]], neck_xz)):
            if best is None or cen[1] > best[0]:
                best = (cen[1], c)
    return None if best is None else best[1]


def _half_is_v(pts: np.ndarray, width: float) -> tuple[bool, float]:
    """(is a V, angle [deg]) of one neckline half: ``pts`` (k, 2) [m], the half's points in loop
    order, seen from the front (x across, y up)."""
    if len(pts) < 5:
        return False, 180.0
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])  # arc length along the half [m]
    i0 = int(np.argmin(pts[:, 1]))
    arm = V_ARM * width
    if s[i0] < 0.5 * arm or s[-1] - s[i0] < 0.5 * arm:
        return False, 180.0  # the lowest point is a corner of the half (a side), not its bottom
    a = np.array([np.interp(s[i0] - arm, s, pts[:, k]) for k in range(2)]) - pts[i0]
    b = np.array([np.interp(s[i0] + arm, s, pts[:, k]) for k in range(2)]) - pts[i0]
    cosang = float(a @ b / max(np.linalg.norm(a) * np.linalg.norm(b), 1e-12))
    ang = float(np.degrees(np.arccos(np.clip(cosang, -1.0, 1.0))))
    return ang < V_ANGLE_DEG, ang


def _half_run(side: np.ndarray) -> np.ndarray:
    """Indices of a loop's points where ``side`` (k,) bool holds, in loop order as one run (the
    walk starts just after a point of the other side)."""
    start = int(np.flatnonzero(~side)[0]) if (~side).any() else 0
    order = np.roll(np.arange(len(side)), -start)
    return order[side[order]]


def read_necklines(verts, faces, skeleton, *, contours=None) -> tuple[tuple[str, str], dict]:
    """The front and back neckline shapes of a top or dress, each ``"round"`` or ``"v"``
    (:data:`unsew.pattern.base.tshirt.NECKLINES`), and what they were read from: ``{"front_deg",
    "back_deg"}`` (the angle at each half's lowest point, :data:`V_ANGLE_DEG`). Without a neck
    opening (a strapless top): ("round", "round") and an empty dict.

    verts: (V, 3) float64 [m], world frame (Y up, the body facing +Z); faces: (F, 3) int.
    """
    v = np.asarray(verts, dtype=np.float64)
    loops = open_contours(v, faces) if contours is None else contours
    neck = _neck_opening(v, loops, skeleton)
    if neck is None:
        return ("round", "round"), {}
    idx = np.asarray(neck.indices)
    p = v[idx]
    cz = float(p[:, 2].mean())
    width = float(np.ptp(p[:, 0]))
    out, said = [], {}
    for name, side in (("front", p[:, 2] >= cz), ("back", p[:, 2] < cz)):
        if side.sum() < 5:
            out.append("round")
            continue
        is_v, ang = _half_is_v(p[_half_run(side)][:, :2], width)
        out.append("v" if is_v else "round")
        said[f"{name}_deg"] = round(ang, 1)
    return (out[0], out[1]), said
