"""The fit's start when meta.json names no garment type: designs drafted from the design read off
the target (unsew.fit.designs), dressed and compared as the library's bases are."""

from types import SimpleNamespace

import numpy as np
import pytest

from unsew.body.body import default_body
from unsew.errors import InputError
from unsew.fit.config import FitConfig
from unsew.fit.designs import MAX_CANDIDATES, design_candidates, drafted_candidates
from unsew.fit.progress import Progress
from unsew.grading.design_reading import FLARE_EDGES, DesignReading
from unsew.pattern.design import draft

CLASSES = ("none", "short", "long")

READINGS = {
    "skirt": DesignReading("skirt", skirt="flared", length="knee", numbers={"flare": 1.9, "hem_share": 0.45}),
    "skirt_near_edge": DesignReading(
        "skirt", skirt="pencil", length="knee", numbers={"flare": FLARE_EDGES[0] - 0.02, "hem_share": 0.45}
    ),
    "dress": DesignReading(
        "dress",
        sleeves="short",
        neck_front="v",
        neck_back="square",
        skirt="a-line",
        length="knee",
        numbers={"flare": 1.45, "hem_share": 0.5, "sleeve_share": 0.3},
    ),
    "tshirt": DesignReading(
        "tshirt", sleeves="long", neck_front="round", neck_back="v", numbers={"sleeve_share": 0.9}
    ),
    "pants": DesignReading("pants", length="below knee", numbers={"hem_share": 0.95}),
    "shorts": DesignReading("shorts", length="above knee", numbers={"hem_share": 0.2}),
    "jumpsuit": DesignReading(
        "jumpsuit",
        sleeves="none",
        neck_front="round",
        neck_back="round",
        length="below knee",
        numbers={"hem_share": 0.95, "sleeve_share": 0.0},
    ),
}


def test_darts_decided_by_the_reading_are_drafted_where_the_space_cuts_them():
    """A pencil skirt read as needing darts starts darted; a dress cut to the body starts as a bodice
    with waist darts over a waistband and a skirt; a fitted top keeps a dartless start and tries
    the darted one too; a reading without darts drafts none."""
    from dataclasses import replace

    pencil = replace(READINGS["skirt_near_edge"], darts=True)
    first = design_candidates(pencil)[0][1]
    assert (first.skirt, first.panels, first.darts) == ("pencil", 2, True)
    assert any("dart" in st.label for st in draft(first).stitches)
    dress = design_candidates(replace(READINGS["dress"], darts=True))[0][1]
    assert (dress.waist_seam, dress.waistband, dress.darts) == (True, True, True)
    top = [d for _, d in design_candidates(replace(READINGS["tshirt"], darts=True))]
    assert not top[0].darts and any(d.darts for d in top[1:])
    for kind in ("skirt_near_edge", "dress", "tshirt"):
        assert not any(d.darts for _, d in design_candidates(READINGS[kind]))


@pytest.mark.parametrize("kind", sorted(READINGS))
def test_candidates_keep_what_was_read_and_draft(kind):
    r = READINGS[kind]
    cands = design_candidates(r)
    assert 2 <= len(cands) <= MAX_CANDIDATES
    assert len({d for _, d in cands}) == len(cands) and len({n for n, _ in cands}) == len(cands)
    for name, d in cands:
        assert d.garment == r.garment
        if r.neck_front is not None:
            assert (d.neckline_front, d.neckline_back) == (r.neck_front, r.neck_back), name
        p = draft(d)
        assert p.name == name and p.panels
    if r.sleeves is not None:  # as read first; a sleeve cannot be grown or removed: a neighbour too
        sleeves = [d.sleeves for _, d in cands]
        assert sleeves[0] == r.sleeves and len(set(sleeves)) >= 2
        assert all(abs(CLASSES.index(s) - CLASSES.index(r.sleeves)) <= 1 for s in sleeves)


def test_a_flared_skirt_gets_circle_skirts_of_more_flare_than_an_aline():
    wide = design_candidates(READINGS["skirt"])
    assert all(d.skirt == "circle" for _, d in wide)
    fractions = {d.circle_fraction for _, d in wide}
    flatter = design_candidates(
        DesignReading("skirt", skirt="flared", numbers={"flare": 1.55, "hem_share": 0.45})
    )
    assert max(d.circle_fraction for _, d in flatter if d.skirt == "circle") < min(fractions)
    # what the reading cannot see is tried: a waistband and more gores
    assert {d.waistband for _, d in wide} == {False, True} and len({d.panels for _, d in wide}) > 1


def test_a_flare_near_a_class_edge_tries_the_neighbouring_style():
    styles = {d.skirt for _, d in design_candidates(READINGS["skirt_near_edge"])}
    assert styles == {"pencil", "aline"}
    far = DesignReading("skirt", skirt="pencil", numbers={"flare": 1.0, "hem_share": 0.45})
    assert {d.skirt for _, d in design_candidates(far)} == {"pencil"}


@pytest.mark.parametrize("garment", ["tshirt", "dress", "jumpsuit"])
def test_a_sleeve_class_read_through_the_opening_far_from_an_edge_is_kept(garment):
    """An armhole the arm line passes through near the shoulder drafts no sleeve, a sleeve end
    it passes through past the elbow no short sleeve; the same shares read off an opening's
    centre (a sleeve hanging off the arm) or near a class edge draft the neighbouring class too."""
    from dataclasses import replace

    def sleeves(cls, share, through):
        nums = {**READINGS[garment].numbers, "sleeve_share": share, "sleeve_through": through}
        cands = design_candidates(replace(READINGS[garment], sleeves=cls, numbers=nums))
        return {d.sleeves for _, d in cands}

    assert sleeves("none", 0.05, 1.0) == {"none"}
    assert sleeves("long", 0.85, 1.0) == {"long"}
    assert sleeves("none", 0.05, 0.0) == {"none", "short"}
    assert sleeves("none", 0.15, 1.0) == {"none", "short"}  # within the margin of the armhole's edge
    assert sleeves("short", 0.35, 1.0) == {"short"} and sleeves("short", 0.45, 1.0) == {"short", "long"}


def test_the_read_hem_depth_sets_the_length():
    short, long = (
        design_candidates(DesignReading("pants", length=c, numbers={"hem_share": s}))[0][1]
        for c, s in (("knee", 0.5), ("below knee", 0.95))
    )
    assert short.leg == "knee" and long.leg == "full" and long.length > short.length + 0.2


def test_a_dress_is_tried_in_one_piece_and_as_bodice_and_skirt():
    cands = design_candidates(READINGS["dress"])
    assert {d.waist_seam for _, d in cands} == {False, True}
    assert cands[0][1].sleeves == "short"


@pytest.mark.parametrize("collar", ["hood", "turtle"])
@pytest.mark.parametrize("garment", ["tshirt", "dress", "jumpsuit"])
def test_a_hood_or_a_standing_collar_read_is_on_every_candidate(garment, collar):
    """A top read with a hood (or a turtle collar) over an unread neckline: every candidate has
    it, sewn to round necklines, its panels drafted and its name saying so; the same reading
    without the collar drafts none."""
    from dataclasses import replace

    base = READINGS[garment]
    r = replace(base, collar=collar, neck_front=None, neck_back=None)
    cands = design_candidates(r)
    assert len(cands) >= 2
    for name, d in cands:
        assert d.collar == collar and (d.neckline_front, d.neckline_back) == ("round", "round"), name
        assert collar in name.split("-")
        assert sum(collar in n for n in draft(d).panels) == 2, name
    plain = design_candidates(replace(base, collar="none"))
    assert all(d.collar == "none" and "hood" not in n and "turtle" not in n for n, d in plain)


@pytest.mark.parametrize("garment", ["tshirt", "dress", "jumpsuit"])
def test_a_top_read_without_cloth_over_the_shoulders_starts_strapless_at_the_read_height(garment):
    """No neckline read (no cloth over the shoulders): the first candidate is strapless, its edge
    at the read top height, and the sleeveless round neck is tried too (straps the reading
    missed); a top with a neckline read drafts no strapless candidate."""
    from dataclasses import replace

    from unsew.pattern.base._frame import body_frame
    from unsew.pattern.measurements import Measurements

    r = replace(READINGS[garment], sleeves="none", neck_front="none", neck_back="none", collar="none")
    m = Measurements()
    y = body_frame(m).armpit_y + 0.05
    cands = design_candidates(r, m, measures={"top_y": y})
    first = cands[0][1]
    assert first.strapless and first.sleeves == "none" and first.top_drop == pytest.approx(-0.05)
    assert "strapless" in cands[0][0]
    assert any(not d.strapless and d.sleeves == "none" for _, d in cands[1:])
    top = draft(first, m).panels["front"]
    (e,) = [e for e in top.edges if e.label == "strapless_top"]
    assert top.to_world(top.vertices[[e.start]])[0, 1] == pytest.approx(y, abs=0.006)  # to 1 cm
    assert not any(d.strapless for _, d in design_candidates(READINGS[garment], m, measures={"top_y": y}))


def test_a_type_outside_the_design_space_is_refused_in_one_line():
    with pytest.raises(InputError) as e:
        design_candidates(DesignReading("kimono"))
    assert "\n" not in str(e.value)


def _fake_drapes(monkeypatch, closest: str):
    """choose_base's drapes replaced by markers: the drape of a candidate lies 10 mm from the
    target when its name contains ``closest``, else 20 mm; nothing is simulated."""
    import unsew.fit.start as start_mod

    monkeypatch.setattr(
        start_mod,
        "dress",
        lambda pat, body, **k: SimpleNamespace(
            x=SimpleNamespace(numpy=lambda: pat.name), mesh=SimpleNamespace(faces=None)
        ),
    )
    monkeypatch.setattr(start_mod, "check_dressed", lambda d, body: SimpleNamespace(ok=True, reason=""))
    monkeypatch.setattr(start_mod, "arm_openings", lambda x, f, sk, contours=None: (0, 0))
    return SimpleNamespace(
        verts=None,
        faces=None,
        contours=[],
        distance_mm=lambda x, f, **k: 10.0 if closest in x else 20.0,
        band_distance_mm=lambda x, f, sk, lo, hi: 10.0 if closest in x else 20.0,
    )


@pytest.mark.parametrize("kind", ["jumpsuit", "skirt"])
def test_a_case_without_a_type_chooses_among_the_drafted_designs(monkeypatch, kind):
    from unsew.fit.start import choose_base

    body = default_body()
    target = _fake_drapes(monkeypatch, "band" if kind == "skirt" else "hem_flare")
    case = SimpleNamespace(garment=kind, body=body, design=READINGS[kind])
    lines = []
    ch = choose_base(case, target, None, FitConfig(), None, progress=Progress(False), log=lines.append)
    names = [n for n, _ in design_candidates(READINGS[kind], _measure(body))]
    assert sorted(r["base"] for r in ch.table) == sorted(names)
    assert ch.name in names and ("band" if kind == "skirt" else "hem_flare") in ch.name
    assert ch.pattern.name == ch.name and ch.pattern.unsew["design"]["garment"] == kind
    assert any(line.startswith("designs drafted from the reading: ") for line in lines)
    assert f"{ch.name} chosen" in lines[-1]
    if kind == "skirt":  # a named base wins over the reading
        ch = choose_base(case, target, None, FitConfig(base="skirt_band"), None, progress=Progress(False))
        assert ch.name == "skirt_band" and ch.table == []


def torch_finite(x) -> bool:
    return bool(np.isfinite(x.detach().cpu().numpy()).all())


def _measure(body):
    from unsew.body.measure import measure_body

    return measure_body(body)


def test_a_jumpsuit_named_in_meta_keeps_its_name_and_its_cut_is_read(monkeypatch):
    """meta.json names a jumpsuit (no library base): the design is read off the target and drafted
    as jumpsuits whatever type the target reads as, the disagreement logged; a named type with
    library bases keeps them (no reading)."""
    import unsew.fit.start as start_mod
    from unsew.fit.start import with_garment_read
    from unsew.grading.garment_type import GarmentReading

    read = READINGS["pants"]
    monkeypatch.setattr(
        start_mod, "read_garment_type", lambda v, f, sk, **k: GarmentReading("pants", "two leg openings")
    )
    monkeypatch.setattr(start_mod, "read_design", lambda v, f, sk, **k: read)
    from pathlib import Path

    from unsew.io.case import Case

    case = Case(Path("case"), "jumpsuit", None, None, default_body())
    lines = []
    named = with_garment_read(case, FitConfig(), log=lines.append)
    assert named.garment == "jumpsuit" and named.design.garment == "jumpsuit"
    assert with_garment_read(named, FitConfig(), log=lines.append) is named  # read once
    assert "names a jumpsuit" in lines[0] and "reads as a pants" in lines[0]
    cands = design_candidates(named.design, _measure(case.body))
    assert cands and all(d.garment == "jumpsuit" for _, d in cands)
    assert all(d.leg == "full" for _, d in cands[:1])  # the legs as read (below the knee)
    dressy = Case(Path("case"), "dress", None, None, case.body)
    assert with_garment_read(dressy, FitConfig(), log=lines.append) is dressy


def test_drafted_candidates_are_sized_to_the_wearer():
    from unsew.pattern.measurements import Measurements

    small, big = (
        drafted_candidates(READINGS["pants"], Measurements(hip=h, waist=h - 0.2)) for h in (0.85, 1.15)
    )
    assert list(small) == list(big)
    # the cloth's width, all panels side by side [m]
    width = [
        sum(np.ptp(q.vertices[:, 0]) for q in p.panels.values())
        for p in (next(iter(small.values())), next(iter(big.values())))
    ]
    assert width[1] > width[0] + 0.2  # girths 0.3 m apart


#: (kind, the base's design, the target's): the target cut otherwise where grading reaches (hems,
#: cuffs, lengths), each kind of drafted pattern once.
GRADED = {
    "jumpsuit": (
        dict(garment="jumpsuit", sleeves="short"),
        dict(garment="jumpsuit", sleeves="short", leg="knee"),
    ),
    "dress_seam": (
        dict(garment="dress", waist_seam=True, skirt="circle", panels=4, sleeves="none"),
        dict(garment="dress", waist_seam=True, skirt="circle", panels=4, sleeves="none", length="mini"),
    ),
    "tshirt2": (
        dict(garment="tshirt", sleeve_pieces=2, cuffs=True),
        dict(garment="tshirt", sleeves="long", sleeve_pieces=2, cuffs=True),
    ),
    "tshirt_hood": (dict(collar="hood"), dict(collar="hood", sleeves="long")),
    "skirt6": (
        dict(garment="skirt", skirt="circle", panels=6, waistband=True),
        dict(garment="skirt", skirt="circle", panels=6, waistband=True, length="midi"),
    ),
    "skirt_darts": (
        dict(garment="skirt", skirt="pencil", darts=True, waistband=True),
        dict(garment="skirt", skirt="pencil", darts=True, waistband=True, length="midi"),
    ),
    "pants_darts": (
        dict(garment="pants", darts=True),
        dict(garment="pants", darts=True, leg="knee"),
    ),
    "dress_band_darts": (
        dict(garment="dress", waist_seam=True, waistband=True, darts=True, sleeves="none"),
        dict(garment="dress", waist_seam=True, waistband=True, darts=True, sleeves="none", length="mini"),
    ),
}


@pytest.mark.slow
@pytest.mark.parametrize("kind", sorted(GRADED))
def test_drafted_patterns_are_graded(kind):
    """Grading (phase one) takes every kind of drafted pattern: its edit drapes, and the graded
    drape lies closer to a target cut otherwise than the base's drape."""
    from unsew.body.sdf import BodySDF
    from unsew.dress import dress
    from unsew.fit.config import load_config
    from unsew.fit.scene import Scene
    from unsew.fit.start import start
    from unsew.fit.target import Target
    from unsew.losses.contours import open_contours
    from unsew.pattern.design import Design
    from unsew.sim.material import get_material

    small = {"drape.edge_length": 0.05, "drape.steps": 8, "drape.sew_steps": 60, "drape.settle_steps": 20}
    cfg = load_config(**small, **{"loss.target_points": 1500})
    body = default_body()
    sdf, m = BodySDF.build(body), _measure(body)
    base_kw, target_kw = GRADED[kind]
    d = dress(draft(Design(**target_kw), m), body, sdf=sdf, settings=cfg.drape)
    x, f = d.x.numpy(), np.asarray(d.mesh.faces)
    target = Target(x, f, open_contours(x, f))
    scene = Scene(body, target, sdf, cfg, Progress(False), lambda s: None)
    s = start(draft(Design(**base_kw), m), scene, get_material("cotton"))
    assert s.grade_table and np.isfinite(s.x).all()
    assert target.distance_mm(s.x, s.mesh.faces) < target.distance_mm(s.x_base, s.mesh_base.faces)
    # and phase two takes the graded pattern: one iteration drapes it and measures a finite loss
    from unsew.fit.material import MaterialChoice
    from unsew.fit.optimize import PhaseTwo

    it = PhaseTwo(MaterialChoice(s), target, sdf, cfg).step()
    assert np.isfinite(it.terms["total"]) and torch_finite(it.x)


@pytest.mark.slow
def test_a_case_folder_without_a_type_starts_from_drafted_designs(tmp_path, monkeypatch):
    """End to end on the small known-truth t-shirt case with meta.json's garment removed: the type
    and design are read, designs drafted from the reading are dressed (coarse), one is chosen and
    the log names them."""
    import json

    import unsew.fit.start as start_mod
    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.fit.config import load_config
    from unsew.fit.demo import make_truth_case
    from unsew.fit.target import Target
    from unsew.sim.material import get_material

    monkeypatch.setattr(start_mod, "BASE_CHOICE_EDGE", 0.06)
    small = {"drape.edge_length": 0.04, "drape.steps": 8, "drape.sew_steps": 60, "drape.settle_steps": 20}
    d = make_truth_case(tmp_path / "tshirt", settings=load_config(**small).drape)
    meta = json.loads((d / "meta.json").read_text())
    meta.pop("garment")
    (d / "meta.json").write_text(json.dumps(meta))
    lines = []
    case = start_mod.with_garment_read(load_case(d), FitConfig(), log=lines.append)
    assert case.garment == "tshirt" and case.design is not None
    ch = start_mod.choose_base(
        case,
        Target.of_case(case),
        BodySDF.build(case.body),
        FitConfig(),
        get_material("cotton"),
        progress=Progress(False),
        log=lines.append,
    )
    names = [n for n, _ in design_candidates(case.design, _measure(case.body))]
    assert ch.name in names and [r["base"] for r in ch.table if r["base"] in names] == [
        r["base"] for r in ch.table
    ]
    said = "\n".join(lines)
    assert case.design.summary() in said and "designs drafted from the reading: " + ", ".join(names) in said
    assert f"{ch.name} chosen" in lines[-1]
    assert ch.table[0]["chamfer_mm"] is not None and ch.table[0]["arms"]  # the truth has short sleeves


def test_when_no_drafted_design_dresses_the_library_bases_are_chosen_among(monkeypatch):
    import unsew.fit.start as start_mod
    from unsew.pattern.base import bases_for

    target = _fake_drapes(monkeypatch, "band")
    # every drafted design (named garment-choices...) falls off the body; the library's bases dress
    monkeypatch.setattr(
        start_mod,
        "check_dressed",
        lambda d, body: SimpleNamespace(ok="-" not in d.x.numpy(), reason="fallen off the body"),
    )
    case = SimpleNamespace(garment="skirt", body=default_body(), design=READINGS["skirt"])
    lines = []
    ch = start_mod.choose_base(
        case, target, None, FitConfig(), None, progress=Progress(False), log=lines.append
    )
    assert ch.name in bases_for("skirt") and "band" in ch.name
    assert sorted(r["base"] for r in ch.table) == sorted(bases_for("skirt"))
    assert any("the library's skirt bases instead" in line for line in lines)
