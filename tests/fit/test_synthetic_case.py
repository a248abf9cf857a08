"""A known-truth case whose body is written into the folder: the target is the drape a fit can
reproduce from the folder alone (the true pattern, the true fabric, the body as loaded)."""

import json

import numpy as np


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
