"""The fit's body contact read from the target (mode "target" of unsew.fit.contact): the gap
measured on a target at a known distance from the body, its clamping, and the mode check."""

import numpy as np
import pytest

from unsew.body.body import Body
from unsew.body.sdf import BodySDF
from unsew.body.skeleton import Skeleton
from unsew.errors import InputError
from unsew.fit.config import load_config
from unsew.fit.contact import CONTACT_STIFF, GAP_RANGE_M, contact_for_target, target_gap


@pytest.fixture(scope="module")
def sphere():
    import trimesh

    m = trimesh.creation.icosphere(subdivisions=4, radius=0.1)
    sk = Skeleton(["pelvis"], [-1], [[0.0, 0.0, 0.0]], ["torso"])
    body = Body(np.asarray(m.vertices, float), np.asarray(m.faces, np.int64), sk)
    # a ball, not a person standing: no ground under it
    return body, BodySDF.build(body, voxel=0.005, margin=0.03, use_cache=False, floor=False)


def _shell(r, n=4000, seed=0):
    """n points on the sphere of radius r [m] about the origin."""
    p = np.random.default_rng(seed).normal(size=(n, 3))
    return r * p / np.linalg.norm(p, axis=1, keepdims=True)


def test_the_gap_is_where_the_targets_cloth_rests(sphere):
    body, sdf = sphere
    # a cloth resting 4 mm off the body over a fifth of it, the rest hanging farther out
    pts = np.vstack([_shell(0.104, 1000, 1), _shell(0.13, 4000, 2)])
    gap = target_gap(pts, body, sdf)
    assert 0.0038 < gap < 0.0041  # the body's facets lie at most 0.1 mm inside its sphere
    cfg, info = contact_for_target(load_config(), pts, body, sdf, mode="target")
    assert cfg.drape.contact_threshold == pytest.approx(gap)
    assert cfg.drape.contact_stiffness == CONTACT_STIFF
    assert info["mode"] == "target" and info["gap_mm"] == pytest.approx(gap * 1e3)
    assert info["threshold_mm"] == pytest.approx(gap * 1e3)


def test_a_target_inside_the_body_gets_the_thinnest_zone(sphere):
    body, sdf = sphere
    pts = _shell(0.095, 2000)  # 5 mm inside: the signed gap is negative
    assert target_gap(pts, body, sdf) < -0.004
    cfg, info = contact_for_target(load_config(), pts, body, sdf, mode="target")
    assert cfg.drape.contact_threshold == GAP_RANGE_M[0]
    far = _shell(0.2, 2000)  # 10 cm out: loose all over
    cfg, _ = contact_for_target(load_config(), far, body, sdf, mode="target")
    assert cfg.drape.contact_threshold == GAP_RANGE_M[1]


def test_the_default_contact_is_left_as_configured(sphere):
    body, sdf = sphere
    cfg0 = load_config()
    cfg, info = contact_for_target(cfg0, _shell(0.104), body, sdf)
    assert cfg is cfg0
    assert info == {"mode": "default", "threshold_mm": pytest.approx(5.0), "stiffness": 1e7}


def test_an_unknown_contact_mode_is_refused(sphere):
    body, sdf = sphere
    with pytest.raises(ValueError, match="contact mode must be one of default, target"):
        contact_for_target(load_config(), _shell(0.104), body, sdf, mode="tight")
    with pytest.raises(InputError, match="'contact' is no longer a setting: it is the constant"):
        load_config(contact="target")
