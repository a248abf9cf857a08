"""Posing a body by linear blend skinning."""

import numpy as np
import pytest
from helpers import assert_close

from unsew.body.body import default_body
from unsew.body.pose import POSES, pose_body, rotation_matrix
from unsew.errors import InputError


def test_rotation_matrix():
    R = rotation_matrix([0, 0, np.pi / 2])
    assert_close(R @ [1, 0, 0], [0, 1, 0], atol=1e-15)
    assert_close(R.T @ R, np.eye(3), atol=1e-15)


def test_zero_pose_is_identity():
    b = default_body()
    p = pose_body(b, {"left_shoulder": (0.0, 0.0, 0.0)})
    assert_close(p.verts, b.verts, atol=1e-12)
    assert_close(p.skeleton.positions, b.skeleton.positions, atol=1e-12)


def test_raised_arm_moves_the_arm_only():
    b = default_body()
    p = pose_body(b, "left_arm_up")
    sk, i = b.skeleton, b.skeleton.names.index
    # the left wrist rotates about the left shoulder by 25 degrees, upwards
    R = rotation_matrix(POSES["left_arm_up"]["left_shoulder"])
    s = sk.positions[i("left_shoulder")]
    assert_close(
        p.skeleton.positions[i("left_wrist")], R @ (sk.positions[i("left_wrist")] - s) + s, atol=1e-12
    )
    assert p.skeleton.positions[i("left_wrist"), 1] > sk.positions[i("left_wrist"), 1] + 0.1
    assert_close(p.skeleton.positions[i("right_wrist")], sk.positions[i("right_wrist")], atol=1e-12)
    # vertices far from the left arm stay put; the left hand moves up
    legs = b.verts[:, 1] < 0.6
    assert_close(p.verts[legs], b.verts[legs], atol=1e-9)
    hand = np.linalg.norm(b.verts - sk.positions[i("left_hand")], axis=1) < 0.03
    assert (p.verts[hand, 1] - b.verts[hand, 1]).min() > 0.1


def test_bad_pose():
    b = default_body()
    with pytest.raises(InputError, match="unknown pose"):
        pose_body(b, "dab")
    with pytest.raises(InputError, match="lacks"):
        pose_body(b, {"tail": (0, 0, 1)})
