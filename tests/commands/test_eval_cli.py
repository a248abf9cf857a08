"""``unsew eval``: metrics of a result folder against a case folder, and its errors."""

import json

import numpy as np
import pytest

from helpers import assert_close
from unsew.cli import main
from unsew.io.garmentcode import save_pattern
from unsew.io.mesh import write_obj
from unsew.pattern.model import Edge, Panel, Pattern


def _plane(z, n=5):
    """A 0.5 m square at depth z [m] across the default body's torso (worn: it lies on the body)."""
    s = np.linspace(0, 0.5, n)
    X, Y = np.meshgrid(s, s)
    V = np.stack([X.ravel() - 0.25, Y.ravel() + 0.9, np.full(X.size, z)], 1)
    F = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            F += [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]]
    return V, np.array(F)


def _pattern(scale=1.0, names=("front", "back")):
    panels = {}
    for k, name in enumerate(names):
        v = np.array([[0, 0], [0.4, 0], [0.4, 0.6], [0, 0.6]]) * scale
        edges = [Edge(i, (i + 1) % 4) for i in range(4)]
        panels[name] = Panel(name, v, edges, np.array([0.0, 0.0, 0.2 - 0.4 * k]), np.zeros(3))
    return Pattern("p", panels)


META = {"garment": "skirt", "body": "default"}


@pytest.fixture
def folders(tmp_path):
    res, case = tmp_path / "result", tmp_path / "case"
    res.mkdir()
    case.mkdir()
    write_obj(res / "garment.obj", *_plane(0.0))
    write_obj(case / "target.obj", *_plane(0.005, n=7))
    (case / "meta.json").write_text(json.dumps(META))
    return res, case


def test_eval_3d_only_writes_json(folders, capsys):
    res, case = folders
    assert main(["eval", str(res), str(case), "--samples", "2000"]) == 0
    out = capsys.readouterr().out
    assert "Chamfer" in out and "2D: skipped" in out
    ev = json.loads((res / "eval.json").read_text())
    assert_close(ev["3d"]["chamfer_mm"], 5.0, rtol=1e-6)
    assert_close(ev["3d"]["hausdorff_mm"], 5.0, rtol=1e-6)
    assert ev["2d"] is None and ev["3d"]["n_samples"] == 2000
    assert not [p for p in res.iterdir() if p.name.endswith(".part")]


def test_eval_with_patterns_and_json_flag(folders, capsys):
    res, case = folders
    save_pattern(_pattern(1.1), res / "pattern.json")
    save_pattern(_pattern(1.0), case / "pattern_gt.json")
    (case / "meta.json").write_text(json.dumps({**META, "units": "m", "up": "y", "front": "z"}))
    capsys.readouterr()
    assert main(["eval", str(res), str(case), "--samples", "1000", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)  # stdout holds the JSON alone
    ev = json.loads((res / "eval.json").read_text())
    assert printed == ev
    assert_close(ev["2d"]["area_error_rel_mean"], 0.21, rtol=1e-9)
    assert ev["2d"]["turning_distance_mean"] < 1e-9
    assert set(ev["2d"]["panels"]) == {"front", "back"}


def test_eval_target_units_from_meta(folders):
    res, case = folders
    # the target written in cm, 0.5 cm = 5 mm above the result
    write_obj(case / "target.obj", _plane(0.0)[0] * 100 + [0, 0, 0.5], _plane(0.0)[1])
    (case / "meta.json").write_text(json.dumps({**META, "units": "cm"}))
    assert main(["eval", str(res), str(case), "--samples", "500"]) == 0
    ev = json.loads((res / "eval.json").read_text())
    assert_close(ev["3d"]["chamfer_mm"], 5.0, rtol=1e-6)


def test_eval_refuses_a_case_in_the_wrong_units_as_fit_does(folders, capsys):
    res, case = folders
    write_obj(case / "target.obj", _plane(0.0)[0] * 100 + [0, 0, 0.5], _plane(0.0)[1])  # cm, meta says m
    _fails(["eval", str(res), str(case), "--samples", "500"], capsys, match="--units cm")
    assert not (res / "eval.json").exists()
    # the option fixes it
    assert main(["eval", str(res), str(case), "--samples", "500", "--units", "cm"]) == 0
    assert_close(json.loads((res / "eval.json").read_text())["3d"]["chamfer_mm"], 5.0, rtol=1e-6)


def test_eval_refuses_a_target_off_its_body(folders, tmp_path, capsys):
    res, case = folders
    V, F = _plane(0.005, n=7)
    write_obj(case / "target.obj", V + [0, 0, 5.0], F)  # 5 m in front of the wearer
    write_obj(res / "garment.obj", _plane(0.0)[0] + [0, 0, 5.0], _plane(0.0)[1])
    _fails(["eval", str(res), str(case), "--samples", "500"], capsys, match="does not lie on its wearer")
    assert not (res / "eval.json").exists()
    # fit refuses the same case with the same line
    _fails(
        ["fit", str(case), "--out", str(tmp_path / "r"), "--no-progress"],
        capsys,
        match="does not lie on its wearer",
    )


def test_eval_json_is_not_replaced_without_overwrite(folders, capsys):
    res, case = folders
    assert main(["eval", str(res), str(case), "--samples", "500"]) == 0
    first = (res / "eval.json").read_text()
    _fails(["eval", str(res), str(case), "--samples", "600"], capsys, match="pass --overwrite")
    assert (res / "eval.json").read_text() == first
    assert main(["eval", str(res), str(case), "--samples", "600", "--overwrite"]) == 0
    assert json.loads((res / "eval.json").read_text())["3d"]["n_samples"] == 600


def _fails(args, capsys, *, match):
    rc = main(args)
    err = capsys.readouterr().err
    assert rc == 2
    assert match in err and err.count("\n") == 1 and "Traceback" not in err


def test_missing_files(folders, tmp_path, capsys):
    res, case = folders
    _fails(["eval", str(tmp_path / "nope"), str(case)], capsys, match="does not exist")
    (case / "target.obj").unlink()
    _fails(["eval", str(res), str(case)], capsys, match="no target.obj")
    (res / "garment.obj").unlink()
    _fails(["eval", str(res), str(case)], capsys, match="no garment.obj")
    assert not (res / "eval.json").exists()


def test_empty_and_nan_meshes(folders, capsys):
    res, case = folders
    (res / "garment.obj").write_text("# nothing\n")
    _fails(["eval", str(res), str(case)], capsys, match="garment.obj")
    V, F = _plane(0.0)
    V[2, 0] = np.nan
    write_obj(res / "garment.obj", V, F)
    _fails(["eval", str(res), str(case)], capsys, match="NaN")
    assert not (res / "eval.json").exists()


def test_unmatched_panels_are_reported(folders, capsys):
    """A true panel the result lacks (a waistband) is listed and counted at its full area in the
    area-weighted error; the base/graded patterns saved beside pattern.json are evaluated too."""
    res, case = folders
    save_pattern(_pattern(1.0, names=("front",)), res / "pattern.json")
    save_pattern(_pattern(1.0, names=("front",)), res / "pattern_base.json")
    save_pattern(_pattern(1.0), case / "pattern_gt.json")
    assert main(["eval", str(res), str(case), "--samples", "500"]) == 0
    out = capsys.readouterr().out
    assert "unmatched panels: estimated [], true ['back']" in out
    ev = json.loads((res / "eval.json").read_text())
    assert ev["2d"]["unmatched"] == {"estimated": [], "true": ["back"]}
    assert ev["2d"]["area_error_rel_mean"] == 0.0  # the matched front is exact
    assert_close(ev["2d"]["area_error_weighted_rel"], 0.5, rtol=1e-9)  # the missing back: half the fabric
    assert_close(ev["2d"]["area_error_total_rel"], 0.5, rtol=1e-9)
    assert_close(ev["2d_base"]["area_error_weighted_rel"], 0.5, rtol=1e-9) and "2d_graded" not in ev
