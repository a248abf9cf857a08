"""Panel areas, area error, panel correspondence and vertex L2."""

import numpy as np
import pytest

from helpers import assert_close
from unsew.errors import PatternError
from unsew.metrics.panels import area_error, match_panels, panel_area, panel_vertex_l2_cm, pattern_metrics
from unsew.pattern.model import Curvature, Edge, Panel, Pattern


def _poly_panel(name, verts, *, label="", translation=(0, 0, 0), curv=None):
    n = len(verts)
    edges = [Edge(i, (i + 1) % n, (curv or {}).get(i)) for i in range(n)]
    return Panel(name, np.asarray(verts, float), edges, np.asarray(translation, float), np.zeros(3), label)


SQ = [[0, 0], [1, 0], [1, 1], [0, 1]]
TRI = [[0, 0], [0.6, 0], [0.3, 0.5]]
PENT = [[0, 0], [0.5, 0], [0.7, 0.3], [0.25, 0.6], [-0.2, 0.3]]


def test_area_with_circular_edge():
    semi = Curvature("circle", [0.5, False, True])  # top edge (1,1)->(0,1) bulging up: a half disk
    p = _poly_panel("p", SQ, curv={2: semi})
    assert_close(panel_area(p), 1 + np.pi / 8, rtol=1e-4)
    assert_close(panel_area(_poly_panel("q", SQ)), 1.0, rtol=1e-15)


@pytest.mark.parametrize("s", [0.9, 1.1, 1.5])
def test_area_error_of_scaled_panel(s):
    semi = Curvature("circle", [0.5, False, True])
    gt = Pattern("gt", {"a": _poly_panel("a", SQ, curv={2: semi})})
    est_p = _poly_panel("a", np.asarray(SQ) * s, curv={2: Curvature("circle", [0.5 * s, False, True])})
    est = Pattern("est", {"a": est_p})
    ae = area_error(est, gt)
    assert_close(ae.per_panel["a"], abs(s * s - 1), rtol=1e-6)
    assert_close(ae.mean, abs(s * s - 1), rtol=1e-6)


def test_correspondence_by_name_label_and_assignment():
    gt = Pattern(
        "gt",
        {
            "front": _poly_panel("front", SQ, translation=(0, 0, 0.2)),
            "sleeve": _poly_panel("sleeve", TRI, label="arm", translation=(0.5, 0, 0)),
            "back": _poly_panel("back", PENT, translation=(0, 0, -0.2)),
            "belt": _poly_panel("belt", np.asarray(SQ) * [2, 0.1], translation=(0, 0.3, 0)),
        },
    )
    est = Pattern(
        "est",
        {
            "front": _poly_panel("front", SQ, translation=(0, 0, 0.2)),  # by name
            "s1": _poly_panel("s1", TRI, label="arm", translation=(0.5, 0, 0)),  # by label
            "x": _poly_panel("x", np.asarray(PENT) * 1.05, translation=(0, 0, -0.18)),  # by shape
            "y": _poly_panel("y", np.asarray(SQ) * [2.1, 0.1], translation=(0, 0.31, 0)),
        },
    )
    m = match_panels(est, gt)
    assert m == {"front": "front", "s1": "sleeve", "x": "back", "y": "belt"}


def test_unmatched_panels_raise():
    gt = Pattern("gt", {"a": _poly_panel("a", SQ), "b": _poly_panel("b", TRI)})
    est = Pattern("est", {"a": _poly_panel("a", SQ)})
    with pytest.raises(PatternError, match="without a counterpart"):
        match_panels(est, gt)
    assert match_panels(est, gt, strict=False) == {"a": "a"}


def test_vertex_l2_rigid_and_scaled():
    gt = _poly_panel("a", PENT)
    th = 0.8
    R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    moved = _poly_panel("b", np.roll(np.asarray(PENT) @ R.T + [3, -1], 2, axis=0))
    assert panel_vertex_l2_cm(moved, gt) < 1e-12
    sq = _poly_panel("s", np.asarray(SQ) - 0.5)
    big = _poly_panel("t", (np.asarray(SQ) - 0.5) * 1.01)
    assert_close(panel_vertex_l2_cm(big, sq), 100 * 0.01 * np.sqrt(2) / 2, rtol=1e-12)
    assert panel_vertex_l2_cm(_poly_panel("t", TRI), sq) is None


def test_pattern_metrics_identity_is_zero():
    gt = Pattern("gt", {"a": _poly_panel("a", SQ), "b": _poly_panel("b", PENT, translation=(1, 0, 0))})
    m = pattern_metrics(gt.copy(), gt)
    assert m["turning_distance_mean"] < 1e-9
    assert m["area_error_rel_mean"] == 0.0
    assert m["vertex_l2_cm_mean"] < 1e-12
    assert set(m["panels"]) == {"a", "b"}
    assert m["unmatched"] == {"estimated": [], "true": []}
    assert m["area_error_weighted_rel"] == 0.0 and m["area_error_total_rel"] == 0.0


def test_pattern_metrics_with_different_panel_sets():
    """Missing and extra panels: listed, left out of the matched means, counted at full area in the
    area-weighted error; the total-area error needs no correspondence."""
    belt = np.asarray(SQ) * [2, 0.1]
    gt = Pattern(
        "gt",
        {
            "front": _poly_panel("front", SQ, translation=(0, 0, 0.2)),
            "back": _poly_panel("back", SQ, translation=(0, 0, -0.2)),
            "belt": _poly_panel("belt", belt, translation=(0, 0.6, 0)),
        },
    )
    est = Pattern(
        "est",
        {
            "front": _poly_panel("front", np.asarray(SQ) * [1, 1.1], translation=(0, 0, 0.2)),
            "back": _poly_panel("back", SQ, translation=(0, 0, -0.2)),
        },
    )
    m = pattern_metrics(est, gt)
    assert m["unmatched"] == {"estimated": [], "true": ["belt"]}
    assert_close(m["unmatched_area_m2"]["true"]["belt"], 0.2, rtol=1e-9) and m["unmatched_area_m2"][
        "estimated"
    ] == {}
    assert set(m["panels"]) == {"front", "back"}
    assert_close(m["area_error_rel_mean"], 0.05, rtol=1e-9)  # (0.1 + 0) / 2 over matched panels
    # 0.045: the belt hidden by front
    assert_close(m["area_error_total_rel"], abs(2.1 - 2.2) / 2.2, rtol=1e-9)
    assert_close(m["area_error_weighted_rel"], (0.1 + 0.2) / 2.2, rtol=1e-9)  # the belt counts in full
    with pytest.raises(PatternError, match="without a counterpart"):
        pattern_metrics(est, gt, strict=True)
    # an extra estimated panel counts at its own area
    est2 = Pattern(
        "est2", {**gt.panels, "pocket": _poly_panel("pocket", np.asarray(SQ) * 0.3, translation=(0, 0, 0.3))}
    )
    m2 = pattern_metrics(est2, gt)
    assert m2["unmatched"] == {"estimated": ["pocket"], "true": []} and m2["area_error_rel_mean"] == 0.0
    assert_close(m2["area_error_weighted_rel"], 0.09 / 2.2, rtol=1e-9)
    assert_close(m2["area_error_total_rel"], 0.09 / 2.2, rtol=1e-9)


def test_the_report_draws_each_true_panel_over_its_match():
    """unsew.fit.report.truth_over: a true panel matched to a final one (metrics.json's pattern.panels)
    takes its name and is moved so the area centroids coincide; an unmatched true panel keeps its
    name and place, marked "(true)" when a final panel has that name."""
    from unsew.fit.report import truth_over
    from unsew.metrics.panels import panel_centroid2d

    belt = np.asarray(SQ) * [2, 0.1]
    gt = Pattern(
        "gt",
        {
            "front_l": _poly_panel("front_l", np.asarray(SQ) + 5),
            "back_l": _poly_panel("back_l", PENT),
            "left_back": _poly_panel("left_back", belt),
        },
        panel_order=["left_back", "front_l", "back_l"],
    )
    est = Pattern(
        "est",
        {
            "left_front": _poly_panel("left_front", np.asarray(SQ) * 1.1),
            "left_back": _poly_panel("left_back", np.asarray(PENT) - 2),
        },
    )
    matched = {
        "panels": {"front_l": {"estimated_panel": "left_front"}, "back_l": {"estimated_panel": "left_back"}}
    }
    drawn = truth_over(gt, est, matched)
    assert drawn.panel_order == ["left_back (true)", "left_front", "left_back"]
    assert set(drawn.panels) == set(drawn.panel_order) and drawn.panels["left_front"].name == "left_front"
    for name in ("left_front", "left_back"):
        assert_close(panel_centroid2d(drawn.panels[name]), panel_centroid2d(est.panels[name]), atol=1e-12)
    # the same shape, moved
    assert_close(drawn.panels["left_back"].vertices, np.asarray(PENT) - 2.0, atol=1e-12)
    assert_close(drawn.panels["left_back (true)"].vertices, belt, atol=0)
    assert truth_over(gt, est, None) is gt
    # the real matching's form
    assert set(truth_over(gt, est, pattern_metrics(est, gt)).panels) >= set(est.panels)


def _halves_patterns():
    """A front drawn as two halves sewn at the centre (GarmentCode's way) with a belt on top, and
    one whole front; the same back in both, sewn to the front's sides."""
    from unsew.pattern.model import Stitch, StitchSide

    half = [[0, 0], [0.5, 0], [0.5, 1], [0, 1]]
    back = np.asarray(SQ) * [1, 0.6]
    gt = Pattern(
        "gt",
        {
            "rf": _poly_panel("rf", half, translation=(-0.5, 0, 0.2)),
            "lf": _poly_panel("lf", half, translation=(0, 0, 0.2)),
            "back": _poly_panel("back", back, translation=(-0.5, 0, -0.2)),
            "belt": _poly_panel("belt", np.asarray(SQ) * [1, 0.1], translation=(-0.5, 1, 0.2)),
        },
    )
    gt.stitches = [
        Stitch(StitchSide("rf", 1), StitchSide("lf", 3)),  # centre front
        Stitch(StitchSide("lf", 1), StitchSide("back", 1)),  # side seams
        Stitch(StitchSide("rf", 3), StitchSide("back", 3)),
        Stitch(StitchSide("belt", 0), StitchSide("lf", 2)),
    ]
    est = Pattern(
        "est",
        {
            "front": _poly_panel("front", np.asarray(SQ) * [1, 1.1], translation=(-0.5, 0, 0.2)),
            "back": _poly_panel("back", back, translation=(-0.5, 0, -0.2)),
        },
    )
    est.stitches = [
        Stitch(StitchSide("front", 1), StitchSide("back", 1)),
        Stitch(StitchSide("front", 3), StitchSide("back", 3)),
    ]
    return est, gt


def test_two_halves_sewn_at_the_centre_are_compared_as_one_panel():
    """GarmentCode's left and right halves against one whole panel: the areas are compared summed;
    the belt (a fifth of a half) stays missing, and the left half is not taken for the back's other
    half though it is sewn to it and near its area (their pair lies farther from the back)."""
    from unsew.metrics.panels import merge_halves

    est, gt = _halves_patterns()
    m = pattern_metrics(est, gt)
    assert m["unmatched"] == {"estimated": [], "true": ["belt"]}
    (front_gt,) = [g for g, v in m["panels"].items() if v["estimated_panel"] == "front"]
    v = m["panels"][front_gt]
    assert set(v["halves"].values()) == {None, ({"rf", "lf"} - {front_gt}).pop()}
    assert_close(v["area_error_rel"], 0.1, rtol=1e-9)  # 1.1 against 0.5 + 0.5
    assert m["panels"]["back"]["area_error_rel"] == 0.0 and "halves" not in m["panels"]["back"]
    assert_close(m["area_error_weighted_rel"], (0.1 + 0.1) / 1.7, rtol=1e-9)  # the belt in full
    # the other way round: halves on the estimated side
    m2 = pattern_metrics(gt, est)
    assert m2["unmatched"] == {"estimated": ["belt"], "true": []}
    assert_close(m2["panels"]["front"]["area_error_rel"], 0.1 / 1.1, rtol=1e-9)
    # without the centre seam the two halves are two panels, one of them missing
    gt.stitches = gt.stitches[1:]
    assert merge_halves(est, gt, match_panels(est, gt, strict=False)) == {"estimated": {}, "true": {}}
