"""A known-truth case whose body is written into the folder: the target is the drape a fit can
reproduce from the folder alone (the true pattern, the true fabric, the body as loaded)."""

import json

import numpy as np
import pytest


def test_target_is_reproducible_from_the_case_folder(tmp_path):
    from unsew.body.body import default_body
    from unsew.dress import dress
    from unsew.fit.synthetic import make_truth_case
    from unsew.body.case import load_case
    from unsew.sim.drape import DrapeSettings
    from unsew.sim.material import MATERIALS

    body = default_body().transformed(scale=np.array([1.05, 1.0, 1.05]))
    assert body.weights is not None  # in memory the body carries skinning weights; body.obj does not
    settings = DrapeSettings(edge_length=0.05, sew_steps=30, settle_steps=5, dt=0.05)
    d = make_truth_case(tmp_path / "case", garment="tshirt", body=body, body_meta=None, settings=settings)
    case = load_case(d)
    assert case.body.weights is None
    material = MATERIALS[json.loads((d / "meta.json").read_text())["truth"]["material"]]
    again = dress(case.pattern_gt, case.body, material=material, settings=settings)
    np.testing.assert_allclose(again.x.detach().numpy(), case.target_verts, atol=1e-6)


def test_alterations_grading_cannot_make():
    """ "hem@back" alters only the back panel's hem; "waist" moves only the dress's side-seam
    corners (vertices 2 and 9 of front and back), inward for a negative length, and keeps the
    stitched side seams of equal length."""
    from unsew.fit.synthetic import Alteration, make_truth_pattern
    from unsew.pattern.base import make_base_pattern
    from unsew.body.body import default_body
    from unsew.body.measure import measure_body

    base = {g: make_base_pattern(g, measure_body(default_body())) for g in ("tshirt", "dress")}
    t = make_truth_pattern("tshirt", Alteration({"hem@back": (0.0, 0.2)}, "cotton"))
    assert np.array_equal(t.panels["front"].vertices, base["tshirt"].panels["front"].vertices)
    moved = np.flatnonzero(
        np.abs(t.panels["back"].vertices - base["tshirt"].panels["back"].vertices).max(1) > 1e-9
    )
    assert moved.tolist() == [0, 1]

    d = make_truth_pattern("dress", Alteration({"waist": (-0.03, 0.0)}, "cotton"))
    for name in ("front", "back"):
        delta = d.panels[name].vertices - base["dress"].panels[name].vertices
        assert np.flatnonzero(np.abs(delta).max(1) > 1e-9).tolist() == [2, 9]
        assert (
            delta[2, 0] == pytest.approx(-0.03)
            and delta[9, 0] == pytest.approx(0.03)
            and not delta[:, 1].any()
        )
    for st in (st for st in d.stitches if "side" in st.label):
        la, lb = (
            np.linalg.norm(
                np.subtract(
                    *d.panels[s.panel].vertices[
                        [d.panels[s.panel].edges[s.edge].start, d.panels[s.panel].edges[s.edge].end]
                    ]
                )
            )
            for s in (st.a, st.b)
        )
        assert la == pytest.approx(lb, rel=1e-9), st.label
