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

__all__ = ["GarmentReading", "read_garment_type", "READ_TYPES"]

#: Types the reading can return: the library's five and a one-piece suit (legs and arms or a bodice).
READ_TYPES = ("tshirt", "dress", "pants", "shorts", "skirt", "jumpsuit")
#: A loop goes round a limb when the limb's line passes within its radius of its centre, or within
#: this distance [m] of it, whichever is larger (a tight cuff's radius is small, and it hangs
#: off-centre on a bent arm) ...
LIMB_NEAR = 0.05
#: ... the line running on past the wrist and the ankle by this much [m] (a hand, a foot).
LIMB_END = 0.08
#: Fraction of the way from the hip joints up to the shoulder joints above which a garment covers
#: the chest: a skirt's or trousers' waistband stays below it, a bodice reaches above it.
CHEST_LEVEL = 0.7
#: Fraction of the way from the hip joints down to the knees below which an upper garment's hem
#: makes it a dress rather than a top.
DRESS_HEM = 0.5
#: Leg openings higher than this [m] under the knee joints are shorts', lower ones trousers'.
TROUSER_BELOW_KNEE = 0.08


@dataclass
class GarmentReading:
    """What a garment's shape says of its type.

    garment: one of :data:`READ_TYPES`; reason: one line saying why.
    legs, arms: openings found round the left and right leg / arm, (left, right).
    torso: number of openings round the torso (waist, hem, neckline).
    top_y, hem_y: the garment's highest point and its lowest torso opening's centre height [m]
    (hem_y NaN without a torso opening).
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
    need = [f"{s}_{j}" for s in ("left", "right") for j in ("shoulder", "elbow", "wrist", "hip", "knee", "ankle")]
    missing = [n for n in need if n not in skeleton]
    if missing:
        raise InputError(f"the skeleton lacks joint(s) {missing}: the garment type cannot be read; "
                         "name it in meta.json or pass --base")
    out = {}
    for s in ("left", "right"):
        for limb, joints in (("arm", ("shoulder", "elbow", "wrist")), ("leg", ("hip", "knee", "ankle"))):
            p = [skeleton.position(f"{s}_{j}") for j in joints]
            d = p[-1] - p[-2]
            out[f"{s}_{limb}"] = [*p, p[-1] + LIMB_END * d / max(float(np.linalg.norm(d)), 1e-9)]
    return out


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
        raise InputError("the target has no opening (no hem, waist or neckline): the garment type cannot be read")
    chains = _limb_chains(skeleton)
    centres = np.stack([np.asarray(c.centre, dtype=np.float64) for c in loops])  # (C, 3) [m]
    radii = np.array([np.linalg.norm(v[np.asarray(c.indices)] - c.centre, axis=1).mean() for c in loops])
    dist = {k: _chain_distance(centres, j) for k, j in chains.items()}  # limb -> (C,) [m]
    near = np.maximum(radii, LIMB_NEAR)
    on = {}
    for side, other in (("left", "right"), ("right", "left")):
        for limb in ("arm", "leg"):
            # round this limb, with the other side's limb outside the loop
            on[f"{side}_{limb}"] = (dist[f"{side}_{limb}"] < near) & (dist[f"{other}_{limb}"] > radii)
    leg = on["left_leg"] | on["right_leg"]
    arm = (on["left_arm"] | on["right_arm"]) & ~leg
    torso = ~(leg | arm)
    legs = (int(on["left_leg"].sum()), int(on["right_leg"].sum()))
    arms = (int((on["left_arm"] & arm).sum()), int((on["right_arm"] & arm).sum()))
    hip_y = 0.5 * (skeleton.position("left_hip")[1] + skeleton.position("right_hip")[1])
    shoulder_y = 0.5 * (skeleton.position("left_shoulder")[1] + skeleton.position("right_shoulder")[1])
    knee_y = 0.5 * (skeleton.position("left_knee")[1] + skeleton.position("right_knee")[1])
    top_y = float(v[:, 1].max())
    hem_y = float(centres[torso, 1].min()) if torso.any() else float("nan")
    chest = hip_y + CHEST_LEVEL * (shoulder_y - hip_y)
    upper = bool(any(arms)) or top_y > chest
    split = min(legs) >= 1
    said = (f"{sum(legs)} leg, {sum(arms)} arm and {int(torso.sum())} torso opening(s), "
            f"top {100 * (top_y - chest):+.0f} cm from the chest line")
    if split and upper:
        garment = "jumpsuit"
        why = f"openings round both legs and a bodice ({said})"
    elif split:
        leg_y = float(centres[leg, 1].mean())
        garment = "pants" if leg_y < knee_y - TROUSER_BELOW_KNEE else "shorts"
        why = f"openings round both legs {100 * (leg_y - knee_y):+.0f} cm from the knees ({said})"
    elif upper:
        dress_line = hip_y - DRESS_HEM * (hip_y - knee_y)
        garment = "dress" if np.isfinite(hem_y) and hem_y < dress_line else "tshirt"
        why = (f"a bodice with its hem {100 * (hem_y - dress_line):+.0f} cm from mid-thigh ({said})"
               if np.isfinite(hem_y) else f"a bodice ({said})")
    else:
        garment = "skirt"
        why = f"one tube round the hips and legs ({said})"
    return GarmentReading(garment, why, legs, arms, int(torso.sum()), top_y, hem_y,
                          {"hip_y": hip_y, "knee_y": knee_y, "chest_y": chest})
