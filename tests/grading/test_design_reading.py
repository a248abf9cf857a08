"""The structural choices read off a draped garment: newton drapes of the foreign benchmark on
the default body (named by their cut), and small synthetic shapes."""

from pathlib import Path

import numpy as np
import pytest

from unsew.body.body import default_body
from unsew.grading.design_reading import read_design
from unsew.io.mesh import read_garment

CASES = Path(__file__).resolve().parents[2] / "benchmarks" / "foreign" / "cases"


def _target(name):
    if not (CASES / name / "target.obj").is_file():
        pytest.skip(f"benchmark case {name} not in this checkout")
    v, f, _ = read_garment(CASES / name / "target.obj")
    return v, f


@pytest.fixture(scope="module")
def skeleton():
    return default_body().skeleton


@pytest.mark.parametrize(
    "name, sleeves",
    [
        ("tank_top__default", "none"),
        ("tee_fitted_short__default", "short"),
        ("tee_fitted_long__default", "long"),
    ],
)
def test_sleeves_read_as_cut(name, sleeves, skeleton):
    r = read_design(*_target(name), skeleton)
    assert r.sleeves == sleeves, r.evidence
    assert (r.neck_front, r.neck_back, r.collar) == ("round", "round", "none"), r.evidence
    assert r.skirt is None and r.length is None  # a top has neither


@pytest.mark.parametrize(
    "name, skirt, length",
    [
        ("skirt_pencil_mini__default", "pencil", "above knee"),
        ("skirt_circle_knee__default", "flared", "knee"),
        ("trousers_slim__default", None, "below knee"),
        ("shorts_short__default", None, "above knee"),
    ],
)
def test_skirt_kind_and_length_read_as_cut(name, skirt, length, skeleton):
    r = read_design(*_target(name), skeleton)
    assert (r.skirt, r.length) == (skirt, length), r.evidence
    assert r.sleeves is None and r.neck_front is None


def test_a_hood_over_the_head_is_read_and_hides_the_neckline(skeleton):
    """A tee with an open tube rising round the head: a hood; its neckline is not read."""
    import trimesh

    v, f = _target("tee_fitted_short__default")
    head = skeleton.position("head")
    tube = trimesh.creation.cylinder(radius=0.13, height=0.3, sections=24)
    keep = np.abs(tube.face_normals[:, 2]) < 0.5  # the side wall only: an open tube
    tube = trimesh.Trimesh(tube.vertices, tube.faces[keep], process=True)
    tube.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [1, 0, 0]))
    tube.apply_translation(head + [0, 0.05, 0])
    both_v = np.concatenate([v, tube.vertices])
    both_f = np.concatenate([f, np.asarray(tube.faces) + len(v)])
    r = read_design(both_v, both_f, skeleton)
    assert r.collar == "hood" and r.neck_front is None, r.evidence
    assert "hood" in r.summary() and r.summary().startswith("read: tshirt")


def test_neckline_halves_square_v_round():
    """Neckline halves seen from the front (x across, y up, [m]): a square bottom between two
    corners, a round arc and a straight-sided V."""
    from unsew.grading.design_reading import _is_square
    from unsew.grading.garment_type import _half_is_v

    width = 0.2
    x = np.linspace(-0.1, 0.1, 41)
    square = np.stack([x, np.where(np.abs(x) < 0.09, -0.1, -0.1 + (np.abs(x) - 0.09) * 10)], axis=1)
    arc = np.stack([x, -np.sqrt(np.maximum(0.1**2 - x**2, 0))], axis=1)
    vee = np.stack([x, -0.15 + 1.5 * np.abs(x)], axis=1)
    shallow = np.stack([x, -0.01 * np.sqrt(np.maximum(1 - (x / 0.1) ** 2, 0))], axis=1)
    assert _is_square(square, width)[0]
    assert not _is_square(arc, width)[0] and not _half_is_v(arc, width)[0]
    assert not _is_square(shallow, width)[0]  # flat, but without corners: a shallow round back
    assert _half_is_v(vee, width)[0] and not _is_square(vee, width)[0]
