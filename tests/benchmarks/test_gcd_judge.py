"""The GarmentCode benchmark's judge merging panels along seams the 3D shape cannot show: a seam
merges or not by its own two panels, whatever else they are sewn to and in whichever order the
file lists the stitches."""

import importlib.util
import itertools
import sys
from pathlib import Path

import numpy as np
import pytest

GCD = Path(__file__).resolve().parents[2] / "benchmarks" / "gcd"


@pytest.fixture(scope="module")
def judge():
    sys.path.insert(0, str(GCD))
    spec = importlib.util.spec_from_file_location("_gcd_judge_merge", GCD / "judge.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _spec(panels, stitches):
    return {
        "pattern": {
            "panels": panels,
            "stitches": [[{"panel": a, "edge": i}, {"panel": b, "edge": j}] for a, i, b, j in stitches],
        },
        "properties": {"units_in_meter": 100, "curvature_coords": "relative"},
    }


def _panel(verts, t=(0, 0, 0), curves=None):
    n = len(verts)
    edges = [{"endpoints": [i, (i + 1) % n]} for i in range(n)]
    for k, curvature in (curves or {}).items():
        edges[k]["curvature"] = curvature
    return {"vertices": verts, "edges": edges, "translation": list(t), "rotation": [0, 0, 0]}


def _rect(w, h, t, curves=None):
    """Edges: 0 bottom (the hem), 1 right side, 2 top (the waist), 3 left side [cm]."""
    return _panel([[0, 0], [w, 0], [w, h], [0, h]], t, curves)


#: A waist curved up by 3 cm of its 50 (the edge runs right to left: its left is downward).
WAIST_UP = {"type": "quadratic", "params": [[0.5, -0.06]]}
#: The waistband's lower edge curved the same way (the edge runs left to right).
BAND_UP = {"type": "quadratic", "params": [[0.5, 0.06]]}


def _gores_and_band(band_width=50.0, curved=False):
    """Two skirt gores (50 x 60 cm, sewn along both sides into a tube) and a waistband in two halves
    (band_width x 5 cm, sewn along both sides), each half sewn to a gore's waist."""
    panels = {
        "skirt_front": _rect(50, 60, (-25, 40, 15), {2: WAIST_UP} if curved else None),
        "skirt_back": _rect(50, 60, (25, 40, -15), {2: WAIST_UP} if curved else None),
        "wb_front": _rect(band_width, 5, (-25, 100, 15), {0: BAND_UP} if curved else None),
        "wb_back": _rect(band_width, 5, (25, 100, -15), {0: BAND_UP} if curved else None),
    }
    stitches = [
        ("skirt_front", 1, "skirt_back", 3),
        ("skirt_back", 1, "skirt_front", 3),
        ("wb_front", 1, "wb_back", 3),
        ("wb_back", 1, "wb_front", 3),
        ("wb_front", 0, "skirt_front", 2),
        ("wb_back", 0, "skirt_back", 2),
    ]
    return panels, stitches


def _perimeter(loop):
    return float(np.linalg.norm(np.roll(loop, -1, axis=0) - loop, axis=1).sum())


def _is_rectangle(piece, w, h):
    """Whether a piece's outline (in its first panel's frame, here axis-aligned) is a w x h rectangle
    [m]: its area fills its bounding box and it is no longer than the box's perimeter (an outline
    with a slit into it would be)."""
    loop = piece.loop()
    return (
        np.allclose(np.sort(np.ptp(loop, axis=0)), sorted([w, h]), atol=1e-6)
        and piece.area == pytest.approx(w * h, rel=1e-6)
        and _perimeter(loop) == pytest.approx(2 * (w + h), rel=1e-6)
    )


def _pieces(judge, panels, stitches):
    return sorted(judge.merge_invisible(_spec(panels, stitches)), key=lambda p: -p.area)


def test_a_straight_waistband_on_straight_gores_makes_one_flat_tube_whatever_the_stitch_order(judge):
    panels, stitches = _gores_and_band()
    for order in list(itertools.permutations(stitches))[::29]:  # 25 of the 720 orders
        pieces = _pieces(judge, panels, list(order))
        assert len(pieces) == 1, order
        # laid flat and cut open along one side: a plain 100 x 65 cm rectangle, no slit inside
        assert _is_rectangle(pieces[0], 1.0, 0.65), order


@pytest.mark.parametrize("band", ["gathered", "curved"])
def test_gores_merge_along_their_sides_with_a_waistband_they_stay_apart_from(judge, band):
    panels, stitches = (
        _gores_and_band(band_width=40.0) if band == "gathered" else _gores_and_band(curved=True)
    )
    alone = _pieces(judge, {k: v for k, v in panels.items() if k.startswith("skirt")}, stitches[:2])
    for order in (stitches, stitches[::-1]):
        pieces = _pieces(judge, panels, order)
        names = sorted(sorted(p.names) for p in pieces)
        assert names == [["skirt_back", "skirt_front"], ["wb_back", "wb_front"]]
        skirt = pieces[0]
        # the gores' own piece is the one they make without a waistband
        assert len(alone) == 1 and skirt.area == pytest.approx(alone[0].area, rel=1e-9)
        assert judge.turning_distance(skirt.loop(), alone[0].loop()) < 1e-6


def test_flared_gores_keep_a_side_seam_that_shows_at_the_hem(judge):
    # trapezoids 40 cm at the waist, 60 cm at the hem: the joined hem has a corner at the seam
    gore = [[0, 0], [60, 0], [50, 60], [10, 60]]
    panels = {"front": _panel(gore, (-30, 40, 15)), "back": _panel(gore, (30, 40, -15))}
    assert len(_pieces(judge, panels, [("front", 1, "back", 3)])) == 2


def _halves(right_lower=None, bulge=0.0):
    """Two mirror halves (30 x 60 cm) whose centre seam comes in two edges: lower (0-30 cm) and upper.
    ``bulge`` [cm] puts a kink outward at 30 cm; ``right_lower``/its mirror: the lower edges' curves."""
    right = _panel([[0, 0], [30, 0], [30 + bulge, 30], [30, 60], [0, 60]], (-30, 60, 15))
    left = _panel([[0, 60], [-30, 60], [-30 - bulge, 30], [-30, 0], [0, 0]], (30, 60, 15))
    if right_lower is not None:
        right["edges"][1]["curvature"], left["edges"][2]["curvature"] = right_lower
    stitches = [("right", 1, "left", 2), ("right", 2, "left", 1)]
    return {"right": right, "left": left}, stitches


def test_a_seam_in_two_edges_merges_when_straight_through_and_not_when_kinked_or_curved(judge):
    panels, stitches = _halves()
    pieces = _pieces(judge, panels, stitches)
    assert len(pieces) == 1
    assert _is_rectangle(pieces[0], 0.6, 0.6)
    # both halves bulge out 5 cm at the middle of the seam: it shapes the garment
    assert len(_pieces(judge, *_halves(bulge=5.0))) == 2
    # a crotch-like lower part: curved out of the straight upper part without a corner
    crotch = (
        {"type": "cubic", "params": [[1 / 6, -1 / 3], [2 / 3, 0]]},
        {"type": "cubic", "params": [[1 / 3, 0], [5 / 6, -1 / 3]]},
    )
    assert len(_pieces(judge, *_halves(right_lower=crotch))) == 2


def _v_neck_halves(overshoot=0.0):
    """A front in two mirror halves (25 x 40 cm) sewn at the centre from the hem up to a V-neck's
    point (20 cm up); each half's neck edge curves from the point up to the shoulder, running
    past the centre line on its way when ``overshoot`` [cm, the control point's side] is > 0 (as
    GarmentCode's deep necks do, a few mm). Control points in the panels' own coordinates."""
    right = _panel([[0, 0], [25, 0], [25, 40], [8, 40], [0, 20]], (-12.5, 100, 15))
    right["edges"][3]["curvature"] = {"type": "quadratic", "params": [[-overshoot, 30]]}
    left = _panel([[0, 20], [-8, 40], [-25, 40], [-25, 0], [0, 0]], (12.5, 100, 15))
    left["edges"][0]["curvature"] = {"type": "quadratic", "params": [[overshoot, 30]]}
    return {"right": right, "left": left}, [("right", 4, "left", 4)]


@pytest.mark.parametrize("overshoot", [-4.0, 3.0])
def test_a_v_necks_centre_seam_merges_its_mirror_halves_as_a_fold_would(judge, overshoot):
    panels, stitches = _v_neck_halves(overshoot)
    spec = _spec(panels, stitches)
    spec["properties"]["curvature_coords"] = "absolute"
    pieces = judge.merge_invisible(spec)
    assert len(pieces) == 1
    loop = pieces[0].loop()
    assert not len(judge._crossings(loop))  # the union's outline, no loop where the necks cross
    assert np.ptp(loop, axis=0) == pytest.approx([0.5, 0.4], abs=1e-6)
    # the same halves turned apart (the right one's grain 20 degrees off the left's) stay two
    right = panels["right"]
    turned = dict(right, vertices=_turned(right["vertices"], 20))
    turned["edges"] = [dict(e) for e in right["edges"]]
    turned["edges"][3]["curvature"] = {"type": "quadratic", "params": _turned([[-overshoot, 30]], 20)}
    spec = _spec(dict(panels, right=turned), stitches)
    spec["properties"]["curvature_coords"] = "absolute"
    assert len(judge.merge_invisible(spec)) == 2


def _turned(verts, deg):
    a = np.radians(deg)
    R = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    return (np.asarray(verts, float) @ R.T).tolist()


def _sheet(x0, x1, y0, y1, z, step=0.02):
    """A flat triangulated sheet [m] at depth z: (vertices (N, 3), triangles (F, 3))."""
    xs, ys = np.arange(x0, x1 + 1e-9, step), np.arange(y0, y1 + 1e-9, step)
    X, Y = np.meshgrid(xs, ys)
    v = np.c_[X.ravel(), Y.ravel(), np.full(X.size, z)]
    n = len(xs)
    k = (np.arange(len(ys) - 1)[:, None] * n + np.arange(n - 1)[None]).ravel()
    f = np.r_[np.c_[k, k + 1, k + n + 1], np.c_[k, k + n + 1, k + n]]
    return v, f


def _drape(*sheets):
    """(vertices, triangles, panel name per vertex) of named sheets (name, (v, f)) in one mesh."""
    vs, fs, names, off = [], [], [], 0
    for name, (v, f) in sheets:
        vs.append(v)
        fs.append(f + off)
        names += [name] * len(v)
        off += len(v)
    return np.concatenate(vs), np.concatenate(fs), np.array(names)


def test_a_leg_cut_in_one_piece_gives_each_true_panel_its_share_of_the_cloth(judge):
    # the truth: a leg's front and back (40 x 60 cm each); recovered: the same leg in one 80 x 60
    # piece, whose two halves drape where the true front and back do
    true = _spec({"front": _rect(40, 60, (-20, 30, 10)), "back": _rect(40, 60, (20, 30, -10))}, [])
    rec = _spec({"leg": _rect(80, 60, (-40, 30, 10))}, [])
    tx, _, tp = _drape(
        ("front", _sheet(-0.2, 0.2, 0.3, 0.9, 0.1)), ("back", _sheet(-0.2, 0.2, 0.3, 0.9, -0.1))
    )
    front, back = _sheet(-0.2, 0.2, 0.3, 0.9, 0.11), _sheet(-0.2, 0.2, 0.3, 0.9, -0.11)
    rx, rf, rp = _drape(("leg", front), ("leg", back))
    shares = judge.drape_shares(tx, tp, rx, rf, rp)
    assert shares["leg"]["front"] == pytest.approx(0.5, abs=0.02)
    assert shares["leg"]["back"] == pytest.approx(0.5, abs=0.02)
    by_drape = judge.compare_patterns(true, rec, shares)
    assert by_drape["panel_err"] < 0.05
    # matched one to one by placement, the piece stands for one panel and leaves the other out
    assert judge.compare_patterns(true, rec)["panel_err"] > 0.5


def test_a_sleeve_does_not_stand_for_a_missing_waistband(judge):
    # the truth: a top and a waistband; recovered: the top and a sleeve, no band; the sleeve's area
    # is the band's, so a match by placement and area pairs them
    true = _spec({"top": _rect(50, 40, (-25, 100, 15)), "band": _rect(50, 5, (-25, 95, 15))}, [])
    rec = _spec({"top": _rect(50, 40, (-25, 100, 15)), "sleeve": _rect(25, 10, (30, 120, 0))}, [])
    tx, _, tp = _drape(
        ("top", _sheet(-0.25, 0.25, 1.0, 1.4, 0.15)), ("band", _sheet(-0.25, 0.25, 0.95, 1.0, 0.15))
    )
    rx, rf, rp = _drape(
        ("top", _sheet(-0.25, 0.25, 1.0, 1.4, 0.16)), ("sleeve", _sheet(0.3, 0.55, 1.2, 1.3, 0.0))
    )
    shares = judge.drape_shares(tx, tp, rx, rf, rp)
    assert shares["sleeve"] == {}  # it lies off the true garment's cloth
    r = judge.compare_patterns(true, rec, shares)
    assert r["panel_err"] == pytest.approx(0.5, abs=0.01)  # the top right, the band missing (1)
    assert [m[:2] for m in r["matched"]] == [(["top"], ["top"])]
    by_placement = judge.compare_patterns(true, rec)
    assert (["band"], ["sleeve"]) in [tuple(m[:2]) for m in by_placement["matched"]]
