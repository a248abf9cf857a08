"""fit/outputs.pattern_errors: the final, base and graded patterns each judged against the true one,
panels without a counterpart reported rather than sinking the metrics (fast: hand-made patterns)."""

from types import SimpleNamespace

import numpy as np

from unsew.fit.outputs import pattern_errors
from unsew.pattern.model import Edge, Panel, Pattern


def _rect(name, w, h, z):
    v = np.array([[0, 0], [w, 0], [w, h], [0, h]], float)
    return Panel(name, v, [Edge(i, (i + 1) % 4) for i in range(4)], np.array([0.0, 0.0, z]), np.zeros(3))


def test_pattern_errors_with_a_waistband_the_base_lacks():
    gt = Pattern(
        "gt",
        {
            "front": _rect("front", 0.4, 0.5, 0.2),
            "back": _rect("back", 0.4, 0.5, -0.2),
            "waistband": _rect("waistband", 0.8, 0.05, 0.0),
        },
    )
    base = Pattern("base", {"front": _rect("front", 0.3, 0.5, 0.2), "back": _rect("back", 0.3, 0.5, -0.2)})
    graded = Pattern(
        "graded", {"front": _rect("front", 0.4, 0.55, 0.2), "back": _rect("back", 0.4, 0.55, -0.2)}
    )
    result = SimpleNamespace(pattern=graded, base_pattern=base, graded_pattern=graded)
    m = pattern_errors(result, gt)
    assert set(m) == {"pattern", "pattern_base", "pattern_graded"}
    for key in m:
        assert m[key]["unmatched"] == {"estimated": [], "true": ["waistband"]}
    # graded: front/back 0.22 m^2 each against 0.20, the 0.04 m^2 waistband missing: total area exact
    assert abs(m["pattern_graded"]["area_error_total_rel"]) < 1e-9
    assert abs(m["pattern_graded"]["area_error_weighted_rel"] - 0.08 / 0.44) < 1e-9
    assert abs(m["pattern_base"]["area_error_weighted_rel"] - (0.1 + 0.04) / 0.44) < 1e-9
    assert m["pattern"]["area_error_weighted_rel"] < m["pattern_base"]["area_error_weighted_rel"]


def test_pattern_errors_keeps_the_others_when_one_cannot_be_compared():
    gt = Pattern("gt", {"front": _rect("front", 0.4, 0.5, 0.2)})
    empty = Pattern("empty", {})
    result = SimpleNamespace(pattern=gt.copy(), base_pattern=empty, graded_pattern=None)
    m = pattern_errors(result, gt)
    assert "error" in m["pattern_base"] and "pattern_graded" not in m
    assert m["pattern"]["area_error_weighted_rel"] == 0.0
