"""The library's base variants (unsew.pattern.base.BASES beyond the five defaults) mesh, sew and
drape on the default body (small mode: 4 cm edges, as test_dress.py) and on the anny default body built by the
model (slow): judged by the drape verdict (sim.checks), seams closed, nothing inside."""

import pytest

from unsew.body.body import default_body
from unsew.body.sdf import BodySDF
from unsew.dress import DRESS_SETTINGS, dress, dress_stats
from unsew.pattern.base import BASES, GARMENTS, make_base_pattern
from unsew.sim.checks import check_dressed

VARIANTS = [b for b in BASES if b not in GARMENTS]


@pytest.fixture(scope="module")
def body_sdf():
    b = default_body()
    return b, BodySDF.build(b)


def _check(name, d, body, *, strict: bool = True):
    """The verdict, seams and place; ``strict`` also at most one folded triangle and no edge
    stretched 1.5x (on the anny body at 3 cm, 1-2 triangles of tshirt_long, shorts_band and
    skirt_band end folded and dress_sleeveless has an edge at 1.50x; the circle skirt's flutes
    fold one triangle of its 4 cm mesh on the default body, as its mesh falls)."""
    v = check_dressed(d, body=body)
    assert v.ok, f"{name}: {v.reason}"
    s = dress_stats(d)
    assert s["inside_pct"] < 0.5, name
    assert s["seam_gap"] < 2e-3, f"{name}: seams {s['seam_gap'] * 1000:.1f} mm open after sewing"
    if strict:
        assert s["stretch"] < 1.5, f"{name}: an edge stretched {s['stretch']:.3f}x"
        assert s["inverted"] <= 1, name
    lo, hi = s["bbox"]
    sk = body.skeleton
    if any(k in name for k in ("band", "circle")):  # a waistband at the waist
        assert abs(hi[1] - sk.position("spine")[1]) < 0.15, f"{name}: top at {hi[1]:.3f} m"
    if name.startswith(("tshirt", "dress")):
        assert lo[1] < sk.position("chest")[1] < hi[1] < sk.position("head")[1]


@pytest.mark.parametrize("name", VARIANTS)
def test_variant_dresses_small(body_sdf, name):
    body, sdf = body_sdf
    d = dress(make_base_pattern(name), body, sdf=sdf, settings=DRESS_SETTINGS.replace(edge_length=0.04))
    _check(name, d, body)


@pytest.mark.slow
@pytest.mark.parametrize("name", VARIANTS)
def test_variant_dresses_on_anny_default(name):
    from unsew.body.anny_body import make_anny_body
    from unsew.body.measure import measure_body

    body = make_anny_body(phenotype={}, pose="A")
    d = dress(
        make_base_pattern(name, measure_body(body)),
        body,
        sdf=BodySDF.build(body),
        settings=DRESS_SETTINGS.replace(edge_length=0.03),
    )
    _check(name, d, body, strict=False)
