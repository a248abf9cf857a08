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
