"""``unsew grade CASE_DIR --base tshirt --out graded/`` through unsew.cli.main (flat drapes)."""

from __future__ import annotations

import json

import pytest

from unsew.cli import main
from unsew.grading.alter import alter_pattern, alteration_groups
from unsew.grading.grade import flat_drape
from unsew.io.mesh import write_obj
from unsew.meshing.sew import mesh_pattern
from unsew.pattern.base import make_base_pattern


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    d = tmp_path_factory.mktemp("case")
    p = make_base_pattern("tshirt")
    t = alter_pattern(p, alteration_groups(p)["hem"], length=0.06)
    m = mesh_pattern(t, edge_length=0.04)
    write_obj(d / "target.obj", flat_drape(t, m), m.faces)
    (d / "meta.json").write_text(json.dumps({"garment": "tshirt", "units": "m", "body": "default"}))
    return d


def test_grade_cli_writes_pattern_drape_and_table(case, tmp_path, capsys):
    out = tmp_path / "graded"
    assert (
        main(["grade", str(case), "--base", "tshirt", "--out", str(out), "--flat", "--edge-length", "0.04"])
        == 0
    )
    assert sorted(p.name for p in out.iterdir()) == [
        "contours.json",
        "garment.obj",
        "garment_init.obj",
        "pattern.json",
    ]
    doc = json.loads((out / "contours.json").read_text())
    assert doc["units"] == "m" and len(doc["contours"]) == 4
    hem = next(r for r in doc["contours"] if r["part"] == "torso")
    assert hem["extension_m"] == pytest.approx(0.06, abs=0.01)
    # laid flat, the hem's cloth length to the neckline is 6 cm longer too
    assert doc["length"] == "cloth" and hem["cloth_difference_m"] == pytest.approx(0.06, abs=0.01)
    assert "torso" in capsys.readouterr().out


def test_grade_cli_axial_length_leaves_cloth_unmeasured(case, tmp_path):
    out = tmp_path / "graded"
    args = ["grade", str(case), "--out", str(out), "--flat", "--edge-length", "0.04", "--length", "axial"]
    assert main(args) == 0
    doc = json.loads((out / "contours.json").read_text())
    assert doc["length"] == "axial" and all(r["cloth_difference_m"] is None for r in doc["contours"])


def test_grade_cli_refuses_existing_out_and_leaves_nothing_on_failure(case, tmp_path, capsys):
    out = tmp_path / "graded"
    out.mkdir()
    assert main(["grade", str(case), "--out", str(out), "--flat"]) == 2
    assert "exists" in capsys.readouterr().err
    bad = tmp_path / "bad"
    assert main(["grade", str(case), "--out", str(bad), "--flat", "--edge-length", "5"]) == 2
    assert not bad.exists()
    assert main(["grade", str(tmp_path / "nope"), "--out", str(tmp_path / "x"), "--flat"]) == 2
    assert not (tmp_path / "x").exists()
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


def test_grade_cli_takes_library_bases_sized_to_the_wearer(case, tmp_path, capsys):
    out = tmp_path / "long"
    assert (
        main(
            [
                "grade",
                str(case),
                "--base",
                "tshirt_long",
                "--out",
                str(out),
                "--flat",
                "--edge-length",
                "0.04",
            ]
        )
        == 0
    )
    assert json.loads((out / "contours.json").read_text())["base"] == "tshirt_long"
    assert main(["grade", str(case), "--base", "skirt_band", "--out", str(tmp_path / "x"), "--flat"]) == 2
    assert "cannot make a tshirt" in capsys.readouterr().err and not (tmp_path / "x").exists()
    assert main(["grade", str(case), "--base", "cape", "--out", str(tmp_path / "y"), "--flat"]) == 2
    assert "neither a base pattern" in capsys.readouterr().err and not (tmp_path / "y").exists()
