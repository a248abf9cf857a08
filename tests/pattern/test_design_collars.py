"""Collars of the design space: a hood (two side panels) and a turtle collar (a front and a back
band) sewn to a top's neckline halves: they draft valid patterns, carry names the GarmentCode
benchmark reads as a collar piece (GarmentCode's own hood names), follow the body's size, stay
where the placement keeps free panels, and dress on the default body."""

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from unsew.errors import InputError
from unsew.pattern.curves import edge_length, panel_outline
from unsew.pattern.design import Design, design_name, draft
from unsew.pattern.design._collar import head_girth
from unsew.pattern.measurements import Measurements
from unsew.pattern.validate import validate_pattern

ROOT = Path(__file__).resolve().parents[2]
#: A taller body with a taller head than the default (1.625 m, the neck's base at 1.379 m).
TALL = Measurements(height=1.80, neck_height=1.52, neck=0.36)

COLLARED = [
    Design(collar="hood"),
    Design(collar="turtle", sleeves="long", collar_height=0.12),
    Design(garment="dress", collar="hood", sleeves="none"),
    Design(garment="dress", collar="turtle", waist_seam=True, panels=4),
    Design(garment="dress", collar="hood", waist_seam=True, waistband=True, darts=True),
    Design(garment="jumpsuit", collar="hood", sleeves="long", sleeve_pieces=2, cuffs=True),
]


@pytest.fixture(scope="module")
def bodies():
    from unsew.body.body import default_body
    from unsew.body.sdf import BodySDF

    b = default_body()
    return {"default": (b, BodySDF.build(b))}


def _truth():
    """benchmarks/gcd/truth.py, which reads a recovered pattern's pieces from its panel names."""
    sys.path.insert(0, str(ROOT / "benchmarks" / "gcd"))
    path = ROOT / "benchmarks" / "gcd" / "truth.py"
    spec = importlib.util.spec_from_file_location("_gcd_truth_collars", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _sides(p, panel):
    return {(s.a.panel, s.a.edge) for s in p.stitches if s.a.panel == panel} | {
        (s.b.panel, s.b.edge) for s in p.stitches if s.b.panel == panel
    }


@pytest.mark.parametrize("design", COLLARED, ids=design_name)
def test_collars_draft_valid_patterns_sewn_to_the_neckline(design):
    p = draft(design)
    assert validate_pattern(p) == []
    assert design.collar in p.name.split("-")
    names = {"hood": ["left_hood", "right_hood"], "turtle": ["turtle_front", "turtle_back"]}[design.collar]
    assert set(names) <= set(p.panels)
    for s in p.stitches:
        la, lb = edge_length(p.panels[s.a.panel], s.a.edge), edge_length(p.panels[s.b.panel], s.b.edge)
        assert abs(la - lb) < 1e-3, f"{s.label}: {la:.4f} vs {lb:.4f} m"
    # every neckline half of the front and the back is sewn to the collar, nothing else open there
    for torso in ("front", "back"):
        halves = [i for i, e in enumerate(p.panels[torso].edges) if e.label.endswith("neckline")]
        assert len(halves) == 2
        for i in halves:
            other = [
                (s.b.panel if s.a.panel == torso else s.a.panel)
                for s in p.stitches
                if (s.a.panel, s.a.edge) == (torso, i) or (s.b.panel, s.b.edge) == (torso, i)
            ]
            assert other and other[0] in names, (torso, i, other)
    if design.collar == "hood":
        for n in names:  # the face edge alone is left open
            open_edges = [e.label for i, e in enumerate(p.panels[n].edges) if (n, i) not in _sides(p, n)]
            assert open_edges == ["face"], (n, open_edges)
    else:
        for n in names:
            assert np.ptp(panel_outline(p.panels[n])[:, 1]) == pytest.approx(design.collar_height, abs=1e-9)


def test_collar_names_read_as_the_benchmark_reads_them():
    """The benchmark's truth reads a recovered pattern's pieces from its panel names: a collar
    piece, and no sleeve, waistband or cuff that is not there; hoods bear GarmentCode's own names."""
    import json

    truth = _truth()
    gc_hood = json.loads((ROOT / "tests" / "data" / "gc_dress_cuffs_specification.json").read_text())
    gc_names = {n for n in gc_hood["pattern"]["panels"] if "hood" in n}
    from unsew.io.garmentcode import pattern_to_dict

    for collar in ("hood", "turtle"):
        spec = pattern_to_dict(draft(Design(collar=collar, sleeves="none")))
        got = truth.choices_of_spec(spec)
        want = {"sleeves": False, "waistband": False, "collar": True, "cuffs": False, "strapless": False}
        assert got == want, collar
        pieces = [n for n in spec["pattern"]["panels"] if collar in n]
        assert len(pieces) == 2
        if collar == "hood":
            assert set(pieces) == gc_names
    plain = truth.choices_of_spec(pattern_to_dict(draft(Design())))
    assert plain["collar"] is False


def test_the_hood_is_sized_to_the_head():
    """A taller head gets a taller and deeper hood; the hood rises above the crown and is deeper
    than the head is wide."""
    for m in (Measurements(), TALL):
        hood = draft(Design(collar="hood"), m).panels["right_hood"]
        o = panel_outline(hood)
        assert np.ptp(o[:, 1]) > m.height - m.neck_height
        assert np.ptp(o[:, 0]) > head_girth(m) / np.pi
    short = panel_outline(draft(Design(collar="hood")).panels["right_hood"])
    tall = panel_outline(draft(Design(collar="hood"), TALL).panels["right_hood"])
    assert np.ptp(tall[:, 1]) > np.ptp(short[:, 1]) + 0.02 and np.ptp(tall[:, 0]) > np.ptp(short[:, 0])
    assert 0.5 < head_girth(Measurements()) < 0.6  # an adult's head girth [m]


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(collar="cowl"), "collar must be one of"),
        (dict(collar="hood", neckline_front="v"), "round necklines"),
        (dict(collar="turtle", collar_height=0.5), "collar_height"),
    ],
)
def test_bad_collars_are_refused_in_one_line(kw, match):
    with pytest.raises(InputError, match=match) as e:
        Design(**kw)
    assert "\n" not in str(e.value)


def test_collar_panels_stay_where_drafted_around_the_head(bodies):
    from unsew.body.placement import panel_roles

    body, _ = bodies["default"]
    for collar in ("hood", "turtle"):
        roles = panel_roles(draft(Design(collar=collar)), body)
        assert roles["front"] == roles["back"] == "torso"
        assert [r for n, r in roles.items() if collar in n] == ["free", "free"], roles


@pytest.mark.parametrize("collar", ["hood", "turtle"])
def test_a_collared_tee_dresses_the_default_body(bodies, collar):
    """On the default body: the drape verdict, nothing inside, seams closed; a hood over the head
    (above the crown, round the head joint), a turtle collar round the neck, under the head joint."""
    from unsew.dress import DRESS_SETTINGS, dress, dress_stats
    from unsew.sim.checks import check_dressed

    body, sdf = bodies["default"]
    sk = body.skeleton
    r = dress(draft(Design(collar=collar)), body, sdf=sdf, settings=DRESS_SETTINGS.replace(edge_length=0.04))
    v, s = check_dressed(r, body=body), dress_stats(r)
    assert v.ok, v.reason
    assert s["inside_pct"] < 0.5 and s["seam_gap"] < 5e-3, (s["inside_pct"], s["seam_gap"])
    assert s["stretch"] < (1.5 if collar == "hood" else 2.0), s["stretch"]
    x = r.x.detach().numpy()
    names, part = r.mesh.panel_names, r.mesh.uv_panel
    pieces = [names.index(n) for n in names if collar in n]
    xc = x[np.unique(r.mesh.x_of_u[np.isin(part, pieces)])]
    head, neck = sk.position("head"), sk.position("neck")
    if collar == "hood":
        assert xc[:, 1].max() > float(body.verts[:, 1].max())  # over the crown
        assert xc[:, 0].min() < head[0] < xc[:, 0].max() and xc[:, 2].min() < head[2] < xc[:, 2].max()
        assert abs(xc[:, 1].mean() - head[1]) < 0.1
    else:
        assert neck[1] < xc[:, 1].max() < head[1]
        assert xc[:, 0].min() < neck[0] < xc[:, 0].max() and xc[:, 2].min() < neck[2] < xc[:, 2].max()


@pytest.mark.parametrize("collar", ["hood", "turtle"])
def test_collared_drafts_mesh_parameterize_and_round_trip(collar, tmp_path):
    """Ready for the fit: the mesh is sound, each collar panel mirror-symmetric or paired (the
    hood's two sides), the parameters rebuild the mesh, and GarmentCode JSON keeps the design."""
    from helpers import assert_close
    from unsew.io.garmentcode import load_pattern, save_pattern
    from unsew.meshing import mesh_pattern
    from unsew.pattern.model import pattern_diff
    from unsew.pattern.params import PatternParams
    from unsew.pattern.symmetry import detect_symmetry

    d = Design(collar=collar, sleeves="long", sleeve_pieces=2)
    p = draft(d)
    mesh = mesh_pattern(p, edge_length=0.05)
    assert mesh.quality()["bad_triangles"] == 0
    sym = detect_symmetry(p)
    pairs = {(pr.source, pr.target) for pr in sym.pairs}
    if collar == "hood":
        assert ("left_hood", "right_hood") in pairs or ("right_hood", "left_hood") in pairs
    else:
        assert {"turtle_front", "turtle_back"} <= {m.panel for m in sym.mirrors}
    params = PatternParams.build(p, mesh, symmetry=sym)
    assert_close(params.uv(params.K0).detach().numpy(), mesh.uv, atol=1e-9)
    save_pattern(p, tmp_path / "p.json")
    back = load_pattern(tmp_path / "p.json")
    assert pattern_diff(back, p, atol=1e-9) == [] and Design.from_dict(back.unsew["design"]) == d
