"""Skeleton of a body: named joints, bones (parent -> child segments) and body parts.

A bone is the segment from a joint's parent to the joint (shared/FORMATS.md), so every joint but
the root ends exactly one bone, named after that joint; ``Skeleton.parts[j]`` is the body part of
that bone (``torso``, ``head``, ``left_arm``, ``right_arm``, ``left_leg``, ``right_leg``).

A skeleton read from a file gets its parts from its structure (:func:`structural_parts`), not
from the file's ``part`` labels: rigs disagree on them (many label the shoulder and hip joints
with their limb, where the bone chest -> shoulder is a clavicle and the bone pelvis -> hip lies
in the pelvis), and a measurement that takes the lower trunk for a leg reads a 6 cm waist.

Also here: the axial coordinate and distance of points to a bone, and the paper's
``EncircledBones`` test (supplementary Algorithm 2) used by grading to measure how far an open
contour (a cuff, a hem) sits along the skeleton.

All positions in metres, world frame (Y up, facing +Z, body's left at +X).
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from unsew.errors import InputError
from unsew.io.atomic import atomic_write

__all__ = [
    "PARTS",
    "REQUIRED_JOINTS",
    "Skeleton",
    "Bone",
    "Encircled",
    "load_skeleton",
    "save_skeleton",
    "structural_parts",
    "axial_coordinate",
    "distance_to_bone",
    "encircled_bones",
]

#: Body parts a bone may belong to.
PARTS = ("torso", "head", "left_arm", "right_arm", "left_leg", "right_leg")

#: Joints every skeleton has (shared/FORMATS.md); more are allowed and kept.
REQUIRED_JOINTS = (
    "pelvis", "spine", "chest", "neck", "head",
    "left_shoulder", "left_elbow", "left_wrist", "left_hip", "left_knee", "left_ankle",
    "right_shoulder", "right_elbow", "right_wrist", "right_hip", "right_knee", "right_ankle",
)  # fmt: skip

#: skeleton.json format version written by :func:`save_skeleton`.
SKELETON_FORMAT_VERSION = 1


@dataclass(frozen=True)
class Bone:
    """One bone: the segment from joint ``parent`` (at ``a``) to joint ``child`` (at ``b``).

    ``name`` equals ``child``; ``a``, ``b``: (3,) float64 [m]; ``part``: one of :data:`PARTS`;
    ``index``: the child joint's index in the skeleton.
    """

    name: str
    parent: str
    child: str
    a: np.ndarray
    b: np.ndarray
    part: str
    index: int = -1

    @property
    def length(self) -> float:
        """Bone length [m]."""
        return float(np.linalg.norm(self.b - self.a))

    @property
    def direction(self) -> np.ndarray:
        """Unit vector from ``a`` to ``b``, shape (3,) float64."""
        d = self.b - self.a
        return d / max(np.linalg.norm(d), 1e-12)


@dataclass
class Skeleton:
    """Joints of a body.

    names: joint names, length J (unique).
    parents: (J,) int64, index of each joint's parent, -1 for the root.
    positions: (J, 3) float64 [m], joint positions in the world frame.
    parts: length J, the body part of the bone ending at each joint (the root's is ``torso``).
    """

    names: list[str]
    parents: np.ndarray
    positions: np.ndarray
    parts: list[str]
    _index: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        self.names = [str(n) for n in self.names]
        self.parents = np.asarray(self.parents, dtype=np.int64).reshape(-1)
        self.positions = np.asarray(self.positions, dtype=np.float64).reshape(-1, 3)
        self.parts = [str(p) for p in self.parts]
        J = len(self.names)
        if not (len(self.parents) == J == len(self.positions) == len(self.parts)):
            raise InputError(
                f"skeleton has {J} names, {len(self.parents)} parents, {len(self.positions)} positions "
                f"and {len(self.parts)} parts; give one of each per joint"
            )
        if len(set(self.names)) != J:
            dup = sorted({n for n in self.names if self.names.count(n) > 1})
            raise InputError(f"skeleton joint names must be unique; repeated: {dup}")
        if not np.isfinite(self.positions).all():
            raise InputError("skeleton has non-finite joint positions; fix the skeleton file")
        bad = [p for p in self.parts if p not in PARTS]
        if bad:
            raise InputError(f"skeleton part(s) {sorted(set(bad))} unknown; use one of {list(PARTS)}")
        if ((self.parents < -1) | (self.parents >= J)).any():
            raise InputError("skeleton parent index out of range")
        if (self.parents == -1).sum() != 1:
            roots = [self.names[i] for i in np.flatnonzero(self.parents == -1)]
            raise InputError(f"skeleton must have exactly one root joint (parent null); found {roots}")
        # cycles: walking up from any joint must reach the root in < J steps
        for j in range(J):
            k, steps = j, 0
            while k != -1:
                k = int(self.parents[k])
                steps += 1
                if steps > J:
                    raise InputError(f"skeleton parents form a cycle through joint {self.names[j]!r}")
        self._index = {n: i for i, n in enumerate(self.names)}

    # -- lookup ---------------------------------------------------------------------------------
    def index(self, name: str) -> int:
        """Index of joint ``name``; raises KeyError naming the known joints."""
        try:
            return self._index[name]
        except KeyError:
            raise KeyError(f"no joint {name!r}; joints: {self.names}") from None

    def __contains__(self, name: str) -> bool:
        return name in self._index

    def position(self, name: str) -> np.ndarray:
        """Position of joint ``name``, shape (3,) float64 [m] (a copy)."""
        return self.positions[self.index(name)].copy()

    def missing(self, required=REQUIRED_JOINTS) -> list[str]:
        """Names from ``required`` that this skeleton lacks."""
        return [n for n in required if n not in self._index]

    def children(self, j: int) -> list[int]:
        """Indices of the joints whose parent is joint ``j``."""
        return [int(i) for i in np.flatnonzero(self.parents == j)]

    def moved_part(self) -> list[str]:
        """Part moved by each joint's rotation: the part of its child bones when they agree
        (the left shoulder moves the left arm), else its own bone's part. Length J."""
        out = []
        for j in range(len(self.names)):
            kids = {self.parts[c] for c in self.children(j)}
            out.append(kids.pop() if len(kids) == 1 else self.parts[j])
        return out

    # -- bones ----------------------------------------------------------------------------------
    def bones(self) -> list[Bone]:
        """All bones (one per non-root joint), in joint order."""
        out = []
        for j, p in enumerate(self.parents):
            if p < 0:
                continue
            out.append(
                Bone(
                    name=self.names[j],
                    parent=self.names[p],
                    child=self.names[j],
                    a=self.positions[p].copy(),
                    b=self.positions[j].copy(),
                    part=self.parts[j],
                    index=j,
                )
            )
        return out

    def bone(self, name: str) -> Bone:
        """The bone ending at joint ``name``."""
        j = self.index(name)
        if self.parents[j] < 0:
            raise KeyError(f"joint {name!r} is the root; no bone ends there")
        return next(b for b in self.bones() if b.index == j)

    def distance_to_root(self, bone: Bone, u: float | np.ndarray) -> float | np.ndarray:
        """Distance along the skeleton [m] from the root joint to the point at axial coordinate
        ``u`` on ``bone`` (the paper's ``distToRoot``): sum of the bone lengths from the root to
        the bone's parent joint plus ``u`` times the bone length. ``u``: scalar or array."""
        acc = 0.0
        k = self.index(bone.parent)
        while self.parents[k] >= 0:
            p = int(self.parents[k])
            acc += float(np.linalg.norm(self.positions[k] - self.positions[p]))
            k = p
        if np.ndim(u):
            return acc + np.asarray(u, dtype=np.float64) * bone.length
        return acc + float(u) * bone.length

    # -- transforms and files -------------------------------------------------------------------
    def transformed(self, *, scale: float | np.ndarray = 1.0, offset: np.ndarray | None = None) -> "Skeleton":
        """A copy with positions ``p * scale + offset`` (scale: scalar or (3,); offset (3,) [m])."""
        pos = self.positions * np.asarray(scale, dtype=np.float64)
        if offset is not None:
            pos = pos + np.asarray(offset, dtype=np.float64)
        return Skeleton(list(self.names), self.parents.copy(), pos, list(self.parts))

    def to_dict(self) -> dict:
        """The skeleton.json mapping (shared/FORMATS.md), units metres."""
        return {
            "units": "m",
            "format_version": SKELETON_FORMAT_VERSION,
            "joints": [
                {
                    "name": n,
                    "parent": None if p < 0 else self.names[p],
                    "position": [float(v) for v in pos],
                    "part": part,
                }
                for n, p, pos, part in zip(self.names, self.parents, self.positions, self.parts)
            ],
        }

    @classmethod
    def from_dict(cls, d: dict, *, scale: float = 1.0, require: tuple = REQUIRED_JOINTS) -> "Skeleton":
        """Build from a skeleton.json mapping. ``scale`` converts its positions to metres (0.01 for
        cm); a ``units`` key in ``d`` overrides it. Missing required joints raise InputError
        naming them. With the required joints present, the parts come from the structure
        (:func:`structural_parts`); the joints' ``part`` labels must be names of :data:`PARTS`
        and are otherwise not read."""
        if not isinstance(d, dict) or not isinstance(d.get("joints"), list) or not d["joints"]:
            raise InputError('skeleton must be a JSON object with a non-empty "joints" list (see FORMATS.md)')
        units = d.get("units")
        if units is not None:
            factors = {"m": 1.0, "cm": 0.01, "mm": 0.001}
            if units not in factors:
                raise InputError(f"skeleton units {units!r} unknown; use one of {list(factors)}")
            scale = factors[units]
        names, parent_names, positions, parts = [], [], [], []
        for k, jt in enumerate(d["joints"]):
            name, parent, pos, part = _read_joint(k, jt)
            names.append(name)
            parent_names.append(parent)
            positions.append(pos)
            parts.append(part)
        missing = [n for n in require if n not in names]
        if missing:
            raise InputError(
                f"skeleton is missing required joint(s) {missing}; add them (names as in FORMATS.md, "
                "e.g. left_shoulder, right_knee)"
            )
        idx = {n: i for i, n in enumerate(names)}
        parents = []
        for n, p in zip(names, parent_names):
            if p is None:
                parents.append(-1)
            elif p not in idx:
                raise InputError(f"skeleton joint {n!r} has parent {p!r}, which is not a joint")
            else:
                parents.append(idx[p])
        parents = np.array(parents, dtype=np.int64)
        if all(n in idx for n in REQUIRED_JOINTS):
            _check_tree(names, parents)
            parts = structural_parts(names, parents)
        return cls(names, parents, np.array(positions) * scale, parts)


def _read_joint(k: int, jt) -> tuple[str, object, list[float], str]:
    """(name, parent name or None, position [x, y, z] in the file's unit, part) of joint #k of
    a skeleton.json mapping; a missing part is guessed from the name. InputError names what is
    wrong."""
    if not isinstance(jt, dict) or "name" not in jt or "position" not in jt:
        raise InputError(f'skeleton joint #{k} needs "name" and "position"')
    pos = jt["position"]
    if not (isinstance(pos, (list, tuple)) and len(pos) == 3):
        raise InputError(f"skeleton joint {jt['name']!r}: position must be [x, y, z]")
    part = str(jt.get("part", "") or "")
    if part and part not in PARTS:
        raise InputError(f"skeleton joint {jt['name']!r}: part {part!r} unknown; use one of {list(PARTS)}")
    return str(jt["name"]), jt.get("parent"), [float(v) for v in pos], part or _guess_part(str(jt["name"]))


def _check_tree(names: list[str], parents: np.ndarray) -> None:
    """Refuse parents that do not form one tree (one root, no cycle), naming a joint."""
    roots = [names[i] for i in np.flatnonzero(parents == -1)]
    if len(roots) != 1:
        raise InputError(f"skeleton must have exactly one root joint (parent null); found {roots}")
    for j in range(len(names)):
        k, steps = j, 0
        while k != -1:
            k = int(parents[k])
            steps += 1
            if steps > len(names):
                raise InputError(f"skeleton parents form a cycle through joint {names[j]!r}")


def _subtree(children: list[list[int]], j: int) -> list[int]:
    out, todo = [], [j]
    while todo:
        k = todo.pop()
        out.append(k)
        todo.extend(children[k])
    return out


def structural_parts(names: list[str], parents: np.ndarray) -> list[str]:
    """The part of the bone ending at each joint, from the skeleton's structure alone (the joint
    names of FORMATS.md and the parent chain; no ``part`` label is read).

    - a limb's bones are those below its root joint: every joint in the subtree of the shoulder
      (hip) other than the shoulder (hip) itself ends an arm (leg) bone; so do the elbow and the
      wrist (knee, ankle) and their subtrees when a rig hangs them elsewhere. The bone ending at
      the shoulder (hip) is torso: it runs inside the trunk (a clavicle, a half pelvis), whatever
      joints (a collar) lie on the way;
    - the head's bones: the chain from the neck down to the head joint (not the neck's own bone)
      and the head's subtree;
    - every other bone, the root's included, is torso.

    names: J joint names with :data:`REQUIRED_JOINTS` among them; parents: (J,) int64, -1 for
    the root, forming a tree. Returns J part names from :data:`PARTS`. Raises InputError when a
    required joint of one part hangs below another part's (a knee under an elbow, a shoulder
    under the head), naming both joints.
    """
    J = len(names)
    idx = {n: i for i, n in enumerate(names)}
    children: list[list[int]] = [[] for _ in range(J)]
    for j, p in enumerate(parents):
        if p >= 0:
            children[int(p)].append(j)
    parts = ["torso"] * J
    owner = {}  # joint -> the required joint whose rule set its part

    def claim(joints, part, by):
        for k in joints:
            if k in owner and owner[k][0] != part:
                raise InputError(
                    f"skeleton joint {names[k]!r} would be both {owner[k][0]} and {part} (it hangs below "
                    f"{names[owner[k][1]]!r} and {names[by]!r}); each limb and the head must hang from the "
                    "trunk on their own"
                )
            owner[k] = (part, by)
            parts[k] = part

    _check_trunk(names, parents, idx)
    head = idx["head"]
    claim(set(_head_chain(parents, idx)) | set(_subtree(children, head)), "head", head)
    for side in ("left", "right"):
        for limb, (root, mid, end) in (
            ("arm", ("shoulder", "elbow", "wrist")),
            ("leg", ("hip", "knee", "ankle")),
        ):
            r, m, e = (idx[f"{side}_{n}"] for n in (root, mid, end))
            below = set(_subtree(children, r)) - {r}
            below |= set(_subtree(children, m)) | set(_subtree(children, e))
            claim(below, f"{side}_{limb}", r)
    return parts


def _check_trunk(names: list[str], parents: np.ndarray, idx: dict[str, int]) -> None:
    """Refuse a trunk joint (pelvis, spine, chest, neck, shoulders, hips) that hangs below a
    limb's joint or the head: the trunk's joints hang from the root through trunk joints only."""
    limbs = {idx["head"]} | {
        idx[f"{s}_{n}"]
        for s in ("left", "right")
        for n in ("shoulder", "elbow", "wrist", "hip", "knee", "ankle")
    }
    for n in (
        "pelvis",
        "spine",
        "chest",
        "neck",
        *(f"{s}_{j}" for s in ("left", "right") for j in ("shoulder", "hip")),
    ):
        k = int(parents[idx[n]])
        while k != -1:
            if k in limbs:
                raise InputError(
                    f"skeleton joint {n!r} hangs below {names[k]!r}; the trunk's joints must hang from the "
                    "root, not from a limb or the head"
                )
            k = int(parents[k])


def _head_chain(parents: np.ndarray, idx: dict[str, int]) -> list[int]:
    """The joints from the head up to the neck (the neck left out); InputError when the head
    does not hang below the neck."""
    neck = idx["neck"]
    chain, k = [], idx["head"]
    while k != -1 and k != neck:
        chain.append(k)
        k = int(parents[k])
    if k != neck:
        raise InputError(
            "skeleton joint 'head' does not hang below 'neck'; give the head's parent chain through the neck"
        )
    return chain


def _guess_part(name: str) -> str:
    """Part of a joint from its name when the file gives none."""
    side = "left" if name.startswith("left") else "right" if name.startswith("right") else None
    if side:
        if any(k in name for k in ("shoulder", "elbow", "wrist", "hand", "arm")):
            return "torso" if "shoulder" in name else f"{side}_arm"
        if any(k in name for k in ("hip", "knee", "ankle", "foot", "toe", "leg")):
            return "torso" if "hip" in name else f"{side}_leg"
        return "torso"
    return "head" if "head" in name else "torso"


def load_skeleton(path: str | os.PathLike, *, scale: float = 1.0) -> Skeleton:
    """Read skeleton.json (shared/FORMATS.md). Positions are converted to metres by its ``units``
    key (or ``scale`` if it has none). Raises InputError on a missing file, bad JSON or missing
    required joints (named)."""
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise InputError(f"skeleton file {path!r} not found; give the wearer's skeleton.json")
    try:
        with open(path, encoding="utf-8") as fh:
            d = json.load(fh)
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise InputError(
            f"skeleton file {path!r} is not valid JSON ({exc.msg if hasattr(exc, 'msg') else exc})"
        ) from None
    try:
        return Skeleton.from_dict(d, scale=scale)
    except InputError as exc:
        raise InputError(f"{path}: {exc}") from None


def save_skeleton(skeleton: Skeleton, path: str | os.PathLike) -> None:
    """Write skeleton.json atomically (temporary name in the same folder, then rename)."""
    text = json.dumps(skeleton.to_dict(), indent=1)
    with atomic_write(path) as tmp:
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text + "\n")


# -- geometry of points and bones ---------------------------------------------------------------


def axial_coordinate(points: np.ndarray, bone: Bone) -> np.ndarray:
    """Axial coordinate of points along a bone: u = (p - a).(b - a) / |b - a|^2 (0 at the parent
    joint, 1 at the child joint, unclamped).

    points: (N, 3) or (3,) float64 [m]. Returns (N,) or scalar float64 [dimensionless].
    """
    p = np.asarray(points, dtype=np.float64)
    d = bone.b - bone.a
    return (p - bone.a) @ d / max(float(d @ d), 1e-24)


def distance_to_bone(points: np.ndarray, bone: Bone, *, clamp: bool = True) -> np.ndarray:
    """Distance of points to a bone [m]: to the segment a-b (``clamp=True``) or to its infinite
    line (``clamp=False``).

    points: (N, 3) or (3,) float64 [m]. Returns (N,) or scalar float64 [m].
    """
    p = np.asarray(points, dtype=np.float64)
    u = axial_coordinate(p, bone)
    if clamp:
        u = np.clip(u, 0.0, 1.0)
    foot = bone.a + np.multiply.outer(u, bone.b - bone.a)
    return np.linalg.norm(p - foot, axis=-1)


class Encircled(NamedTuple):
    """One bone a closed contour's centre projects onto (Algorithm 2's L_i)."""

    bone: Bone
    u: float  #: axial coordinate of the contour centre on the bone, in (0, 1)
    P: np.ndarray  #: (3,) projection of the contour centre onto the bone [m]
    h: float  #: distance from the contour centre to P [m]


def encircled_bones(contour_points: np.ndarray, bones: list[Bone]) -> list[Encircled]:
    """The paper's EncircledBones (supplementary Algorithm 2): the bones onto which the centre of
    a closed contour projects inside the bone (0 < u < 1), with u, the projection P and the
    distance h of the centre to P; sorted by h (the encircled bone first).

    contour_points: (k, 3) float64 [m], the contour's vertices; its centre is their mean.
    bones: candidate bones (``Skeleton.bones()``).
    """
    pts = np.asarray(contour_points, dtype=np.float64).reshape(-1, 3)
    if len(pts) == 0:
        return []
    c = pts.mean(axis=0)
    out = []
    for b in bones:
        u = float(axial_coordinate(c, b))
        if 0.0 < u < 1.0 and math.isfinite(u):
            P = b.a + u * (b.b - b.a)
            out.append(Encircled(b, u, P, float(np.linalg.norm(c - P))))
    out.sort(key=lambda e: e.h)
    return out
