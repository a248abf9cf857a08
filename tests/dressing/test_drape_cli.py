"""unsew drape: writes a draped OBJ with pattern UVs; bad input is one line and exit 2."""

import numpy as np

from unsew.cli import main
from unsew.io.garmentcode import save_pattern
from unsew.meshing import mesh_pattern
from unsew.pattern.base import make_base_pattern


def test_drape_cli_writes_obj(tmp_path, capsys):
    pj = tmp_path / "skirt.json"
    save_pattern(make_base_pattern("skirt"), pj)
    out = tmp_path / "garment.obj"
    rc = main(
        [
            "drape",
            str(pj),
            "--body",
            "default",
            "--edge-length",
            "0.05",
            "--sew-steps",
            "30",  # 20 left the skirt's seams 93 mm open: unsewn
            "--settle-steps",
            "2",
            "--no-progress",
            "--out",
            str(out),
        ]
    )
    assert rc == 0 and out.is_file()
    from unsew.io.mesh import read_mesh

    v, f = read_mesh(out)[:2]
    assert len(v) > 50 and np.isfinite(v).all()
    assert "vt " in out.read_text()


def test_drape_cli_bad_input(tmp_path, capsys):
    out = tmp_path / "g.obj"
    assert main(["drape", str(tmp_path / "missing.json"), "--out", str(out)]) == 2
    assert "not found" in capsys.readouterr().err
    pj = tmp_path / "p.json"
    save_pattern(make_base_pattern("skirt"), pj)
    assert main(["drape", str(pj), "--body", str(tmp_path / "nobody.obj"), "--out", str(out)]) == 2
    assert main(["drape", str(pj), "--material", "unobtainium", "--out", str(out)]) == 2
    assert main(["drape", str(pj), "--edge-length", "2", "--out", str(out)]) == 2
    assert not out.exists()


def test_drape_cli_uses_the_patterns_fitted_material(tmp_path, capsys):
    """A pattern.json written by unsew fit carries its fitted material; drape uses it unless
    --material names another, and refuses a broken one in one line."""
    from unsew.sim.material import MATERIALS, material_to_dict

    p = make_base_pattern("skirt")
    p.unsew = {**p.unsew, "material": material_to_dict(MATERIALS["jersey"])}
    pj = tmp_path / "fitted.json"
    save_pattern(p, pj)
    out = tmp_path / "garment.obj"
    small = ["--edge-length", "0.05", "--sew-steps", "30", "--settle-steps", "1", "--no-progress"]
    assert main(["drape", str(pj), *small, "--out", str(out)]) == 0
    assert "the pattern's fitted material" in out.read_text().splitlines()[0]
    assert main(["drape", str(pj), *small, "--material", "cotton", "--out", str(out), "--overwrite"]) == 0
    assert "cotton" in out.read_text().splitlines()[0]
    p.unsew["material"] = {"H00_N_per_m": 1.0}
    save_pattern(p, pj)
    out.unlink()
    assert main(["drape", str(pj), *small, "--out", str(out)]) == 2
    assert "material lacks" in capsys.readouterr().err
    assert not out.exists()


def test_drape_cli_body_folder(tmp_path, capsys):
    """--body takes a body folder as `unsew body make` writes it (body.obj + skeleton.json);
    one without skeleton.json is rigged from its mesh and drapes too."""
    from unsew.body.body import default_body
    from unsew.body.skeleton import save_skeleton
    from unsew.io.mesh import write_obj

    b = default_body()
    folder = tmp_path / "body"
    folder.mkdir()
    write_obj(folder / "body.obj", b.verts, b.faces)
    pj = tmp_path / "skirt.json"
    save_pattern(make_base_pattern("skirt"), pj)
    out = tmp_path / "garment.obj"
    small = ["--edge-length", "0.06", "--sew-steps", "5", "--settle-steps", "0", "--no-progress"]
    assert main(["drape", str(pj), "--body", str(folder), *small, "--out", str(out)]) == 0
    assert out.is_file()
    out.unlink()
    save_skeleton(b.skeleton, folder / "skeleton.json")
    assert main(["drape", str(pj), "--body", str(folder), *small, "--out", str(out)]) == 0
    assert out.is_file()


def test_drape_cli_case_folder_without_its_target(tmp_path, capsys):
    """--body takes a case folder before its garment is draped (meta.json and body.obj, no
    target): its wearer is read in meta.json's units; a folder whose meta.json names no body
    and has no body.obj is refused in one line."""
    import json

    from unsew.body.body import default_body
    from unsew.io.mesh import write_obj

    b = default_body()
    case = tmp_path / "case"
    case.mkdir()
    write_obj(case / "body.obj", b.verts * 100.0, b.faces)  # centimetres, as meta.json says
    (case / "meta.json").write_text(json.dumps({"units": "cm"}))
    pj = tmp_path / "skirt.json"
    save_pattern(make_base_pattern("skirt"), pj)
    out = tmp_path / "garment.obj"
    small = ["--edge-length", "0.06", "--sew-steps", "30", "--settle-steps", "0", "--no-progress"]
    assert main(["drape", str(pj), "--body", str(case), *small, "--out", str(out)]) == 0
    from unsew.io.mesh import read_mesh

    v = read_mesh(out)[0]
    assert 0.5 < v[:, 1].mean() < 1.3  # on the body in metres, not a hundred times off
    (case / "body.obj").unlink()
    out.unlink()
    assert main(["drape", str(pj), "--body", str(case), *small, "--out", str(out)]) == 2
    assert "names no body" in capsys.readouterr().err and not out.exists()


def test_drape_cli_uses_the_contact_a_fit_wrote(tmp_path, capsys):
    """A fit with ``contact: target`` writes its contact into pattern.json (pattern_with_extras);
    drape reads it back and rests the cloth with it; a default-contact fit writes none; a broken
    contact is refused in one line with no --out written."""
    from types import SimpleNamespace

    from unsew.commands.drape import pattern_contact
    from unsew.fit.outputs import pattern_with_extras
    from unsew.io.garmentcode import load_pattern
    from unsew.sim.material import MATERIALS

    def written(contact):
        pattern = make_base_pattern("skirt")
        mesh = mesh_pattern(pattern, edge_length=0.05)
        x = np.zeros((mesh.n_x, 3))
        x[np.asarray(mesh.x_of_u)] = mesh.uv_placed3d  # draped where placed
        result = SimpleNamespace(
            pattern=pattern,
            params=None,
            material=MATERIALS["cotton"],
            contact=contact,
            mesh=mesh,
            uv=mesh.uv,
            x=x,
        )
        pj = tmp_path / f"{contact['mode']}.json"
        save_pattern(pattern_with_extras(result), pj)
        return pj

    plain = written({"mode": "default", "threshold_mm": 5.0, "stiffness": 1e7})
    assert pattern_contact(load_pattern(plain)) is None
    fitted = written({"mode": "target", "gap_mm": 3.4, "threshold_mm": 3.4, "stiffness": 1e9})
    assert pattern_contact(load_pattern(fitted)) == {"contact_threshold": 3.4e-3, "contact_stiffness": 1e9}
    out = tmp_path / "garment.obj"
    small = ["--edge-length", "0.05", "--sew-steps", "30", "--settle-steps", "1", "--no-progress"]
    assert main(["drape", str(fitted), *small, "--out", str(out)]) == 0
    assert "fitted contact: threshold 3.4 mm, stiffness 1e+09" in capsys.readouterr().out
    p = load_pattern(fitted)
    p.unsew = {**p.unsew, "contact": {"threshold_m": -1.0, "stiffness_n_m4": 1e9}}
    bad = tmp_path / "bad.json"
    save_pattern(p, bad)
    out.unlink()
    assert main(["drape", str(bad), *small, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "positive threshold" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


def test_drape_cli_case_folder_reads_its_wearer_only(tmp_path, capsys):
    """--body CASE takes the case's wearer: its pattern_gt.json is not what is draped, so a true
    pattern that does not read (or warns) neither stops the drape nor speaks in its output."""
    from unsew.body.body import default_body
    from unsew.io.mesh import write_obj

    b = default_body()
    case = tmp_path / "case"
    case.mkdir()
    write_obj(case / "body.obj", b.verts, b.faces)
    c = b.verts[b.faces].mean(axis=1)
    band = b.faces[(c[:, 1] > 1.0) & (c[:, 1] < 1.2)]  # an open tube lying on the torso
    write_obj(case / "target.obj", b.verts, band)
    (case / "meta.json").write_text("{}")
    (case / "pattern_gt.json").write_text("{ not a pattern")
    pj = tmp_path / "skirt.json"
    save_pattern(make_base_pattern("skirt"), pj)
    out = tmp_path / "garment.obj"
    small = ["--edge-length", "0.06", "--sew-steps", "30", "--settle-steps", "0", "--no-progress"]
    assert main(["drape", str(pj), "--body", str(case), *small, "--out", str(out)]) == 0
    assert out.is_file() and "pattern_gt" not in capsys.readouterr().err
