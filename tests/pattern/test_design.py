"""The design space: every sampled design drafts, validates, meshes, parameterizes (symmetry, K ->
U) and round-trips through GarmentCode JSON; each choice shows in the geometry; the library's bases
are points of the space."""

import numpy as np
import pytest

from helpers import assert_close
from unsew.errors import InputError
from unsew.io.garmentcode import load_pattern, pattern_to_dict, save_pattern
from unsew.meshing import mesh_pattern
from unsew.pattern.base import BASES, make_base_pattern
from unsew.pattern.base._frame import body_frame
from unsew.pattern.curves import edge_length, panel_outline, sample_edge
from unsew.pattern.design import (
    CHOICES,
    GARMENTS,
    Design,
    design_name,
    design_of_base,
    design_space,
    draft,
    length_to,
)
from unsew.pattern.measurements import Measurements
from unsew.pattern.model import pattern_diff
from unsew.pattern.params import PatternParams
from unsew.pattern.symmetry import detect_symmetry
from unsew.pattern.validate import signed_area, validate_pattern

#: A body unlike the default one (curvier, taller), so that sizes follow measurements.
OTHER = Measurements(
    height=1.78,
    bust=0.98,
    waist=0.74,
    hip=1.04,
    upper_arm=0.31,
    neck_height=1.52,
    waist_height=1.11,
    crotch_height=0.83,
    leg_length=0.87,
    arm_length=0.53,
)


def _sample():
    """Every garment's space, thinned to about 60 designs in all, spread over its choices."""
    out = []
    for g in GARMENTS:
        space = design_space(g)
        step = max(1, len(space) // 12)
        out += space[::step]
    return out


SAMPLE = _sample() + [
    Design(garment=g, sleeves="none", strapless=True) for g in ("tshirt", "dress", "jumpsuit")
]


@pytest.mark.parametrize("name", BASES)
def test_bases_are_points_of_the_space(name):
    for m in (None, OTHER):
        p = draft(design_of_base(name), m)
        assert p.unsew.pop("design") == design_of_base(name).as_dict()
        base = make_base_pattern(name, m)
        # a lower garment's open top is labelled as the edge it hangs from; the library keeps its name
        held = [
            (n, i)
            for n, pa in p.panels.items()
            for i, e in enumerate(pa.edges)
            if e.label == "lower_interface"
        ]
        assert bool(held) == (design_of_base(name).garment in ("skirt", "pants", "shorts"))
        for n, i in held:
            was = base.panels[n].edges[i].label
            assert was.startswith("waist") or was == "top", (n, i, was)
            p.panels[n].edges[i].label = was
        assert pattern_diff(p, base, atol=1e-9) == []
    assert design_name(design_of_base(name)) == name
    assert design_of_base(name) in design_space(design_of_base(name).garment)


@pytest.mark.parametrize(
    "design, lower",
    [
        (Design(garment="dress", waist_seam=True), {"skirt_front", "skirt_back"}),
        (
            Design(garment="dress", waist_seam=True, waistband=True, darts=True),
            {"waistband_front", "waistband_back"},
        ),
        (Design(garment="jumpsuit"), {"left_front", "right_front", "left_back", "right_back"}),
        (Design(garment="dress"), set()),
    ],
    ids=["seamed-dress", "banded-dress", "jumpsuit", "one-piece-dress"],
)
def test_a_joined_garments_waist_seam_is_labelled_where_its_lower_part_hangs(design, lower):
    """A dress's or jumpsuit's lower part (skirt, band, legs) is labelled as GarmentCode labels it
    where it is sewn to the bodice, and only there; the GarmentCode JSON keeps the label."""
    p = draft(design)
    held = {
        (n, i) for n, pa in p.panels.items() for i, e in enumerate(pa.edges) if e.label == "lower_interface"
    }
    assert {n for n, _ in held} == lower
    to_bodice = {
        (me.panel, me.edge)
        for st in p.stitches
        for me, other in ((st.a, st.b), (st.b, st.a))
        if other.panel in ("front", "back") and me.panel in lower
    }
    assert held == to_bodice
    spec = pattern_to_dict(p)
    assert sum(
        e.get("label") == "lower_interface" for pd in spec["pattern"]["panels"].values() for e in pd["edges"]
    ) == len(held)


@pytest.mark.parametrize("design", SAMPLE, ids=design_name)
def test_sampled_designs_draft_validate_mesh_and_round_trip(design, tmp_path):
    p = draft(design)
    assert validate_pattern(p) == []  # closed, no self-intersection, stitches in range, lengths match
    for pan in p.panels.values():
        assert signed_area(pan) > 0, pan.name
    sides = [s.a for s in p.stitches] + [s.b for s in p.stitches]
    assert len(sides) == len(set(sides))
    labels = [s.label for s in p.stitches]
    assert all(labels) and len(set(labels)) == len(labels)
    for s in p.stitches:
        la, lb = edge_length(p.panels[s.a.panel], s.a.edge), edge_length(p.panels[s.b.panel], s.b.edge)
        assert abs(la - lb) < 1e-3, f"{s.label}: {la:.4f} vs {lb:.4f} m"
    mesh = mesh_pattern(p, edge_length=0.05)
    q = mesh.quality()
    assert q["bad_triangles"] == 0 and q["sewn_vertices"] < q["uv_vertices"]
    # ready for the fit: every panel mirror-symmetric or paired, the parameters rebuild the mesh
    sym = detect_symmetry(p)
    kept = {m.panel for m in sym.mirrors} | {pr.source for pr in sym.pairs} | {pr.target for pr in sym.pairs}
    assert kept == set(p.panels)
    params = PatternParams.build(p, mesh, symmetry=sym)
    assert_close(params.uv(params.K0).detach().numpy(), mesh.uv, atol=1e-9)
    save_pattern(p, tmp_path / "p.json")
    back = load_pattern(tmp_path / "p.json")
    assert pattern_diff(back, p, atol=1e-9) == []
    assert Design.from_dict(back.unsew["design"]) == design


def test_design_space_enumerates_distinct_candidates():
    for g in GARMENTS:
        space = design_space(g)
        assert len(space) == len(set(space)) == len({design_name(d) for d in space}), g
        assert all(d.garment == g for d in space)
    tees = design_space("tshirt")
    # sleeves none: 16 necklines; short and long: 2 pieces x 2 cuffs x 16 necklines; a hood and
    # a turtle collar on round necklines with each sleeve choice (1 + 2 x 2 x 2); strapless
    assert len(tees) == 16 + 2 * 2 * 2 * 16 + 2 * (1 + 2 * 2 * 2) + 1
    assert sum(d.strapless for d in tees) == 1
    assert {d.neckline_front for d in tees} == set(CHOICES["neckline_front"])
    assert {d.collar for d in tees} == set(CHOICES["collar"])
    assert all(d.collar == "none" for g in ("skirt", "pants", "shorts") for d in design_space(g))
    skirts = design_space("skirt")
    assert {d.panels for d in skirts} == set(CHOICES["panels"])
    assert {d.skirt for d in skirts} == set(CHOICES["skirt"])


def _neck(p, panel):
    """Sampled neckline points (k, 2) [m] of ``panel`` and the neckline's vertices (j, 2)."""
    pan = p.panels[panel]
    idx = [i for i, e in enumerate(pan.edges) if "neckline" in e.label]
    pts = np.concatenate([sample_edge(pan, i, 64) for i in idx])
    verts = pan.vertices[sorted({pan.edges[i].start for i in idx} | {pan.edges[i].end for i in idx})]
    return pts, verts


@pytest.mark.parametrize("garment", ["tshirt", "dress", "jumpsuit"])
def test_necklines_have_their_shapes(garment):
    kw = dict(garment=garment, waist_seam=True) if garment == "dress" else dict(garment=garment)
    shapes = {s: draft(Design(neckline_front=s, **kw)) for s in CHOICES["neckline_front"]}
    for panel in ("front",):
        pts = {s: _neck(p, panel) for s, p in shapes.items()}
        top = {s: v[:, 1].max() for s, (_, v) in pts.items()}  # the neck points
        depth = {s: top[s] - pts[s][0][:, 1].min() for s in pts}
        width = {s: np.ptp(pts[s][1][:, 0]) for s in pts}
        # V: its lowest point a vertex on the centre line, deeper than the round neck's bottom
        lo_v = pts["v"][0][np.argmin(pts["v"][0][:, 1])]
        assert any(np.allclose(lo_v, v, atol=1e-12) for v in pts["v"][1]) and abs(lo_v[0]) < 1e-12
        assert depth["v"] > depth["round"] + 0.03
        # boat: wider and shallower than round
        assert width["boat"] > width["round"] + 0.08 and depth["boat"] < depth["round"] - 0.03
        # square: its two lowest points are corners at one height either side of the centre line,
        # where the neckline turns a right angle
        v = pts["square"][1]
        low = v[np.argsort(v[:, 1])[:2]]
        assert low[0, 1] == pytest.approx(low[1, 1], abs=1e-12) and low[0, 0] == pytest.approx(-low[1, 0])
        assert pts["square"][0][:, 1].min() == pytest.approx(low[0, 1], abs=1e-12)
        up = v[np.argsort(v[:, 1])[2:]]
        assert_close(np.sort(up[:, 0]), np.sort(low[:, 0]), atol=1e-12)  # straight down from the neck points
    # the shoulder seams meet with any pair of necklines (boat widens both sides)
    p = draft(Design(neckline_front="boat", neckline_back="square", **kw))
    assert validate_pattern(p) == []


def _skirt_panels(p):
    return [q for n, q in p.panels.items() if not n.startswith("waistband") and "hem" in q.edges[0].label]


@pytest.mark.parametrize("panels", [2, 4, 6, 8])
@pytest.mark.parametrize("fraction", [0.25, 0.6, 1.0])
def test_circle_skirt_hems_sum_to_the_circle_fraction(panels, fraction):
    for band in (False, True):
        p = draft(
            Design(garment="skirt", skirt="circle", circle_fraction=fraction, panels=panels, waistband=band)
        )
        gores = _skirt_panels(p)
        assert len(gores) == panels
        r_hem = {g.edges[0].curvature.params[0] for g in gores}
        r_top = {g.edges[2].curvature.params[0] for g in gores}
        assert len(r_hem) == len(r_top) == 1
        (r_hem,), (r_top,) = r_hem, r_top
        hem = sum(edge_length(g, 0) for g in gores)
        assert hem == pytest.approx(2 * np.pi * r_hem * fraction, rel=1e-6)  # arcs measured sampled
        top = sum(edge_length(g, 2) for g in gores)
        assert top == pytest.approx(2 * np.pi * r_top * fraction, rel=1e-6)
        # a cone: the side seams run from the top arc to the hem arc
        assert edge_length(gores[0], 1) == pytest.approx(r_hem - r_top, rel=1e-9)


def test_skirt_panels_share_the_waist_and_the_aline_flare_opens_the_cone():
    def hem_angle(d):
        gores = _skirt_panels(draft(d))
        return sum(edge_length(g, 0) for g in gores) / gores[0].edges[0].curvature.params[0]

    waists = []
    for n in (2, 4, 6, 8):
        d = Design(garment="skirt", panels=n)
        gores = _skirt_panels(draft(d))
        waists.append(sum(edge_length(g, 2) for g in gores))
        assert hem_angle(d.replace(aline_flare=0.7)) - hem_angle(d) == pytest.approx(0.35, rel=1e-6)
    assert np.ptp(waists) < 1e-6
    # a pencil is as wide at the hem as at the hips, whatever its number of panels
    for n in (2, 6):
        gores = _skirt_panels(draft(Design(garment="skirt", skirt="pencil", panels=n)))
        assert len(gores) == n
        hem = sum(edge_length(g, 0) for g in gores)
        hips = sum(np.ptp(g.vertices[[2, 5], 0]) for g in gores)
        assert hem == pytest.approx(hips, abs=1e-9) and hem > Measurements().hip


def test_skirt_length_reaches_its_landmark():
    m = Measurements()
    f = body_frame(m)
    for where in ("mini", "knee", "midi"):
        p = draft(Design(garment="skirt", panels=4, length=length_to(m, where)), m)
        low = min(g.to_world(panel_outline(g))[:, 1].min() for g in p.panels.values())
        assert low == pytest.approx(f.waist_y - length_to(m, where), abs=1e-9)
    assert length_to(m, "mini") < length_to(m, "knee") < length_to(m, "midi") < length_to(m, "ankle")
    # a length named by a place on the body falls there on any body
    for body in (m, OTHER):
        for d in (
            Design(garment="skirt", skirt="pencil", length="midi"),
            Design(garment="pants", length="knee"),
        ):
            p = draft(d, body)
            low = min(g.to_world(panel_outline(g))[:, 1].min() for g in p.panels.values())
            assert low == pytest.approx(body_frame(body).waist_y - length_to(body, d.length), abs=1e-9)
            metres = draft(d.replace(length=length_to(body, d.length)), body)
            metres.name, metres.unsew = p.name, p.unsew
            assert pattern_diff(p, metres) == []  # the same cut as that length in metres


def test_a_top_may_end_at_or_above_the_waist():
    """A fitted bodice ends at the natural waist and a crop top above it: a top's hem lies where
    its length puts it, above the waist too; no other garment's may, and a top's hem must leave
    a side seam under the armpit (one line, not a broken pattern)."""
    for body in (Measurements(), OTHER):
        f = body_frame(body)
        for length in (0.0, -0.03):
            p = draft(Design(garment="tshirt", length=length, darts=True, hem_girth=0.8 * body.bust), body)
            assert validate_pattern(p) == []
            low = min(
                g.to_world(panel_outline(g))[:, 1].min() for g in p.panels.values() if "sleeve" not in g.name
            )
            assert low == pytest.approx(f.waist_y - length, abs=1e-9)
    with pytest.raises(InputError, match="length"):
        Design(garment="skirt", length=-0.03)
    with pytest.raises(InputError, match="length"):
        Design(garment="tshirt", length=-0.2)
    f = body_frame(Measurements())
    too_high = round(f.waist_y - f.armpit_y + 0.02, 2)  # 3 cm under the armpit
    with pytest.raises(InputError, match="under the armpit"):
        draft(Design(garment="tshirt", length=too_high), Measurements())


def _sleeve_panels(p):
    return [q for n, q in p.panels.items() if "sleeve" in n]


@pytest.mark.parametrize("garment", ["tshirt", "dress", "jumpsuit"])
def test_two_piece_sleeves_are_the_one_piece_cut_in_half(garment):
    for sleeves in ("short", "long"):
        one = draft(Design(garment=garment, sleeves=sleeves))
        two = draft(Design(garment=garment, sleeves=sleeves, sleeve_pieces=2))
        s1, s2 = _sleeve_panels(one), _sleeve_panels(two)
        assert len(s2) == 2 * len(s1) == 4
        assert sum(map(signed_area, s2)) == pytest.approx(sum(map(signed_area, s1)), rel=1e-6)
        # each arm's halves are sewn along the one-piece sleeve's centre line (cap top to hem),
        # where they meet in 3D, and face the front and the back of the arm
        for side in ("left", "right"):
            whole = one.panels[f"{side}_sleeve"]
            top, bottom = whole.vertices[:, 1].max(), whole.vertices[:, 1].min()
            line = whole.to_world([(0.0, top), (0.0, bottom)])
            (seam,) = [s for s in two.stitches if s.label == f"{side}_sleeve_top"]
            for sd in (seam.a, seam.b):
                q = two.panels[sd.panel]
                e = q.edges[sd.edge]
                ends = q.to_world(q.vertices[[e.start, e.end]])
                assert_close(np.sort(ends, axis=0), np.sort(line, axis=0), atol=1e-9)
            normals = {q.name: q.rotation_matrix()[:, 2] for q in s2 if q.name.startswith(side)}
            nf, nb = normals[f"{side}_sleeve_front"], normals[f"{side}_sleeve_back"]
            assert nf[2] > 0.9 and nb[2] < -0.9
            # turned alike either way from the one-piece sleeve's facing
            n = whole.rotation_matrix()[:, 2]
            assert_close(np.cross(nf + nb, n), np.zeros(3), atol=1e-9)
            assert nf @ n == pytest.approx(nb @ n, abs=1e-9)


def reach(p, side):
    """Furthest point [m] of one arm's sleeve pieces and cuff from the top of its sleeve cap."""
    pieces = [q for n, q in p.panels.items() if n.startswith(side) and ("sleeve" in n or "cuff" in n)]
    cap = pieces[0].to_world([(0.0, pieces[0].vertices[:, 1].max())])[0]
    return max(np.linalg.norm(q.to_world(panel_outline(q)) - cap, axis=1).max() for q in pieces)


def test_cuffs_close_the_sleeves_at_the_same_length():
    for pieces in (1, 2):
        plain = draft(Design(sleeves="long", sleeve_pieces=pieces))
        cuffed = draft(Design(sleeves="long", sleeve_pieces=pieces, cuffs=True))
        for side in ("left", "right"):
            cuff = cuffed.panels[f"{side}_cuff"]
            assert reach(cuffed, side) == pytest.approx(reach(plain, side), abs=1e-9)
            sewn = [
                s for s in cuffed.stitches if cuff.name in (s.a.panel, s.b.panel) and s.a.panel != s.b.panel
            ]
            top = sum(edge_length(cuff, s.b.edge) for s in sewn)
            assert len(sewn) == pieces and top == pytest.approx(edge_length(cuff, 0), rel=1e-9)
    assert "left_cuff" not in draft(Design(sleeves="none", cuffs=True)).panels


@pytest.mark.parametrize(
    "design",
    [
        Design(garment="pants", leg_cuffs=True),
        Design(garment="shorts", leg_cuffs=True, waistband=True, darts=True),
        Design(garment="jumpsuit", leg="knee", leg_cuffs=True, sleeves="long", cuffs=True),
    ],
    ids=design_name,
)
def test_leg_cuffs_end_the_legs_where_the_plain_legs_end(design):
    """A cuffed leg's opening lies where the plain leg's hem lies, as wide; the leg panels end a
    cuff's height higher; each cuff's top is sewn to its leg panel's whole hem and a leg's front
    and back cuffs to each other (a tube)."""
    from unsew.pattern.design._top import CUFF_HEIGHT

    plain, cuffed = draft(design.replace(leg_cuffs=False)), draft(design)

    def low(p, names):  # the lowest point of the named panels as placed [m]
        return min(p.panels[n].to_world(panel_outline(p.panels[n]))[:, 1].min() for n in names)

    legs = ("left_front", "left_back", "right_front", "right_back")
    cuffs = [f"{n}_cuff" for n in legs]
    assert set(cuffs) <= set(cuffed.panels) and not set(cuffs) & set(plain.panels)
    assert low(cuffed, cuffs) == pytest.approx(low(plain, legs), abs=1e-9)
    assert low(cuffed, legs) == pytest.approx(low(plain, legs) + CUFF_HEIGHT, abs=1e-9)
    for leg in legs:
        hem = next(i for i, e in enumerate(plain.panels[leg].edges) if e.label == "hem")
        cuff = cuffed.panels[f"{leg}_cuff"]
        opening = [i for i, e in enumerate(cuff.edges) if e.label == "hem"]
        assert len(opening) == 1
        assert edge_length(cuff, opening[0]) == pytest.approx(edge_length(plain.panels[leg], hem), rel=1e-9)
        sewn = {(s.a.panel, s.b.panel) for s in cuffed.stitches if f"{leg}_cuff" in (s.a.panel, s.b.panel)}
        assert (leg, f"{leg}_cuff") in sewn
    for side in ("left", "right"):
        pair = {f"{side}_front_cuff", f"{side}_back_cuff"}
        between = [s for s in cuffed.stitches if {s.a.panel, s.b.panel} == pair]
        assert len(between) == 2


def test_a_cuff_is_shortened_where_the_leg_ends_just_below_the_crotch():
    """Shorts whose hem lies 6 cm under the crotch point keep MIN_INSEAM of inseam above a
    shortened cuff; at 4 cm there is no room for a cuff: refused in one line."""
    from unsew.pattern.base import pants as _pants
    from unsew.pattern.design._draft import MIN_INSEAM

    f = body_frame(Measurements())
    depth = f.waist_y - (f.crotch_y - _pants.CROTCH_DROP - 0.06)
    cuff = draft(Design(garment="shorts", length=depth, leg_cuffs=True)).panels["left_front_cuff"]
    assert np.ptp(cuff.vertices[:, 1]) == pytest.approx(0.06 - MIN_INSEAM, abs=1e-9)
    with pytest.raises(InputError, match="no room for a cuff"):
        draft(Design(garment="shorts", length=depth - 0.02, leg_cuffs=True))


def _seam_length(p, label_start, panels):
    """Total length of the sides on ``panels`` of the stitches whose label starts with ``label_start``."""
    total = 0.0
    for s in p.stitches:
        if s.label.startswith(label_start):
            for side in (s.a, s.b):
                if side.panel in panels:
                    total += edge_length(p.panels[side.panel], side.edge)
    return total


@pytest.mark.parametrize("skirt, n", [("aline", 2), ("aline", 6), ("pencil", 4), ("circle", 8)])
def test_dress_waist_seam_sides_have_equal_length(skirt, n):
    for m in (None, OTHER):
        p = draft(Design(garment="dress", waist_seam=True, skirt=skirt, panels=n), m)
        gores = [k for k in p.panels if k.startswith("skirt_")]
        assert len(gores) == n
        bodice = _seam_length(p, "front_waist", {"front"}) + _seam_length(p, "back_waist", {"back"})
        skirt_top = _seam_length(p, "front_waist", set(gores)) + _seam_length(p, "back_waist", set(gores))
        assert bodice == pytest.approx(skirt_top, abs=1e-6)  # arcs measured sampled
        assert bodice == pytest.approx((m or Measurements()).waist + 0.10, abs=1e-9)  # the dress's waist ease
        # the whole waist of both is sewn: the bodice's lower edges, the gores' tops
        assert bodice == pytest.approx(
            sum(
                edge_length(p.panels[k], e)
                for k in ("front", "back")
                for e, ed in enumerate(p.panels[k].edges)
                if "waist" in ed.label
            )
        )


def test_jumpsuit_bodice_and_trouser_waists_match():
    for leg in ("full", "knee", "shorts"):
        for m in (None, OTHER):
            p = draft(Design(garment="jumpsuit", leg=leg, sleeves="none"), m)
            legs = {"left_front", "right_front", "left_back", "right_back"}
            bodice = sum(
                _seam_length(p, f"{s}_{fb}_waist", {"front", "back"})
                for s in ("left", "right")
                for fb in ("front", "back")
            )
            trousers = sum(
                _seam_length(p, f"{s}_{fb}_waist", legs)
                for s in ("left", "right")
                for fb in ("front", "back")
            )
            assert bodice == pytest.approx(trousers, abs=1e-9) and bodice > (m or Measurements()).waist
            # the waist seam joins the bodice's centre front to the trousers' centre front seam
            fw = p.panels["front"].to_world(p.panels["front"].vertices[[1]])[0]
            lf = p.panels["left_front"].to_world(p.panels["left_front"].vertices[[4]])[0]
            assert_close(fw[:2], lf[:2], atol=1e-9)


def test_trouser_lengths_and_flare():
    m = Measurements()
    hem = lambda p: min(q.to_world(panel_outline(q))[:, 1].min() for q in p.panels.values())  # noqa: E731
    full, knee, short = (draft(Design(garment="pants", leg=g)) for g in ("full", "knee", "shorts"))
    assert hem(full) < hem(knee) < hem(short) < body_frame(m).crotch_y
    wide = draft(Design(garment="pants", leg="knee", hem_flare=0.04))
    # the flare widens a leg panel's hem half width: its hem by twice that
    assert edge_length(wide.panels["left_front"], 0) == pytest.approx(
        edge_length(knee.panels["left_front"], 0) + 0.08
    )


def test_ease_loosens_the_girths():
    tight, loose = draft(Design()), draft(Design(ease=0.08))
    width = lambda p: sum(np.ptp(panel_outline(p.panels[k])[:, 0]) for k in ("front", "back"))  # noqa: E731
    assert width(loose) == pytest.approx(width(tight) + 0.08, abs=1e-9)  # front and back span the girth


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(garment="hat"), "garment must be one of"),
        (dict(panels=3), "even number of panels"),
        (dict(circle_fraction=1.5), "circle_fraction"),
        (dict(garment="shorts", leg="full"), "shorts have leg"),
        (dict(neckline_front="sweetheart"), "neckline_front must be one of"),
        (dict(sleeve_pieces=True), "sleeve_pieces must be one of"),
        (dict(length=-0.2), "length must be a number"),
        (dict(length="shin"), "length must be metres or one of"),
    ],
)
def test_bad_designs_are_refused_in_one_line(kw, match):
    with pytest.raises(InputError, match=match) as e:
        Design(**kw)
    assert "\n" not in str(e.value)


def test_designs_that_cannot_be_cut_are_refused():
    with pytest.raises(InputError, match="darted skirt has 2 panels"):
        draft(Design(garment="skirt", skirt="darted", panels=4, waistband=True))
    with pytest.raises(InputError, match="above the crotch"):
        draft(Design(garment="pants", length=0.15))
    with pytest.raises(InputError, match="unknown design field"):
        Design.from_dict({"garment": "skirt", "colour": "red"})


@pytest.mark.slow
def test_three_designs_dress_the_default_body():
    """A tee with long two-piece sleeves and cuffs, a V front and a boat back; a waist-seamed
    dress of four gores with a square neck; a knee-length jumpsuit with a waistband and cuffed
    legs: each goes on the default body (the drape verdict, seams within 5 mm after sewing,
    nothing inside, no edge stretched twice its length), its top between the chest and the head."""
    from unsew.body.body import default_body
    from unsew.body.sdf import BodySDF
    from unsew.dress import DRESS_SETTINGS, dress, dress_stats
    from unsew.sim.checks import check_dressed

    body = default_body()
    sdf = BodySDF.build(body)
    sk = body.skeleton
    designs = [
        Design(neckline_front="v", neckline_back="boat", sleeves="long", sleeve_pieces=2, cuffs=True),
        Design(garment="dress", waist_seam=True, panels=4, neckline_front="square", sleeves="none"),
        Design(garment="jumpsuit", leg="knee", neckline_front="v", leg_cuffs=True, waistband=True),
    ]
    for d in designs:
        r = dress(draft(d), body, sdf=sdf, settings=DRESS_SETTINGS.replace(edge_length=0.04))
        v = check_dressed(r, body=body)
        s = dress_stats(r)
        name = design_name(d)
        assert v.ok, f"{name}: {v.reason}"
        assert s["inside_pct"] < 0.5 and s["seam_gap"] < 5e-3, (name, s["inside_pct"], s["seam_gap"])
        assert s["stretch"] < 2.0, (name, s["stretch"])
        lo, hi = s["bbox"]
        assert lo[1] < sk.position("chest")[1] < hi[1] < sk.position("head")[1], name


@pytest.mark.parametrize(
    "kw",
    [
        dict(garment="tshirt"),
        dict(garment="dress"),
        dict(garment="dress", waist_seam=True, panels=4),
        dict(garment="dress", waist_seam=True, waistband=True, darts=True),
        dict(garment="jumpsuit"),
    ],
    ids=lambda kw: "-".join(str(v) for v in kw.values()),
)
def test_a_strapless_top_has_no_shoulders_and_ends_straight_under_the_arms(kw):
    m = OTHER
    for drop in (0.03, -0.06):
        d = Design(sleeves="none", strapless=True, top_drop=drop, **kw)
        p = draft(d, m)
        assert validate_pattern(p) == [] and design_name(d).endswith("strapless") == (drop == 0.03)
        assert not any("shoulder" in s.label or "armhole" in s.label for s in p.stitches)
        assert not any(e.label == "neckline" or "armhole" in e.label for e in p.panels["front"].edges)
        want = body_frame(m).armpit_y - drop  # world height of the top edge [m]
        for side in ("front", "back"):
            pan = p.panels[side]
            (top,) = [i for i, e in enumerate(pan.edges) if e.label == "strapless_top"]
            ends = pan.to_world(pan.vertices[[pan.edges[top].start, pan.edges[top].end]])
            assert_close(ends[:, 1], [want, want], atol=1e-9)
            assert abs(ends[0, 0] - ends[1, 0]) > m.bust / 2 - 0.01  # across the whole front or back
            sewn = {s.a.edge for s in p.stitches if s.a.panel == side} | {
                s.b.edge for s in p.stitches if s.b.panel == side
            }
            assert top not in sewn  # an opening, held where it is placed when dressed
    tee = draft(Design(sleeves="none", **kw), m)
    assert any("shoulder" in s.label for s in tee.stitches)  # the same top with straps has them


@pytest.mark.parametrize(
    "kw",
    [
        dict(garment="skirt"),
        dict(garment="tshirt", sleeves="short"),
        dict(garment="dress", sleeves="none", collar="hood"),
        dict(garment="tshirt", sleeves="none", neckline_front="v"),
        dict(garment="tshirt", sleeves="none", top_drop=0.5),
    ],
)
def test_a_strapless_design_that_cannot_be_cut_is_refused(kw):
    with pytest.raises(InputError):
        Design(strapless=True, **kw)
