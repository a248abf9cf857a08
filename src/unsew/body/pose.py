"""Pose a body by linear blend skinning: rotate joints of its skeleton and move the mesh with
its skinning weights. Used to make targets in other poses (one arm or leg moved) without anny.

Rotations are given per joint as rotation vectors (axis * angle [rad]) in the world frame,
applied about the joint's rest position; a joint's rotation moves every bone below it (the
weights' convention in :class:`unsew.body.body.Body`: column j is the influence of joint j).
Forward kinematics composes them down the hierarchy: G_j = G_parent(j) * T(p_j) R_j T(-p_j).
"""

from __future__ import annotations

import numpy as np

from unsew.body.body import Body
from unsew.body.skeleton import Skeleton
from unsew.errors import InputError

__all__ = ["pose_body", "rotation_matrix", "POSES"]

#: Named poses: joint -> rotation vector [rad], world frame (Y up, facing +Z, left at +X).
POSES = {
    # the left arm raised by 25 degrees towards the side (about +Z turns +X towards +Y)
    "left_arm_up": {"left_shoulder": (0.0, 0.0, np.deg2rad(25.0))},
    # the right leg swung 20 degrees forward (about -X turns -Y towards +Z)
    "right_leg_forward": {"right_hip": (-np.deg2rad(20.0), 0.0, 0.0)},
}


def rotation_matrix(rotvec) -> np.ndarray:
    """(3, 3) rotation matrix of a rotation vector (3,) [rad] (Rodrigues' formula)."""
    r = np.asarray(rotvec, dtype=np.float64).reshape(3)
    th = float(np.linalg.norm(r))
    if th < 1e-15:
        return np.eye(3)
    k = r / th
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * (K @ K)


def pose_body(body, rotations: dict | str, *, name: str | None = None):
    """A new Body in another pose.

    body: unsew.body.body.Body with skinning weights (V, J).
    rotations: joint name -> rotation vector (3,) [rad], world frame, or a name from POSES.
    Returns a Body with moved vertices (V, 3) [m], moved joint positions, the same faces and weights.
    """
    if isinstance(rotations, str):
        if rotations not in POSES:
            raise InputError(f"unknown pose {rotations!r}; known: {', '.join(sorted(POSES))}")
        label, rotations = rotations, POSES[rotations]
    else:
        label = "posed"
    if body.weights is None:
        raise InputError(
            "this body has no skinning weights, so it cannot be posed; give a posed mesh instead"
        )
    sk = body.skeleton
    idx = {n: i for i, n in enumerate(sk.names)}
    unknown = [n for n in rotations if n not in idx]
    if unknown:
        raise InputError(f"pose names joints the skeleton lacks: {unknown}")
    J = len(sk.names)
    # parents before children
    order, seen = [], set()
    while len(order) < J:
        for j in range(J):
            p = int(sk.parents[j])
            if j not in seen and (p < 0 or p in seen):
                order.append(j)
                seen.add(j)
    G = np.zeros((J, 3, 4))
    for j in order:
        R = rotation_matrix(rotations.get(sk.names[j], (0.0, 0.0, 0.0)))
        pj = sk.positions[j]
        local = np.concatenate([R, (pj - R @ pj)[:, None]], axis=1)  # T(p) R T(-p)
        p = int(sk.parents[j])
        if p < 0:
            G[j] = local
        else:
            Gp = G[p]
            G[j] = np.concatenate(
                [Gp[:, :3] @ local[:, :3], (Gp[:, :3] @ local[:, 3] + Gp[:, 3])[:, None]], axis=1
            )
    W = np.asarray(body.weights, dtype=np.float64)  # (V, J)
    v = np.asarray(body.verts, dtype=np.float64)
    vh = np.concatenate([v, np.ones((len(v), 1))], axis=1)  # (V, 4)
    per_joint = np.einsum("jab,vb->vja", G, vh)  # (V, J, 3)
    verts = np.einsum("vj,vja->va", W, per_joint)
    pos = sk.positions.copy()
    for j in range(J):
        p = int(sk.parents[j])
        if p >= 0:
            pos[j] = G[p][:, :3] @ sk.positions[j] + G[p][:, 3]
    skel = Skeleton(list(sk.names), sk.parents.copy(), pos, list(sk.parts))
    return Body(verts, np.asarray(body.faces).copy(), skel, W.copy(), name=name or f"{body.name}-{label}")
