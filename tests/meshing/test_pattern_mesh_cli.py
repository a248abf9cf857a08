"""``unsew pattern mesh``: figures printed, OBJ written, bad input as one line."""

from __future__ import annotations

import subprocess
import sys

import pytest
from meshing.handmade_patterns import mini_shirt

from unsew.io.garmentcode import save_pattern


def _unsew(*args):
    return subprocess.run([sys.executable, "-m", "unsew", *map(str, args)], capture_output=True, text=True)


@pytest.fixture()
def pattern_file(tmp_path):
    path = tmp_path / "p.json"
    save_pattern(mini_shirt(), path)
    return path


def test_mesh_writes_obj_and_prints_figures(pattern_file, tmp_path):
    out = tmp_path / "rest.obj"
    r = _unsew("pattern", "mesh", pattern_file, "--edge-length", "0.03", "--out", out)
    assert r.returncode == 0, r.stderr
    assert "triangles" in r.stdout and "min angle" in r.stdout
    text = out.read_text()
    n_f = sum(1 for line in text.splitlines() if line.startswith("f "))
    tri_line = next(line for line in r.stdout.splitlines() if line.startswith("triangles"))
    assert n_f == int(tri_line.split()[-1]) > 0
    assert sum(1 for line in text.splitlines() if line.startswith("vt ")) > 0


@pytest.mark.parametrize(
    "extra",
    [["--edge-length", "0.001"], ["--edge-length", "0.5"]],
)
def test_bad_edge_length_is_one_line(pattern_file, tmp_path, extra):
    out = tmp_path / "rest.obj"
    r = _unsew("pattern", "mesh", pattern_file, *extra, "--out", out)
    assert r.returncode != 0
    assert "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert not out.exists()


def test_missing_and_empty_files(tmp_path):
    out = tmp_path / "rest.obj"
    r = _unsew("pattern", "mesh", tmp_path / "missing.json", "--out", out)
    assert r.returncode != 0 and "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1
    empty = tmp_path / "empty.json"
    empty.write_text("")
    r = _unsew("pattern", "mesh", empty, "--out", out)
    assert r.returncode != 0 and "Traceback" not in r.stderr
    assert not out.exists() and [p.name for p in tmp_path.iterdir()] == ["empty.json"]
