"""Every failure a clear line: unwritable outputs, a full disk, patterns far out of scale and a
target its body does not wear end in one ``unsew: error:`` line, a non-zero exit and nothing
left looking finished (driven through unsew.cli.main; one subprocess for the file-size limit)."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh

from unsew.cli import main
from unsew.io.mesh import write_obj

SRC = Path(__file__).resolve().parents[2] / "src"


def _one_line_error(capsys, code, want: str = "", *, status: int = 2) -> str:
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert code == status, err
    assert len(lines) == 1 and lines[0].startswith("unsew: error: "), err
    assert "Traceback" not in err
    assert want in lines[0], lines[0]
    return lines[0]


def _no_outputs(folder: Path) -> list[str]:
    """Names under ``folder`` that look like outputs or their temporaries."""
    return sorted(
        p.name
        for p in folder.rglob("*")
        if p.suffix in (".svg", ".dxf", ".obj", ".part", ".probe", ".partial")
    )


@pytest.fixture
def pattern_file(tmp_path):
    f = tmp_path / "t.json"
    assert main(["pattern", "new", "tshirt", "--out", str(f)]) == 0
    return f


def _scaled(pattern_file: Path, units_in_meter: float) -> Path:
    d = json.loads(pattern_file.read_text())
    d["properties"]["units_in_meter"] = units_in_meter
    out = pattern_file.with_name(f"scaled_{units_in_meter:g}.json")
    out.write_text(json.dumps(d))
    return out


@pytest.mark.parametrize("verb", ["new", "mesh", "export"])
def test_out_under_a_file(verb, tmp_path, pattern_file, capsys):
    (tmp_path / "afile").write_text("x")
    target = (
        tmp_path / "afile" / "sub" / ("p.json" if verb == "new" else "p.obj" if verb == "mesh" else "p.svg")
    )
    capsys.readouterr()
    args = {
        "new": ["pattern", "new", "tshirt", "--out", str(target)],
        "mesh": ["pattern", "mesh", str(pattern_file), "--out", str(target)],
        "export": ["pattern", "export", str(pattern_file), "--svg", str(target)],
    }[verb]
    _one_line_error(capsys, main(args), "is a file, not a folder")
    assert (tmp_path / "afile").read_text() == "x"


def test_out_is_a_device(tmp_path, pattern_file, capsys):
    if not os.path.exists("/dev/null"):
        pytest.skip("no /dev/null")
    link = tmp_path / "p.json"
    link.symlink_to("/dev/null")
    capsys.readouterr()
    _one_line_error(capsys, main(["pattern", "new", "tshirt", "--out", str(link)]), "not a regular file")
    assert link.is_symlink() and os.path.realpath(link) == "/dev/null"


def test_result_folder_under_a_file_fails_before_the_fit(tmp_path, capsys):
    (tmp_path / "afile").write_text("x")
    case = tmp_path / "case"
    case.mkdir()  # an empty case: the --out check must come first, before the case is read
    code = main(["fit", str(case), "--out", str(tmp_path / "afile" / "r"), "--no-progress"])
    _one_line_error(capsys, code, "cannot write --out")
    code = main(["batch", str(case), "--out", str(tmp_path / "afile" / "r"), "--no-progress"])
    _one_line_error(capsys, code, "cannot write --out")
    code = main(["demo", "--out", str(tmp_path / "afile" / "r"), "--no-progress"])
    _one_line_error(capsys, code, "cannot write --out")


@pytest.mark.skipif(sys.platform == "win32", reason="RLIMIT_FSIZE is POSIX")
def test_disk_full_leaves_nothing(tmp_path, pattern_file):
    """A file-size limit of 4 KB makes every larger write fail as on a full disk (EFBIG)."""
    code = (
        "import resource, sys; resource.setrlimit(resource.RLIMIT_FSIZE, (4096, resource.RLIM_INFINITY)); "
        "from unsew.cli import main; sys.exit(main(sys.argv[1:]))"
    )
    out = tmp_path / "out"
    out.mkdir()
    args = ["pattern", "export", str(pattern_file), "--svg", str(out / "p.svg"), "--dxf", str(out / "p.dxf")]
    env = {**os.environ, "PYTHONPATH": str(SRC), "OMP_WAIT_POLICY": "PASSIVE"}
    r = subprocess.run(
        [sys.executable, "-c", code, *args], capture_output=True, text=True, env=env, timeout=120
    )
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2, r.stderr
    assert len(lines) == 1 and lines[0].startswith("unsew: error: cannot write") and "p.svg" in lines[0], (
        r.stderr
    )
    assert list(out.iterdir()) == []


def test_write_failure_inside_atomic_write_is_one_output_error(tmp_path):
    import errno

    from unsew.errors import OutputError
    from unsew.io.atomic import atomic_dir, atomic_write

    with pytest.raises(OutputError, match="cannot write .*a.txt: No space left on device"):
        with atomic_write(tmp_path / "a.txt") as tmp:
            tmp.write_text("partial")
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    with pytest.raises(OutputError, match=r"cannot write .*res.*: No space left"):
        with atomic_dir(tmp_path / "res") as tmp:
            with atomic_write(tmp / "inner.txt") as t2:
                raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(t2))
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    # an OSError about some other file (an input) is not relabelled as the output's
    with pytest.raises(FileNotFoundError):
        with atomic_write(tmp_path / "b.txt"):
            open(tmp_path / "missing-input.txt")
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_pattern_mesh_of_a_pattern_100x_too_large_is_refused_up_front(tmp_path, pattern_file, capsys):
    big = _scaled(pattern_file, 1)  # centimetre numbers read as metres: 100x too large
    capsys.readouterr()
    line = _one_line_error(
        capsys,
        main(["pattern", "mesh", str(big), "--out", str(tmp_path / "big.obj")]),
        "triangles (limit 250,000)",
    )
    assert "units_in_meter" in line and "--max-triangles" in line
    _one_line_error(
        capsys, main(["pattern", "export", str(big), "--obj", str(tmp_path / "big.obj")]), "triangles"
    )
    assert _no_outputs(tmp_path) == []
    # the limit is an option: the ordinary pattern passes the default and fails a small one
    assert main(["pattern", "mesh", str(pattern_file), "--out", str(tmp_path / "ok.obj")]) == 0
    capsys.readouterr()
    _one_line_error(
        capsys,
        main(
            [
                "pattern",
                "mesh",
                str(pattern_file),
                "--out",
                str(tmp_path / "no.obj"),
                "--max-triangles",
                "1000",
            ]
        ),
        "limit 1,000",
    )
    assert not (tmp_path / "no.obj").exists()


def test_triangle_estimate_is_close():
    from unsew.commands._checks import estimate_triangles
    from unsew.meshing.sew import mesh_pattern
    from unsew.pattern.base import make_base_pattern

    for garment in ("tshirt", "skirt"):
        p = make_base_pattern(garment)
        n = len(mesh_pattern(p, edge_length=0.03).faces)
        assert 0.8 * n <= estimate_triangles(p, 0.03) <= 1.3 * n


@pytest.mark.parametrize(
    "units_in_meter,size", [(1, "far too large"), (10, "far too large"), (10000, "far too small")]
)
def test_drape_of_a_pattern_out_of_scale_is_refused(units_in_meter, size, tmp_path, pattern_file, capsys):
    p = _scaled(pattern_file, units_in_meter)
    capsys.readouterr()
    code = main(["drape", str(p), "--out", str(tmp_path / "g.obj"), "--no-progress"])
    _one_line_error(capsys, code, size)
    assert not (tmp_path / "g.obj").exists()


def _tube_case(tmp_path, shift=(0.0, 0.0, 0.0)):
    d = tmp_path / "case"
    d.mkdir(parents=True)
    m = trimesh.creation.cylinder(radius=0.17, height=0.4, sections=24)
    keep = np.abs(m.face_normals[:, 2]) < 0.5
    v = m.vertices[:, [0, 2, 1]] + [0, 1.15, 0.0] + np.asarray(shift)
    write_obj(d / "target.obj", v, m.faces[keep])
    (d / "meta.json").write_text(json.dumps({"garment": "tshirt", "body": "default"}))
    return d


def test_target_beside_the_body_is_refused(tmp_path, capsys):
    from unsew.body.case import load_case

    load_case(_tube_case(tmp_path / "a"))  # worn: loads
    d = _tube_case(tmp_path / "b", shift=(0.0, 0.0, 0.5))  # half a metre in front of the body
    for cmd in (
        ["fit", str(d), "--out", str(tmp_path / "r"), "--no-progress"],
        ["grade", str(d), "--out", str(tmp_path / "r"), "--flat"],
    ):
        _one_line_error(capsys, main(cmd), "does not lie on its wearer")
        assert not (tmp_path / "r").exists() and not (tmp_path / "r.partial").exists()


def test_triangle_limit_default_is_one_number():
    from unsew.commands._checks import MAX_TRIANGLES
    from unsew.commands.pattern import MAX_TRIANGLES as in_help

    assert in_help == MAX_TRIANGLES
