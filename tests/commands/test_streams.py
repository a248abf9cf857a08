"""What goes to which stream: progress bars only on a terminal; a file or a pipe gets plain lines,
never a carriage return or an escape code (fit, drape, batch, demo); ``--json`` puts JSON alone on
stdout. Real commands run through pipes (subprocess) with small inputs; the fit and the demo
through pipes are marked slow, the progress layer they share is tested here directly."""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from unsew.fit.progress import Progress, is_terminal

TESTS = Path(__file__).resolve().parents[1]
SRC = TESTS.parent / "src"
ENV = {**os.environ, "PYTHONPATH": str(SRC), "OMP_WAIT_POLICY": "PASSIVE"}
CONTROL = ("\r", "\x1b")  # a bar's redraw: carriage return, cursor/erase codes


def _clean(text: str, what: str) -> None:
    bad = [c for c in CONTROL if c in text]
    assert not bad, f"{what} holds {bad!r}: {text[:300]!r}"


def _unsew(*args, timeout=300) -> subprocess.CompletedProcess:
    """``python -m unsew ARGS`` with stdout and stderr to pipes (not terminals)."""
    return subprocess.run(
        [sys.executable, "-m", "unsew", *map(str, args)],
        capture_output=True,
        text=True,
        env=ENV,
        timeout=timeout,
    )


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


class _Closed(io.StringIO):
    def isatty(self) -> bool:
        raise ValueError("I/O operation on closed file")


def test_the_stream_decides_bars_or_lines():
    assert not is_terminal(io.StringIO()) and is_terminal(_Terminal())
    assert not is_terminal(None) and not is_terminal(object()) and not is_terminal(_Closed())

    def run(stream):
        p = Progress(stream=stream, every=2)
        p.line("fit: start")
        with p.phase("drape") as cb:
            for phase, n in (("sew", 30), ("settle", 10)):
                for k in range(1, n + 1):
                    cb(phase, k, n)

        class Info:
            last = False

        it = p.iterations(6, 0, lambda info: 3.5)
        for i in range(6):
            info = Info()
            info.iteration = i
            it(info)
        it.close()
        return stream.getvalue()

    plain = run(io.StringIO())
    _clean(plain, "a file's progress")
    lines = plain.splitlines()
    assert lines[0] == "fit: start"
    assert sum(ln.startswith("drape: ") for ln in lines) == 2  # a line per phase, not per step
    iters = [ln for ln in lines if ln.startswith("fit: iteration")]
    assert len(iters) == 3 and iters[-1].startswith("fit: iteration 6/6, Chamfer 3.50 mm")  # every 2nd
    bars = run(_Terminal())
    assert "\r" in bars  # a terminal gets tqdm's bars
    assert not Progress(False, stream=io.StringIO()).enabled


def test_drape_through_a_pipe_has_no_control_codes(tmp_path):
    pattern, out = tmp_path / "s.json", tmp_path / "g.obj"
    assert _unsew("pattern", "new", "skirt", "--out", pattern).returncode == 0
    r = _unsew(
        "drape", pattern, "--out", out, "--edge-length", "0.05", "--sew-steps", "30", "--settle-steps", "5"
    )
    assert r.returncode == 0, r.stderr
    _clean(r.stdout, "stdout")
    _clean(r.stderr, "stderr")
    assert "drape: sew (30 steps)" in r.stderr.splitlines() and r.stdout.startswith(f"wrote {out}")
    assert out.is_file()


_BATCH_DRIVER = """
import sys
sys.path.insert(0, {tests!r})
from batch.fakes import fake_fit
from unsew.batch import run_batch
from unsew.fit.config import load_config
cfg = load_config(optimizer={{"iterations": 2}}, output={{"report": False}})
run_batch({cases!r}, {out!r}, cfg=cfg, workers=1, fit_fn=fake_fit, progress=True)
"""


def test_batch_progress_through_a_pipe_is_a_line_per_case(tmp_path):
    from batch.fakes import make_fake_case

    for name in ("a", "b"):
        make_fake_case(tmp_path / "cases" / name)
    make_fake_case(tmp_path / "cases" / "c", garment="sweater")
    script = _BATCH_DRIVER.format(tests=str(TESTS), cases=str(tmp_path / "cases"), out=str(tmp_path / "out"))
    r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=ENV, timeout=120)
    assert r.returncode == 0, r.stderr
    _clean(r.stderr, "the batch's stderr")
    lines = r.stderr.splitlines()
    assert lines[0].startswith("batch: 3 cases, 3 to fit")
    assert sorted(ln.split()[2] for ln in lines[1:]) == ["a", "b", "c"]  # "batch: 1/3 a done"
    assert any(ln.startswith("batch: ") and " c failed: garment 'sweater'" in ln for ln in lines)


def test_json_flags_print_json_alone(tmp_path):
    from unsew.body.body import default_body
    from unsew.io.mesh import write_obj

    b = default_body()
    write_obj(tmp_path / "body.obj", b.verts, b.faces)  # no skeleton: rigged, with a note
    r = _unsew("body", "measure", tmp_path / "body.obj", "--json")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["units"] == "m" and "note:" in r.stderr
    # `unsew body measure X.obj --json > m.json`, then `unsew pattern new --measurements m.json`
    (tmp_path / "m.json").write_text(r.stdout)
    sized = tmp_path / "sized.json"
    r = _unsew("pattern", "new", "skirt", "--measurements", tmp_path / "m.json", "--out", sized)
    assert r.returncode == 0 and sized.is_file(), r.stderr
    _clean(r.stdout + r.stderr, "pattern new's output")
    pattern = tmp_path / "p.json"
    assert _unsew("pattern", "new", "tshirt", "--out", pattern).returncode == 0
    r = _unsew("pattern", "symmetry", pattern, "--json")
    assert r.returncode == 0 and json.loads(r.stdout)["units"] == "m"


def test_eval_json_through_a_pipe_is_the_json_it_writes(tmp_path):
    import trimesh

    from unsew.io.mesh import write_obj

    res, case = tmp_path / "result", tmp_path / "case"
    res.mkdir()
    case.mkdir()
    box = trimesh.creation.box(extents=(0.4, 0.6, 0.2))
    tube = np.asarray(box.faces)[np.abs(box.face_normals[:, 1]) < 0.5]  # open at the top and the hem
    write_obj(res / "garment.obj", np.asarray(box.vertices), tube)
    write_obj(case / "target.obj", np.asarray(box.vertices) + [0.0, 0.0, 0.004], tube)
    (case / "meta.json").write_text(
        json.dumps({"garment": "skirt", "body": "default", "units": "m", "up": "y", "front": "z"})
    )
    r = _unsew("eval", res, case, "--samples", "500", "--json")
    assert r.returncode == 0, r.stderr
    _clean(r.stdout + r.stderr, "eval's output")
    assert json.loads(r.stdout) == json.loads((res / "eval.json").read_text())


# ---------------------------------------------------------------- the fit, batch and demo, real

TINY = {
    "drape.edge_length": 0.05,
    "drape.sew_steps": 10,
    "drape.settle_steps": 5,
    "drape.steps": 3,
    "loss.target_points": 1000,
    "output.report": False,
    "material.start": "cotton",
    "optimizer.iterations": 1,
}


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    import yaml

    from unsew.fit.config import load_config
    from unsew.fit.demo import make_truth_case

    root = tmp_path_factory.mktemp("tiny")
    (root / "tiny.yaml").write_text(yaml.safe_dump(TINY))
    make_truth_case(root / "cases" / "tshirt", settings=load_config(**TINY).drape)
    return root


@pytest.mark.slow
@pytest.mark.parametrize("command", ["fit", "batch", "demo"])
def test_real_commands_through_a_pipe_have_no_control_codes(command, tiny, tmp_path):
    cfg, cases = tiny / "tiny.yaml", tiny / "cases"
    args = {
        "fit": ["fit", cases / "tshirt", "--out", tmp_path / "r", "--config", cfg],
        "batch": ["batch", cases, "--out", tmp_path / "r", "--config", cfg, "--workers", "1"],
        "demo": ["demo", "--out", tmp_path / "r", "--config", cfg],
    }[command]
    r = _unsew(*args, timeout=900)
    assert r.returncode == 0, r.stderr[-2000:]
    _clean(r.stdout, f"{command}'s stdout")
    _clean(r.stderr, f"{command}'s stderr")
    assert r.stderr.strip(), "no progress at all"
