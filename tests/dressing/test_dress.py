"""dress(): every base pattern placed, sewn and settled on the default body (small mode: 4 cm
edges), and on a wider body at 3 cm (slow)."""

import numpy as np
import pytest
import torch

from unsew.body.body import default_body
from unsew.body.sdf import BodySDF
from unsew.dress import DRESS_SETTINGS, dress, dress_stats, hold_vertices
from unsew.pattern.base import make_base_pattern
from unsew.sim.checks import check_dressed

GARMENTS = ["tshirt", "dress", "pants", "shorts", "skirt"]
WIDE = [1.08, 1.0, 1.08]


@pytest.fixture(scope="module")
def body_sdf():
    b = default_body()
    return b, BodySDF.build(b)


def _check(g, body, s, *, stretch_max):
    sk = body.skeleton
    assert s["depth_mm"] < 2.0, f"{g}: a vertex {s['depth_mm']:.1f} mm inside the body"
    assert s["inside_pct"] < 0.5
    assert s["seam_gap"] < 2e-3, f"{g}: seams {s['seam_gap'] * 1000:.1f} mm open after sewing"
    assert s["stretch"] < stretch_max, f"{g}: an edge stretched {s['stretch']:.3f}x"
    assert s["inverted"] == 0
    assert s["max_speed"] < 0.1, f"{g}: not at rest, {s['max_speed']:.3f} m/s"
    lo, hi = s["bbox"]
    # still where it belongs
    if g in ("tshirt", "dress"):
        assert hi[1] > sk.position("chest")[1] and lo[1] < sk.position("chest")[1]
        assert hi[1] < sk.position("head")[1]
    if g in ("pants", "shorts", "skirt"):
        assert lo[1] < sk.position("left_hip")[1] - 0.1 < hi[1]
        assert hi[1] > sk.position("pelvis")[1]
    if g == "pants":
        assert lo[1] < sk.position("left_knee")[1] - 0.2


@pytest.mark.parametrize("garment", GARMENTS)
def test_dress_small(body_sdf, garment):
    body, sdf = body_sdf
    d = dress(make_base_pattern(garment), body, sdf=sdf, settings=DRESS_SETTINGS.replace(edge_length=0.04))
    assert d.x.shape == (d.mesh.n_x, 3)
    for k in ("place_s", "sew_s", "settle_s", "seam_gap", "max_speed"):
        assert k in d.stats
    _check(garment, body, dress_stats(d), stretch_max=1.12)
    # where it was placed, vertex by vertex: the base garments neither rose nor slid
    assert d.x_start.shape == (d.mesh.n_x, 3)
    v = check_dressed(d, body=body)
    assert v.rise_pct == 0.0 and abs(v.drop) < 0.1, v


def test_hold_waist_only_for_lower_garments(body_sdf):
    from unsew.body.placement import place_garment
    from unsew.meshing import mesh_pattern

    body, sdf = body_sdf
    for g, held in (("tshirt", False), ("skirt", True)):
        pat = make_base_pattern(g)
        mesh = mesh_pattern(pat, edge_length=0.05)
        x = place_garment(pat, mesh, body, sdf=sdf)
        h = hold_vertices(pat, mesh, body, x)
        assert (len(h) > 0) == held
        if held:
            assert np.all(x[h, 1] > x[:, 1].max() - 0.021)


@pytest.mark.slow
@pytest.mark.parametrize("garment", GARMENTS)
def test_dress_wide_body(garment):
    from unsew.body.measure import measure_body

    body = default_body().transformed(scale=WIDE)
    sdf = BodySDF.build(body)
    d = dress(
        make_base_pattern(garment, measure_body(body)),
        body,
        sdf=sdf,
        settings=DRESS_SETTINGS.replace(edge_length=0.03),
    )
    _check(garment, body, dress_stats(d), stretch_max=1.3)


def test_settle_drapes_a_sewn_garment_in_another_fabric(body_sdf):
    """settle() (the material choice's cheap drape): a skirt dressed in cotton as the fit dresses,
    settled 40 steps in silk, moves (the softer fabric hangs closer) but stays on the body;
    settled in its own fabric it barely moves."""
    from unsew.dress import settle

    body, sdf = body_sdf
    from unsew.sim.drape import DrapeSettings

    settings = DrapeSettings(edge_length=0.05)  # the fit's sewing and settling
    d = dress(make_base_pattern("skirt"), body, sdf=sdf, settings=settings)
    x0 = d.x.numpy()
    same = settle(d.mesh, x0, sdf, "cotton", settings=settings)
    silk = settle(d.mesh, x0, sdf, "silk", settings=settings)
    assert same.shape == silk.shape == x0.shape and np.isfinite(silk).all()
    moved_same = np.linalg.norm(same - x0, axis=1).mean()
    moved_silk = np.linalg.norm(silk - x0, axis=1).mean()
    assert moved_same < 2e-3 and moved_silk > 2 * moved_same  # [m]; measured 1.1 and 3.5 mm
    with torch.no_grad():
        sd, _ = sdf.query(torch.as_tensor(silk))
    assert float((sd < 0).double().mean()) < 0.005
    with pytest.raises(ValueError, match="x_from must be"):
        settle(d.mesh, x0[:-1], sdf, "silk", settings=settings.replace(settle_steps=1))
