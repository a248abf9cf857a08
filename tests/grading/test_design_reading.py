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
    if sleeves != "long":  # the arm line passes through an armhole and a short sleeve's end
        assert r.numbers["sleeve_through"] == 1.0, r.evidence
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


def test_a_top_cut_under_the_armpits_reads_strapless(skeleton):
    """A tee's shape cut off under the armpits leaves no cloth over the shoulders: a strapless
    top, no neckline and no collar read; the tee itself reaches over them."""
    from unsew.grading.design_reading import _over_shoulders

    v, f = _target("tee_fitted_short__default")
    sh_y = 0.5 * (skeleton.position("left_shoulder")[1] + skeleton.position("right_shoulder")[1])
    assert _over_shoulders(v, skeleton) > 0.0
    keep = (v[f, 1] < sh_y - 0.1).all(axis=1)
    used, faces = np.unique(f[keep], return_inverse=True)
    r = read_design(v[used], faces.reshape(-1, 3), skeleton)
    assert r.garment == "tshirt", r.evidence
    assert (r.neck_front, r.neck_back, r.collar) == ("none", "none", "none"), r.evidence
    assert "strapless" in r.summary()


def _ring(centre, normal, radius, n=24, squash=1.0):
    """(n, 3) points [m] of an ellipse round ``centre`` in the plane normal to ``normal``."""
    normal = np.asarray(normal, float) / np.linalg.norm(normal)
    a = np.cross(normal, [0.0, 0.0, 1.0] if abs(normal[2]) < 0.9 else [1.0, 0.0, 0.0])
    a /= np.linalg.norm(a)
    b = np.cross(normal, a)
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)[:, None]
    return np.asarray(centre) + radius * (np.cos(t) * a + squash * np.sin(t) * b)


def test_a_deep_armhole_is_crossed_at_the_shoulder_and_a_sleeve_end_where_it_ends(skeleton):
    """The arm line passes through a deep armhole (its centre 17 cm under the shoulder,
    well along the arm's direction) beside the shoulder, and through a sleeve's end at the elbow."""
    from unsew.grading.design_reading import ARMHOLE_SHARE, _arm_crossing, _arm_share
    from unsew.grading.garment_type import _limb_chains

    arm = _limb_chains(skeleton)["left_arm"]
    sh = skeleton.position("left_shoulder")
    mid = 0.5 * (sh + skeleton.position("right_shoulder"))
    hole = _ring(sh + [0.01, -0.17, 0.0], [1.0, 0.0, 0.0], 0.2, squash=0.5)  # tall, in a side plane
    assert _arm_share(hole.mean(axis=0), arm) > ARMHOLE_SHARE  # its centre alone says a sleeve
    p = _arm_crossing(hole, arm, mid)
    assert p is not None and _arm_share(p, arm) < ARMHOLE_SHARE
    elbow = skeleton.position("left_elbow")
    end = _ring(elbow, elbow - sh, 0.06)
    p = _arm_crossing(end, arm, mid)
    reach = np.linalg.norm(elbow - sh) / (np.linalg.norm(elbow - sh) + np.linalg.norm(arm[2] - elbow))
    assert p is not None and abs(_arm_share(p, arm) - reach) < 0.02


def _with_bands(v, f, centre, radius):
    """The garment (V, 3), (F, 3) with a short open tube of ``radius`` [m] at ``centre`` (3,) [m]
    and its mirror across x = 0, their axes front to back: two free loops per side."""
    import trimesh

    out_v, out_f = [v], [f]
    n = len(v)
    for c in (np.asarray(centre, float), np.asarray(centre, float) * [-1.0, 1.0, 1.0]):
        t = trimesh.creation.cylinder(radius=radius, height=0.03, sections=24)
        t = trimesh.Trimesh(t.vertices, t.faces[np.abs(t.face_normals[:, 2]) < 0.5], process=True)
        t.apply_translation(c)
        out_v.append(np.asarray(t.vertices))
        out_f.append(np.asarray(t.faces) + n)
        n += len(t.vertices)
    return np.concatenate(out_v), np.concatenate(out_f)


def test_a_wide_cuff_hanging_far_from_the_shoulder_is_a_sleeve_end(skeleton):
    """A loop round no limb, 6.5 cm in radius (wider than a tight cuff), hanging beside the
    torso: by the wrist's height a bell sleeve's end (a long sleeve); 20 cm under the shoulder
    joint an armhole's rim, which leaves the sleeveless top sleeveless."""
    v, f = _target("tank_top__default")
    wrist, sh = skeleton.position("left_wrist"), skeleton.position("left_shoulder")
    r = read_design(*_with_bands(v, f, wrist + [0.0, 0.08, -0.12], 0.065), skeleton)
    assert r.sleeves == "long" and "off the arm line" in r.evidence["sleeves"], r.evidence
    r = read_design(*_with_bands(v, f, sh + [0.05, -0.2, 0.0], 0.065), skeleton)
    assert r.sleeves == "none", r.evidence


def _tube(radius, top, bottom, slit=0.0, n=48, rows=12):
    """(V, 3), (F, 3) an open cylinder round the Y axis [m] from height ``top`` down to
    ``bottom``, with a slit ``slit`` [m] high up the front from its hem."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) + np.pi / 2  # column 0 at the front (+Z)
    ys = np.linspace(top, bottom, rows)
    v = np.array([[radius * np.cos(a), y, radius * np.sin(a)] for y in ys for a in t])
    f = []
    for i in range(rows - 1):
        for j in range(n):
            k = (j + 1) % n
            if k == 0 and ys[i + 1] < bottom + slit:  # the slit: front columns not joined
                continue
            a, b, c, d = i * n + j, i * n + k, (i + 1) * n + j, (i + 1) * n + k
            f += [[a, c, b], [b, c, d]]
    return v, np.array(f)


def test_a_slit_leaves_the_skirts_flare_as_it_was(skeleton):
    """A straight tube skirt round the hips reads pencil, with or without a slit up its front;
    twice as wide at its hem (a cone) it reads flared."""
    from unsew.grading.design_reading import _hip_girth

    body = default_body()
    hip = 0.5 * (skeleton.position("left_hip")[1] + skeleton.position("right_hip")[1])
    knee = 0.5 * (skeleton.position("left_knee")[1] + skeleton.position("right_knee")[1])
    radius = 1.05 * _hip_girth(skeleton, body) / (2 * np.pi)  # a little ease round the hips
    for slit in (0.0, 0.25):
        v, f = _tube(radius, hip + 0.12, knee, slit=slit)
        r = read_design(v, f, skeleton, body=body)
        assert r.garment == "skirt" and r.skirt == "pencil", r.evidence
        assert "the body's girth" in r.evidence["skirt"]
    v, f = _tube(radius, hip + 0.12, knee)
    y = v[:, 1]
    scale = 1.0 + np.clip((hip - y) / (hip - knee), 0.0, 1.0) * 1.2  # the hem 2.2 x the hips' radius
    r = read_design(v * np.c_[scale, np.ones_like(y), scale], f, skeleton, body=body)
    assert r.skirt == "flared", r.evidence


#: Drafted designs and the choices they are read back as (the design's own choices in the
#: reading's words: a circle skirt is flared, full trouser legs end below the knee).
ROUND_TRIP = [
    (dict(garment="tshirt", sleeves="none"), dict(sleeves="none", neck_front="round", collar="none")),
    (dict(garment="tshirt", sleeves="short", neckline_front="v"), dict(sleeves="short", neck_front="v")),
    (
        dict(garment="tshirt", sleeves="long", neckline_front="square"),
        dict(sleeves="long", neck_front="square"),
    ),
    (
        dict(garment="dress", sleeves="short", skirt="circle", length="midi", waist_seam=True),
        dict(sleeves="short", skirt="flared"),
    ),
    (dict(garment="pants", leg="full"), dict(length="below knee")),
    (dict(garment="shorts"), dict(length="above knee")),
]


@pytest.mark.parametrize("design, expected", ROUND_TRIP)
def test_a_drafted_design_placed_on_the_body_is_read_as_its_own_choices(design, expected):
    """A design drafted (unsew.pattern.design), meshed and placed round the body (no drape; each
    sewn vertex at its copies' mean) is read back as its type and its choices."""
    from unsew.body.placement import place_garment
    from unsew.meshing import mesh_pattern
    from unsew.pattern.design import Design, draft

    body = default_body()
    pattern = draft(Design(**design))
    mesh = mesh_pattern(pattern, edge_length=0.04)
    x = place_garment(pattern, mesh, body)  # (Nu, 3) [m], seam copies apart
    xs = np.zeros((mesh.n_x, 3))
    np.add.at(xs, mesh.x_of_u, x)
    xs /= np.bincount(mesh.x_of_u, minlength=mesh.n_x)[:, None]
    r = read_design(xs, mesh.faces, body.skeleton, body=body)
    assert r.garment == design["garment"], r.evidence
    assert {k: r.choices()[k] for k in expected} == expected, r.evidence


def test_darts_are_decided_by_how_close_a_straight_skirt_follows_the_hips(skeleton):
    """A straight tube skirt on the hips (as wide as the body there) takes waist darts; one hanging
    15 % wider does not; a flared one never (its cone takes the waist in); without a body to
    measure against nothing is decided."""
    from unsew.grading.design_reading import _hip_girth

    body = default_body()
    hip = 0.5 * (skeleton.position("left_hip")[1] + skeleton.position("right_hip")[1])
    knee = 0.5 * (skeleton.position("left_knee")[1] + skeleton.position("right_knee")[1])
    girth = _hip_girth(skeleton, body)
    fitted = read_design(*_tube(girth / (2 * np.pi), hip + 0.12, knee), skeleton, body=body)
    loose = read_design(*_tube(1.15 * girth / (2 * np.pi), hip + 0.12, knee), skeleton, body=body)
    assert (fitted.skirt, loose.skirt) == ("pencil", "pencil"), (fitted.evidence, loose.evidence)
    assert fitted.darts is True and loose.darts is False, (fitted.evidence["darts"], loose.evidence["darts"])
    assert fitted.choices()["darts"] is True
    v, f = _tube(girth / (2 * np.pi), hip + 0.12, knee)
    y = v[:, 1]
    scale = 1.0 + np.clip((hip - y) / (hip - knee), 0.0, 1.0) * 1.2
    assert read_design(v * np.c_[scale, np.ones_like(y), scale], f, skeleton, body=body).darts is False
    assert read_design(*_tube(girth / (2 * np.pi), hip + 0.12, knee), skeleton).darts is None
