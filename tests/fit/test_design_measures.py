"""Continuous measures read off a target (unsew.fit.designs.read_measures) and the designs drafted
with them: their hems as long as the target's."""

import warnings
from pathlib import Path

import numpy as np
import pytest

from unsew.body.body import default_body
from unsew.body.measure import measure_body
from unsew.fit.designs import design_candidates, read_measures
from unsew.grading.design_reading import DesignReading, read_design
from unsew.pattern.curves import edge_length, sample_edge
from unsew.pattern.design import draft

CASES = Path(__file__).resolve().parents[2] / "benchmarks" / "foreign" / "cases"


def hem_length(pattern, *, legs: bool) -> float:
    """The pattern's hem as placed [m]: its unstitched edges that run within 3 cm of a panel's
    lowest point, summed (``legs``: per side of the body, x > 0 and x < 0, and averaged)."""
    sewn = {(s.a.panel, s.a.edge) for s in pattern.stitches} | {
        (s.b.panel, s.b.edge) for s in pattern.stitches
    }
    sides = [0.0, 0.0]
    for name, p in pattern.panels.items():
        pts = [p.to_world(sample_edge(p, i, 8)) for i in range(len(p.edges))]
        low = min(w[:, 1].min() for w in pts)
        for i, w in enumerate(pts):
            if (name, i) not in sewn and w[:, 1].max() < low + 0.03:
                sides[int(w[:, 0].mean() > 0)] += edge_length(p, i)
    return 0.5 * sum(sides) if legs else sum(sides)


def _cone(top_r: float, hem_r: float, top_y: float, hem_y: float, n: int = 96, rows: int = 12):
    """A cone-shaped tube (vertices (V, 3) [m], faces (F, 3)) round the body's vertical axis."""
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    ring = [
        np.stack([r * np.sin(t), np.full(n, y), 0.8 * r * np.cos(t)], axis=1)
        for r, y in zip(np.linspace(top_r, hem_r, rows), np.linspace(top_y, hem_y, rows))
    ]
    v = np.concatenate(ring)
    f = []
    for k in range(rows - 1):
        for j in range(n):
            a, b, c, d = k * n + j, k * n + (j + 1) % n, (k + 1) * n + j, (k + 1) * n + (j + 1) % n
            f += [[a, c, b], [b, c, d]]
    return v, np.asarray(f)


def _ellipse_length(a: float, b: float) -> float:
    return float(np.pi * (3 * (a + b) - np.sqrt((3 * a + b) * (a + 3 * b))))  # Ramanujan


def test_a_tapered_skirt_drafts_as_a_pencil_with_the_targets_hem():
    """A tube from the waist narrowing to 0.82 of the hips' girth at the knee: the hem's girth and
    height are read to 1 % and 5 mm, and the drafted pencil's hem is that long (the default
    pencil's is the hips')."""
    body = default_body()
    m = measure_body(body)
    hem_r, hem_y = 0.82 * m.hip / (2 * np.pi * 0.9), 0.45
    v, f = _cone(m.waist / (2 * np.pi * 0.9), hem_r, 1.0, hem_y)
    got = read_measures(v, f, body.skeleton)
    true_hem = _ellipse_length(hem_r, 0.8 * hem_r)
    assert got["hem_girth"] == pytest.approx(true_hem, rel=0.01)
    assert abs(got["hem_y"] - hem_y) < 0.005
    reading = DesignReading("skirt", skirt="pencil", length="knee", numbers={"flare": 0.8, "hem_share": 0.5})
    first = design_candidates(reading, m, measures=got)[0][1]
    plain = design_candidates(reading, m)[0][1]
    assert hem_length(draft(first, m), legs=False) == pytest.approx(true_hem, rel=0.01)
    assert hem_length(draft(plain, m), legs=False) > 1.15 * true_hem


def test_a_tube_open_at_the_chest_reads_its_top_height():
    """A tube from under the arms to the knee (a strapless dress's two openings): the top's
    height is read to 5 mm; a tube with one opening reads none."""
    body = default_body()
    m = measure_body(body)
    r = m.bust / (2 * np.pi * 0.9)
    v, f = _cone(r, 1.2 * r, 1.25, 0.5)
    got = read_measures(v, f, body.skeleton)
    assert abs(got["top_y"] - 1.25) < 0.005 and abs(got["hem_y"] - 0.5) < 0.005
    closed = np.vstack([v, [[0.0, 1.25, 0.0]]])  # the top ring capped by a fan
    n = 96
    fan = [[len(v), (j + 1) % n, j] for j in range(n)]
    assert "top_y" not in read_measures(closed, np.vstack([f, fan]), body.skeleton)


def _true_and_target(name):
    from unsew.io.garmentcode import load_pattern
    from unsew.io.mesh import read_garment

    if not (CASES / name / "target.obj").is_file():
        pytest.skip(f"benchmark case {name} not in this checkout")
    v, f, _ = read_garment(CASES / name / "target.obj")
    with warnings.catch_warnings():  # clockwise panels are mirrored, with a warning
        warnings.simplefilter("ignore")
        true = load_pattern(CASES / name / "pattern_gt.json")
    return v, f, true


@pytest.mark.parametrize(
    "name", ["trousers_slim__default", "shorts_wide__default", "skirt_pencil_mini__default"]
)
def test_drafted_hems_land_near_the_true_patterns(name):
    """On newton drapes of patterns nobody drafted with unsew (default body): the hems (each
    leg's, or the skirt's) of the design cut to the read hem (a skirt's first drafted candidate;
    trousers of the read leg openings) lie within 8 % of the true pattern's, nearer than the
    garment's own hems."""
    v, f, true = _true_and_target(name)
    body = default_body()
    m = measure_body(body)
    reading = read_design(v, f, body.skeleton)
    got = read_measures(v, f, body.skeleton)
    legs = reading.garment in ("pants", "shorts")
    want = hem_length(true, legs=legs)
    plain = design_candidates(reading, m)[0][1]
    if legs:  # the fit's trousers keep their own hem first: the design with the read one drafts it
        first = plain.replace(hem_girth=round(got["leg_girth"], 3))
    else:
        first = design_candidates(reading, m, measures=got)[0][1]
    with_m, without = (hem_length(draft(d, m), legs=legs) for d in (first, plain))
    assert abs(with_m - want) < 0.08 * want, (with_m, want)
    assert abs(with_m - want) < abs(without - want)


def test_a_top_is_drafted_to_the_read_hem_height_and_girth():
    """A top whose hem was read 10 cm below the natural waist and 0.95 m round is drafted with its
    hem there (to 1 cm) and that long (to 1 %); a hem read past the guards is held at them."""
    from unsew.pattern.base._frame import body_frame

    body = default_body()
    m = measure_body(body)
    waist_y = body_frame(m).waist_y
    reading = DesignReading("tshirt", sleeves="none", neck_front="round", neck_back="round")
    first = design_candidates(reading, m, measures={"hem_girth": 0.95, "hem_y": waist_y - 0.10})[0][1]
    p = draft(first, m)
    hem_y = min(pp.to_world(pp.vertices)[:, 1].min() for pp in p.panels.values())
    assert abs(hem_y - (waist_y - 0.10)) < 0.01
    assert hem_length(p, legs=False) == pytest.approx(0.95, rel=0.01)
    wide = design_candidates(reading, m, measures={"hem_girth": 9.0, "hem_y": waist_y - 0.10})[0][1]
    assert hem_length(draft(wide, m), legs=False) < 1.7 * m.hip
