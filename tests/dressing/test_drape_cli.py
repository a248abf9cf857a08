"""unsew drape: writes a draped OBJ with pattern UVs; bad input is one line and exit 2."""

import numpy as np

from unsew.cli import main
from unsew.io.garmentcode import save_pattern
from unsew.pattern.base import make_base_pattern


def test_drape_cli_writes_obj(tmp_path, capsys):
    pj = tmp_path / "skirt.json"
    save_pattern(make_base_pattern("skirt"), pj)
    out = tmp_path / "garment.obj"
    rc = main(["drape", str(pj), "--body", "default", "--edge-length", "0.05", "--sew-steps", "20",
               "--settle-steps", "2", "--no-progress", "--out", str(out)])
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
    small = ["--edge-length", "0.05", "--sew-steps", "10", "--settle-steps", "1", "--no-progress"]
    assert main(["drape", str(pj), *small, "--out", str(out)]) == 0
    assert "the pattern's fitted material" in out.read_text().splitlines()[0]
    assert main(["drape", str(pj), *small, "--material", "cotton", "--out", str(out)]) == 0
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
