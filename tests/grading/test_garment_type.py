"""The garment type read off a draped garment: newton drapes of the foreign benchmark on the
default body, whose meta.json names the type the fit is not told."""

from pathlib import Path

import numpy as np
import pytest

from unsew.body.body import default_body
from unsew.errors import InputError
from unsew.grading.garment_type import read_garment_type
from unsew.io.mesh import read_garment

CASES = Path(__file__).resolve().parents[2] / "benchmarks" / "foreign" / "cases"
#: one drape of each kind: sleeved and sleeveless dresses, a long-sleeved and a tank top, knee and
#: short shorts, slim and wide trousers, a pencil and a circle skirt
KINDS = {
    "dress_sheath_sleeved__default": "dress",
    "dress_shift_sleeveless__default": "dress",
    "tee_fitted_long__default": "tshirt",
    "tank_top__default": "tshirt",
    "shorts_knee__default": "shorts",
    "shorts_short__default": "shorts",
    "trousers_slim__default": "pants",
    "trousers_wide__default": "pants",
    "skirt_pencil_mini__default": "skirt",
    "skirt_circle_knee__default": "skirt",
}


def _target(name):
    if not (CASES / name / "target.obj").is_file():
        pytest.skip(f"benchmark case {name} not in this checkout")
    v, f, _ = read_garment(CASES / name / "target.obj")
    return v, f


@pytest.mark.parametrize("name", sorted(KINDS))
def test_the_type_of_a_drape_made_elsewhere(name):
    v, f = _target(name)
    reading = read_garment_type(v, f, default_body().skeleton)
    assert reading.garment == KINDS[name], reading.reason


def test_legs_and_a_bodice_read_as_a_one_piece_suit():
    """Trousers and a tee in one mesh: openings round both legs and both arms."""
    (v1, f1), (v2, f2) = _target("trousers_slim__default"), _target("tee_fitted_short__default")
    v, f = np.concatenate([v1, v2]), np.concatenate([f1, f2 + len(v1)])
    reading = read_garment_type(v, f, default_body().skeleton)
    assert reading.garment == "jumpsuit" and min(reading.legs) >= 1 and min(reading.arms) >= 1


def test_the_reading_does_not_trust_part_labels():
    """Limb joints labelled with the limb (as other rigs label them) read the same."""
    v, f = _target("trousers_slim__default")
    sk = default_body().skeleton
    relabelled = type(sk)(
        list(sk.names),
        sk.parents.copy(),
        sk.positions.copy(),
        [
            ("left_leg" if n.startswith("left_") and n.endswith(("hip", "shoulder")) else p)
            for n, p in zip(sk.names, sk.parts)
        ],
    )
    assert read_garment_type(v, f, relabelled).garment == "pants"


def test_a_closed_shape_is_refused():
    import trimesh

    box = trimesh.creation.box((0.4, 0.6, 0.3))
    box.apply_translation((0, 1.2, 0))
    with pytest.raises(InputError, match="no opening"):
        read_garment_type(np.asarray(box.vertices), np.asarray(box.faces), default_body().skeleton)


def test_necklines_of_drapes_made_elsewhere_read_round():
    from unsew.grading.garment_type import read_necklines

    for name in ("dress_sheath_sleeved__default", "tee_fitted_short__default", "tank_top__default"):
        v, f = _target(name)
        assert read_necklines(v, f, default_body().skeleton)[0] == ("round", "round"), name


def test_a_v_neck_is_read_off_its_drape():
    """A tee cut with a V in front and a round back, dressed on the default body, reads as cut."""
    from unsew.body.measure import measure_body
    from unsew.dress import dress
    from unsew.grading.garment_type import read_necklines
    from unsew.pattern.base import make_base_pattern
    from unsew.sim.drape import DrapeSettings

    body = default_body()
    d = dress(
        make_base_pattern("tshirt", measure_body(body), necklines=("v", "round")),
        body,
        settings=DrapeSettings(edge_length=0.04),
    )
    shapes, angles = read_necklines(d.x.numpy(), d.mesh.faces, body.skeleton)
    assert shapes == ("v", "round"), angles


def test_a_leg_opening_its_legs_line_misses_is_paired_with_its_twin():
    """Trousers whose right hem the right leg's line misses (the ankle moved back, as a hem lying
    on the floor round a foot lies forward of the ankle's line): the right hem mirrors the left one
    across the hips, at its height and of its size, so both legs' openings are read."""
    from unsew.grading import garment_type as gt
    from unsew.losses.contours import open_contours

    v, f = _target("trousers_slim__default")
    sk = default_body().skeleton
    pos = sk.positions.copy()
    pos[list(sk.names).index("right_ankle"), 2] -= 0.1
    moved = type(sk)(list(sk.names), sk.parents.copy(), pos, list(sk.parts))
    loops = open_contours(v, f)
    hem = min(loops, key=lambda c: c.centre[1] + 10.0 * (c.centre[0] > sk.position("pelvis")[0]))
    line = gt._limb_chains(moved)["right_leg"]
    assert gt._chain_distance(np.asarray([hem.centre]), line)[0] > max(gt._radius(v, hem), gt.LIMB_NEAR)
    reading = read_garment_type(v, f, moved)
    assert reading.garment == "pants" and min(reading.legs) == 1, reading.reason
