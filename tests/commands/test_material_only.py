"""``unsew fit --material-only --base P.json``: the pattern held as given, only its material fitted."""

import json

import numpy as np
import pytest

from unsew.cli import main


def test_material_only_needs_a_pattern_file(tmp_path, capsys):
    case = tmp_path / "case"
    case.mkdir()
    code = main(["fit", str(case), "--out", str(tmp_path / "r"), "--material-only", "--base", "tshirt"])
    err = capsys.readouterr().err
    assert code == 2 and "--material-only" in err and err.count("\n") == 1
    assert not (tmp_path / "r").exists()


@pytest.mark.slow
def test_material_only_keeps_the_pattern_and_fits_the_fabric(tmp_path):
    """A tee dressed in denim, fitted from its own pattern: the pattern comes back as given."""
    from unsew.body.body import default_body
    from unsew.body.measure import measure_body
    from unsew.dress import dress
    from unsew.io.garmentcode import load_pattern, save_pattern
    from unsew.io.mesh import write_obj
    from unsew.pattern.base import make_base_pattern
    from unsew.sim.drape import DrapeSettings
    from unsew.sim.material import get_material

    body = default_body()
    truth = make_base_pattern("tshirt", measure_body(body))
    d = dress(truth, body, material=get_material("denim"), settings=DrapeSettings(edge_length=0.04))
    case = tmp_path / "case"
    case.mkdir()
    write_obj(case / "target.obj", d.x.numpy(), d.mesh.faces)
    (case / "meta.json").write_text(json.dumps({"body": "default"}))
    save_pattern(truth, case / "pattern_gt.json")
    (tmp_path / "small.yaml").write_text(
        "drape: {edge_length: 0.04, steps: 6}\noptimizer: {iterations: 3}\noutput: {report: false}\n"
    )
    code = main(
        [
            "fit",
            str(case),
            "--out",
            str(tmp_path / "r"),
            "--material-only",
            "--base",
            str(case / "pattern_gt.json"),
            "--config",
            str(tmp_path / "small.yaml"),
            "--no-progress",
        ]
    )
    assert code == 0
    got = load_pattern(tmp_path / "r" / "pattern.json")
    for name, panel in truth.panels.items():
        np.testing.assert_allclose(got.panels[name].vertices, panel.vertices, atol=1e-6)
    m = json.loads((tmp_path / "r" / "metrics.json").read_text())
    assert m["pattern"]["area_error_rel_mean"] < 1e-4 and m["ok"]
