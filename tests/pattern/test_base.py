"""Base patterns: valid, counter-clockwise, symmetric, sewn the right way, sized and placed."""

import numpy as np
import pytest

from helpers import assert_close
from unsew.pattern.measurements import Measurements
from unsew.errors import InputError
from unsew.pattern.base import BASES, GARMENTS, bases_for, garment_of, make_base_pattern
from unsew.pattern.base.skirt import HIP_EASE
from unsew.pattern.base._frame import body_frame
from unsew.pattern.curves import edge_length, panel_outline, sample_edge
from unsew.pattern.validate import signed_area, validate_pattern


@pytest.mark.parametrize("garment", BASES)
def test_valid_ccw_no_length_warnings(garment):
    p = make_base_pattern(garment)
    assert validate_pattern(p) == []  # also: closed, no self-intersection, stitches in range
    for pan in p.panels.values():
        assert signed_area(pan) > 0, pan.name
        # modest number of control points (a darted panel: two darts of three vertices each)
        assert len(pan.vertices) <= (12 if garment == "skirt_darts" else 10), pan.name
    sides = [s.a for s in p.stitches] + [s.b for s in p.stitches]
    assert len(sides) == len(set(sides))


def test_unknown_garment():
    with pytest.raises(InputError, match="unknown garment 'hat'"):
        make_base_pattern("hat")


def _mirror_matches(panel, i, j):
    """Edge j is the mirror image (x -> -x) of edge i, traversed the other way."""
    a = sample_edge(panel, i, 20) * np.array([-1.0, 1.0])
    b = sample_edge(panel, j, 20)[::-1]
    assert_close(a, b, atol=1e-9, what=f"{panel.name} edges {i}/{j}: ")


def test_tshirt_front_back_mirror_symmetric_and_sleeves_mirror_images():
    p = make_base_pattern("tshirt")
    assert set(p.panels) >= {"front", "back", "left_sleeve", "right_sleeve"}
    for name in ("front", "back"):
        pan = p.panels[name]
        n = len(pan.edges)
        for i in range(1, n // 2):
            _mirror_matches(pan, i, n - i)
        _mirror_matches(pan, 0, 0)
        _mirror_matches(pan, n // 2, n // 2)
    ls, rs = p.panels["left_sleeve"], p.panels["right_sleeve"]
    n = len(ls.edges)
    for i in range(n):
        a = sample_edge(ls, i, 20) * np.array([-1.0, 1.0])
        b = sample_edge(rs, (n - i) % n, 20)[::-1]
        assert_close(a, b, atol=1e-9)


def _join_classes(p):
    """Union-find over panel corners joined by stitches (a.start~b.end, a.end~b.start)."""
    parent = {}

    def find(x):
        parent.setdefault(x, x)
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for s in p.stitches:
        ea = p.panels[s.a.panel].edges[s.a.edge]
        eb = p.panels[s.b.panel].edges[s.b.edge]
        parent[find((s.a.panel, ea.start))] = find((s.b.panel, eb.end))
        parent[find((s.a.panel, ea.end))] = find((s.b.panel, eb.start))
    return find


def test_tshirt_seams_join_the_right_corners():
    p = make_base_pattern("tshirt")
    find = _join_classes(p)
    f, b = p.panels["front"], p.panels["back"]
    # Front/back vertex layout: 0 hem -x, 1 hem +x, 2 underarm +x, 3 shoulder tip +x, 4 neck +x, 5..7
    # mirrored. Front +x is the body's left; back +x is the body's right.
    assert find(("front", 3)) == find(("back", 6)) == find(("left_sleeve", 3))  # left shoulder tip = cap top
    assert find(("front", 6)) == find(("back", 3)) == find(("right_sleeve", 3))
    assert find(("front", 4)) == find(("back", 5))  # left neck point
    assert find(("front", 1)) == find(("back", 0))  # left hem corner
    # Left underarm: front, back and both underarm corners of the left sleeve meet in one point.
    assert find(("front", 2)) == find(("back", 7)) == find(("left_sleeve", 2)) == find(("left_sleeve", 4))
    assert find(("left_sleeve", 1)) == find(("left_sleeve", 0))  # sleeve hem corners
    assert find(("front", 2)) != find(("front", 7))
    # Torso seams run against each other in 3D too: a.start is nearer b.end than b.start.
    for s in p.stitches:
        if "sleeve" in s.a.panel + s.b.panel:
            continue
        pa, pb = p.panels[s.a.panel], p.panels[s.b.panel]
        ea, eb = pa.edges[s.a.edge], pb.edges[s.b.edge]
        xa = pa.to_world(pa.vertices[[ea.start]])[0]
        d_end = np.linalg.norm(xa - pb.to_world(pb.vertices[[eb.end]])[0])
        d_start = np.linalg.norm(xa - pb.to_world(pb.vertices[[eb.start]])[0])
        assert d_end < d_start, s.label
    del f, b


def test_pants_seams_join_the_right_corners():
    p = make_base_pattern("pants")
    find = _join_classes(p)
    # Leg layout (left front, right back): 0 hem in, 1 hem out, 2 hip, 3 waist side, 4 centre waist, 5 crotch.
    # Mirrored panels keep vertex indices.
    assert (
        find(("left_front", 5))
        == find(("left_back", 5))
        == find(("right_front", 5))
        == find(("right_back", 5))
    )
    assert find(("left_front", 4)) == find(("right_front", 4))  # centre front waist
    assert find(("left_back", 4)) == find(("right_back", 4))
    assert find(("left_front", 3)) == find(("left_back", 3))  # left waist side
    assert find(("left_front", 0)) == find(("left_back", 0))  # left inner hem
    assert find(("left_front", 4)) != find(("left_back", 4))


def test_sizes_follow_measurements_with_ease():
    m = Measurements()
    p = make_base_pattern("tshirt")
    width = lambda pan: np.ptp(panel_outline(pan)[:, 0])  # noqa: E731
    chest = width(p.panels["front"]) + width(p.panels["back"])
    assert 0.08 <= chest - m.bust <= 0.15
    # the front is max(bust + bust ease, hip + hip ease) / 2 wide: 16 cm more bust widens it so
    from unsew.pattern.base.tshirt import BUST_EASE, HIP_EASE

    big = make_base_pattern("tshirt", Measurements(bust=m.bust + 0.16, hip=m.hip))
    want = (max(m.bust + 0.16 + BUST_EASE, m.hip + HIP_EASE) - max(m.bust + BUST_EASE, m.hip + HIP_EASE)) / 2
    assert_close(width(big.panels["front"]) - width(p.panels["front"]), want, atol=1e-9)
    assert want > 0.07
    skirt = make_base_pattern("skirt")
    waist = edge_length(skirt.panels["front"], 2) + edge_length(skirt.panels["back"], 2)
    assert 0.0 < waist - m.waist <= 0.05


def test_placement_in_world_frame():
    m = Measurements()
    fr = body_frame(m)
    p = make_base_pattern("tshirt")
    world = {n: pan.to_world(panel_outline(pan)) for n, pan in p.panels.items()}
    assert (world["front"][:, 2] > 0.1).all() and (world["back"][:, 2] < -0.1).all()
    assert (world["left_sleeve"][:, 0] > 0.1).all() and (world["right_sleeve"][:, 0] < -0.1).all()
    top = world["front"][:, 1].max()
    assert abs(top - fr.neck_y) < 1e-9
    assert_close(world["front"][:, 1].min(), fr.hip_y - 0.02, atol=1e-9)
    # Front faces +Z, back faces -Z: the panel normal R @ (0, 0, 1).
    assert_close(p.panels["front"].rotation_matrix()[:, 2], [0, 0, 1], atol=1e-12)
    assert_close(p.panels["back"].rotation_matrix()[:, 2], [0, 0, -1], atol=1e-12)
    pants = make_base_pattern("pants")
    for n, pan in pants.panels.items():
        w = pan.to_world(panel_outline(pan))
        assert w[:, 1].max() == pytest.approx(fr.waist_y, abs=1e-9), n
        outer = w[np.argmax(np.abs(w[:, 0])), 0]
        assert (outer > 0) == n.startswith("left"), n


def test_library_lists_each_type_default_first():
    assert set(GARMENTS) <= set(BASES)
    for g in GARMENTS:
        names = bases_for(g)
        assert names[0] == g and all(garment_of(n) == g for n in names)
    assert sorted(n for g in GARMENTS for n in bases_for(g)) == sorted(BASES)
    assert len(bases_for("skirt")) >= 3 and len(bases_for("tshirt")) >= 3
    with pytest.raises(InputError, match="unknown garment 'hat'"):
        bases_for("hat")


VARIANTS = [b for b in BASES if b not in GARMENTS]


@pytest.mark.parametrize("name", VARIANTS)
def test_variant_symmetric_seams_labelled_and_matched(name):
    """Every variant: torso/band panels mirror-symmetric or paired, left/right pieces paired by
    a reflection (Algorithm 1 finds it), every stitch labelled (labels unique) and joining
    edges of equal length."""
    from unsew.pattern.symmetry import detect_symmetry

    p = make_base_pattern(name)
    assert p.name == name
    sym = detect_symmetry(p)
    mirrored = {m.panel for m in sym.mirrors}
    paired = {q.target for q in sym.pairs} | {q.source for q in sym.pairs}
    for pname in p.panels:
        assert pname in mirrored or pname in paired, f"{name}: panel {pname} has no symmetry"
    labels = [s.label for s in p.stitches]
    assert all(labels) and len(set(labels)) == len(labels), labels
    for s in p.stitches:
        la = edge_length(p.panels[s.a.panel], s.a.edge)
        lb = edge_length(p.panels[s.b.panel], s.b.edge)
        assert abs(la - lb) < 2e-3, f"{name} {s.label}: {la:.4f} vs {lb:.4f} m"


@pytest.mark.parametrize("name", ["tshirt", "dress", "tshirt_long", "dress_straight"])
def test_sleeve_caps_sew_into_their_armholes_on_a_thick_arm(name):
    """An upper arm too thick for the armhole (0.41 m read on GarmentCode's A-pose bodies before
    measure_body passed over cuts reaching the armpit; the caps came out 20 mm longer than the
    armholes) still makes caps as long as their armholes: the sleeve narrows."""
    from unsew.pattern.seams import stitch_length_gaps

    for upper_arm in (0.273, 0.41, 0.6):
        p = make_base_pattern(name, Measurements(upper_arm=upper_arm))
        assert np.abs(stitch_length_gaps(p)).max() < 1e-3, (name, upper_arm)
    thick = make_base_pattern(name, Measurements(upper_arm=0.6)).panels["left_sleeve"]
    usual = make_base_pattern(name, Measurements(upper_arm=0.273)).panels["left_sleeve"]
    assert np.ptp(thick.vertices[:, 0]) > np.ptp(usual.vertices[:, 0])  # wider, as wide as can sew


def test_variants_differ_where_they_should():
    m = Measurements()
    fr = body_frame(m)
    tee, long, tank = (make_base_pattern(n) for n in ("tshirt", "tshirt_long", "tshirt_sleeveless"))
    assert (
        "left_sleeve" not in tank.panels and "left_sleeve" not in make_base_pattern("dress_sleeveless").panels
    )
    sleeve = lambda p: np.ptp(panel_outline(p.panels["left_sleeve"])[:, 1])  # noqa: E731
    assert sleeve(long) > m.arm_length > 2 * sleeve(tee)
    # long sleeves narrow to the wrist
    hem = lambda p: edge_length(p.panels["left_sleeve"], 0)  # noqa: E731
    assert hem(long) < hem(tee) - 0.04
    # waistbands: two bands, their top at the natural waist, the rest starting below them
    for n in ("skirt_band", "skirt_circle", "skirt_pencil", "skirt_darts", "pants_band", "shorts_band"):
        p = make_base_pattern(n)
        bands = [q for q in p.panels if q.startswith("waistband")]
        assert len(bands) == 2, n
        for b in bands:
            w = p.panels[b].to_world(panel_outline(p.panels[b]))
            assert w[:, 1].max() == pytest.approx(fr.waist_y, abs=1e-9), n
    # the half-circle skirt's hem is far wider than the A-line's, its waist the same
    a, c = make_base_pattern("skirt_band"), make_base_pattern("skirt_circle")
    assert edge_length(c.panels["front"], 0) > 1.4 * edge_length(a.panels["front"], 0)
    assert edge_length(c.panels["front"], 2) == pytest.approx(edge_length(a.panels["front"], 2), abs=1e-6)
    # the pencil skirt: as wide at the hem as at the hips (with their ease), its waist the
    # A-line's, its hem far narrower than the A-line's; its bands as long as its waist
    pen = make_base_pattern("skirt_pencil")
    f = pen.panels["front"]
    assert edge_length(f, 0) == pytest.approx((m.hip + HIP_EASE) / 2, abs=1e-9)
    assert np.ptp(f.vertices[[2, 5], 0]) == pytest.approx(edge_length(f, 0), abs=1e-9)
    assert edge_length(f, 3) == pytest.approx(edge_length(a.panels["front"], 2), abs=1e-6)
    assert edge_length(f, 0) < 0.8 * edge_length(a.panels["front"], 0)
    assert edge_length(pen.panels["waistband_front"], 0) == pytest.approx(edge_length(f, 3), abs=1e-9)
    # the darted skirt: two darts per panel with legs of one length, sewn leg to leg; the band's
    # lower pieces as long as the top pieces they meet; its top without the darts the pencil's
    # waist, its hips the pencil's, its hem wider
    dar = make_base_pattern("skirt_darts")
    f = dar.panels["front"]
    for a, b in ((4, 5), (7, 8)):
        assert edge_length(f, a) == pytest.approx(edge_length(f, b), abs=1e-12)
        assert any(
            {(s.a.panel, s.a.edge), (s.b.panel, s.b.edge)} == {("front", a), ("front", b)}
            for s in dar.stitches
        )
    pieces = [edge_length(dar.panels["waistband_front"], k) for k in range(3)]
    assert pieces == pytest.approx([edge_length(f, e) for e in (9, 6, 3)], abs=1e-12)
    assert sum(pieces) == pytest.approx(edge_length(pen.panels["front"], 3), abs=1e-9)
    assert np.ptp(f.vertices[[2, 11], 0]) == pytest.approx(
        np.ptp(pen.panels["front"].vertices[[2, 5], 0]), abs=1e-9
    )
    assert edge_length(f, 0) > edge_length(pen.panels["front"], 0) + 0.05


def test_straight_dress_is_unwaisted_and_shorter():
    """The straight dress: no waist curve (its side seam runs straight from the hips to the
    underarm, so at the waist it is wider than the waisted dress), its hem at the knee above the
    waisted dress's mid-calf hem and barely wider than its hips; sleeved and sleeveless share
    the cut below the underarm."""
    from unsew.pattern.base.dress import HIP_EASE as DRESS_HIP_EASE, STRAIGHT_FLARE

    m = Measurements()
    fr = body_frame(m)
    waisted, straight = make_base_pattern("dress"), make_base_pattern("dress_straight")
    sleeveless = make_base_pattern("dress_straight_sleeveless")
    assert "left_sleeve" in straight.panels and "left_sleeve" not in sleeveless.panels
    f, w = straight.panels["front"], waisted.panels["front"]
    assert f.edges[2].curvature is None  # hip -> underarm: a straight line
    assert w.edges[2].curvature is not None
    assert_close(sleeveless.panels["front"].vertices[:3], f.vertices[:3], atol=1e-12)

    def half_width_at(panel, y_world):
        """Largest |x| [m] where the panel's outline crosses the height y_world."""
        o = panel.to_world(panel_outline(panel))
        a, b = o, np.roll(o, -1, axis=0)
        cross = (a[:, 1] - y_world) * (b[:, 1] - y_world) < 0
        t = (y_world - a[cross, 1]) / (b[cross, 1] - a[cross, 1])
        return np.abs(a[cross, 0] + t * (b[cross, 0] - a[cross, 0])).max()

    assert half_width_at(f, fr.waist_y) > half_width_at(w, fr.waist_y) + 0.02
    hem_y = lambda p: p.to_world(panel_outline(p))[:, 1].min()  # noqa: E731
    assert hem_y(f) > hem_y(w) + 0.1
    assert edge_length(f, 0) == pytest.approx((m.hip + DRESS_HIP_EASE) / 2 + 2 * STRAIGHT_FLARE, abs=1e-9)


def test_cli_lists_the_library():
    from unsew.commands.pattern import BASES as CLI_BASES

    assert CLI_BASES == BASES


TOPS = [b for b in BASES if garment_of(b) in ("tshirt", "dress")]


@pytest.mark.parametrize("name", TOPS)
@pytest.mark.parametrize("necklines", [("v", "round"), ("v", "v"), ("round", "v")])
def test_v_necklines_are_valid_symmetric_and_sewn(name, necklines):
    """A top or dress with V necklines: valid, its torso panels still mirror-symmetric with the V's
    point on the centre line and lower than the round neckline's bottom, every stitch joining edges
    of equal length, and the V's sides left open (a neckline, not a seam)."""
    from unsew.pattern.symmetry import detect_symmetry

    p, round_p = make_base_pattern(name, necklines=necklines), make_base_pattern(name)
    assert validate_pattern(p) == []
    mirrored = {m.panel for m in detect_symmetry(p).mirrors}
    for panel, shape in zip(("front", "back"), necklines):
        v, r = p.panels[panel].vertices, round_p.panels[panel].vertices
        assert panel in mirrored
        if shape == "v":
            assert len(v) == len(r) + 1
            on_axis = v[np.abs(v[:, 0]) < 1e-9]  # the V's point: the only vertex on the centre line
            assert len(on_axis) == 1 and on_axis[0, 1] < r[:, 1].max() - 0.06
    sewn = {(s.a.panel, s.a.edge) for s in p.stitches} | {(s.b.panel, s.b.edge) for s in p.stitches}
    for panel in ("front", "back"):
        open_edges = [i for i in range(len(p.panels[panel].edges)) if (panel, i) not in sewn]
        labels = sorted(p.panels[panel].edges[i].label for i in open_edges)
        assert labels == sorted(
            ["hem"]
            + (["left_neckline", "right_neckline"] if necklines[panel == "back"] == "v" else ["neckline"])
            + ([] if p.panels.keys() - {"front", "back"} else ["left_armhole", "right_armhole"])
        ), labels
    for s in p.stitches:
        la, lb = edge_length(p.panels[s.a.panel], s.a.edge), edge_length(p.panels[s.b.panel], s.b.edge)
        assert abs(la - lb) < 2e-3, f"{name} {s.label}: {la:.4f} vs {lb:.4f} m"
