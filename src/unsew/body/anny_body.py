"""Bodies from anny (optional extra ``pip install unsew[anny]``).

anny (NAVER, Apache-2.0 code, CC0 data) is a MakeHuman-based parametric body with six
phenotypes in [0, 1] (gender, age, muscle, weight, height, proportions) and a 104-bone rig. Its
frame is Z up, facing -Y, left at +X; ours is Y up, facing +Z, left at +X, so a point maps as
(x, y, z) -> (x, z, -y). Only anny's bundled data is used (never its optional non-commercial
download). Its first construction builds a cache (about 2 minutes, ~0.8 GB) under
``$ANNY_CACHE_DIR`` (default ``~/.cache/anny``).

``make_anny_body(phenotype, pose)`` -> ``Body`` with our skeleton (``JOINT_MAP``) and skinning
weights aggregated onto our joints; ``save_body_npz`` stores a body compactly (used for the
embedded default body, see scripts/make_default_body.py).
"""

from __future__ import annotations

import json
import os

import numpy as np

from unsew.body.body import Body, clean_body_mesh
from unsew.body.skeleton import Skeleton
from unsew.errors import InputError
from unsew.geometry.topology import components
from unsew.io.atomic import atomic_write

__all__ = ["PHENOTYPES", "JOINT_MAP", "make_anny_body", "save_body_npz", "parse_pose"]

#: anny's phenotype names, each in [0, 1] (0.5 = average).
PHENOTYPES = ("gender", "age", "muscle", "weight", "height", "proportions")

#: Our joints: name -> (anny bone whose head is the joint, parent joint, part of the bone ending
#: at the joint). ``head_top`` has no anny bone: it is put at the top of the head (see below).
JOINT_MAP: dict[str, tuple[str | None, str | None, str]] = {
    "pelvis": ("root", None, "torso"),
    "spine": ("spine03", "pelvis", "torso"),
    "chest": ("spine01", "spine", "torso"),
    "neck": ("neck01", "chest", "torso"),
    "head": ("head", "neck", "head"),
    "head_top": (None, "head", "head"),
    **{
        f"{side}_{j}": (
            f"{bone}.{s}",
            f"{side}_{par}" if par not in ("chest", "pelvis") else par,
            part.format(side=side),
        )
        for side, s in (("left", "L"), ("right", "R"))
        for j, bone, par, part in (
            ("collar", "clavicle", "chest", "torso"),
            ("shoulder", "upperarm01", "collar", "torso"),
            ("elbow", "lowerarm01", "shoulder", "{side}_arm"),
            ("wrist", "wrist", "elbow", "{side}_arm"),
            ("hand", "finger3-1", "wrist", "{side}_arm"),
            ("hip", "upperleg01", "pelvis", "torso"),
            ("knee", "lowerleg01", "hip", "{side}_leg"),
            ("ankle", "foot", "knee", "{side}_leg"),
            ("toe", "toe2-1", "ankle", "{side}_leg"),
        )
    },
}

#: anny -> world rotation: (x, y, z) -> (x, z, -y).
ANNY_TO_WORLD = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])


def _require_anny():
    try:
        import anny  # noqa: F401
    except ImportError:
        raise InputError(
            "making a body needs anny, which is not installed: pip install unsew[anny]"
        ) from None
    return anny


def parse_pose(pose: str) -> dict[str, list[float]]:
    """A pose: ``"A"`` (anny's rest pose), ``"T"`` (arms raised to horizontal) or the path of a
    JSON file mapping our joint names (or anny bone names) to a rotation vector [rad] in the
    world frame, applied to that joint's subtree. Returns {joint: rotvec (3,) [rad]}, world frame."""
    if pose in ("A", "a", "rest"):
        return {}
    if pose in ("T", "t"):
        return {"__T__": [0.0, 0.0, 0.0]}
    if not os.path.isfile(pose):
        raise InputError(f"pose {pose!r} must be A, T or a JSON file of joint rotations")
    try:
        with open(pose, encoding="utf-8") as fh:
            d = json.load(fh)
    except json.JSONDecodeError as exc:
        raise InputError(f"pose file {pose} is not valid JSON ({exc.msg})") from None
    if not isinstance(d, dict):
        raise InputError(
            'pose JSON must map joint names to rotation vectors, e.g. {"left_shoulder": [0, 0, 0.5]}'
        )
    out = {}
    for k, v in d.items():
        if not (isinstance(v, (list, tuple)) and len(v) == 3):
            raise InputError(f"pose joint {k!r}: give a rotation vector [rx, ry, rz] in radians")
        out[str(k)] = [float(x) for x in v]
    return out


def _rotvec_to_matrix(r: np.ndarray) -> np.ndarray:
    th = float(np.linalg.norm(r))
    if th < 1e-12:
        return np.eye(3)
    k = r / th
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * K @ K


def _anny_pose_tensor(model, rest_out, rotations_world: dict, torch):
    """Delta transforms (1, J, 4, 4) for anny's 'world' pose parameterization from rotations of
    subtrees given in our world frame."""
    labels = list(model.bone_labels)
    parents = list(model.bone_parents)
    rest = rest_out["bone_poses"][0].detach().double()  # (J, 4, 4) world rest bone poses (anny frame)
    heads = rest[:, :3, 3].numpy()
    # subtree rotations about each joint, composed top-down: every bone's world transform
    glob = [np.eye(4) for _ in labels]
    local_rot = {}
    inv_map = {v[0]: k for k, v in JOINT_MAP.items() if v[0]}
    for name, rv in rotations_world.items():
        bone = JOINT_MAP[name][0] if name in JOINT_MAP else name
        if bone not in labels:
            raise InputError(
                f"pose names unknown joint {name!r}; use one of "
                f"{sorted(k for k in JOINT_MAP if JOINT_MAP[k][0])}"
            )
        # world frame -> anny frame
        local_rot[labels.index(bone)] = ANNY_TO_WORLD.T @ _rotvec_to_matrix(np.asarray(rv)) @ ANNY_TO_WORLD
    del inv_map
    for j, p in enumerate(parents):
        G = glob[p].copy() if p >= 0 else np.eye(4)
        if j in local_rot:
            T = np.eye(4)
            c = G[:3, :3] @ heads[j] + G[:3, 3]  # current position of this joint
            T[:3, :3] = local_rot[j]
            T[:3, 3] = c - local_rot[j] @ c
            G = T @ G
        glob[j] = G
    G = torch.tensor(np.stack(glob))  # (J, 4, 4): posed = G @ rest
    return (G @ rest)[None]  # world bone poses


def make_anny_body(
    phenotype: dict[str, float] | None = None,
    *,
    pose: str | dict = "A",
    top_k: int = 4,
) -> Body:
    """Build a body with anny.

    phenotype: {name: value in [0, 1]} for names in PHENOTYPES (missing ones are 0.5).
    pose: "A" (rest), "T", a JSON path, or a dict {joint: rotvec (3,) [rad], world frame}.
    Returns a Body in the world frame (feet at y = 0, pelvis at x = z = 0), largest closed
    component, with skinning weights (V, J) on our joints (each vertex's ``top_k`` largest kept).
    """
    anny = _require_anny()
    ph = _phenotype(phenotype)
    rot = parse_pose(pose) if isinstance(pose, str) else dict(pose)
    model, out = _run_anny(anny, ph, rot)
    labels = list(model.bone_labels)
    verts = out["vertices"][0].double().numpy() @ ANNY_TO_WORLD.T  # (V, 3) world [m]
    heads = out["bone_poses"][0, :, :3, 3].double().numpy() @ ANNY_TO_WORLD.T  # (104, 3) [m]
    faces = model.get_triangular_faces().numpy().astype(np.int64)
    W = _joint_weights(model, len(verts))

    # largest closed component, keeping the weights of the kept vertices
    keep_v, faces = _largest_component(verts, faces)
    verts, W = verts[keep_v], W[keep_v]
    v2, faces, _ = clean_body_mesh(verts, faces, what="anny body")
    if len(v2) != len(verts):
        raise RuntimeError("anny body component is not closed as generated")  # pragma: no cover
    verts, sk = _skeleton(verts, heads, labels)
    W = _keep_top_k(W, top_k)
    label = ",".join(f"{k}={ph[k]:g}" for k in PHENOTYPES)
    return Body(verts, faces, sk, W, name=f"anny({label};pose={pose if isinstance(pose, str) else 'custom'})")


def _phenotype(phenotype: dict[str, float] | None) -> dict[str, float]:
    """All PHENOTYPES with values in [0, 1], missing ones 0.5; InputError on unknown names."""
    ph = {k: 0.5 for k in PHENOTYPES}
    for k, v in (phenotype or {}).items():
        if k not in PHENOTYPES:
            raise InputError(f"unknown phenotype {k!r}; use {list(PHENOTYPES)}")
        v = float(v)
        if not 0.0 <= v <= 1.0:
            raise InputError(f"phenotype {k}={v} must be in [0, 1]")
        ph[k] = v
    return ph


def _run_anny(anny, ph: dict[str, float], rot: dict):
    """The anny model and its output for phenotype ``ph``, posed by ``rot`` (world-frame rotvecs,
    or the T-pose marker) when given."""
    import torch

    model = anny.Anny()
    labels = list(model.bone_labels)
    with torch.no_grad():
        out = model(phenotype_kwargs={k: torch.tensor([v], dtype=torch.float64) for k, v in ph.items()})
        if rot:
            if "__T__" in rot:
                rot = _t_pose_rotations(out, labels)
            posed = _anny_pose_tensor(model, out, rot, torch).to(out["bone_poses"].dtype)
            out = model(
                pose_parameters=posed,
                phenotype_kwargs={k: torch.tensor([v], dtype=torch.float64) for k, v in ph.items()},
                pose_parameterization="world",
            )
    return model, out


def _joint_weights(model, n_verts: int) -> np.ndarray:
    """Skinning weights (V, J) float64 on our joints: anny's (V, 9) sparse weights over 104 bones,
    each bone given to its nearest ancestor that JOINT_MAP maps."""
    labels, parents = list(model.bone_labels), list(model.bone_parents)
    src = {v[0]: i for i, (k, v) in enumerate(JOINT_MAP.items()) if v[0]}
    bone_to_joint = np.zeros(len(labels), dtype=np.int64)
    for b in range(len(labels)):
        k = b
        while labels[k] not in src:
            k = parents[k]
        bone_to_joint[b] = src[labels[k]]
    wv = model.vertex_bone_weights.double().numpy()
    wi = model.vertex_bone_indices.numpy().astype(np.int64)
    W = np.zeros((n_verts, len(JOINT_MAP)))
    np.add.at(W, (np.arange(n_verts)[:, None], bone_to_joint[wi]), wv)
    return W


def _skeleton(verts: np.ndarray, heads: np.ndarray, labels: list[str]) -> tuple[np.ndarray, Skeleton]:
    """Our skeleton from anny's bone heads (104, 3) [m] (head_top: the highest vertex near the
    head's vertical axis), body and skeleton moved to feet at y = 0, pelvis at x = z = 0."""
    names = list(JOINT_MAP)
    pos = np.zeros((len(names), 3))
    for j, n in enumerate(names):
        bone = JOINT_MAP[n][0]
        if bone is not None:
            pos[j] = heads[labels.index(bone)]
    hj = names.index("head")
    near = np.linalg.norm((verts - pos[hj])[:, [0, 2]], axis=1) < 0.06
    pos[names.index("head_top")] = [pos[hj, 0], verts[near, 1].max(), pos[hj, 2]]

    offset = np.array([-pos[0, 0], -verts[:, 1].min(), -pos[0, 2]])
    verts, pos = verts + offset, pos + offset
    par = np.array([-1 if JOINT_MAP[n][1] is None else names.index(JOINT_MAP[n][1]) for n in names])
    return verts, Skeleton(names, par, pos, [JOINT_MAP[n][2] for n in names])


def _keep_top_k(W: np.ndarray, top_k: int) -> np.ndarray:
    """Weights (V, J) with all but each vertex's ``top_k`` largest zeroed, rows normalized to 1."""
    if top_k and top_k < W.shape[1]:
        idx = np.argsort(-W, axis=1)[:, top_k:]
        np.put_along_axis(W, idx, 0.0, axis=1)
    W /= np.maximum(W.sum(axis=1, keepdims=True), 1e-12)
    return W


def _t_pose_rotations(out, labels) -> dict:
    """World-frame rotations raising both upper arms to horizontal (forearms follow)."""
    H = out["bone_poses"][0, :, :3, 3].double().numpy() @ ANNY_TO_WORLD.T
    rots = {}
    for side, s, sign in (("left", "L", 1.0), ("right", "R", -1.0)):
        a = H[labels.index(f"upperarm01.{s}")]
        w = H[labels.index(f"wrist.{s}")]
        d = w - a
        d[2] = 0.0  # rotate in the frontal plane only
        target = np.array([sign, 0.0, 0.0])
        d /= np.linalg.norm(d)
        ang = np.arctan2(np.cross(d, target)[2], d @ target)
        rots[f"{side}_shoulder"] = [0.0, 0.0, float(ang)]
    return rots


def _largest_component(verts: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vertex indices (kept, sorted) and re-indexed faces of the component (vertex-connected)
    with most faces."""
    n, lab = components(faces, len(verts), by="vertex")
    keep_f = faces[lab == np.bincount(lab, minlength=n).argmax()]
    keep_v = np.unique(keep_f)
    remap = -np.ones(len(verts), dtype=np.int64)
    remap[keep_v] = np.arange(len(keep_v))
    return keep_v, remap[keep_f]


def save_body_npz(body: Body, path: str | os.PathLike, *, top_k: int = 4, meta: dict | None = None) -> None:
    """Store a body compactly: vertices float32 [m], faces int32, skeleton float64, the top-k
    skinning weights per vertex (uint8 joint index, float32 weight). Written atomically."""
    sk = body.skeleton
    arrays = dict(
        verts=body.verts.astype(np.float32),
        faces=body.faces.astype(np.int32),
        joint_names=np.array(sk.names),
        joint_parents=sk.parents.astype(np.int32),
        joint_positions=sk.positions.astype(np.float64),
        joint_parts=np.array(sk.parts),
        name=np.array(body.name),
        meta=np.array(json.dumps(meta or {})),
    )
    if body.weights is not None:
        order = np.argsort(-body.weights, axis=1)[:, :top_k]
        arrays["weight_index"] = order.astype(np.uint8)
        arrays["weight_value"] = np.take_along_axis(body.weights, order, axis=1).astype(np.float32)
    with atomic_write(path) as tmp:
        with open(tmp, "wb") as fh:
            np.savez_compressed(fh, **arrays)
