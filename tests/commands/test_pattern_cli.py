"""``unsew pattern new`` and ``unsew pattern export`` through unsew.cli.main and one subprocess."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from unsew.cli import main
from unsew.io.garmentcode import load_pattern

HANDMADE = Path(__file__).parent.parent / "data" / "handmade_specification.json"


def test_new_then_export(tmp_path, capsys):
    out = tmp_path / "t.json"
    assert main(["pattern", "new", "tshirt", "--out", str(out)]) == 0
    p = load_pattern(out)
    assert set(p.panels) == {"front", "back", "left_sleeve", "right_sleeve"}
    svg, dxf, obj = tmp_path / "t.svg", tmp_path / "t.dxf", tmp_path / "t.obj"
    assert main(["pattern", "export", str(out), "--svg", str(svg), "--dxf", str(dxf), "--obj", str(obj)]) == 0
    assert svg.stat().st_size > 0 and dxf.stat().st_size > 0 and obj.stat().st_size > 0
    assert "warning" not in capsys.readouterr().err


def test_new_with_measurements(tmp_path):
    from unsew.pattern.measurements import Measurements

    d = Measurements()
    m = tmp_path / "m.yaml"
    # 16 cm more bust (hip unchanged): the front is (bust + ease) / 2 wide, so 4 cm more each side
    m.write_text(f"bust: {d.bust + 0.16}\nhip: {d.hip}\n")
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    assert main(["pattern", "new", "tshirt", "--out", str(a)]) == 0
    assert main(["pattern", "new", "tshirt", "--measurements", str(m), "--out", str(b)]) == 0
    va, vb = load_pattern(a).panels["front"].vertices, load_pattern(b).panels["front"].vertices
    from unsew.pattern.base.tshirt import BUST_EASE, HIP_EASE

    want = (max(d.bust + 0.16 + BUST_EASE, d.hip + HIP_EASE) - max(d.bust + BUST_EASE, d.hip + HIP_EASE)) / 4
    assert vb[:, 0].max() - va[:, 0].max() == pytest.approx(want) and want > 0.035


def _bad_files(tmp_path):
    d = json.loads(HANDMADE.read_text())
    files = {"empty": "", "invalid": "{oops", "missing": None}
    open_loop = json.loads(json.dumps(d))
    open_loop["pattern"]["panels"]["back"]["edges"][2]["endpoints"] = [2, 0]
    files["open_loop"] = json.dumps(open_loop)
    no_target = json.loads(json.dumps(d))
    no_target["pattern"]["stitches"][0][1] = {"panel": "collar", "edge": 0}
    files["no_target"] = json.dumps(no_target)
    paths = {}
    for k, text in files.items():
        f = tmp_path / f"{k}.json"
        if text is not None:
            f.write_text(text)
        paths[k] = f
    return paths


@pytest.mark.parametrize("case", ["empty", "invalid", "missing", "open_loop", "no_target"])
def test_malformed_inputs_one_line_nothing_written(case, tmp_path, capsys):
    f = _bad_files(tmp_path)[case]
    svg = tmp_path / "out.svg"
    code = main(["pattern", "export", str(f), "--svg", str(svg), "--dxf", str(tmp_path / "out.dxf")])
    err = capsys.readouterr().err
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("unsew: error: ") and "Traceback" not in err
    assert sorted(x.name for x in tmp_path.iterdir() if x.suffix in (".svg", ".dxf", ".part")) == []


def test_bad_measurements_and_outputs(tmp_path, capsys):
    m = tmp_path / "m.yaml"
    m.write_text("bust: 94\n")  # centimetres by mistake
    assert (
        main(["pattern", "new", "tshirt", "--measurements", str(m), "--out", str(tmp_path / "x.json")]) == 2
    )
    assert "implausible" in capsys.readouterr().err
    assert not (tmp_path / "x.json").exists()
    assert main(["pattern", "export", str(HANDMADE)]) == 2
    assert "nothing to export" in capsys.readouterr().err


def test_subprocess_error_is_one_line(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("")
    env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
    r = subprocess.run(
        [sys.executable, "-m", "unsew", "pattern", "export", str(bad), "--svg", str(tmp_path / "o.svg")],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert r.returncode == 2
    assert r.stderr.strip().count("\n") == 0 and "empty" in r.stderr and "Traceback" not in r.stderr
    assert not (tmp_path / "o.svg").exists()


def test_body_measure_json_feeds_pattern_new(tmp_path, capsys):
    """`unsew body measure BODY.obj --json > m.json` (a body without skeleton: a note is printed)
    then `unsew pattern new --measurements m.json`: stdout holds the JSON alone, the pattern is
    sized to that body."""
    from unsew.body.body import default_body
    from unsew.io.mesh import write_obj

    body = default_body().transformed(scale=np.array([1.15, 1.0, 1.15]))  # a wider wearer
    write_obj(tmp_path / "body.obj", body.verts, body.faces)
    capsys.readouterr()
    assert main(["body", "measure", str(tmp_path / "body.obj"), "--json"]) == 0
    out, err = capsys.readouterr()
    assert "note:" in err and "note:" not in out
    m = tmp_path / "m.json"
    m.write_text(out)
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    assert main(["pattern", "new", "tshirt", "--out", str(a)]) == 0
    assert main(["pattern", "new", "tshirt", "--measurements", str(m), "--out", str(b)]) == 0
    wa = np.ptp(load_pattern(a).panels["front"].vertices[:, 0])
    wb = np.ptp(load_pattern(b).panels["front"].vertices[:, 0])
    assert wb > wa * 1.05  # the front is wider for the wider body


def test_measurements_in_centimetres(tmp_path):
    from unsew.pattern.measurements import Measurements

    d = Measurements()
    cm, metres = tmp_path / "cm.yaml", tmp_path / "m.yaml"
    cm.write_text(f"units: cm\nbust: {(d.bust + 0.1) * 100}\n")
    metres.write_text(f"bust: {d.bust + 0.1}\n")
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    assert main(["pattern", "new", "tshirt", "--measurements", str(cm), "--out", str(a)]) == 0
    assert main(["pattern", "new", "tshirt", "--measurements", str(metres), "--out", str(b)]) == 0
    assert np.allclose(load_pattern(a).panels["front"].vertices, load_pattern(b).panels["front"].vertices)
    cm.write_text("units: inch\nbust: 37\n")
    assert (
        main(["pattern", "new", "tshirt", "--measurements", str(cm), "--out", str(tmp_path / "c.json")]) == 2
    )
