"""One ``--out`` rule for every command that writes: a missing parent folder is an error (one line,
exit 2, nothing created), an existing result is refused without ``--overwrite`` (left as it was)
and replaced with it. The long work of fit, demo, batch and body make is replaced by a stand-in
that records the call: the rule is the command's, checked before that work starts."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import trimesh

from unsew.cli import main
from unsew.io.mesh import write_obj


def _refused(capsys, code: int, want: str) -> str:
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert code == 2, err
    assert len(lines) == 1 and lines[0].startswith("unsew: error: ") and want in lines[0], err
    return lines[0]


@pytest.fixture
def pattern(tmp_path):
    p = tmp_path / "in" / "t.json"
    p.parent.mkdir()
    assert main(["pattern", "new", "tshirt", "--out", str(p)]) == 0
    return p


@pytest.fixture
def case(tmp_path):
    """A tube worn on the default body's chest (a valid case for fit and grade)."""
    d = tmp_path / "in" / "case"
    d.mkdir(parents=True)
    m = trimesh.creation.cylinder(radius=0.17, height=0.4, sections=24)
    keep = np.abs(m.face_normals[:, 2]) < 0.5
    write_obj(d / "target.obj", m.vertices[:, [0, 2, 1]] + [0, 1.15, 0.0], m.faces[keep])
    (d / "meta.json").write_text(json.dumps({"garment": "tshirt", "body": "default"}))
    return d


def _file_commands(pattern: Path) -> dict:
    """Commands writing one file: argv with the output path as {out}."""
    return {
        "pattern new": ["pattern", "new", "skirt", "--out", "{out}.json"],
        "pattern mesh": ["pattern", "mesh", str(pattern), "--edge-length", "0.03", "--out", "{out}.obj"],
        "pattern export svg": ["pattern", "export", str(pattern), "--svg", "{out}.svg"],
        "pattern export dxf": ["pattern", "export", str(pattern), "--dxf", "{out}.dxf"],
        "pattern export obj": ["pattern", "export", str(pattern), "--obj", "{out}.obj"],
        "drape": [
            "drape",
            str(pattern),
            "--edge-length",
            "0.05",
            "--sew-steps",
            "10",
            "--settle-steps",
            "5",
            "--no-progress",
            "--out",
            "{out}.obj",
        ],
    }


def _fill(argv: list[str], out: Path) -> list[str]:
    return [a.replace("{out}", str(out)) for a in argv]


@pytest.mark.parametrize("name", list(_file_commands(Path("p.json"))))
def test_file_outputs(name, tmp_path, pattern, capsys):
    argv = _file_commands(pattern)[name]
    capsys.readouterr()
    # a missing parent folder: refused, not created
    line = _refused(capsys, main(_fill(argv, tmp_path / "missing" / "x")), "does not exist")
    assert str(tmp_path / "missing") in line and not (tmp_path / "missing").exists()
    # an existing result: refused without --overwrite, left alone
    out = tmp_path / "x"
    existing = Path(_fill(argv, out)[-1])
    existing.write_text("mine")
    _refused(capsys, main(_fill(argv, out)), "pass --overwrite")
    assert existing.read_text() == "mine"
    # with --overwrite: replaced
    assert main([*_fill(argv, out), "--overwrite"]) == 0, capsys.readouterr().err
    assert existing.read_text() != "mine" and existing.stat().st_size > 0


def test_grade(tmp_path, case, capsys):
    argv = ["grade", str(case), "--flat", "--edge-length", "0.05", "--out"]
    _refused(capsys, main([*argv, str(tmp_path / "missing" / "g")]), "does not exist")
    assert not (tmp_path / "missing").exists()
    out = tmp_path / "g"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    _refused(capsys, main([*argv, str(out)]), "pass --overwrite")
    assert (out / "keep.txt").read_text() == "mine"
    assert main([*argv, str(out), "--overwrite"]) == 0
    assert (out / "pattern.json").is_file() and not (out / "keep.txt").exists()


def test_body_rig(tmp_path, capsys):
    from unsew.body.body import default_body

    b = default_body()
    body = tmp_path / "b" / "body.obj"
    body.parent.mkdir()
    write_obj(body, b.verts, b.faces)
    skel = body.parent / "skeleton.json"
    skel.write_text("mine")  # the default --out, beside the body
    _refused(capsys, main(["body", "rig", str(body)]), "pass --overwrite")
    assert skel.read_text() == "mine"
    _refused(
        capsys,
        main(["body", "rig", str(body), "--out", str(tmp_path / "missing" / "s.json")]),
        "does not exist",
    )
    (tmp_path / "rig.png").write_text("mine")
    _refused(
        capsys,
        main(
            [
                "body",
                "rig",
                str(body),
                "--out",
                str(tmp_path / "s.json"),
                "--preview",
                str(tmp_path / "rig.png"),
            ]
        ),
        "--preview",
    )
    assert not (tmp_path / "s.json").exists()
    assert main(["body", "rig", str(body), "--overwrite"]) == 0
    assert json.loads(skel.read_text())["units"] == "m"


@pytest.fixture
def stand_ins(monkeypatch):
    """Replace the long work behind fit, demo, batch and body make; record what reached it."""
    from unsew.body.body import default_body

    calls: list[str] = []

    def fit(case, cfg, out, **kw):
        calls.append("fit")
        Path(out).mkdir(exist_ok=True)
        return None, {}

    def demo(out, **kw):
        calls.append("demo")

    def batch(cases, out, **kw):
        calls.append("batch")
        raise SystemExit(0)  # stop before the summary

    def anny(phenotype, pose="A"):
        calls.append("body make")
        return default_body()

    monkeypatch.setattr("unsew.fit.run.run_fit", fit)
    monkeypatch.setattr("unsew.fit.demo.run_demo", demo)
    monkeypatch.setattr("unsew.batch.runner.run_batch", batch)
    monkeypatch.setattr("unsew.body.anny_body.make_anny_body", anny)
    return calls


def _folder_commands(case: Path) -> dict:
    return {
        "fit": ["fit", str(case), "--no-progress", "--out"],
        "demo": ["demo", "--no-progress", "--out"],
        "body make": ["body", "make", "--out"],
    }


@pytest.mark.parametrize("name", ["fit", "demo", "body make"])
def test_result_folders(name, tmp_path, case, stand_ins, capsys):
    argv = _folder_commands(case)[name]
    _refused(capsys, main([*argv, str(tmp_path / "missing" / "r")]), "does not exist")
    assert not (tmp_path / "missing").exists()
    out = tmp_path / "r"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    _refused(capsys, main([*argv, str(out)]), "pass --overwrite")
    assert (out / "keep.txt").read_text() == "mine" and stand_ins == []
    assert main([*argv, str(out), "--overwrite"]) == 0, capsys.readouterr().err
    assert stand_ins == [name]


def test_batch_reuses_its_folder_but_not_a_missing_parent(tmp_path, case, stand_ins, capsys):
    argv = ["batch", str(case.parent), "--no-progress", "--out"]
    _refused(capsys, main([*argv, str(tmp_path / "missing" / "r")]), "does not exist")
    assert not (tmp_path / "missing").exists() and stand_ins == []
    (tmp_path / "r").mkdir()  # a rerun continues in its results folder
    with pytest.raises(SystemExit):
        main([*argv, str(tmp_path / "r")])
    assert stand_ins == ["batch"]
