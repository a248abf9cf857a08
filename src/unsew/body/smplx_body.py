"""Bodies from SMPL-X, for users who have its model files (optional; nothing else needs it).

SMPL-X's weights cannot be shipped or downloaded by unsew: install the ``smplx`` package
(``pip install unsew[smplx]``) and give the folder holding the model files you obtained under
SMPL-X's own license. SMPL-X's frame is ours (metres, Y up, facing +Z, left at +X); the body is
moved so its soles are at y = 0 and its pelvis joint at x = z = 0, as the default body.

Our joints are SMPL-X joints by index (below); SMPL-X's 55 skinning-weight columns are folded
onto them (each SMPL-X joint onto itself if it is one of ours, else onto its nearest ancestor
that is), so the body can be posed with :func:`unsew.body.pose.pose_body`.
"""

from __future__ import annotations

import numpy as np

from unsew.body.body import Body, check_body_plausible, clean_body_mesh
from unsew.body.skeleton import Skeleton
from unsew.errors import InputError

__all__ = ["SMPLX_JOINTS", "SMPLX_PARENTS", "make_smplx_body"]

#: Our joint -> (SMPL-X joint index, our parent joint, part of the bone ending at the joint).
SMPLX_JOINTS: dict[str, tuple[int, str | None, str]] = {
    "pelvis": (0, None, "torso"),
    "spine": (3, "pelvis", "torso"),
    "chest": (9, "spine", "torso"),
    "neck": (12, "chest", "torso"),
    "head": (15, "neck", "head"),
    "left_collar": (13, "chest", "torso"),
    "left_shoulder": (16, "left_collar", "torso"),
    "left_elbow": (18, "left_shoulder", "left_arm"),
    "left_wrist": (20, "left_elbow", "left_arm"),
    "right_collar": (14, "chest", "torso"),
    "right_shoulder": (17, "right_collar", "torso"),
    "right_elbow": (19, "right_shoulder", "right_arm"),
    "right_wrist": (21, "right_elbow", "right_arm"),
    "left_hip": (1, "pelvis", "torso"),
    "left_knee": (4, "left_hip", "left_leg"),
    "left_ankle": (7, "left_knee", "left_leg"),
    "left_toe": (10, "left_ankle", "left_leg"),
    "right_hip": (2, "pelvis", "torso"),
    "right_knee": (5, "right_hip", "right_leg"),
    "right_ankle": (8, "right_knee", "right_leg"),
    "right_toe": (11, "right_ankle", "right_leg"),
}

#: Parents of SMPL-X's first 22 body joints (its kinematic tree); hands, jaw and eyes (22-54)
#: hang from the wrists (hands) and the head (face) for folding the weights.
SMPLX_PARENTS = [-1, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9, 9, 12, 13, 14, 16, 17, 18, 19]


def _smplx_parent(j: int) -> int:
    if j < len(SMPLX_PARENTS):
        return SMPLX_PARENTS[j]
    if 22 <= j <= 24:  # jaw, eyes
        return 15
    return 20 if j < 40 else 21  # 25-39 left hand, 40-54 right hand


def _fold_matrix(n_smplx: int) -> np.ndarray:
    """(n_smplx, J) 0/1 matrix sending each SMPL-X joint's skinning weight to the nearest of its
    ancestors (itself included) among the J joints of SMPLX_JOINTS."""
    ours = {idx: k for k, (idx, _, _) in enumerate(SMPLX_JOINTS.values())}
    fold = np.zeros((n_smplx, len(SMPLX_JOINTS)))
    for j in range(n_smplx):
        a = j
        while a not in ours:
            a = _smplx_parent(a)
        fold[j, ours[a]] = 1.0
    return fold


def make_smplx_body(
    model_path,
    *,
    gender: str = "neutral",
    betas=None,
    body_pose=None,
    global_orient=None,
    name: str = "smplx",
):
    """A Body from SMPL-X.

    model_path: folder with the SMPL-X model files (``smplx.create``'s ``model_path``).
    betas: (B,) shape coefficients [-]; body_pose: (63,) axis-angle [rad] of the 21 body joints;
    global_orient: (3,) [rad]. Returns unsew.body.body.Body with verts (V, 3) [m], the joints
    of SMPLX_JOINTS, and folded skinning weights (V, J).
    """
    try:
        import smplx
        import torch
    except ImportError:
        raise InputError(
            "SMPL-X bodies need the smplx package: pip install unsew[smplx] (and SMPL-X's model files)"
        ) from None

    betas = np.zeros(10) if betas is None else np.asarray(betas, dtype=np.float64).reshape(-1)
    try:
        model = smplx.create(
            str(model_path), model_type="smplx", gender=gender, num_betas=len(betas), use_pca=False
        )
    except Exception as exc:  # missing or unreadable model files
        raise InputError(f"cannot load SMPL-X from {model_path}: {exc}".splitlines()[0]) from None
    kw = {"betas": torch.as_tensor(betas, dtype=torch.float32)[None], "return_verts": True}
    if body_pose is not None:
        kw["body_pose"] = torch.as_tensor(
            np.asarray(body_pose, dtype=np.float64).reshape(1, -1), dtype=torch.float32
        )
    if global_orient is not None:
        kw["global_orient"] = torch.as_tensor(
            np.asarray(global_orient, dtype=np.float64).reshape(1, 3), dtype=torch.float32
        )
    with torch.no_grad():
        out = model(**kw)
    v = out.vertices[0].detach().cpu().numpy().astype(np.float64)
    joints = out.joints[0].detach().cpu().numpy().astype(np.float64)
    W55 = np.asarray(model.lbs_weights.detach().cpu().numpy(), dtype=np.float64)  # (V, 55)

    names = list(SMPLX_JOINTS)
    W = W55 @ _fold_matrix(W55.shape[1])
    faces = np.asarray(model.faces, dtype=np.int64)
    keep_v, keep_f, _ = clean_body_mesh(v, faces, what="SMPL-X body")
    # clean_body_mesh may drop components (the eyeballs): carry the weights of the kept vertices
    idx = _match_rows(v, keep_v)
    W = W[idx]
    pos = np.array([joints[SMPLX_JOINTS[n][0]] for n in names])
    shift = np.array([-pos[0, 0], -keep_v[:, 1].min(), -pos[0, 2]])
    parents = np.array([-1 if SMPLX_JOINTS[n][1] is None else names.index(SMPLX_JOINTS[n][1]) for n in names])
    sk = Skeleton(names, parents, pos + shift, [SMPLX_JOINTS[n][2] for n in names])
    body = Body(keep_v + shift, keep_f, sk, W / W.sum(1, keepdims=True), name=name)
    check_body_plausible(body.verts, sk, what="SMPL-X body")
    return body


def _match_rows(full: np.ndarray, kept: np.ndarray) -> np.ndarray:
    """Index into ``full`` of each row of ``kept`` (exact copies)."""
    from scipy.spatial import cKDTree

    d, i = cKDTree(full).query(kept)
    if d.max() > 1e-9:
        raise InputError("SMPL-X mesh cleaning moved vertices; cannot carry the skinning weights")
    return i
